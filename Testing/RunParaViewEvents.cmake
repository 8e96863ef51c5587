# Plays a ParaView GUI test (recorded events: menus, buttons) and exits:
# paraview --test-script=EVENTS --exit, the plugin loaded at start-up
# through PV_PLUGIN_PATH. ParaView exits 1 when an event cannot be played
# (a menu entry missing or disabled). Needs an X display: without one the
# test says so and is reported as skipped; .ci/run runs it under Xvfb.
#   -DPARAVIEW=paraview -DEVENTS=file.xml -DPLUGIN_DIR=dir
if ("$ENV{DISPLAY}" STREQUAL "")
  message(STATUS "skipped: the ParaView GUI needs an X display")
  return ()
endif ()
set(ENV{PV_PLUGIN_PATH} "${PLUGIN_DIR}")
execute_process(COMMAND "${PARAVIEW}" --dr "--test-script=${EVENTS}" --exit
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "the GUI could not play ${EVENTS} (exit code ${rc})\nstdout: ${out}\nstderr: ${err}")
endif ()
message(STATUS "the GUI played ${EVENTS}")
