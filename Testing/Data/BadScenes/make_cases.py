# Writes the malformed scene files of this directory: python3 make_cases.py .
# Each case breaks a valid base scene (good.json) in one place; cases.txt lists
# the message each must produce. The support files were made once: sphere.vdb
# (a unit fog sphere written with openvdb::io::File), truncated.vdb (its first
# three quarters), header-only.vdb (its first 600 bytes), corrupt.vdb (its magic
# followed by random bytes), huge-lengths.vdb (a fuzzer's find: lengths that
# made OpenVDB allocate 7 GB), version-zero.vdb (header-only.vdb with version
# 0), garbage.* (text that is no such file), truncated.stl (a binary STL
# announcing 1000 triangles, holding one), absurd-count.stl (announcing
# 4294967280), absurd-count.vt[pu] (4e12 points announced), short-points.vtp
# (4e8 points announced, three held), malformed-header.ply (a fuzzer's find:
# an unknown header keyword, then properties VTK's parser attached to no
# element), malformed-element.ply (another: an element line of four words),
# bad-index.ply (a third: a binary face list indexing past the vertices),
# no-indices.ply (a fourth: a face element without vertex_indices),
# bad-entry.obj (a fifth: a vertex that is no number, a face index 0),
# short-row.ply (a sixth: an ASCII row with fewer values than properties),
# control-char.ply (a seventh: end_header followed by a form feed and a NUL),
# twice.ply (an eighth: two vertex and two face elements),
# non-ascii.ply (a ninth: a byte 0xaf in an element's name, which left VTK an
# element without properties), no-property.ply (such an element, by hand),
# face-without-indices.ply (by hand: faces whose list is not vertex_indices),
# the two
# density volumes (a NaN and a negative voxel) and points.vtp (no cells).
# Four cases were added by hand: mesh-truncated-binary-ply, mesh-absurd-count-ply,
# density-vdb-huge-lengths and density-vdb-version-zero; and two more, with
# their .vti files: density-vti-nested-datasets (a fuzzer's find: the image
# VTK reads is the root's second child, behind a nested VTKFile, and its
# component count is "10485ii") and density-vti-whole-extent (a piece of 2 x 2
# points in a whole extent of 4096 x 4096 x 1024, which VTK allocates); and
# density-vti-short-data and -short-compressed (512^3 and 256^3 float values
# announced by files of a few hundred bytes, plain and zlib-compressed), and
# mesh-nul-in-row-ply with nul-in-row.ply (a fuzzer's find: NUL bytes inside
# an ASCII row, which VTK's parser reads as the row's end, then indexes
# words past it) and mesh-empty-header-line-ply with empty-header-line.ply
# (another: a header line of a tab alone, on which VTK's parser compares a
# word it never set; brume crashed); and density-vti-inverted-extent with
# inverted-extent.vti (a fuzzer's find: the image VTK reads has the whole
# extent "0 1023 0 1023 8 0", whose -7340032 points became a count of 2^64
# less that much); and mesh-blank-row-ply with blank-row.ply (another: a
# blank line among an ASCII body's rows, on which VTK's reader aborts); and
# density-vdb-old-version with old-version.vdb (a third: a version-211 grid,
# whose transform follows its topology, announcing a 3 GB transform name).
import json, copy, os, sys
out = sys.argv[1]
base = {
  "brume_scene": 1,
  "name": "a valid base that every case breaks in one place",
  "camera": {"position": [0, 0, 4], "focal_point": [0, 0, 0], "view_up": [0, 1, 0], "view_angle": 40},
  "render": {"particles": 2000, "size": [16, 16]},
  "surfaces": [{"name": "floor", "quad": [[-1, -1, -1], [-1, -1, 1], [1, -1, 1], [1, -1, -1]],
                "material": {"reflectance": [0.5, 0.5, 0.5]}}],
  "media": [{"name": "fog", "box": [[-1, -1, -1], [1, 1, 1]], "sigma_a": [0.1, 0.1, 0.1],
             "sigma_s": [0.5, 0.5, 0.5], "g": 0.3}],
  "lights": [{"type": "point", "position": [0, 0.9, 0], "intensity": [1, 1, 1]}],
}
cases = {}
def case(name, edit):
    s = copy.deepcopy(base); edit(s); cases[name] = s
def setp(path, value):
    def f(s):
        o = s
        for k in path[:-1]: o = o[k]
        o[path[-1]] = value
    return f
def delp(path):
    def f(s):
        o = s
        for k in path[:-1]: o = o[k]
        del o[path[-1]]
    return f
