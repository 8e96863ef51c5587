# Runs COMMAND (a list) and passes its exit code and output through; when it
# fails only because the X server refused the connection ("bad X server
# connection": the display, not the code under test), it is run once more.
# pvbatch opens its window at start-up and met this now and then under Xvfb.
# pvbatch (ParaView's VTK, built for X) needs an X display: without one the
# test says so and is reported as skipped (SKIP_REGULAR_EXPRESSION).
if ("$ENV{DISPLAY}" STREQUAL "")
  message(STATUS "skipped: pvbatch needs an X display")
  return ()
endif ()
foreach (attempt RANGE 1 2)
  execute_process(COMMAND ${COMMAND} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(FIND "${out}${err}" "bad X server connection" display_failure)
  if (rc EQUAL 0 OR display_failure EQUAL -1 OR attempt EQUAL 2)
    break ()
  endif ()
  message(STATUS "attempt ${attempt}: the X server refused the connection; once more")
  execute_process(COMMAND "${CMAKE_COMMAND}" -E sleep 1)
endforeach ()
message(STATUS "${out}")
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "exit code ${rc}\nstdout: ${out}\nstderr: ${err}")
endif ()
