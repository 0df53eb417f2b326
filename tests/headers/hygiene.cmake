# Checks every public header for the rules of the style guide that a compiler will not catch:
#   - `#pragma once`;
#   - no `using namespace` (it leaks into every user's code);
#   - no <iostream> / <fstream> outside include/cellforge/io/ (the core does no I/O);
#   - <filesystem> only in io/file_path.hpp and <chrono> only in core/detail/stopwatch.hpp, each
#     behind its platform switch (on POSIX neither is parsed: together about 0.7x of the
#     standard-headers baseline's compile time, docs/benchmarks.md "Compile time");
#   - no non-template `inline` function at namespace scope: it would be compiled in every file
#     that includes the header, used or not (docs/infra.md; make it a template);
#   - no header outside samples/ includes one in it (but a deprecated forwarder);
#   - no public header outside detail/ over 700 lines;
#   - cellforge/cellforge.hpp includes every public header except io/, samples/, detail/ and
#     sketch/ (its comment says so), and none that
#     needs Eigen, directly or through another header (so a user without Eigen can include it);
#     cellforge/sketch.hpp includes every sketch/ header but instantiate.hpp; deprecated headers
#     (those that emit a `#pragma message` and forward to their new path) are in no umbrella.
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
    if(code MATCHES "^#pragma message")  # a deprecated header that forwards: in no umbrella
      list(APPEND deprecated_headers "${header}")
    endif()
    if(code MATCHES "^[ \t]*#[ \t]*include[ \t]*\"cellforge/samples/" AND NOT header MATCHES "^cellforge/samples/")
      list(APPEND sample_includers "${header}:${n}")
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
    if(code MATCHES "^[ \t]*#[ \t]*include[ \t]*<(filesystem|chrono)>")
      set(slow_header "${CMAKE_MATCH_1}")
      if(NOT "${slow_header}:${header}" MATCHES
         "^(filesystem:cellforge/io/file_path\\.hpp|chrono:cellforge/core/detail/stopwatch\\.hpp)$")
        message("${header}:${n}: <${slow_header}> is slow to compile; use io::file_path / detail::stopwatch")
        math(EXPR problems "${problems} + 1")
      endif()
    endif()
  endforeach()
  if(NOT has_pragma)
    message("${header}: missing `#pragma once`")
    math(EXPR problems "${problems} + 1")
  endif()
  # A page a reader can take in: the engine of a longer header goes to detail/ (docs/infra.md).
  if(n GREATER 701 AND NOT header MATCHES "/detail/")  # n counts the piece after the last newline
    message("${header}: over 700 lines; a public header keeps its page under 700 lines, its engine in detail/")
    math(EXPR problems "${problems} + 1")
  endif()
endforeach()
# Test data stays out of the library: no header outside samples/ includes one in it, but the
# deprecated forwarders left at the samples' old paths.
foreach(at IN LISTS sample_includers)
  string(REGEX REPLACE ":[0-9]+$" "" header "${at}")
  if(NOT header IN_LIST deprecated_headers)
    message("${at}: includes a samples/ header; the library must not depend on its test data")
    math(EXPR problems "${problems} + 1")
  endif()
endforeach()
# The umbrellas' promises: each includes every header of its scope but the exempt ones.
function(check_umbrella umbrella scope exempt)
  file(READ "${INCLUDE_DIR}/${umbrella}" text)
  foreach(header IN LISTS headers)
    if(NOT header MATCHES "${scope}" OR header MATCHES "${exempt}" OR header IN_LIST deprecated_headers)
      continue()
    endif()
    string(FIND "${text}" "#include \"${header}\"" at)
    if(at EQUAL -1)
      message("${umbrella}: does not include ${header}")
      math(EXPR problems "${problems} + 1")
    endif()
  endforeach()
  set(problems ${problems} PARENT_SCOPE)
endfunction()
# The 3D library: everything but io/, samples/, detail/ and the line drawings.
check_umbrella(cellforge/cellforge.hpp "^cellforge/"
               "^cellforge/(io/|samples/|.*/detail/|cellforge\\.hpp$|sketch\\.hpp$|sketch/)")
# The line drawings: every sketch/ header but instantiate.hpp (explicit instantiations, for one
# file of a program: docs/sketch.md).
check_umbrella(cellforge/sketch.hpp "^cellforge/sketch/" "/detail/|/instantiate\\.hpp$")
# Headers that need Eigen: those that include it, then those that include one of them, until
# no more are found.
set(needs_eigen "")
foreach(header IN LISTS headers)
  file(STRINGS "${INCLUDE_DIR}/${header}" includes REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]")
  set(direct_${header} "")
  foreach(line IN LISTS includes)
    if(line MATCHES "<(unsupported/)?Eigen/")
      list(APPEND needs_eigen "${header}")
    elseif(line MATCHES "\"(cellforge/[^\"]+)\"")
      list(APPEND direct_${header} "${CMAKE_MATCH_1}")
    endif()
  endforeach()
endforeach()
list(REMOVE_DUPLICATES needs_eigen)
set(grew TRUE)
while(grew)
  set(grew FALSE)
  foreach(header IN LISTS headers)
    if(header IN_LIST needs_eigen)
      continue()
    endif()
    foreach(inc IN LISTS direct_${header})
      if(inc IN_LIST needs_eigen)
        list(APPEND needs_eigen "${header}")
        set(grew TRUE)
        break()
      endif()
    endforeach()
  endforeach()
endwhile()
foreach(inc IN LISTS direct_cellforge/cellforge.hpp)
  if(inc IN_LIST needs_eigen)
    message("cellforge/cellforge.hpp: includes ${inc}, which needs Eigen; the umbrella promises it does not "
            "(list it in its comment and in umbrella_exempt instead)")
    math(EXPR problems "${problems} + 1")
  endif()
endforeach()

list(LENGTH headers count)
if(problems GREATER 0)
  message(FATAL_ERROR "header hygiene: ${problems} problem(s) in ${count} headers")
endif()
message(STATUS "header hygiene: ${count} headers ok")
