# Installs Brume into a fresh prefix, then configures, builds and runs the
# downstream example against that install tree.
file(REMOVE_RECURSE "${WORK}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD}" --prefix "${WORK}/install"
  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "install failed: ${err}")
endif ()
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SOURCE}" -B "${WORK}/build" -G Ninja
  -DCMAKE_BUILD_TYPE=Release "-DBrume_DIR=${WORK}/install/lib/cmake/brume"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "configure failed:\n${out}\n${err}")
endif ()
execute_process(COMMAND "${CMAKE_COMMAND}" --build "${WORK}/build"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "build failed:\n${out}\n${err}")
endif ()
execute_process(COMMAND "${WORK}/build/downstream"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${out}")
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "the downstream program failed (${rc}):\n${out}\n${err}")
endif ()