case("good", lambda s: None)
case("top-not-object", lambda s: s.clear())  # replaced below
case("missing-version", delp(["brume_scene"]))
case("version-2", setp(["brume_scene"], 2))
case("version-string", setp(["brume_scene"], "1"))
case("unknown-top-key", setp(["lihgts"], []))
case("surfaces-not-array", setp(["surfaces"], {"name": "floor"}))
case("surface-no-name", delp(["surfaces", 0, "name"]))
case("surface-file-and-quad", setp(["surfaces", 0, "file"], "room.obj"))
case("surface-no-geometry", delp(["surfaces", 0, "quad"]))
case("quad-three-corners", setp(["surfaces", 0, "quad"], [[0, 0, 0], [1, 0, 0], [1, 1, 0]]))
case("quad-infinite", setp(["surfaces", 0, "quad", 1, 0], "INF"))
case("quad-degenerate", setp(["surfaces", 0, "quad"], [[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]]))
case("quad-corner-string", setp(["surfaces", 0, "quad", 2], "corner"))
case("mesh-missing-file", lambda s: (delp(["surfaces", 0, "quad"])(s), setp(["surfaces", 0, "file"], "no-such-mesh.obj")(s)))
case("mesh-unknown-format", lambda s: (delp(["surfaces", 0, "quad"])(s), setp(["surfaces", 0, "file"], "mesh.xyz")(s)))
case("mesh-garbage-obj", lambda s: (delp(["surfaces", 0, "quad"])(s), setp(["surfaces", 0, "file"], "garbage.obj")(s)))
case("mesh-truncated-ply", lambda s: (delp(["surfaces", 0, "quad"])(s), setp(["surfaces", 0, "file"], "truncated.ply")(s)))
case("mesh-degenerate-obj", lambda s: (delp(["surfaces", 0, "quad"])(s), setp(["surfaces", 0, "file"], "degenerate.obj")(s)))
case("name-number", setp(["name"], 5))
for name, file in [("mesh-truncated-stl", "truncated.stl"), ("mesh-absurd-count-stl", "absurd-count.stl"),
                   ("mesh-absurd-count-vtp", "absurd-count.vtp"), ("mesh-absurd-count-vtu", "absurd-count.vtu"),
                   ("mesh-short-points-vtp", "short-points.vtp"),
                   ("mesh-malformed-ply", "malformed-header.ply"),
                   ("mesh-malformed-element-ply", "malformed-element.ply"),
                   ("mesh-bad-index-ply", "bad-index.ply"),
                   ("mesh-no-indices-ply", "no-indices.ply"),
                   ("mesh-bad-entry-obj", "bad-entry.obj"),
                   ("mesh-short-row-ply", "short-row.ply"),
                   ("mesh-control-char-ply", "control-char.ply"),
                   ("mesh-twice-ply", "twice.ply"),
                   ("mesh-non-ascii-ply", "non-ascii.ply"),
                   ("mesh-no-property-ply", "no-property.ply"),
                   ("mesh-face-without-indices-ply", "face-without-indices.ply")]:
    case(name, lambda s, file=file: (delp(["surfaces", 0, "quad"])(s), setp(["surfaces", 0, "file"], file)(s)))
