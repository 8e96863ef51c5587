# Renders the default scene through EGL and, where there is an X display,
# through X (BRUME_RENDER_WINDOW), and compares the float images: the same
# rasteriser must give the same radiance, bit for bit, whatever the window.
#   -DBRUME=brume -DOUTPUT=dir
set(args render --size 64x64 --particles 50000)
execute_process(COMMAND "${CMAKE_COMMAND}" -E env BRUME_RENDER_WINDOW=egl
    "${BRUME}" ${args} -o "${OUTPUT}/window-egl.vti"
  RESULT_VARIABLE egl OUTPUT_VARIABLE out ERROR_VARIABLE err)
if (NOT egl EQUAL 0)
  message(FATAL_ERROR "the EGL render failed (${egl}):\n${out}\n${err}")
endif ()
if ("$ENV{DISPLAY}" STREQUAL "")
  message(STATUS "skipped: no X display to compare the EGL image with")
  return ()
endif ()
execute_process(COMMAND "${CMAKE_COMMAND}" -E env BRUME_RENDER_WINDOW=x
    "${BRUME}" ${args} -o "${OUTPUT}/window-x.vti"
  RESULT_VARIABLE x OUTPUT_VARIABLE out ERROR_VARIABLE err)
if (NOT x EQUAL 0)
  message(FATAL_ERROR "the X render failed (${x}):\n${out}\n${err}")
endif ()
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files
    "${OUTPUT}/window-egl.vti" "${OUTPUT}/window-x.vti" RESULT_VARIABLE same)
if (NOT same EQUAL 0)
  message(FATAL_ERROR "the images through EGL and X differ")
endif ()
message(STATUS "EGL and X give the same image")
