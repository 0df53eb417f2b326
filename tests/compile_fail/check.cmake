# Runs one compile-fail test (see CMakeLists.txt next to this file):
# the control target must build, the test target must not, and its diagnostic must match
# every `// expect: <regex>` line of SOURCE.
cmake_minimum_required(VERSION 3.21)
foreach(var IN ITEMS BUILD_DIR SOURCE TARGET CONTROL_TARGET)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "check.cmake: ${var} is not set")
  endif()
endforeach()
set(config_args)
if(CONFIG)
  set(config_args --config "${CONFIG}")
endif()
get_filename_component(name "${SOURCE}" NAME)

execute_process(COMMAND "${CMAKE_COMMAND}" --build "${BUILD_DIR}" --target "${CONTROL_TARGET}" ${config_args}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${name}: the control build (CELLFORGE_COMPILE_FAIL_CONTROL defined) failed, so the test "
                      "source itself is broken:\n${out}")
endif()

execute_process(COMMAND "${CMAKE_COMMAND}" --build "${BUILD_DIR}" --target "${TARGET}" ${config_args}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(rc EQUAL 0)
  message(FATAL_ERROR "${name}: compiled, but it must be rejected")
endif()
file(STRINGS "${SOURCE}" expect_lines REGEX "^// expect: ")
foreach(line IN LISTS expect_lines)
  string(REGEX REPLACE "^// expect: *" "" regex "${line}")
  if(NOT out MATCHES "${regex}")
    message(FATAL_ERROR "${name}: failed to compile, but the diagnostic does not match '${regex}':\n${out}")
  endif()
  message(STATUS "${name}: rejected as expected (matched '${regex}')")
endforeach()