case("mesh-points-only-vtp", lambda s: (delp(["surfaces", 0, "quad"])(s), setp(["surfaces", 0, "file"], "points.vtp")(s)))
case("material-unknown-type", setp(["surfaces", 0, "material", "type"], "velvet"))
case("material-unknown-key", setp(["surfaces", 0, "material", "roughness"], 0.2))
case("reflectance-negative", setp(["surfaces", 0, "material", "reflectance"], [0.5, -0.1, 0.5]))
case("reflectance-above-one", setp(["surfaces", 0, "material", "reflectance"], [1.5, 0.5, 0.5]))
case("reflectance-two-numbers", setp(["surfaces", 0, "material", "reflectance"], [0.5, 0.5]))
case("phong-exponent-negative", setp(["surfaces", 0, "material"], {"type": "phong", "reflectance": [0.3, 0.3, 0.3], "specular": [0.3, 0.3, 0.3], "exponent": -4}))
case("phong-energy-above-one", setp(["surfaces", 0, "material"], {"type": "phong", "reflectance": [0.7, 0.7, 0.7], "specular": [0.6, 0.6, 0.6], "exponent": 20}))
case("media-not-array", setp(["media"], 3))
case("sigma-a-negative", setp(["media", 0, "sigma_a"], [0.1, -0.1, 0.1]))
case("sigma-s-infinite", setp(["media", 0, "sigma_s", 0], "INF"))
case("sigma-s-missing", delp(["media", 0, "sigma_s"]))
case("g-one", setp(["media", 0, "g"], 1.0))
case("g-below-minus-one", setp(["media", 0, "g"], -1.5))
case("g-string", setp(["media", 0, "g"], "forward"))
case("density-scale-negative", setp(["media", 0, "density_scale"], -2))
case("box-empty", setp(["media", 0, "box"], [[0, 0, 0], [1, 0, 1]]))
case("box-missing", delp(["media", 0, "box"]))
case("density-vdb-and-vti", setp(["media", 0, "density"], {"vdb": "truncated.vdb", "vti": "nan-density.vti"}))
case("density-vti-missing", setp(["media", 0, "density"], {"vti": "no-such-volume.vti"}))
case("density-vti-nan", setp(["media", 0, "density"], {"vti": "nan-density.vti", "array": "density"}))
case("density-vti-negative", setp(["media", 0, "density"], {"vti": "negative-density.vti", "array": "density"}))
case("density-vti-wrong-array", setp(["media", 0, "density"], {"vti": "nan-density.vti", "array": "temperature"}))
case("density-vti-garbage", setp(["media", 0, "density"], {"vti": "garbage.vti"}))
case("density-vti-absurd-extent", setp(["media", 0, "density"], {"vti": "absurd-extent.vti"}))
case("density-vdb-missing", setp(["media", 0, "density"], {"vdb": "no-such-volume.vdb"}))
case("density-vdb-truncated", setp(["media", 0, "density"], {"vdb": "truncated.vdb"}))
case("density-vdb-header-only", setp(["media", 0, "density"], {"vdb": "header-only.vdb"}))
case("density-vdb-corrupt", setp(["media", 0, "density"], {"vdb": "corrupt.vdb"}))
case("density-vdb-not-vdb", setp(["media", 0, "density"], {"vdb": "garbage.vdb"}))
case("density-vdb-wrong-grid", setp(["media", 0, "density"], {"vdb": "sphere.vdb", "grid": "temperature"}))
case("lights-not-array", setp(["lights"], {"type": "point"}))
case("no-lights", setp(["lights"], []))
case("light-unknown-type", setp(["lights", 0, "type"], "area"))
case("light-zero-power", setp(["lights", 0, "intensity"], [0, 0, 0]))
case("light-negative-intensity", setp(["lights", 0, "intensity"], [1, -1, 1]))
case("light-unknown-key", setp(["lights", 0, "radius"], 0.1))
case("spot-zero-direction", setp(["lights", 0], {"type": "spot", "position": [0, 0.9, 0], "direction": [0, 0, 0], "intensity": [1, 1, 1], "cone_angle": 30}))
case("spot-zero-cone", setp(["lights", 0], {"type": "spot", "position": [0, 0.9, 0], "direction": [0, -1, 0], "intensity": [1, 1, 1], "cone_angle": 0}))
case("directional-no-irradiance", setp(["lights", 0], {"type": "directional", "direction": [0, -1, 0]}))
case("nothing-to-render", lambda s: (setp(["surfaces"], [])(s), setp(["media"], [])(s)))
case("camera-on-focal-point", setp(["camera", "position"], [0, 0, 0]))
case("camera-up-along-view", setp(["camera", "view_up"], [0, 0, 1]))
case("camera-view-angle-zero", setp(["camera", "view_angle"], 0))
case("render-size-zero", setp(["render", "size"], [0, 16]))
case("render-size-absurd", setp(["render", "size"], [1000000, 1000000]))
case("render-particles-zero", setp(["render", "particles"], 0))
case("render-particles-absurd", setp(["render", "particles"], 1e18))
case("render-unknown-key", setp(["render", "samples"], 16))
case("render-size-fraction", setp(["render", "size"], [512.5, 512]))
case("render-particles-fraction", setp(["render", "particles"], 1000.5))
case("render-seed-fraction", setp(["render", "seed"], 0.25))
os.makedirs(out, exist_ok=True)
for name, s in cases.items():
    text = json.dumps(s, indent=1)
    text = text.replace('"INF"', '1e999')
    if name == "top-not-object":
        text = "[1, 2, 3]\n"
    open(os.path.join(out, name + ".json"), "w").write(text + "\n")
full = json.dumps(base, indent=1)
open(os.path.join(out, "empty.json"), "w").write("")
open(os.path.join(out, "truncated.json"), "w").write(full[: len(full) // 2])
open(os.path.join(out, "trailing-comma.json"), "w").write(full.replace('"g": 0.3', '"g": 0.3,'))
open(os.path.join(out, "nan-literal.json"), "w").write(full.replace('"g": 0.3', '"g": NaN'))
open(os.path.join(out, "binary.json"), "wb").write(bytes(range(256)))
print(len(cases) + 5 - 1, "cases")
