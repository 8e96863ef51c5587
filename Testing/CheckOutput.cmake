# Runs COMMAND (a list): it must exit with 0 (no crash) and its output must
# contain every string of EXPECT (a list).
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "exit code ${rc}\nstdout: ${out}\nstderr: ${err}")
endif ()
foreach (expected IN LISTS EXPECT)
  string(FIND "${out}${err}" "${expected}" found)
  if (found EQUAL -1)
    message(FATAL_ERROR "missing message '${expected}'\nstdout: ${out}\nstderr: ${err}")
  endif ()
endforeach ()
