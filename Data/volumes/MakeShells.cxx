// SPDX-License-Identifier: BSD-3-Clause
// Writes Data/scenes/shells.json's volume: a scalar field with structure at
// every scale, for scientific-volume work at 512^3 and beyond, as a VTK
// image (.vti, float point data "scalar", values in [0, 255], appended raw) over
// [-1, 1]^3:
//
//   MakeShells OUTPUT.vti [N]     (N^3 points, default 512)
//
// - four nested spherical shells about the centre, radii 0.85, 0.65, 0.45
//   and 0.25, 16, 8, 4 and 2 voxels thick (at 512^3), at values 160, 180,
//   200 and 220;
// - three planar sheets one voxel thick whatever N (x = 0.25, y = -0.3 and
//   z = 0.1, the voxels nearest those planes), at 240;
// - a background of value noise (four octaves, from a hash of the lattice
//   point: deterministic, the same file on every machine) between 0 and
//   120, denser towards the centre.
// A transfer function that is 0 below about 130 shows the shells and
// sheets; one with opacity from 60 shows the fog between them too.
#include "BrumeValueNoise.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkXMLImageDataWriter.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{
using BrumeValueNoise::Noise;

// The field at point (x, y, z) of [-1, 1]^3, whose voxels are `voxel` wide.
float Value(double x, double y, double z, double voxel, const int sheet[3], const int index[3])
{
  // The sheets: the voxels nearest their planes, one thick.
  for (int a = 0; a < 3; ++a)
  {
    if (index[a] == sheet[a])
    {
      return 240.f;
    }
  }
  // The shells: thickness in voxels at 512^3, scaled with the grid.
  const double r = std::sqrt(x * x + y * y + z * z);
  const double radii[4] = { 0.85, 0.65, 0.45, 0.25 };
  const double thickness[4] = { 16, 8, 4, 2 };
  const float levels[4] = { 160.f, 180.f, 200.f, 220.f };
  for (int s = 0; s < 4; ++s)
  {
    if (std::abs(r - radii[s]) <= 0.5 * thickness[s] * (2.0 / 512.0) + 0.25 * voxel)
    {
      return levels[s];
    }
  }
  // The fog: four octaves of noise, denser towards the centre.
  double n = 0.0, amplitude = 0.5;
  for (int o = 0; o < 4; ++o)
  {
    const double f = 4.0 * (1 << o);
    n += amplitude * Noise(f * x + 17.0 * o, f * y - 5.0 * o, f * z + 3.0 * o);
    amplitude *= 0.5;
  }
  const double falloff = std::clamp(1.2 - r, 0.0, 1.0);
  return static_cast<float>(120.0 * n * falloff);
}
}

int main(int argc, char* argv[])
{
  if (argc < 2 || argc > 3)
  {
    std::fprintf(
      stderr, "usage: MakeShells OUTPUT.vti [N]   (N^3 points, 8 to 2048; default 512)\n");
    return 2;
  }
  const int n = argc == 3 ? std::atoi(argv[2]) : 512;
  if (n < 8 || n > 2048)
  {
    std::fprintf(stderr, "MakeShells: N must be in [8, 2048], not '%s'\n", argv[2]);
    return 2;
  }
  const double spacing = 2.0 / (n - 1);
  vtkNew<vtkImageData> image;
  image->SetDimensions(n, n, n);
  image->SetOrigin(-1.0, -1.0, -1.0);
  image->SetSpacing(spacing, spacing, spacing);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName("scalar");
  scalars->SetNumberOfValues(static_cast<vtkIdType>(n) * n * n);
  const double planes[3] = { 0.25, -0.3, 0.1 };
  int sheet[3];
  for (int a = 0; a < 3; ++a)
  {
    sheet[a] = static_cast<int>(std::lround((planes[a] + 1.0) / spacing));
  }
  float* out = scalars->GetPointer(0);
  vtkSMPTools::For(0, n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType k = begin; k < end; ++k)
      {
        for (int j = 0; j < n; ++j)
        {
          for (int i = 0; i < n; ++i)
          {
            const int index[3] = { i, j, static_cast<int>(k) };
            out[(static_cast<std::size_t>(k) * n + j) * n + i] = Value(-1.0 + i * spacing,
              -1.0 + j * spacing, -1.0 + static_cast<double>(k) * spacing, spacing, sheet, index);
          }
        }
      }
    });
  image->GetPointData()->SetScalars(scalars);
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName(argv[1]);
  writer->SetInputData(image);
  // Appended raw floats, uncompressed (VTK's default mode, without its
  // compressor): read in 0.3 s where inline LZ4, base64 text that expat
  // scans, took 5.6 s (noise floats barely compress: 505 MB against 512).
  // Brume's scene reader reads appended data under any expat; VTK 9.2's
  // own reader does not under Debian 12's updates (Data/scenes/README.md).
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->SetCompressorTypeToNone();
  if (writer->Write() != 1)
  {
    std::fprintf(stderr, "MakeShells: cannot write '%s'\n", argv[1]);
    return 1;
  }
  return 0;
}
