# Runs COMMAND (a list) and fails unless it exits with EXPECTED.
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if (NOT "${rc}" STREQUAL "${EXPECTED}")
  message(FATAL_ERROR "expected exit code ${EXPECTED}, got '${rc}'\nstdout: ${out}\nstderr: ${err}")
endif ()
if (NOT "${EXPECTED}" STREQUAL "0" AND "${err}" STREQUAL "")
  message(FATAL_ERROR "a failing command must say why on stderr")
endif ()
