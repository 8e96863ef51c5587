# Plays a ParaView GUI test (recorded events: menus, buttons) and exits:
# paraview --test-script=EVENTS --exit, the plugin loaded at start-up
# through PV_PLUGIN_PATH. ParaView exits 1 when an event cannot be played
# (a menu entry missing or disabled). Needs an X display: without one the
# test says so and is reported as skipped; .ci/run runs it under Xvfb.
#   -DPARAVIEW=paraview -DEVENTS=file.xml -DPLUGIN_DIR=dir
# Optional:
#   -DSETUP=script.py    run first (--script): the user's own pipeline
#   -DTEST_DIRECTORY=dir emptied first; $PARAVIEW_TEST_ROOT in the events
#   -DCHECK=command;args run after the GUI exits, and must exit 0
#   -DFORBID=a;b         strings the GUI must not print (its errors and
#                        warnings, as the Output Messages window shows them)
if ("$ENV{DISPLAY}" STREQUAL "")
  message(STATUS "skipped: the ParaView GUI needs an X display")
  return ()
endif ()
set(ENV{PV_PLUGIN_PATH} "${PLUGIN_DIR}")
set(arguments --dr "--test-script=${EVENTS}" --exit)
if (SETUP)
  list(PREPEND arguments "--script=${SETUP}")
endif ()
if (TEST_DIRECTORY)
  file(REMOVE_RECURSE "${TEST_DIRECTORY}")
  file(MAKE_DIRECTORY "${TEST_DIRECTORY}")
  list(PREPEND arguments "--test-directory=${TEST_DIRECTORY}")
endif ()
execute_process(COMMAND "${PARAVIEW}" ${arguments}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "the GUI could not play ${EVENTS} (exit code ${rc})\nstdout: ${out}\nstderr: ${err}")
endif ()
foreach (forbidden IN LISTS FORBID)
  string(FIND "${out}${err}" "${forbidden}" found)
  if (NOT found EQUAL -1)
    message(FATAL_ERROR "the GUI printed '${forbidden}'\nstdout: ${out}\nstderr: ${err}")
  endif ()
endforeach ()
message(STATUS "the GUI played ${EVENTS}")
if (CHECK)
  execute_process(COMMAND ${CHECK} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
    TIMEOUT 120)
  if (NOT rc EQUAL 0)
    message(FATAL_ERROR "the check failed (exit code ${rc})\nstdout: ${out}\nstderr: ${err}")
  endif ()
  message(STATUS "${out}")
endif ()
