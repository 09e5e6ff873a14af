# Writes OUT (femdem_version.hpp) from IN with the current `git describe`, at every build, and
# only when the text changes: so the revision in `femdem --version` and run.log is that of the
# sources built, not of the last configure, and an unchanged revision rebuilds nothing.
execute_process(COMMAND git describe --always --dirty
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE FEMDEM_GIT OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT FEMDEM_GIT)
  set(FEMDEM_GIT "unknown")
endif()
configure_file(${IN} ${OUT}.new @ONLY)
file(COPY_FILE ${OUT}.new ${OUT} ONLY_IF_DIFFERENT)
file(REMOVE ${OUT}.new)
