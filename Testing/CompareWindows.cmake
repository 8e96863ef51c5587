# Renders the default scene through EGL and, where there is an X display,
# through X (BRUME_RENDER_WINDOW), and compares the float images: the same
# rasteriser must give the same radiance, bit for bit, whatever the window.
#   -DBRUME=brume -DOUTPUT=dir
set(kinds egl)
if ("$ENV{DISPLAY}" STREQUAL "")
  message(STATUS "skipped: no X display to compare the EGL image with")
else ()
  list(APPEND kinds x)
endif ()
foreach (kind IN LISTS kinds)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E env BRUME_RENDER_WINDOW=${kind}
      "${BRUME}" render --size 64x64 --particles 50000 -o "${OUTPUT}/window-${kind}.vti"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if (NOT rc EQUAL 0)
    message(FATAL_ERROR "the ${kind} render failed (${rc}):\n${out}\n${err}")
  endif ()
endforeach ()
list(LENGTH kinds count)
if (count EQUAL 1)
  return ()
endif ()
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files
    "${OUTPUT}/window-egl.vti" "${OUTPUT}/window-x.vti" RESULT_VARIABLE same)
if (NOT same EQUAL 0)
  message(FATAL_ERROR "the images through EGL and X differ")
endif ()
message(STATUS "EGL and X give the same image")
