// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSliceVolumeShader.h"

#include "vtkBrumeSliceVolumeDirectionalFS.h"
#include "vtkBrumeSliceVolumeFS.h"

#include "brume/SphericalHarmonics.h"

#include <iomanip>
#include <sstream>

namespace
{
// Replaces the tag `tag` of a shader by `text`.
void Replace(std::string& shader, const std::string& tag, const std::string& text)
{
  const std::size_t at = shader.find(tag);
  if (at != std::string::npos)
  {
    shader.replace(at, tag.size(), text);
  }
}
}

// The fragment shader of a kind of volume: the slab shader with its
// extinction read as the kind says, plus for directional radiance of an
// order > 0 the evaluation of its spherical-harmonics coefficients toward
// the eye (brume/SphericalHarmonics.h, in GLSL).
std::string vtkBrumeSliceVolumeShader::Fragment(const Kind& kind)
{
  std::string fs = vtkBrumeSliceVolumeFS;
  Replace(fs, "//BRUME::Slice::Defines",
    "#define BRUME_EXTINCTION " + std::to_string(static_cast<int>(kind.Extinction)) +
      "\n#define BRUME_SOURCE_IS_RADIANCE " + (kind.SourceIsRadiance ? "1" : "0") +
      "\n#define BRUME_CLASSIFIED " + (kind.Classified ? "1" : "0") + "\n#define BRUME_ALBEDO " +
      (kind.Albedo ? "1" : "0") + "\n#define BRUME_SLABS " + (kind.Slabs ? "1" : "0") +
      "\n#define BRUME_BENDS " + (kind.Bends ? "1" : "0") + "\n");
  const int order = kind.Order;
  if (order < 1)
  {
    return fs;
  }
  const int coefficients = (order + 1) * (order + 1);
  const int textures = (3 * coefficients + 3) / 4;
  std::string dec;
  std::string fetch = "  float v[" + std::to_string(4 * textures) + "];\n  vec4 f;\n";
  for (int t = 0; t < textures; ++t)
  {
    const std::string n = std::to_string(t);
    dec += "uniform sampler3D shTexture" + n + ";\n";
    fetch += "  f = texture(shTexture" + n + ", texcoord);\n";
    for (int c = 0; c < 4; ++c)
    {
      fetch += "  v[" + std::to_string(4 * t + c) + "] = f[" + std::to_string(c) + "];\n";
    }
  }
  std::ostringstream constants;
  constants << std::setprecision(9) << "#define SH_ORDER " << order << "\n#define BRUME_SH_Y00 "
            << brume::ShY00 << "\n";
  std::string directional = vtkBrumeSliceVolumeDirectionalFS;
  Replace(directional, "//BRUME::Directional::Uniforms", dec + constants.str());
  Replace(directional, "//BRUME::Directional::Fetch", fetch);
  Replace(fs, "//BRUME::Directional::Dec", directional);
  Replace(fs, "//BRUME::Directional::Impl", "emission = directionalSource();");
  return fs;
}
