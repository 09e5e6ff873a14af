# SPDX-License-Identifier: GPL-3.0-or-later
# METIS::METIS, the graph partitioner of distributed runs (engine/distributed/partition.cpp).
# Debian's libmetis-dev ships neither a CMake package nor a pkg-config file. Included by the
# build and by the installed femdemConfig.cmake (static libraries carry their dependencies).
if(NOT TARGET METIS::METIS)
  find_path(METIS_INCLUDE_DIR metis.h REQUIRED)
  find_library(METIS_LIBRARY metis REQUIRED)
  add_library(METIS::METIS UNKNOWN IMPORTED)
  set_target_properties(METIS::METIS PROPERTIES IMPORTED_LOCATION "${METIS_LIBRARY}"
                                                INTERFACE_INCLUDE_DIRECTORIES "${METIS_INCLUDE_DIR}")
endif()
