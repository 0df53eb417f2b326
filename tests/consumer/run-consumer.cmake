# Builds and runs the consumer project in tests/consumer as a user would, and fails loudly
# if any step fails. Run with `cmake -P` and:
#   MODE                package | subdirectory
#   CELLFORGE_SOURCE_DIR, CELLFORGE_BINARY_DIR   the cellforge tree under test
#   WORK_DIR            scratch directory (wiped first)
#   PREFIX              install prefix (package mode; wiped first)
#   GENERATOR, MAKE_PROGRAM, CXX_COMPILER, CONFIG   how to build the consumer
cmake_minimum_required(VERSION 3.21)

foreach(var IN ITEMS MODE CELLFORGE_SOURCE_DIR CELLFORGE_BINARY_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "run-consumer.cmake: ${var} is not set")
  endif()
endforeach()
if(NOT CONFIG)
  set(CONFIG Release)
endif()

# Runs a command; on failure prints what ran and its output, then stops the test.
function(step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "consumer (${MODE}): ${what} failed (${rc})\n  command: ${cmd}\n${out}")
  endif()
  message(STATUS "consumer (${MODE}): ${what}: ok")
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")
set(configure_args -S "${CMAKE_CURRENT_LIST_DIR}" -B "${WORK_DIR}" -G "${GENERATOR}"
    "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" "-DCMAKE_BUILD_TYPE=${CONFIG}" "-DCONSUMER_MODE=${MODE}"
    -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON -DCMAKE_FIND_PACKAGE_NO_SYSTEM_PACKAGE_REGISTRY=ON)
if(MAKE_PROGRAM)
  list(APPEND configure_args "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}")
endif()

if(MODE STREQUAL "package")
  if(NOT PREFIX)
    message(FATAL_ERROR "run-consumer.cmake: PREFIX is not set")
  endif()
  file(REMOVE_RECURSE "${PREFIX}")
  step("install into ${PREFIX}" "${CMAKE_COMMAND}" --install "${CELLFORGE_BINARY_DIR}" --prefix "${PREFIX}"
       --config "${CONFIG}")
  foreach(installed IN ITEMS include/cellforge/core/point_traits.hpp share/cmake/cellforge/cellforge-config.cmake
                             share/cmake/cellforge/cellforge-config-version.cmake
                             share/cmake/cellforge/cellforge-targets.cmake)
    if(NOT EXISTS "${PREFIX}/${installed}")
      message(FATAL_ERROR "consumer (package): ${PREFIX}/${installed} was not installed")
    endif()
  endforeach()
  list(APPEND configure_args "-DCMAKE_PREFIX_PATH=${PREFIX}" "-DCONSUMER_EXPECTED_PREFIX=${PREFIX}")
elseif(MODE STREQUAL "subdirectory")
  list(APPEND configure_args "-DCELLFORGE_SOURCE_DIR=${CELLFORGE_SOURCE_DIR}")
else()
  message(FATAL_ERROR "run-consumer.cmake: MODE must be package or subdirectory, got '${MODE}'")
endif()

step("configure" "${CMAKE_COMMAND}" ${configure_args})
step("build" "${CMAKE_COMMAND}" --build "${WORK_DIR}" --config "${CONFIG}")
set(exe "${WORK_DIR}/consumer")
if(EXISTS "${WORK_DIR}/${CONFIG}/consumer")  # multi-config generators
  set(exe "${WORK_DIR}/${CONFIG}/consumer")
endif()
step("run" "${exe}")
if(NOT step_output MATCHES "consumer ok")
  message(FATAL_ERROR "consumer (${MODE}): the program did not report success:\n${step_output}")
endif()
message(STATUS "${step_output}")
