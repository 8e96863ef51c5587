# Renders the default scene through EGL, OSMesa and, where there is an X
# display, X (BRUME_RENDER_WINDOW), and compares the float images: the same
# rasteriser must give the same radiance, bit for bit, whatever the window.
# Each render's wall time is printed.
#   -DBRUME=brume -DOUTPUT=dir
set(kinds egl osmesa)
if ("$ENV{DISPLAY}" STREQUAL "")
  message(STATUS "no X display: EGL and OSMesa only")
else ()
  list(APPEND kinds x)
endif ()
foreach (kind IN LISTS kinds)
  string(TIMESTAMP start "%s%f")
  execute_process(COMMAND "${CMAKE_COMMAND}" -E env BRUME_RENDER_WINDOW=${kind}
      "${BRUME}" render --size 64x64 --particles 50000 -o "${OUTPUT}/window-${kind}.vti"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(TIMESTAMP stop "%s%f")
  math(EXPR ms "(${stop} - ${start}) / 1000")
  if (NOT rc EQUAL 0)
    message(FATAL_ERROR "the ${kind} render failed (${rc}):\n${out}\n${err}")
  endif ()
  message(STATUS "${kind}: ${ms} ms")
endforeach ()
list(REMOVE_ITEM kinds egl)
foreach (kind IN LISTS kinds)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files
      "${OUTPUT}/window-egl.vti" "${OUTPUT}/window-${kind}.vti" RESULT_VARIABLE same)
  if (NOT same EQUAL 0)
    message(FATAL_ERROR "the images through EGL and ${kind} differ")
  endif ()
  message(STATUS "EGL and ${kind} give the same image")
endforeach ()
