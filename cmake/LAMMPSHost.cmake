# Check the host LAMMPS before anything long happens, and define two interface targets:
#   lammps_headers  include paths and MPI, for the plugin (symbols resolve from the host at load)
#   lammps_library  the same plus liblammps, for tests that run LAMMPS in-process
if(NOT LAMMPS_SOURCE_DIR OR NOT EXISTS "${LAMMPS_SOURCE_DIR}/src/version.h")
  message(FATAL_ERROR "ActiveGrain: set -DLAMMPS_SOURCE_DIR to a LAMMPS source tree (the folder with src/version.h), "
    "or let tools/run-tests fetch and build LAMMPS for you.")
endif()

# Version guard: 2Aug2023 is the oldest LAMMPS whose API we use.
file(STRINGS "${LAMMPS_SOURCE_DIR}/src/version.h" _lmp_version_line REGEX "define LAMMPS_VERSION ")
string(REGEX REPLACE ".*\"([0-9]+) ([A-Za-z]+) ([0-9]+)\".*" "\\1;\\2;\\3" _lmp_date "${_lmp_version_line}")
list(GET _lmp_date 0 _day)
list(GET _lmp_date 1 _mon)
list(GET _lmp_date 2 _year)
set(_months Jan Feb Mar Apr May Jun Jul Aug Sep Oct Nov Dec)
list(FIND _months ${_mon} _m)
math(EXPR LAMMPS_VERSION_NUMBER "${_year} * 10000 + (${_m} + 1) * 100 + ${_day}")
if(_m LESS 0 OR LAMMPS_VERSION_NUMBER LESS 20230802)
  message(FATAL_ERROR "ActiveGrain: LAMMPS '${_day} ${_mon} ${_year}' in ${LAMMPS_SOURCE_DIR} is too old or unreadable; "
    "ActiveGrain needs LAMMPS 2Aug2023 or newer.")
endif()
message(STATUS "ActiveGrain: LAMMPS ${_day} ${_mon} ${_year} (${LAMMPS_VERSION_NUMBER}) from ${LAMMPS_SOURCE_DIR}")

find_program(LAMMPS_EXECUTABLE NAMES lmp lmp_mpi HINTS ${LAMMPS_INSTALL_DIR} PATH_SUFFIXES bin NO_DEFAULT_PATH)
find_library(LAMMPS_LIBRARY NAMES lammps lammps_mpi HINTS ${LAMMPS_INSTALL_DIR} PATH_SUFFIXES lib lib64 NO_DEFAULT_PATH)
if(NOT LAMMPS_EXECUTABLE OR NOT LAMMPS_LIBRARY)
  message(FATAL_ERROR "ActiveGrain: no lmp and liblammps.so under LAMMPS_INSTALL_DIR='${LAMMPS_INSTALL_DIR}'. "
    "Build LAMMPS from ${LAMMPS_SOURCE_DIR} with -DBUILD_SHARED_LIBS=yes -DPKG_PLUGIN=yes -DPKG_RIGID=yes and install it there.")
endif()

# The host must be the same version, built with PLUGIN (to load us) and RIGID (the rods).
get_filename_component(_lmp_libdir ${LAMMPS_LIBRARY} DIRECTORY)
execute_process(COMMAND ${CMAKE_COMMAND} -E env LAMMPS_PLUGIN_PATH= "LD_LIBRARY_PATH=${_lmp_libdir}:$ENV{LD_LIBRARY_PATH}"
  ${LAMMPS_EXECUTABLE} -h
  OUTPUT_VARIABLE _lmp_help RESULT_VARIABLE _lmp_rc ERROR_QUIET)
if(NOT _lmp_rc EQUAL 0)
  message(FATAL_ERROR "ActiveGrain: '${LAMMPS_EXECUTABLE} -h' failed; is that LAMMPS built and its libraries found?")
endif()
string(REGEX MATCH "Installed packages:[^\n]*\n\n?([A-Z0-9 -]|\n)*" _lmp_pkgs "${_lmp_help}")
foreach(_pkg PLUGIN RIGID GRANULAR MOLECULE)
  if(NOT _lmp_pkgs MATCHES "(^|[ \n])${_pkg}([ \n]|$)")
    message(FATAL_ERROR "ActiveGrain: ${LAMMPS_EXECUTABLE} was built without the ${_pkg} package; "
      "rebuild LAMMPS with -DPKG_${_pkg}=yes (tools/run-tests does this for you).")
  endif()
endforeach()
if(NOT _lmp_help MATCHES "${_day} ${_mon} ${_year}")
  message(FATAL_ERROR "ActiveGrain: ${LAMMPS_EXECUTABLE} is not LAMMPS ${_day} ${_mon} ${_year}, "
    "the version of LAMMPS_SOURCE_DIR; a plugin must be built against the sources of its host.")
endif()

set(MPI_CXX_SKIP_MPICXX TRUE)
find_package(MPI REQUIRED COMPONENTS CXX)
add_library(lammps_headers INTERFACE)
target_include_directories(lammps_headers INTERFACE ${LAMMPS_SOURCE_DIR}/src
  ${LAMMPS_SOURCE_DIR}/src/RIGID ${LAMMPS_SOURCE_DIR}/src/GRANULAR ${LAMMPS_SOURCE_DIR}/src/PLUGIN)
target_compile_definitions(lammps_headers INTERFACE LAMMPS_SMALLBIG
  ACTIVEGRAIN_LAMMPS_VERSION=${LAMMPS_VERSION_NUMBER})
target_link_libraries(lammps_headers INTERFACE MPI::MPI_CXX)
add_library(lammps_library INTERFACE)
target_link_libraries(lammps_library INTERFACE lammps_headers ${LAMMPS_LIBRARY})
