# Checks every public header for the rules of the style guide that a compiler will not catch:
#   - `#pragma once`;
#   - no `using namespace` (it leaks into every user's code);
#   - no <iostream> / <fstream> outside include/cellforge/io/ (the core does no I/O);
#   - no non-template `inline` function at namespace scope: it would be compiled in every file
#     that includes the header, used or not (docs/infra.md; make it a template);
#   - cellforge/cellforge.hpp includes every public header except io/, detail/ and the
#     generators and sample data its comment names (so it says what it includes).
# Prints every violation with file and line, then fails if there was any.
cmake_minimum_required(VERSION 3.21)
if(NOT INCLUDE_DIR)
  message(FATAL_ERROR "hygiene.cmake: INCLUDE_DIR is not set")
endif()
file(GLOB_RECURSE headers RELATIVE "${INCLUDE_DIR}" "${INCLUDE_DIR}/cellforge/*.hpp")
list(SORT headers)
set(problems 0)
foreach(header IN LISTS headers)
  # Split into lines by hand: list-special characters are masked so line numbers stay exact.
  file(READ "${INCLUDE_DIR}/${header}" content)
  string(REPLACE ";" "<semicolon>" content "${content}")
  string(REPLACE "[" "<lbracket>" content "${content}")
  string(REPLACE "]" "<rbracket>" content "${content}")
  string(REPLACE "\\" "<backslash>" content "${content}")
  string(REPLACE "\n" ";" lines "${content}")
  set(has_pragma FALSE)
  set(is_io FALSE)
  if(header MATCHES "^cellforge/io/")
    set(is_io TRUE)
  endif()
  set(n 0)
  foreach(line IN LISTS lines)
    math(EXPR n "${n} + 1")
    string(REGEX REPLACE "//.*$" "" code "${line}")  # comments may mention anything
    if(code MATCHES "^[ \t]*#[ \t]*pragma[ \t]+once")
      set(has_pragma TRUE)
    endif()
    if(code MATCHES "(^|[^A-Za-z0-9_])using[ \t]+namespace[ \t]")
      message("${header}:${n}: `using namespace` in a header leaks into users' code")
      math(EXPR problems "${problems} + 1")
    endif()
    if(NOT code MATCHES "^inline[ \t]+[^(]*[ \t]operator" AND
       code MATCHES "^inline[ \t]+([^=(]*[^A-Za-z0-9_=(])?([A-Za-z_][A-Za-z0-9_]*)[ \t]*\\(")
      message("${header}:${n}: non-template inline function ${CMAKE_MATCH_2}(): it compiles in every "
              "file that includes the header; make it a template (docs/infra.md)")
      math(EXPR problems "${problems} + 1")
    endif()
    if(NOT is_io AND code MATCHES "^[ \t]*#[ \t]*include[ \t]*<(iostream|fstream)>")
      message("${header}:${n}: <${CMAKE_MATCH_1}> outside cellforge/io/: the core does no I/O")
      math(EXPR problems "${problems} + 1")
    endif()
  endforeach()
  if(NOT has_pragma)
    message("${header}: missing `#pragma once`")
    math(EXPR problems "${problems} + 1")
  endif()
endforeach()
# The umbrella header's promise.
set(umbrella_exempt "^cellforge/(io/|.*/detail/|cellforge\\.hpp$|algorithms/shapes\\.hpp$|wireframe/sample_models\\.hpp$|tubes/sample_skeletons\\.hpp$|sketch/sample_drawings\\.hpp$|sketch/sample_round_drawings\\.hpp$|sketch/inflation\\.hpp$|sketch/drawing_to_cells\\.hpp$|sketch/tidy\\.hpp$|sketch/arc_detection\\.hpp$|thin/sample_solids\\.hpp$|smooth/sample_solids\\.hpp$)")
file(READ "${INCLUDE_DIR}/cellforge/cellforge.hpp" umbrella)
foreach(header IN LISTS headers)
  if(header MATCHES "${umbrella_exempt}")
    continue()
  endif()
  string(FIND "${umbrella}" "#include \"${header}\"" at)
  if(at EQUAL -1)
    message("cellforge/cellforge.hpp: does not include ${header}")
    math(EXPR problems "${problems} + 1")
  endif()
endforeach()

list(LENGTH headers count)
if(problems GREATER 0)
  message(FATAL_ERROR "header hygiene: ${problems} problem(s) in ${count} headers")
endif()
message(STATUS "header hygiene: ${count} headers ok")
