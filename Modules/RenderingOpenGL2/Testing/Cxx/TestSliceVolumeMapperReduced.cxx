// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeSliceVolumeMapper's ImageSampleDistance: media drawn into a
// coarser buffer and upsampled with the window's depth keep the slab's
// analytic radiance inside a uniform medium, the opaque objects'
// silhouettes within it, and the depth order of several volumes; media it
// cannot draw so (coloured extinction, written depth) are drawn at full
// resolution, exactly.
#include "SliceMapperTesting.h"

#include <cstdlib>

namespace
{
using namespace SliceMapperTesting;

// A grey unit cube seen face-on, its centre at x = `shift`, at `distance`:
// every pixel whose ray crosses both faces against the slab, parallel and
// perspective, and nothing drawn beside the cube (the coarse passes cover
// the cube's rectangle on screen, whose corner moves with `shift`).
bool Uniform(double distance, double shift)
{
  const double box[6] = { shift - 0.5, shift + 0.5, -0.5, 0.5, -0.5, 0.5 };
  const Layer fog{ { 2.0, 1.0, 0.5 }, { 1.5, 1.5, 1.5 } };
  bool ok = true;
  for (bool parallel : { true, false })
  {
    auto volume = Volume(Medium(box, { fog }), 0.0, false);
    auto* mapper = vtkBrumeSliceVolumeMapper::SafeDownCast(volume->GetMapper());
    mapper->SetImageSampleDistance(distance);
    const Frame f = Render({ volume }, parallel);
    const std::string what = std::string(parallel ? "parallel" : "perspective") +
      " view, image sample distance " + std::to_string(distance);
    if (mapper->GetLastImageSampleDistance() != distance)
    {
      std::cerr << what << ": drawn at " << mapper->GetLastImageSampleDistance() << "\n";
      ok = false;
    }
    int checked = 0, empty = 0;
    for (int j = 0; j < Size; ++j)
      for (int i = 0; i < Size; ++i)
      {
        const double x = Coordinate(i), y = Coordinate(j);
        // Away from the cube's edges by more than a coarse pixel (the
        // medium's own silhouette is blurred by up to one).
        const double spread = parallel ? 1.0 : 5.5 / 5.0;
        const double margin = 2.0 * distance / Size;
        const double outer =
          std::max(std::abs(x - shift * (parallel ? 1.0 : 5.0 / 4.5)), std::abs(y)) *
          (parallel ? 1.0 : 4.5 / 5.0);
        if (outer > 0.5 + 2.0 * margin)
        {
          // Beside the cube (its front face, the nearer, is the larger).
          ok = Near(f.At(i, j), { 0.0, 0.0, 0.0 }, 0.0, what + ", beside the cube") && ok;
          ++empty;
          continue;
        }
        if (std::max(std::abs(x - shift), std::abs(y)) * spread > 0.5 - margin)
        {
          continue;
        }
        const double length =
          parallel ? 1.0 : std::sqrt(25.0 + (x - shift) * (x - shift) + y * y) / 5.0;
        ok = Near(f.At(i, j), Slab(fog, length), 0.01, what) && ok;
        ++checked;
      }
    std::cout << what << ", cube at x = " << shift << ": " << checked << " pixels checked, "
              << empty << " beside it\n";
    ok = ok && checked > 300 && (shift == 0.0 || empty > 300);
  }
  return ok;
}

// Two grey volumes one behind the other: their slices still merge in depth
// order in the coarse buffer.
bool DepthOrder()
{
  const StackedVolumes v = Stacked();
  vtkBrumeSliceVolumeMapper::SafeDownCast(v.Back->GetMapper())->SetImageSampleDistance(2.0);
  const Frame f = Render({ v.Back, v.Front }, true);
  const double drawn =
    vtkBrumeSliceVolumeMapper::SafeDownCast(v.Front->GetMapper())->GetLastImageSampleDistance();
  if (drawn != 2.0)
  {
    std::cerr << "depth order: drawn at image sample distance " << drawn
              << ", expected 2 (the largest asked for)\n";
    return false;
  }
  return Near(f.At(Size / 2, Size / 2), v.Expected, 0.01, "two volumes, image sample distance 2");
}

// WriteDepth needs every slice's own depth: full resolution.
bool WriteDepthAtFullResolution()
{
  const double box[6] = { -0.5, 0.5, -0.5, 0.5, -0.5, 0.5 };
  const Layer fog{ { 2.0, 1.0, 0.5 }, { 1.5, 1.5, 1.5 } };
  auto volume = Volume(Medium(box, { fog }), 0.0, false);
  auto* mapper = vtkBrumeSliceVolumeMapper::SafeDownCast(volume->GetMapper());
  mapper->SetImageSampleDistance(2.0);
  mapper->WriteDepthOn();
  const Frame f = Render({ volume }, true);
  if (mapper->GetLastImageSampleDistance() != 1.0)
  {
    std::cerr << "WriteDepth: drawn at image sample distance "
              << mapper->GetLastImageSampleDistance() << ", expected 1\n";
    return false;
  }
  return Near(f.At(Size / 2, Size / 2), Slab(fog, 1.0), 0.01, "WriteDepth");
}
}

int TestSliceVolumeMapperReduced(int, char*[])
{
  bool ok = true;
  ok = Uniform(2.0, 0.0) && ok;
  ok = Uniform(3.0, 0.0) && ok;
  ok = Uniform(2.0, 0.35) && ok;
  ok = Uniform(3.0, -0.4) && ok;
  // A grey medium around a sphere: the pixels next to the sphere's
  // silhouette (one pixel and a half on each side excluded, as at full
  // resolution) keep their own radiance at a quarter of the fragments.
  const Layer grey{ { 1.0, 2.0, 0.5 }, { 2.0, 2.0, 2.0 } };
  ok = Occlusion(grey, 1.0, 1.0, 1.0) && ok;
  ok = Occlusion(grey, 1.0, 2.0, 2.0) && ok;
  ok = Occlusion(grey, 2.5, 2.0, 2.0) && ok;
  ok = DepthOrder() && ok;
  ok = WriteDepthAtFullResolution() && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
