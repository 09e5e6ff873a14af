# SPDX-License-Identifier: GPL-3.0-or-later
# CTest's Install.PackageBuildsAnExternalProgram: installs the build tree BUILD into a fresh
# prefix under WORK, builds tests/install (SRC) against it with find_package(femdem), runs the
# program on SCENE and the installed femdem on --version. Fails on the first step that fails.
#   cmake -DBUILD=... -DSRC=... -DWORK=... -DSCENE=... -DEXPECT=... -P run_install_test.cmake
file(REMOVE_RECURSE ${WORK})
function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "failed (${code}): ${ARGN}\n${out}\n${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()
step(${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix)
foreach(f bin/femdem include/femdem/io/scene/scene_reader.hpp include/femdem/femdem_version.hpp
          lib/cmake/femdem/femdemConfig.cmake share/femdem/tools/plot_history.py
          share/femdem/tools/python/femdem/results.py)
  if(NOT EXISTS ${WORK}/prefix/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
set(generator)
find_program(NINJA ninja)
if(NINJA)
  set(generator -G Ninja)
endif()
step(${CMAKE_COMMAND} -S ${SRC} -B ${WORK}/build ${generator} -DCMAKE_BUILD_TYPE=Release
     -DCMAKE_PREFIX_PATH=${WORK}/prefix)
step(${CMAKE_COMMAND} --build ${WORK}/build)
step(${WORK}/build/load_scene ${SCENE})
message(STATUS "load_scene: ${step_output}")
if(NOT step_output MATCHES "${EXPECT}")
  message(FATAL_ERROR "load_scene printed '${step_output}', expected '${EXPECT}'")
endif()
step(${WORK}/prefix/bin/femdem --version)
message(STATUS "installed femdem --version: ${step_output}")
file(REMOVE_RECURSE ${WORK})
