option(BRUME_WARNINGS_AS_ERRORS "Treat compiler warnings as errors (CI turns this on)." OFF)

# Warnings for Brume's own targets (VTK, Embree and OpenVDB headers are
# system includes through their imported targets).
function (brume_set_warnings target)
  if (CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options("${target}" PRIVATE -Wall -Wextra -Wshadow -Wnon-virtual-dtor)
    if (BRUME_WARNINGS_AS_ERRORS)
      target_compile_options("${target}" PRIVATE -Werror)
    endif ()
  endif ()
endfunction ()

# The same warnings on a VTK module target.
function (brume_module_warnings module)
  if (CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    vtk_module_compile_options("${module}" PRIVATE -Wall -Wextra -Wshadow -Wnon-virtual-dtor)
    if (BRUME_WARNINGS_AS_ERRORS)
      vtk_module_compile_options("${module}" PRIVATE -Werror)
    endif ()
  endif ()
endfunction ()
