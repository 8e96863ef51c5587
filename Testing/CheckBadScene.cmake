# Runs `brume render SCENE -o OUTPUT` on a malformed scene and fails unless it
# exits with 1, says on stderr which file and which field is wrong (MATCH, a
# regular expression after "<scene file>: "), and leaves no output behind.
file(REMOVE "${OUTPUT}" "${OUTPUT}.partial")
execute_process(COMMAND "${BRUME}" render "${SCENE}" -o "${OUTPUT}" --particles 2000
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if (NOT "${rc}" STREQUAL "1")
  message(FATAL_ERROR "expected exit code 1, got '${rc}'\nstdout: ${out}\nstderr: ${err}")
endif ()
get_filename_component(name "${SCENE}" NAME)
string(REGEX REPLACE "([][+.*()^$?|\\\\])" "\\\\\\1" quoted "${name}")
if (NOT err MATCHES "${quoted}: ${MATCH}")
  message(FATAL_ERROR "stderr does not name the file and field ('${name}: ${MATCH}'):\n${err}")
endif ()
if (EXISTS "${OUTPUT}" OR EXISTS "${OUTPUT}.partial")
  message(FATAL_ERROR "a failed render left '${OUTPUT}' behind")
endif ()
