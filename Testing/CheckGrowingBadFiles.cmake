# Files whose size alone used to cost time and memory before their error:
# 2 GiB with no line break named .obj and .ply, 2 GiB of zeros named .stl
# (VTK's reader reads binary triangles to the end of the file), and a PLY
# announcing 2^31 faces over 2 GiB of zeros. Each is made sparse here
# (truncate: no disk written), given to `brume render` as a surface, and
# must end in exit 1 with its message, no output, reading a bounded prefix.
#   -DBRUME=brume -DWORKDIR=dir
file(REMOVE_RECURSE "${WORKDIR}")
file(MAKE_DIRECTORY "${WORKDIR}")
set(size 2147483648)
foreach (name IN ITEMS zeros.obj zeros.ply zeros.stl)
  execute_process(COMMAND truncate -s ${size} "${WORKDIR}/${name}" RESULT_VARIABLE rc)
  if (NOT rc EQUAL 0)
    message(FATAL_ERROR "cannot make the sparse file ${name}")
  endif ()
endforeach ()
file(WRITE "${WORKDIR}/faces.ply" "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
  "property float x\nproperty float y\nproperty float z\nelement face 2147483648\n"
  "property list uchar int vertex_indices\nend_header\n")
# One byte per face (each list count 0) fits: the size checks pass.
execute_process(COMMAND truncate -s 2147487744 "${WORKDIR}/faces.ply")
set(cases
  "zeros.obj|line 1: longer than 1 MiB: not an OBJ file"
  "zeros.ply|is not a PLY file \\(no 'ply' magic\\)"
  "zeros.stl|holds 2147483648 bytes, but its header announces 0 triangles"
  "faces.ply|a face has 0 vertices, not at least 3 \\(element 'face', row 0")
foreach (case IN LISTS cases)
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 mesh)
  list(GET parts 1 expected)
  set(scene "${WORKDIR}/${mesh}.json")
  file(WRITE "${scene}" "{\"brume_scene\": 1, \"surfaces\": [{\"name\": \"s\", \"file\": \"${mesh}\", "
    "\"material\": {\"reflectance\": [0.5, 0.5, 0.5]}}], \"lights\": [{\"type\": \"point\", "
    "\"position\": [0, 2, 0], \"intensity\": [1, 1, 1]}]}\n")
  set(output "${WORKDIR}/${mesh}.png")
  execute_process(COMMAND "${BRUME}" render "${scene}" -o "${output}" --particles 1000 --size 16x16
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
  if (NOT "${rc}" STREQUAL "1")
    message(FATAL_ERROR "${mesh}: expected exit code 1, got '${rc}'\nstderr: ${err}")
  endif ()
  if (NOT err MATCHES "surfaces\\[0\\]\\.file: .*${expected}")
    message(FATAL_ERROR "${mesh}: stderr does not say '${expected}':\n${err}")
  endif ()
  if (EXISTS "${output}")
    message(FATAL_ERROR "${mesh}: a failed render left '${output}' behind")
  endif ()
  message(STATUS "${mesh}: ${err}")
endforeach ()
file(REMOVE_RECURSE "${WORKDIR}")
