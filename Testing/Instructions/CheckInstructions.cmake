cmake_minimum_required(VERSION 3.19)
# Counts the instructions of BrumeInstructionPhases' phases under callgrind
# and compares them with the figures stored in STORED. A phase more than
# TOLERANCE (default 10 %) above or below its stored figure fails: the
# commit that changes a count that much updates the figure (-DUPDATE=ON
# writes the counts measured into STORED: the build target
# brume-update-instruction-counts).
#
# The counts are repeatable for one build on one kind of processor: one
# thread (VTK_SMP_MAX_THREADS=1), llvmpipe rasterizing in the calling
# thread (LP_NUM_THREADS=0). Embree, glibc and llvmpipe choose their code by
# the instruction sets the processor reports, so the figures are stored per
# kind (the "isa" key below); on another kind the test is skipped and says
# how to record that kind's figures.
if (NOT TOLERANCE)
  set(TOLERANCE 10)
endif ()

# The kind of processor as valgrind presents it (it reports no AVX-512).
file(READ "/proc/cpuinfo" cpuinfo)
if (cpuinfo MATCHES "flags[^\n]* avx2")
  set(isa "x86_64-avx2")
elseif (cpuinfo MATCHES "flags[^\n]* avx")
  set(isa "x86_64-avx")
else ()
  set(isa "other")
endif ()

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
execute_process(
  COMMAND "${CMAKE_COMMAND}" -E env --unset=DISPLAY VTK_SMP_MAX_THREADS=1 LP_NUM_THREADS=0
    MESA_SHADER_CACHE_DISABLE=true
    "${VALGRIND}" --tool=callgrind "--callgrind-out-file=${WORK}/callgrind.out" "${PROGRAM}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "${PROGRAM} under callgrind: exit code ${rc}\n${out}\n${err}")
endif ()

# Each dump: "desc: Trigger: Client Request: PHASE" and "summary: COUNT".
set(phases "")
file(GLOB dumps "${WORK}/callgrind.out.*")
foreach (dump IN LISTS dumps)
  file(STRINGS "${dump}" lines REGEX "^(desc: Trigger: Client Request: |summary: )")
  set(phase "")
  set(count "")
  foreach (line IN LISTS lines)
    if (line MATCHES "^desc: Trigger: Client Request: (.+)$")
      set(phase "${CMAKE_MATCH_1}")
    elseif (line MATCHES "^summary: ([0-9]+)$")
      set(count "${CMAKE_MATCH_1}")
    endif ()
  endforeach ()
  if (phase AND count)
    list(APPEND phases "${phase}")
    set("measured_${phase}" "${count}")
  endif ()
endforeach ()
foreach (phase IN ITEMS tracing reconstruction view-update frame)
  if (NOT phase IN_LIST phases)
    message(FATAL_ERROR "no count for phase '${phase}' in ${WORK}\n${out}\n${err}")
  endif ()
endforeach ()

if (UPDATE)
  set(kept "")
  if (EXISTS "${STORED}")
    file(STRINGS "${STORED}" old)
    foreach (line IN LISTS old)
      if (NOT line MATCHES "^${isa} ")
        string(APPEND kept "${line}\n")
      endif ()
    endforeach ()
  endif ()
  foreach (phase IN ITEMS tracing reconstruction view-update frame)
    string(APPEND kept "${isa} ${phase} ${measured_${phase}}\n")
  endforeach ()
  file(WRITE "${STORED}" "${kept}")
  message(STATUS "instruction counts: ${isa} figures written to ${STORED}")
  return ()
endif ()

set(stored "")
if (EXISTS "${STORED}")
  file(STRINGS "${STORED}" stored REGEX "^${isa} ")
endif ()
if (NOT stored)
  message(STATUS "instruction counts: skipped, no figures stored for ${isa} in ${STORED} "
    "(record them: cmake --build build --target brume-update-instruction-counts)")
  return ()
endif ()
set(failures "")
foreach (line IN LISTS stored)
  if (NOT line MATCHES "^[^ ]+ ([^ ]+) ([0-9]+)$")
    message(FATAL_ERROR "${STORED}: malformed line '${line}'")
  endif ()
  set(phase "${CMAKE_MATCH_1}")
  set(figure "${CMAKE_MATCH_2}")
  set(count "${measured_${phase}}")
  # Per mille of the stored figure, in integers (counts fit 64 bits).
  math(EXPR permille "(${count} - ${figure}) * 1000 / ${figure}")
  set(magnitude "${permille}")
  set(sign "+")
  if (permille LESS 0)
    math(EXPR magnitude "-${permille}")
    set(sign "-")
  endif ()
  math(EXPR whole "${magnitude} / 10")
  math(EXPR tenth "${magnitude} % 10")
  set(change "${sign}${whole}.${tenth} %")
  message(STATUS "instruction counts: ${phase} ${count} (stored ${figure}, ${change})")
  math(EXPR limit "${TOLERANCE} * 10")
  if (permille GREATER limit OR permille LESS -${limit})
    list(APPEND failures "${phase} ${change}")
  endif ()
endforeach ()
if (failures)
  message(FATAL_ERROR "instruction counts beyond ${TOLERANCE} % of the stored figures: "
    "${failures}. A change this large updates ${STORED} in the same commit "
    "(Documentation/testing.md, \"Instruction counts\").")
endif ()
