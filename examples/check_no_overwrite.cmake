# No example writes over its input: copies INPUT into an empty WORK_DIR under the name NAME
# (one of the example's output names), runs EXE on it there, and expects a non-zero exit, a
# "refusing to write" message and the file unchanged. Run as `cmake -DEXE=<exe>
# -DINPUT=<file> -DNAME=<name> -DWORK_DIR=<scratch> -P check_no_overwrite.cmake`.
foreach(var EXE INPUT NAME WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_no_overwrite: -D${var}=... is required")
  endif()
endforeach()

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
file(COPY_FILE "${INPUT}" "${WORK_DIR}/${NAME}")
file(SHA256 "${INPUT}" before)
execute_process(COMMAND "${EXE}" "${NAME}" WORKING_DIRECTORY "${WORK_DIR}" RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(SHA256 "${WORK_DIR}/${NAME}" after)
if(NOT after STREQUAL before)
  message(FATAL_ERROR "${EXE} ${NAME}: the input file was written over\nstdout:\n${out}\nstderr:\n${err}")
endif()
if(rc EQUAL 0)
  message(FATAL_ERROR "${EXE} ${NAME}: exit status 0, expected a refusal\nstdout:\n${out}")
endif()
string(FIND "${err}" "refusing to write '${NAME}'" at)
if(at EQUAL -1)
  message(FATAL_ERROR "${EXE} ${NAME}: no 'refusing to write' message naming the file\nstderr:\n${err}")
endif()
