# Installs cellforge, or builds and runs the consumer project in tests/consumer as a user
# would, and fails loudly if any step fails. Run with `cmake -P` and:
#   MODE                install | package | subdirectory
#   CELLFORGE_SOURCE_DIR, CELLFORGE_BINARY_DIR   the cellforge tree under test
#   PREFIX              install prefix (install: wiped and filled; package: read)
#   WORK_DIR            scratch build directory (package, subdirectory; wiped first)
#   GENERATOR, MAKE_PROGRAM, CXX_COMPILER, COMPILER_NAME, CONFIG   how to build the consumer
# An empty or missing CXX_COMPILER fails under CI (environment variable CI set, not 0/false)
# and otherwise prints "consumer: SKIPPED" (the test's SKIP_REGULAR_EXPRESSION) and succeeds.
cmake_minimum_required(VERSION 3.21)

foreach(var IN ITEMS MODE CELLFORGE_SOURCE_DIR CELLFORGE_BINARY_DIR GENERATOR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "run-consumer.cmake: ${var} is not set")
  endif()
endforeach()
if(NOT CONFIG)
  set(CONFIG Release)
endif()
set(what "${MODE}")
if(NOT MODE STREQUAL "install")
  string(APPEND what ", ${COMPILER_NAME} ${CONFIG}")
endif()

# Runs a command; on failure prints what ran and its output, then stops the test. Prints the
# step's wall time in seconds.
function(step name)
  string(TIMESTAMP t0 "%s")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  string(TIMESTAMP t1 "%s")
  math(EXPR seconds "${t1} - ${t0}")
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "consumer (${what}): ${name} failed (${rc})\n  command: ${cmd}\n${out}")
  endif()
  message(STATUS "consumer (${what}): ${name}: ok (${seconds} s)")
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

if(MODE STREQUAL "install")
  if(NOT PREFIX)
    message(FATAL_ERROR "run-consumer.cmake: PREFIX is not set")
  endif()
  file(REMOVE_RECURSE "${PREFIX}")
  step("install into ${PREFIX}" "${CMAKE_COMMAND}" --install "${CELLFORGE_BINARY_DIR}" --prefix "${PREFIX}"
       --config "${CONFIG}")
  foreach(installed IN ITEMS include/cellforge/cellforge.hpp include/cellforge/core/point_traits.hpp
                             share/cmake/cellforge/cellforge-config.cmake
                             share/cmake/cellforge/cellforge-config-version.cmake
                             share/cmake/cellforge/cellforge-targets.cmake
                             share/cmake/cellforge/cellforge-sketch-targets.cmake)
    if(NOT EXISTS "${PREFIX}/${installed}")
      message(FATAL_ERROR "consumer (install): ${PREFIX}/${installed} was not installed")
    endif()
  endforeach()
  return()
endif()

if(NOT WORK_DIR)
  message(FATAL_ERROR "run-consumer.cmake: WORK_DIR is not set")
endif()
if(NOT CXX_COMPILER OR NOT EXISTS "${CXX_COMPILER}")
  set(ci "$ENV{CI}")
  string(TOLOWER "${ci}" ci)
  set(why "no ${COMPILER_NAME} C++ compiler found (set CELLFORGE_CONSUMER_GCC / CELLFORGE_CONSUMER_CLANG, or install it: bash scripts/install-deps.sh --fuzz)")
  if(NOT ci STREQUAL "" AND NOT ci STREQUAL "0" AND NOT ci STREQUAL "false")
    message(FATAL_ERROR "consumer (${what}): ${why}; under CI every consumer case must run")
  endif()
  message(STATUS "consumer: SKIPPED (${what}): ${why}")
  return()
endif()

file(REMOVE_RECURSE "${WORK_DIR}")
set(configure_args -S "${CMAKE_CURRENT_LIST_DIR}" -B "${WORK_DIR}" -G "${GENERATOR}"
    "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" "-DCMAKE_BUILD_TYPE=${CONFIG}" "-DCONSUMER_MODE=${MODE}"
    -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON -DCMAKE_FIND_PACKAGE_NO_SYSTEM_PACKAGE_REGISTRY=ON)
if(MAKE_PROGRAM)
  list(APPEND configure_args "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}")
endif()

if(MODE STREQUAL "package")
  if(NOT PREFIX OR NOT EXISTS "${PREFIX}/share/cmake/cellforge/cellforge-config.cmake")
    message(FATAL_ERROR "consumer (${what}): no cellforge installed in '${PREFIX}' (the consumer_install test sets it up)")
  endif()
  list(APPEND configure_args "-DCMAKE_PREFIX_PATH=${PREFIX}" "-DCONSUMER_EXPECTED_PREFIX=${PREFIX}")
elseif(MODE STREQUAL "subdirectory")
  list(APPEND configure_args "-DCELLFORGE_SOURCE_DIR=${CELLFORGE_SOURCE_DIR}")
else()
  message(FATAL_ERROR "run-consumer.cmake: MODE must be install, package or subdirectory, got '${MODE}'")
endif()

step("configure" "${CMAKE_COMMAND}" ${configure_args})
step("build" "${CMAKE_COMMAND}" --build "${WORK_DIR}" --config "${CONFIG}")
set(exe "${WORK_DIR}/consumer")
if(EXISTS "${WORK_DIR}/${CONFIG}/consumer")  # multi-config generators
  set(exe "${WORK_DIR}/${CONFIG}/consumer")
endif()
step("run" "${exe}" "${WORK_DIR}/scratch")
if(NOT step_output MATCHES "consumer ok")
  message(FATAL_ERROR "consumer (${what}): the program did not report success:\n${step_output}")
endif()
message(STATUS "${step_output}")
