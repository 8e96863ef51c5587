# Runs the ParaView GUI with a Python script and exits (paraview --script
# --exit), then reads the script's verdict from RESULT: "ok" or why not.
# The GUI needs an X display: without one the test says so and is reported
# as skipped (SKIP_REGULAR_EXPRESSION); .ci/run runs it under Xvfb.
#   -DPARAVIEW=paraview -DSCRIPT=file.py -DRESULT=file
if ("$ENV{DISPLAY}" STREQUAL "")
  message(STATUS "skipped: the ParaView GUI needs an X display")
  return ()
endif ()
file(REMOVE "${RESULT}")
execute_process(COMMAND "${PARAVIEW}" --dr "--script=${SCRIPT}" --exit
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 150)
if (NOT EXISTS "${RESULT}")
  message(FATAL_ERROR "the GUI wrote no verdict (exit code ${rc})\nstdout: ${out}\nstderr: ${err}")
endif ()
file(READ "${RESULT}" verdict)
string(STRIP "${verdict}" verdict)
if (NOT verdict STREQUAL "ok")
  message(FATAL_ERROR "${verdict}\nstdout: ${out}\nstderr: ${err}")
endif ()
message(STATUS "the GUI shows the baseline")
