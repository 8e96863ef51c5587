// SPDX-License-Identifier: BSD-3-Clause
// Writes Data/scenes/puff-series.json's time series: a puff of smoke that
// rises and spreads, one VTK image per time step (.vti, float point data
// "density", LZ4) over [-1, 1]^3:
//
//   MakePuffSeries DIRECTORY [STEPS [N]]   (DIRECTORY/puff_000.vti ...;
//                                           default 8 steps of 48^3 points)
//
// Step s of S (time t = s / (S - 1) in [0, 1]): a Gaussian blob whose centre
// rises from y = -0.55 to 0.35 and drifts in x, whose radius grows from 0.22
// to 0.42 while its peak density falls as the same smoke fills more room
// (the blob's integral stays within 20 %), broken up by three octaves of
// value noise that drift with it. Deterministic: the same files on every
// machine.
#include "BrumeValueNoise.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkXMLImageDataWriter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{
using BrumeValueNoise::Noise;

float Density(double x, double y, double z, double t)
{
  const double cx = -0.15 + 0.3 * t, cy = -0.55 + 0.9 * t, cz = 0.0;
  const double radius = 0.22 + 0.2 * t;
  const double peak = 12.0 * std::pow(0.22 / radius, 2.5);
  const double dx = x - cx, dy = y - cy, dz = z - cz;
  const double r2 = (dx * dx + dy * dy + dz * dz) / (radius * radius);
  double n = 0.0, amplitude = 0.5;
  for (int o = 0; o < 3; ++o)
  {
    const double f = 3.0 * (1 << o);
    n += amplitude * Noise(f * dx + 11.0 * o, f * (dy - 0.3 * t) - 7.0 * o, f * dz + 5.0 * o);
    amplitude *= 0.5;
  }
  return static_cast<float>(peak * std::exp(-r2) * std::clamp(0.4 + 1.2 * n, 0.0, 1.5));
}
}

int main(int argc, char* argv[])
{
  if (argc < 2 || argc > 4)
  {
    std::fprintf(stderr,
      "usage: MakePuffSeries DIRECTORY [STEPS [N]]   (2 to 1000 steps, default 8; N^3 points, 8 "
      "to 512, default 48)\n");
    return 2;
  }
  const int steps = argc >= 3 ? std::atoi(argv[2]) : 8;
  const int n = argc == 4 ? std::atoi(argv[3]) : 48;
  if (steps < 2 || steps > 1000 || n < 8 || n > 512)
  {
    std::fprintf(stderr, "MakePuffSeries: STEPS must be in [2, 1000] and N in [8, 512]\n");
    return 2;
  }
  const double spacing = 2.0 / (n - 1);
  for (int s = 0; s < steps; ++s)
  {
    const double t = static_cast<double>(s) / (steps - 1);
    vtkNew<vtkImageData> image;
    image->SetDimensions(n, n, n);
    image->SetOrigin(-1.0, -1.0, -1.0);
    image->SetSpacing(spacing, spacing, spacing);
    vtkNew<vtkFloatArray> density;
    density->SetName("density");
    density->SetNumberOfValues(static_cast<vtkIdType>(n) * n * n);
    float* out = density->GetPointer(0);
    for (int k = 0; k < n; ++k)
    {
      for (int j = 0; j < n; ++j)
      {
        for (int i = 0; i < n; ++i)
        {
          out[(static_cast<std::size_t>(k) * n + j) * n + i] =
            Density(-1.0 + i * spacing, -1.0 + j * spacing, -1.0 + k * spacing, t);
        }
      }
    }
    image->GetPointData()->AddArray(density);
    char name[32];
    std::snprintf(name, sizeof(name), "/puff_%03d.vti", s);
    const std::string file = std::string(argv[1]) + name;
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetFileName(file.c_str());
    writer->SetInputData(image);
    writer->SetDataModeToBinary(); // inline: VTK 9.2 misreads appended data under expat 2.5
    writer->SetCompressorTypeToLZ4();
    if (writer->Write() != 1)
    {
      std::fprintf(stderr, "MakePuffSeries: cannot write '%s'\n", file.c_str());
      return 1;
    }
  }
  return 0;
}
