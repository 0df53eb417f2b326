# Registers the packaging tests (label `packaging`): the consumer project in this directory,
# a CAD application, built the way a user builds it, with -Wall -Wextra -Wpedantic -Werror and
# none of cellforge's developer or sanitizer flags:
#   consumer_install                 cmake --install of this build tree into one prefix (fixture)
#   consumer_package_<cc>_<config>   find_package against that prefix, with g++ and clang++,
#                                    Release (2 cases; they may run in parallel)
#   consumer_subdirectory            add_subdirectory(<source>), the parent's compiler and config
# A compiler that cannot be found fails its cases under CI (environment variable CI set and not
# 0/false) and skips them otherwise. Included from tests/CMakeLists.txt.
get_property(_cellforge_multi_config GLOBAL PROPERTY GENERATOR_IS_MULTI_CONFIG)
if(_cellforge_multi_config)
  set(_cellforge_consumer_config "$<CONFIG>")
elseif(CMAKE_BUILD_TYPE)
  set(_cellforge_consumer_config "${CMAKE_BUILD_TYPE}")
else()
  set(_cellforge_consumer_config Release)
endif()

# The two compilers of the package cases: the parent's compiler when it is of that family,
# otherwise g++ / clang++ from the PATH. Override with the cache variables.
foreach(_cc IN ITEMS gcc clang)
  if(_cc STREQUAL "gcc")
    set(_id GNU)
    set(_names g++)
  else()
    set(_id Clang)
    set(_names clang++)
  endif()
  string(TOUPPER "${_cc}" _CC)
  if(CMAKE_CXX_COMPILER_ID STREQUAL _id)
    set(CELLFORGE_CONSUMER_${_CC} "${CMAKE_CXX_COMPILER}" CACHE FILEPATH "C++ compiler of the ${_cc} consumer tests")
  else()
    find_program(CELLFORGE_CONSUMER_${_CC} NAMES ${_names} DOC "C++ compiler of the ${_cc} consumer tests")
  endif()
endforeach()

set(_cellforge_consumer_common
    "-DCELLFORGE_SOURCE_DIR=${PROJECT_SOURCE_DIR}" "-DCELLFORGE_BINARY_DIR=${PROJECT_BINARY_DIR}"
    "-DPREFIX=${CMAKE_BINARY_DIR}/consumer-prefix" "-DGENERATOR=${CMAKE_GENERATOR}"
    "-DMAKE_PROGRAM=${CMAKE_MAKE_PROGRAM}")
set(_cellforge_consumer_script "${CMAKE_CURRENT_LIST_DIR}/run-consumer.cmake")

if(CELLFORGE_INSTALL)
  add_test(NAME consumer_install
           COMMAND "${CMAKE_COMMAND}" -DMODE=install ${_cellforge_consumer_common}
                   "-DCONFIG=${_cellforge_consumer_config}" -P "${_cellforge_consumer_script}")
  # The dearest cases wait for it: it starts first (COST above theirs).
  set_tests_properties(consumer_install PROPERTIES LABELS "packaging" TIMEOUT 120 COST 1000
                                                   FIXTURES_SETUP cellforge_consumer_prefix)
  foreach(_cc IN ITEMS gcc clang)
    string(TOUPPER "${_cc}" _CC)
    set(_compiler "${CELLFORGE_CONSUMER_${_CC}}")
    if(NOT _compiler)  # NOTFOUND: run-consumer.cmake fails (CI) or skips with a message
      set(_compiler "")
    endif()
    # Release only: the package is one INTERFACE target, the same in every configuration, and
    # the Debug builds of the library's headers are the asan stage's (g++) and the clang stage's.
    set(_configs Release)
    foreach(_config IN LISTS _configs)
      string(TOLOWER "consumer_package_${_cc}_${_config}" _name)
      add_test(NAME ${_name}
               COMMAND "${CMAKE_COMMAND}" -DMODE=package ${_cellforge_consumer_common}
                       "-DWORK_DIR=${CMAKE_BINARY_DIR}/consumer/${_cc}-${_config}"
                       "-DCXX_COMPILER=${_compiler}" "-DCOMPILER_NAME=${_cc}" "-DCONFIG=${_config}"
                       -P "${_cellforge_consumer_script}")
      # COST: ctest -j2 starts the dearest cases first (the -O3 builds, then -O0), so that no
      # long build is left for the end with one core idle. Roughly their CPU seconds.
      if(_config STREQUAL "Release")
        set(_cost 70)
      else()
        set(_cost 25)
      endif()
      if(_cc STREQUAL "gcc")
        math(EXPR _cost "${_cost} + 30")
      endif()
      set_tests_properties(${_name} PROPERTIES LABELS "packaging" TIMEOUT 600 COST ${_cost}
                                               FIXTURES_REQUIRED cellforge_consumer_prefix
                                               SKIP_REGULAR_EXPRESSION "consumer: SKIPPED")
    endforeach()
  endforeach()
endif()

add_test(NAME consumer_subdirectory
         COMMAND "${CMAKE_COMMAND}" -DMODE=subdirectory ${_cellforge_consumer_common}
                 "-DWORK_DIR=${CMAKE_BINARY_DIR}/consumer/subdirectory" "-DCXX_COMPILER=${CMAKE_CXX_COMPILER}"
                 "-DCOMPILER_NAME=${CMAKE_CXX_COMPILER_ID}" "-DCONFIG=${_cellforge_consumer_config}"
                 -P "${_cellforge_consumer_script}")
set_tests_properties(consumer_subdirectory PROPERTIES LABELS "packaging" TIMEOUT 600)

unset(_cc)
unset(_CC)
unset(_id)
unset(_names)
unset(_compiler)
unset(_config)
unset(_configs)
unset(_cost)
unset(_name)
unset(_cellforge_consumer_common)
unset(_cellforge_consumer_script)
unset(_cellforge_consumer_config)
unset(_cellforge_multi_config)
