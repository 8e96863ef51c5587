# brume_test_driver(NAME TESTS file.cxx... LIBRARIES target... [RENDERING])
#
# One test driver executable per test directory, as VTK builds its tests
# (create_test_sourcelist): `NAME TestX [args]` runs TestX(argc, argv) after
# BrumeTestSetup (the threaded SMP backend). RENDERING registers the OpenGL
# implementations (VTK's and the slice mapper's) with the object factories.
#
# BRUME_TEST_COMPILE_OPTIONS (a list) is added to every test executable's own
# sources, after the build's flags: scripts/sanitize.sh compiles them at -O0,
# half the time of -O1 under the sanitizers, the code they test being
# optimized.
set(BRUME_TEST_COMPILE_OPTIONS "" CACHE STRING
  "Compiler options added to the test executables' own sources (a list)")
mark_as_advanced(BRUME_TEST_COMPILE_OPTIONS)

# Tests whose windows go through an X server run alone
# (set_tests_properties(... PROPERTIES ${brume_windows_alone})): an X
# server resets when its last client disconnects and refuses connections
# while it does (Xvfb as `xvfb-run` starts it, without -noreset), so a
# window opened just as another closed was refused now and then, more often
# when several tests opened windows at once. In a build
# configured without a display (CI's first pass, a headless server) they
# draw through EGL or OSMesa, or are skipped where they need X: they then
# keep only from each other, beside the other tests.
if (DEFINED ENV{DISPLAY})
  set(brume_windows_alone RUN_SERIAL TRUE)
else ()
  set(brume_windows_alone RESOURCE_LOCK BrumeWindows)
endif ()
function (brume_test_driver name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "RENDERING" "" "TESTS;LIBRARIES")
  create_test_sourcelist(sources "${name}.cxx" ${arg_TESTS}
    EXTRA_INCLUDE BrumeTestSetup.h
    FUNCTION BrumeTestSetup)
  add_executable("${name}" ${sources})
  target_include_directories("${name}" PRIVATE
    "${CMAKE_CURRENT_SOURCE_DIR}" "${PROJECT_SOURCE_DIR}/Testing/Cxx")
  target_link_libraries("${name}" PRIVATE Brume::DataModel Brume::Conversion ${arg_LIBRARIES})
  brume_set_warnings("${name}")
  target_compile_options("${name}" PRIVATE ${BRUME_TEST_COMPILE_OPTIONS})
  if (arg_RENDERING)
    target_link_libraries("${name}" PRIVATE
      VTK::RenderingOpenGL2 VTK::RenderingVolumeOpenGL2 Brume::RenderingOpenGL2)
    target_compile_definitions("${name}" PRIVATE BRUME_TEST_RENDERING)
    vtk_module_autoinit(TARGETS "${name}"
      MODULES VTK::RenderingOpenGL2 VTK::RenderingVolumeOpenGL2 Brume::RenderingOpenGL2)
  endif ()
endfunction ()
