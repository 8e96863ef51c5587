// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: any bytes as a file a scene names. The first byte picks
// the format (a density .vti, or a surface .ply, .obj, .stl, .vtp or .vtu);
// the rest is the file, read through a fixed scene by vtkBrumeSceneReader, so
// that the size checks run before VTK's readers as they do for a user. The
// reader must fail cleanly or succeed; sanitizers report anything else.
#include "vtkBrumeSceneReader.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkObject.h"

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0)
  {
    return 0;
  }
  static const char* const formats[] = { "vti", "ply", "obj", "stl", "vtp", "vtu" };
  const std::string format = formats[data[0] % 6];
  const std::string stem = "fuzz-file-" + std::to_string(::getpid());
  const std::string file = stem + "." + format, scene = stem + ".json";
  {
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  const std::string surface = format == "vti"
    ? R"("quad": [[-1, -1, -1], [-1, -1, 1], [1, -1, 1], [1, -1, -1]])"
    : R"("file": ")" + file + "\"";
  const std::string density = format == "vti" ? R"(, "density": {"vti": ")" + file + "\"}" : "";
  std::ofstream(scene) << R"({"brume_scene": 1,
    "camera": {"position": [0, 0, 4], "focal_point": [0, 0, 0], "view_up": [0, 1, 0]},
    "surfaces": [{"name": "s", )"
                       << surface << R"(, "material": {"reflectance": [0.5, 0.5, 0.5]}}],
    "media": [{"name": "m", "box": [[-1, -1, -1], [1, 1, 1]], "sigma_a": [0.1, 0.1, 0.1],
               "sigma_s": [0.5, 0.5, 0.5], "g": 0.3)"
                       << density << R"(}],
    "lights": [{"type": "point", "position": [0, 0.9, 0], "intensity": [1, 1, 1]}]})";
  vtkObject::GlobalWarningDisplayOff();
  vtkNew<vtkBrumeSceneReader> reader;
  reader->SetFileName(scene.c_str());
  reader->GetExecutive()->Update();
  return 0;
}
