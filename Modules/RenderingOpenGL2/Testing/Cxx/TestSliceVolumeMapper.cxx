// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeSliceVolumeMapper against analytic answers, read back from a float
// framebuffer: exactness for any slice count, layered and coloured
// extinction, occlusion by opaque geometry, depth order of overlapping
// volumes, scalars classified by a transfer function, thin sheets of an
// extinction grid of its own between slices, and bad input.
#include "vtkActor.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeFloatImageCapture.h"
#include "vtkBrumeOpenGLSliceVolumeMapper.h"
#include "vtkBrumeSliceVolumeMapper.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkShortArray.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedShortArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include "brume/Sampling.h"
#include "brume/SphericalHarmonics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "SliceMapperTesting.h"

namespace
{
using namespace SliceMapperTesting;

bool Exactness()
{
  // A unit cube of constant S and coloured sigma_t, seen face-on.
  const double box[6] = { -0.5, 0.5, -0.5, 0.5, -0.5, 0.5 };
  const Layer fog{ { 2.0, 1.0, 0.5 }, { 1.5, 0.5, 3.0 } };
  bool ok = true;
  for (double spacing : { 1.0, 1.0 / 3.0, 1.0 / 17.0, 0.0 })
  {
    for (bool parallel : { true, false })
    {
      auto volume = Volume(Medium(box, { fog }), spacing, false);
      const Frame f = Render({ volume }, parallel);
      const std::string what = std::string(parallel ? "parallel" : "perspective") +
        " view, slice spacing " + std::to_string(spacing);
      // Pixels whose rays cross the front and back faces.
      for (int j = 0; j < Size; ++j)
        for (int i = 0; i < Size; ++i)
        {
          const double x = Coordinate(i), y = Coordinate(j);
          // Perspective rays through (x, y, 0) from (0, 0, 5): at z = -0.5
          // they are at 5.5/5 of (x, y); keep those inside the back face.
          const double spread = parallel ? 1.0 : 5.5 / 5.0;
          if (std::max(std::abs(x), std::abs(y)) * spread > 0.45)
          {
            continue;
          }
          // Path length through the cube: 1, or 1/cos in perspective.
          const double length = parallel ? 1.0 : std::sqrt(25.0 + x * x + y * y) / 5.0;
          ok = Near(f.At(i, j), Slab(fog, length), 0.01, what) && ok;
        }
      auto* mapper = vtkBrumeSliceVolumeMapper::SafeDownCast(volume->GetMapper());
      std::cout << what << ": " << mapper->GetLastNumberOfSlices() << " slices\n";
    }
  }
  return ok;
}

bool Layers()
{
  // Two layers along z; with nearest sampling and an even number of slabs the
  // layers meet on a slab boundary: L = L_front + T_front L_back, per channel.
  const double box[6] = { -0.5, 0.5, -0.5, 0.5, -0.5, 0.5 };
  const Layer back{ { 3.0, 1.0, 2.0 }, { 2.0, 0.3, 1.0 } };
  const Layer front{ { 0.5, 2.0, 1.0 }, { 0.7, 1.2, 4.0 } };
  RGB expected;
  const RGB lb = Slab(back, 0.5), lf = Slab(front, 0.5);
  for (int c = 0; c < 3; ++c)
  {
    expected[c] = lf[c] + std::exp(-front.SigmaT[c] * 0.5) * lb[c];
  }
  bool ok = true;
  for (double spacing : { 0.5, 1.0 / 8.0, 1.0 / 32.0 })
  {
    const Frame f = Render({ Volume(Medium(box, { back, front }), spacing, true) }, true);
    ok = Near(f.At(Size / 2, Size / 2), expected, 0.01,
           "two layers, spacing " + std::to_string(spacing)) &&
      ok;
    ok = Near(f.At(Size / 3, Size / 2 + 5), expected, 0.01, "two layers, off centre") && ok;
  }
  return ok;
}

bool DepthOrder()
{
  // Two volumes one behind the other, added back one first: compositing must
  // follow depth, not the order of the props.
  const StackedVolumes v = Stacked();
  const Frame f = Render({ v.Back, v.Front }, true);
  const Frame g = Render({ v.Front, v.Back }, true);
  std::cout << "depth order: expected " << v.Expected[0] << ", the other order would give "
            << v.Wrong[0] << "\n";
  return Near(f.At(Size / 2, Size / 2), v.Expected, 0.01, "back volume added first") &&
    Near(g.At(Size / 2, Size / 2), v.Expected, 0.01, "front volume added first");
}

struct ErrorCount
{
  int Count = 0;
  static void Callback(vtkObject*, unsigned long, void* data, void*)
  {
    ++static_cast<ErrorCount*>(data)->Count;
  }
};

bool BadInput()
{
  const double box[6] = { -0.5, 0.5, -0.5, 0.5, -0.5, 0.5 };
  const Layer fog{ { 1.0, 1.0, 1.0 }, { 1.0, 1.0, 1.0 } };
  std::vector<std::pair<std::string, vtkSmartPointer<vtkImageData>>> cases;
  auto noArrays = Medium(box, { fog });
  noArrays->GetCellData()->RemoveArray(vtkBrumeNames::Extinction);
  cases.emplace_back("no Extinction array", noArrays);
  auto zero = Medium(box, { fog });
  zero->SetSpacing(1.0, 0.0, 1.0);
  cases.emplace_back("zero spacing", zero);
  auto negative = Medium(box, { fog });
  negative->SetSpacing(1.0, 1.0, -1.0);
  cases.emplace_back("negative spacing", negative);
  auto empty = vtkSmartPointer<vtkImageData>::New();
  empty->SetDimensions(2, 1, 2);
  cases.emplace_back("empty extent", empty);
  auto nanSigma = Medium(box, { Layer{ { 1, 1, 1 }, { 1, NAN, 1 } } });
  cases.emplace_back("NaN extinction", nanSigma);
  bool ok = true;
  for (const auto& c : cases)
  {
    auto volume = Volume(c.second, 0.0, false);
    ErrorCount errors;
    vtkNew<vtkCallbackCommand> observer;
    observer->SetCallback(ErrorCount::Callback);
    observer->SetClientData(&errors);
    volume->GetMapper()->AddObserver(vtkCommand::ErrorEvent, observer);
    const Frame f = Render({ volume }, true);
    const float* p = f.At(Size / 2, Size / 2);
    if (errors.Count == 0 || p[0] != 0.f || p[1] != 0.f || p[2] != 0.f)
    {
      std::cerr << c.first << ": " << errors.Count << " errors, centre pixel " << p[0] << "\n";
      ok = false;
    }
  }
  // A good volume beside a bad one is still drawn.
  auto good = Volume(Medium(box, { fog }), 0.0, false);
  auto bad = Volume(noArrays, 0.0, false);
  vtkNew<vtkCallbackCommand> silence;
  silence->SetCallback([](vtkObject*, unsigned long, void*, void*) {});
  bad->GetMapper()->AddObserver(vtkCommand::ErrorEvent, silence);
  const Frame f = Render({ bad, good }, true);
  ok = Near(f.At(Size / 2, Size / 2), Slab(fog, 1.0), 0.01, "good volume beside a bad one") && ok;
  return ok;
}
}

bool Directional()
{
  // Directional radiance: a cube lit from one direction w_p (flux Phi per
  // channel), projected to spherical harmonics of order 1 to 3. Seen along
  // +z at the centre, S = Phi p_g(w_p . z) exactly (the lobe tail restores
  // the bands beyond the order), composited as S (1 - exp(-sigma_t)).
  const double box[6] = { -0.5, 0.5, -0.5, 0.5, -0.5, 0.5 };
  const RGB phi{ 1.0, 0.5, 2.0 }, sigmaT{ 1.5, 0.5, 3.0 };
  const double g = 0.5;
  bool ok = true;
  for (int run = 0; run < 6; ++run)
  {
    // Each order, evaluated per voxel, then per fragment.
    const int order = 1 + run % 3;
    const int evaluation =
      run < 3 ? vtkBrumeSliceVolumeMapper::PerVoxel : vtkBrumeSliceVolumeMapper::PerFragment;
    for (const brume::Vec3& wp : { brume::Vec3(0.f, 0.f, 1.f), brume::Vec3(1.f, 0.f, 0.f),
           brume::Normalize(brume::Vec3(1.f, 1.f, -1.f)), brume::Vec3(0.f, 0.6f, 0.8f) })
    {
      auto image = Medium(box, { Layer{ { 0.0, 0.0, 0.0 }, sigmaT } });
      const int k = brume::ShCoefficients(order);
      float y[16];
      brume::EvaluateSh(order, wp, y);
      vtkNew<vtkFloatArray> sh;
      sh->SetName(vtkBrumeNames::SourceRadianceSH);
      sh->SetNumberOfComponents(3 * k);
      sh->SetNumberOfTuples(1);
      for (int j = 0; j < k; ++j)
      {
        for (int c = 0; c < 3; ++c)
        {
          sh->SetComponent(0, 3 * j + c, y[j] * phi[c]);
        }
      }
      image->GetCellData()->AddArray(sh);
      vtkNew<vtkDoubleArray> asymmetry;
      asymmetry->SetName(vtkBrumeNames::PhaseAsymmetry);
      asymmetry->InsertNextValue(g);
      image->GetFieldData()->AddArray(asymmetry);
      auto volume = Volume(image, 1.0 / 16.0, true);
      vtkBrumeSliceVolumeMapper::SafeDownCast(volume->GetMapper())
        ->SetDirectionalEvaluation(evaluation);
      const Frame f = Render({ volume }, true);
      const double p = brume::HenyeyGreenstein(static_cast<float>(g)).Evaluate(wp.z);
      RGB expected;
      for (int c = 0; c < 3; ++c)
      {
        expected[c] = phi[c] * p * (1.0 - std::exp(-sigmaT[c]));
      }
      ok = Near(f.At(Size / 2, Size / 2), expected, 0.015,
             std::string(
               evaluation == vtkBrumeSliceVolumeMapper::PerVoxel ? "per voxel" : "per fragment") +
               ", order " + std::to_string(order) + ", w_p . z = " + std::to_string(wp.z)) &&
        ok;
    }
  }
  return ok;
}

bool NativeExtinction()
{
  // One coarse voxel of source radiance S over the unit cube, and sigma_t
  // on a grid of its own (8 x 8 x 1 cells): the left half full, the right
  // half empty. The image must follow the fine grid (a sharp edge at x = 0)
  // with S (1 - exp(-sigma_t)) on the left, not the coarse extinction.
  const double box[6] = { -0.5, 0.5, -0.5, 0.5, -0.5, 0.5 };
  const Layer coarse{ { 2.0, 1.0, 0.5 }, { 10.0, 10.0, 10.0 } }; // extinction ignored
  const RGB sigmaT{ 1.5, 0.5, 3.0 };
  auto grid = vtkSmartPointer<vtkImageData>::New();
  grid->SetDimensions(9, 9, 2);
  grid->SetOrigin(box[0], box[2], box[4]);
  grid->SetSpacing(1.0 / 8.0, 1.0 / 8.0, 1.0);
  vtkNew<vtkFloatArray> extinction;
  extinction->SetName(vtkBrumeNames::Extinction);
  extinction->SetNumberOfComponents(3);
  for (int j = 0; j < 8; ++j)
  {
    for (int i = 0; i < 8; ++i)
    {
      const RGB zero{ 0.0, 0.0, 0.0 };
      extinction->InsertNextTuple(i < 4 ? sigmaT.data() : zero.data());
    }
  }
  grid->GetCellData()->AddArray(extinction);
  bool ok = vtkBrumeSliceVolumeMapper::ValidateExtinction(Medium(box, { coarse }), grid).empty();
  const Layer full{ coarse.Source, sigmaT };
  for (bool nearest : { true, false })
  {
    auto volume = Volume(Medium(box, { coarse }), 0.0, nearest);
    auto* mapper = vtkBrumeSliceVolumeMapper::SafeDownCast(volume->GetMapper());
    mapper->SetExtinctionData(grid);
    const Frame f = Render({ volume }, true);
    const std::string what = std::string("native extinction, ") + (nearest ? "nearest" : "linear");
    for (int i = 0; i < Size; ++i)
    {
      const double x = Coordinate(i);
      // Away from the edge at x = 0 by more than a fine cell (linear
      // filtering blends over one) and inside the cube.
      if (std::abs(x) < 0.15 || std::abs(x) > 0.45)
      {
        continue;
      }
      const RGB expected = x < 0.0 ? Slab(full, 1.0) : RGB{ 0.0, 0.0, 0.0 };
      ok = Near(f.At(i, Size / 2), expected, 0.01, what) && ok;
    }
    // Slices one fine cell apart along the view: the grid is one cell deep.
    std::cout << what << ": " << mapper->GetLastNumberOfSlices() << " slices\n";
  }
  // An extinction grid over another box is refused.
  grid->SetOrigin(box[0] + 0.25, box[2], box[4]);
  ok = !vtkBrumeSliceVolumeMapper::ValidateExtinction(Medium(box, { coarse }), grid).empty() && ok;
  return ok;
}

bool SparseExtinction(double unit, int texelBytes, double tolerance)
{
  // sigma_t on a grid of 30 x 20 x 4 cells over the unit cube, given densely
  // and in the sparse form written here from its documentation (bricks of
  // 8^3 cells 7 apart, a slot per varying brick, one value otherwise): a
  // smooth field over x < 0.2, a constant 2 beyond, 0 in the top rows.
  // Both forms must draw the same image. With a `unit`, the grid holds
  // whole numbers of it (a scan's integers), which the atlas keeps in
  // `texelBytes` per texel, exactly. Under a `tolerance` of optical depth
  // (SetExtinctionDepthTolerance) other values may go up as 16 bits too,
  // rounded: the image then stays within the bound the mapper states.
  const double box[6] = { -0.5, 0.5, -0.5, 0.5, -0.5, 0.5 };
  const int n[3] = { 30, 20, 4 };
  auto smooth = [&](int i, int j, int k)
  {
    if (j >= 14)
    {
      return 0.0;
    }
    if (i >= 21)
    {
      return 2.0;
    }
    return 1.0 + 0.8 * std::sin(0.5 * i) * std::cos(0.4 * j) + 0.1 * k;
  };
  auto density = [&](int i, int j, int k)
  { return unit > 0.0 ? std::round(smooth(i, j, k) / unit) : smooth(i, j, k); };
  const double per = unit > 0.0 ? unit : 1.0;
  const RGB scale{ 1.5 * per, 0.5 * per, 3.0 * per };
  auto grid = [&]()
  {
    auto g = vtkSmartPointer<vtkImageData>::New();
    g->SetDimensions(n[0] + 1, n[1] + 1, n[2] + 1);
    g->SetOrigin(box[0], box[2], box[4]);
    g->SetSpacing(1.0 / n[0], 1.0 / n[1], 1.0 / n[2]);
    return g;
  };
  auto dense = grid();
  vtkNew<vtkFloatArray> extinction;
  extinction->SetName(vtkBrumeNames::Extinction);
  extinction->SetNumberOfComponents(3);
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
      {
        const double d = density(i, j, k);
        extinction->InsertNextTuple3(d * scale[0], d * scale[1], d * scale[2]);
      }
  dense->GetCellData()->AddArray(extinction);
  auto sparse = grid();
  const int B = vtkBrumeSliceVolumeMapper::ExtinctionBrickSize;
  int bricks[3];
  for (int a = 0; a < 3; ++a)
  {
    bricks[a] = vtkBrumeSliceVolumeMapper::ExtinctionBricksAlong(n[a]);
  }
  vtkNew<vtkIntArray> slots;
  slots->SetName(vtkBrumeNames::ExtinctionBrickSlots);
  vtkNew<vtkFloatArray> values, samples;
  values->SetName(vtkBrumeNames::ExtinctionBrickValues);
  samples->SetName(vtkBrumeNames::ExtinctionBrickSamples);
  int constant = 0;
  for (int bk = 0; bk < bricks[2]; ++bk)
    for (int bj = 0; bj < bricks[1]; ++bj)
      for (int bi = 0; bi < bricks[0]; ++bi)
      {
        std::vector<float> cells;
        for (int k = 0; k < B; ++k)
          for (int j = 0; j < B; ++j)
            for (int i = 0; i < B; ++i)
            {
              cells.push_back(static_cast<float>(density(std::min((B - 1) * bi + i, n[0] - 1),
                std::min((B - 1) * bj + j, n[1] - 1), std::min((B - 1) * bk + k, n[2] - 1))));
            }
        if (std::all_of(cells.begin(), cells.end(), [&](float v) { return v == cells[0]; }))
        {
          slots->InsertNextValue(-1);
          values->InsertNextValue(cells[0]);
          ++constant;
          continue;
        }
        slots->InsertNextValue(static_cast<int>(samples->GetNumberOfTuples() / (B * B * B)));
        values->InsertNextValue(0.f);
        for (float v : cells)
        {
          samples->InsertNextValue(v);
        }
      }
  vtkNew<vtkDoubleArray> perDensity;
  perDensity->SetName(vtkBrumeNames::ExtinctionScale);
  perDensity->SetNumberOfComponents(3);
  perDensity->InsertNextTuple(scale.data());
  for (vtkDataArray* a : { static_cast<vtkDataArray*>(slots), static_cast<vtkDataArray*>(values),
         static_cast<vtkDataArray*>(samples), static_cast<vtkDataArray*>(perDensity) })
  {
    sparse->GetFieldData()->AddArray(a);
  }
  // The same bricks with their samples read from the cells themselves
  // (ExtinctionCellValues: a field's own array, read in place): the same
  // slots, so the same atlas.
  // In the scan's own type where its integers fit 16 bits.
  auto inPlace = grid();
  vtkSmartPointer<vtkDataArray> cellValues;
  if (unit == 0.01)
  {
    cellValues = vtkSmartPointer<vtkUnsignedShortArray>::New();
  }
  else if (unit == 0.001)
  {
    cellValues = vtkSmartPointer<vtkShortArray>::New();
  }
  else
  {
    cellValues = vtkSmartPointer<vtkFloatArray>::New();
  }
  cellValues->SetName(vtkBrumeNames::ExtinctionCellValues);
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
      {
        cellValues->InsertNextTuple1(density(i, j, k));
      }
  for (vtkDataArray* a : { static_cast<vtkDataArray*>(slots), static_cast<vtkDataArray*>(values),
         cellValues.GetPointer(), static_cast<vtkDataArray*>(perDensity) })
  {
    inPlace->GetFieldData()->AddArray(a);
  }
  const Layer coarse{ { 2.0, 1.0, 0.5 }, { 10.0, 10.0, 10.0 } };
  bool ok = constant > 0 && constant < slots->GetNumberOfTuples();
  ok = vtkBrumeSliceVolumeMapper::ValidateExtinction(Medium(box, { coarse }), sparse).empty() && ok;
  ok =
    vtkBrumeSliceVolumeMapper::ValidateExtinction(Medium(box, { coarse }), inPlace).empty() && ok;
  for (bool nearest : { true, false })
  {
    Frame frames[3];
    double depthError = -1.0;
    for (int form = 0; form < 3; ++form)
    {
      auto volume = Volume(Medium(box, { coarse }), 0.0, nearest);
      auto* mapper = vtkBrumeSliceVolumeMapper::SafeDownCast(volume->GetMapper());
      mapper->SetExtinctionDepthTolerance(tolerance);
      mapper->SetExtinctionData(form == 0 ? dense : form == 1 ? sparse : inPlace);
      frames[form] = Render({ volume }, false);
      auto* opengl = vtkBrumeOpenGLSliceVolumeMapper::SafeDownCast(volume->GetMapper());
      if (form > 0 && (!opengl || opengl->GetExtinctionAtlasTexelBytes() != texelBytes))
      {
        std::cerr << "sparse extinction in units of " << unit << ": an atlas of "
                  << (opengl ? opengl->GetExtinctionAtlasTexelBytes() : -1)
                  << " bytes a texel, not " << texelBytes << "\n";
        ok = false;
      }
      if (form > 0 && opengl)
      {
        depthError = opengl->GetExtinctionAtlasDepthError();
      }
    }
    // Rounded to 16 bits (floats, or integers spanning more), the atlas's
    // values move sigma_t by at most e/d along a ray of length at most the
    // diagonal d, e the stated bound: a pixel L = int S sigma exp(-tau) ds
    // moves by at most S e through sigma, and S e through exp(-tau), whose
    // weights sigma exp(-tau) integrate to at most 1.
    const bool rounded = texelBytes == 2 && unit != 0.01 && unit != 0.001;
    if (rounded != (depthError > 0.0) || !(depthError <= tolerance))
    {
      std::cerr << "sparse extinction in units of " << unit << ": a bound of " << depthError
                << " on optical depth under a tolerance of " << tolerance << "\n";
      ok = false;
    }
    const double sourceLargest = 2.0;
    // Both forms interpolate the same cells with the same weights, up to
    // float rounding of the coordinates (an atlas is a larger texture):
    // 1.2e-6 measured under llvmpipe.
    double worst = 0.0, sum = 0.0, rounding = 0.0;
    for (int j = 0; j < Size; ++j)
      for (int i = 0; i < Size; ++i)
        for (int c = 0; c < 3; ++c)
        {
          const double a = frames[0].At(i, j)[c], b = frames[1].At(i, j)[c];
          const double beyond = std::max(0.0, std::abs(a - b) - 2.0 * sourceLargest * depthError);
          worst = std::max(worst, beyond / (std::abs(a) + 1e-3));
          rounding = std::max(rounding, std::abs(a - b));
          sum += a;
        }
    std::cout << "sparse extinction in units of " << unit << ", "
              << (nearest ? "nearest" : "linear") << ", " << texelBytes
              << " bytes a texel: largest difference to the dense grid " << rounding << " (allowed "
              << 2.0 * sourceLargest * depthError << " by the rounding), relative beyond it "
              << worst << "\n";
    // Read from the cells or from the slots, the atlas is the same: bitwise.
    int unequal = 0;
    for (int j = 0; j < Size; ++j)
      for (int i = 0; i < Size; ++i)
        for (int c = 0; c < 3; ++c)
        {
          unequal += frames[1].At(i, j)[c] == frames[2].At(i, j)[c] ? 0 : 1;
        }
    if (unequal != 0)
    {
      std::cerr << "sparse extinction read from its cells, " << (nearest ? "nearest" : "linear")
                << ": " << unequal << " values differ from the slots' samples\n";
      ok = false;
    }
    if (!(worst < 1e-4) || !(sum > 0.0))
    {
      std::cerr << "sparse extinction, " << (nearest ? "nearest" : "linear")
                << ": differs from the dense grid by " << worst << "\n";
      ok = false;
    }
  }
  // Cells' values one short, or two bricks in one slot, are refused.
  cellValues->SetNumberOfValues(cellValues->GetNumberOfValues() - 1);
  ok =
    !vtkBrumeSliceVolumeMapper::ValidateExtinction(Medium(box, { coarse }), inPlace).empty() && ok;
  cellValues->InsertNextTuple1(0.0);
  ok =
    vtkBrumeSliceVolumeMapper::ValidateExtinction(Medium(box, { coarse }), inPlace).empty() && ok;
  vtkIdType stored = 0;
  while (slots->GetValue(stored) < 0)
  {
    ++stored;
  }
  const int firstSlot = slots->GetValue(stored);
  const vtkIdType constantBrick = stored == 0 ? slots->GetNumberOfTuples() - 1 : 0;
  const int was = slots->GetValue(constantBrick);
  slots->SetValue(constantBrick, firstSlot);
  ok =
    !vtkBrumeSliceVolumeMapper::ValidateExtinction(Medium(box, { coarse }), inPlace).empty() && ok;
  slots->SetValue(constantBrick, was);
  // A brick naming a slot the samples do not hold is refused.
  slots->SetValue(0, 1000);
  ok =
    !vtkBrumeSliceVolumeMapper::ValidateExtinction(Medium(box, { coarse }), sparse).empty() && ok;
  slots->SetValue(0, -1);
  samples->SetNumberOfValues(samples->GetNumberOfValues() - 1);
  ok =
    !vtkBrumeSliceVolumeMapper::ValidateExtinction(Medium(box, { coarse }), sparse).empty() && ok;
  return ok;
}

// Linear interpolation between the centres of n cells over [lo, hi],
// clamped beyond the first and last centres, as the renderer samples.
double CellCentred(const std::vector<double>& values, double lo, double hi, double z)
{
  const int n = static_cast<int>(values.size());
  const double x = std::clamp((z - lo) / (hi - lo) * n - 0.5, 0.0, n - 1.0);
  const int i0 = std::min(static_cast<int>(x), n - 1), i1 = std::min(i0 + 1, n - 1);
  return values[i0] + (x - i0) * (values[i1] - values[i0]);
}

// An extinction grid of its own over the box: one cell across x and y, a
// cell per value along z (grey sigma_t, the first value lowest).
vtkSmartPointer<vtkImageData> ColumnGrid(const double box[6], const std::vector<double>& sigma)
{
  const int cells = static_cast<int>(sigma.size());
  auto grid = vtkSmartPointer<vtkImageData>::New();
  grid->SetDimensions(2, 2, cells + 1);
  grid->SetOrigin(box[0], box[2], box[4]);
  grid->SetSpacing(box[1] - box[0], box[3] - box[2], (box[5] - box[4]) / cells);
  vtkNew<vtkFloatArray> extinction;
  extinction->SetName(vtkBrumeNames::Extinction);
  for (double v : sigma)
  {
    extinction->InsertNextValue(static_cast<float>(v));
  }
  grid->GetCellData()->AddArray(extinction);
  return grid;
}

bool ThickSkin()
{
  // A dense medium (sigma_t 64 per unit, 2 optical depths a fine cell)
  // below z = 0.3 in the unit cube, on a grid of its own of 32 cells along
  // z, and a source of 8 cells that grows toward the viewer, as a lit
  // skin's does. What the viewer sees comes from the first optical depths
  // below the skin: slabs several optical depths deep sample the source
  // up to half a slab below it, and the image comes out too dark. By the
  // automatic spacing's rule slabs hold at most two optical depths (here
  // one fine cell); the image must then match the quadrature of the same
  // interpolated fields within 5 % (3.7 % measured), and slabs of half a
  // source cell (4 optical depths, the rule without it) miss by more than
  // twice as much (9.0 %).
  const double box[6] = { -0.5, 0.5, -0.5, 0.5, -0.5, 0.5 };
  const int sourceCells = 8, fineCells = 32;
  const double sigma = 64.0, skin = 0.3;
  std::vector<Layer> layers;
  std::vector<double> sourceValues, sigmaValues;
  for (int k = 0; k < sourceCells; ++k)
  {
    const double z = box[4] + (k + 0.5) / sourceCells;
    const double s = std::exp(6.0 * z);
    sourceValues.push_back(s);
    layers.push_back({ { s, s, s }, { 0.0, 0.0, 0.0 } });
  }
  for (int k = 0; k < fineCells; ++k)
  {
    const double z = box[4] + (k + 0.5) / fineCells;
    sigmaValues.push_back(z < skin ? sigma : 0.0);
  }
  auto grid = ColumnGrid(box, sigmaValues);
  // The quadrature from the front face down, 10^5 steps.
  double expected = 0.0, depth = 0.0;
  const int steps = 100000;
  const double dz = (box[5] - box[4]) / steps;
  for (int n = 0; n < steps; ++n)
  {
    const double z = box[5] - (n + 0.5) * dz;
    const double st = CellCentred(sigmaValues, box[4], box[5], z);
    const double s = CellCentred(sourceValues, box[4], box[5], z);
    expected += s * st * std::exp(-(depth + 0.5 * st * dz)) * dz;
    depth += st * dz;
  }
  bool ok = true;
  double errors[2] = { 0.0, 0.0 };
  for (int rule = 0; rule < 2; ++rule)
  {
    // 0: the automatic spacing; 1: half a source cell, set explicitly.
    auto volume = Volume(Medium(box, layers), rule == 0 ? 0.0 : 0.5 / sourceCells, false);
    auto* mapper = vtkBrumeSliceVolumeMapper::SafeDownCast(volume->GetMapper());
    mapper->SetExtinctionData(grid);
    const Frame f = Render({ volume }, true);
    const float got = f.At(Size / 2, Size / 2)[0];
    errors[rule] = std::abs(got - expected) / expected;
    std::cout << "thick skin, " << (rule == 0 ? "automatic spacing" : "half a source cell") << ": "
              << mapper->GetLastNumberOfSlices() << " slices, " << got << " against " << expected
              << " (" << 100.0 * errors[rule] << " %)\n";
  }
  if (!(errors[0] <= 0.05))
  {
    std::cerr << "thick skin: the automatic spacing is " << 100.0 * errors[0]
              << " % from the quadrature\n";
    ok = false;
  }
  if (!(errors[1] > 2.0 * errors[0]))
  {
    std::cerr << "thick skin: slabs of 4 optical depths should miss by more than twice the "
                 "automatic spacing's error, not "
              << 100.0 * errors[1] << " %\n";
    ok = false;
  }
  return ok;
}

bool ThinSheet()
{
  // A sheet one fine cell thick (sigma_t 32 per unit in cell 13 of 32
  // along z, 0 elsewhere: one optical depth across) under a constant
  // source S = 1. Whatever the sheet's place, the radiance through it is
  // S (1 - exp(-1)), the linear interpolation's tent holding one cell of
  // sigma_t. Slabs four fine cells thick that take sigma_t at their slice
  // alone miss it or draw it a slab thick (two optical depths here); with
  // one sample per fine cell along each ray they hold it exactly (the
  // tents of samples one cell apart sum to one) in a parallel view, and to
  // within the samples' spread along oblique rays in perspective.
  const double box[6] = { -0.5, 0.5, -0.5, 0.5, -0.5, 0.5 };
  const int fineCells = 32;
  const Layer source{ { 1.0, 1.0, 1.0 }, { 0.0, 0.0, 0.0 } };
  std::vector<double> sheet(fineCells, 0.0);
  sheet[13] = fineCells;
  auto grid = ColumnGrid(box, sheet);
  const double expected = 1.0 - std::exp(-1.0);
  bool ok = true;
  for (bool parallel : { true, false })
  {
    for (bool quick : { false, true })
    {
      // Slabs of four fine cells: set so, or two set and a quick draw's
      // SliceSpacingScale of 2.
      auto volume = Volume(Medium(box, { source }), (quick ? 2.0 : 4.0) / fineCells, false);
      auto* mapper = vtkBrumeSliceVolumeMapper::SafeDownCast(volume->GetMapper());
      mapper->SetExtinctionData(grid);
      mapper->SetSliceSpacingScale(quick ? 2.0 : 1.0);
      const Frame f = Render({ volume }, parallel);
      double worst = 0.0;
      for (int j = Size / 4; j < 3 * Size / 4; ++j)
        for (int i = Size / 4; i < 3 * Size / 4; ++i)
        {
          worst = std::max(worst, std::abs(f.At(i, j)[0] - expected) / expected);
        }
      const std::string what = std::string("thin sheet, ") +
        (parallel ? "parallel" : "perspective") + (quick ? ", quick draw" : "");
      std::cout << what << ": " << mapper->GetLastNumberOfSlices() << " slices, "
                << mapper->GetLastSlabSamples() << " samples a slab, largest error "
                << 100.0 * worst << " %\n";
      const int samples = quick ? 1 : 4;
      if (mapper->GetLastSlabSamples() != samples)
      {
        std::cerr << what << ": " << mapper->GetLastSlabSamples() << " samples a slab, not "
                  << samples << "\n";
        ok = false;
      }
      if (!quick)
      {
        // While the camera moves (an interactor style's desired update
        // rate), one sample a slab; still frames, four again.
        SharedWindow()->SetDesiredUpdateRate(15.0);
        Render({ volume }, parallel);
        const int moving = mapper->GetLastSlabSamples();
        SharedWindow()->SetDesiredUpdateRate(0.0001);
        Render({ volume }, parallel);
        if (moving != 1 || mapper->GetLastSlabSamples() != 4)
        {
          std::cerr << what << ": " << moving << " samples a slab while interacting and "
                    << mapper->GetLastSlabSamples() << " still, not 1 and 4\n";
          ok = false;
        }
      }
      // Parallel: exact but for the texture filter's 8-bit weights;
      // perspective: rays up to 20 degrees off the axis stretch the
      // samples' spacing by up to 6 %.
      const double allowed = parallel ? 0.01 : 0.05;
      if (!quick && !(worst <= allowed))
      {
        std::cerr << what << ": " << 100.0 * worst << " % from S (1 - exp(-1)), allowed "
                  << 100.0 * allowed << " %\n";
        ok = false;
      }
      // One sample a slab is what the samples mend: it must miss.
      if (quick && !(worst > 0.1))
      {
        std::cerr << what << ": one sample a slab of four cells should miss the sheet's "
                  << "optical depth, but is within " << 100.0 * worst << " %\n";
        ok = false;
      }
    }
  }
  return ok;
}

bool ClassifiedThinSheet()
{
  // Scalars 200 at the centres of cell 13 of 32 along z, 0 elsewhere,
  // classified after interpolation by opacity 0 up to 50 and 0.5 at 200
  // (per unit distance): sigma_t is -ln(1 - alpha) of the tent the
  // interpolation makes, a function that bends at 50. One sample a fine
  // cell takes 0.79 to 1.51 of the sheet's optical depth, by where the
  // samples fall; the bricks holding the bend are sampled four times as
  // finely (GetNumberOfBendingBricks()), to within 1.5 % of it. Under a
  // constant source S = 1 each pixel is 1 - exp(-tau), tau the sheet's
  // optical depth found here by quadrature; the medium's box ends at the
  // grid's, then half a cell short of it, so that the slabs' samples fall
  // on the cells' centres, then off them.
  const double box[6] = { -0.5, 0.5, -0.5, 0.5, -0.5, 0.5 };
  const int n[3] = { 2, 2, 32 };
  const double perUnit = 64.0;
  auto sigmaOf = [](double s)
  { return -std::log1p(-0.5 * std::clamp((s - 50.0) / 150.0, 0.0, 1.0)); };
  // tau: the tent's scalars along z (in cells), classified, integrated.
  double tau = 0.0;
  const int steps = 200000;
  for (int q = 0; q < steps; ++q)
  {
    const double u = -1.0 + 2.0 * (q + 0.5) / steps; // cells from the sheet's centre
    tau += sigmaOf(200.0 * (1.0 - std::abs(u))) * (2.0 / steps);
  }
  tau *= perUnit / n[2];
  const double expected = 1.0 - std::exp(-tau);
  const int B = vtkBrumeSliceVolumeMapper::ExtinctionBrickSize;
  int bricks[3];
  vtkIdType count = 1;
  for (int a = 0; a < 3; ++a)
  {
    bricks[a] = vtkBrumeSliceVolumeMapper::ExtinctionBricksAlong(n[a]);
    count *= bricks[a];
  }
  const Layer source{ { 1.0, 1.0, 1.0 }, { 0.0, 0.0, 0.0 } };
  bool ok = true;
  for (double offset : { 0.0, 0.5 })
  {
    auto grid = vtkSmartPointer<vtkImageData>::New();
    grid->SetDimensions(n[0] + 1, n[1] + 1, n[2] + 1);
    grid->SetOrigin(box[0], box[2], box[4]);
    grid->SetSpacing(1.0 / n[0], 1.0 / n[1], 1.0 / n[2]);
    vtkNew<vtkIntArray> slots;
    slots->SetName(vtkBrumeNames::ExtinctionBrickSlots);
    vtkNew<vtkFloatArray> values, samples, table;
    values->SetName(vtkBrumeNames::ExtinctionBrickValues);
    samples->SetName(vtkBrumeNames::ExtinctionBrickSamples);
    for (vtkIdType b = 0; b < count; ++b)
    {
      slots->InsertNextValue(static_cast<int>(b));
      values->InsertNextValue(0.f);
      const int bk = static_cast<int>(b / (bricks[0] * bricks[1]));
      for (int k = 0; k < B; ++k)
        for (int j = 0; j < B; ++j)
          for (int i = 0; i < B; ++i)
          {
            samples->InsertNextValue(std::min((B - 1) * bk + k, n[2] - 1) == 13 ? 200.f : 0.f);
          }
    }
    table->SetName(vtkBrumeNames::ExtinctionTransferFunction);
    const int tableValues = 4096;
    for (int i = 0; i < tableValues; ++i)
    {
      table->InsertNextValue(static_cast<float>(sigmaOf(200.0 * i / (tableValues - 1))));
    }
    vtkNew<vtkDoubleArray> range, scale;
    range->SetName(vtkBrumeNames::ExtinctionTransferRange);
    range->SetNumberOfComponents(2);
    range->InsertNextTuple2(0.0, 200.0);
    scale->SetName(vtkBrumeNames::ExtinctionScale);
    scale->SetNumberOfComponents(3);
    scale->InsertNextTuple3(perUnit, perUnit, perUnit);
    for (vtkDataArray* a : { static_cast<vtkDataArray*>(slots), static_cast<vtkDataArray*>(values),
           static_cast<vtkDataArray*>(samples), static_cast<vtkDataArray*>(table),
           static_cast<vtkDataArray*>(range), static_cast<vtkDataArray*>(scale) })
    {
      grid->GetFieldData()->AddArray(a);
    }
    for (bool parallel : { true, false })
    {
      // Slabs of four fine cells, four samples each.
      const double shorter[6] = { box[0], box[1], box[2], box[3], box[4], box[5] - offset / n[2] };
      auto volume = Volume(Medium(shorter, { source }), 4.0 / n[2], false);
      auto* mapper = vtkBrumeOpenGLSliceVolumeMapper::SafeDownCast(volume->GetMapper());
      if (!mapper)
      {
        std::cerr << "classified thin sheet: not an OpenGL slice mapper\n";
        return false;
      }
      mapper->SetExtinctionData(grid);
      const Frame f = Render({ volume }, parallel);
      double worst = 0.0;
      for (int j = Size / 4; j < 3 * Size / 4; ++j)
        for (int i = Size / 4; i < 3 * Size / 4; ++i)
        {
          worst = std::max(worst, std::abs(f.At(i, j)[0] - expected) / expected);
        }
      const std::string what = std::string("classified thin sheet, ") +
        (parallel ? "parallel" : "perspective") + ", " + std::to_string(offset) + " cell off";
      std::cout << what << ": tau " << tau << ", " << mapper->GetNumberOfBendingBricks()
                << " bending bricks (" << mapper->GetNumberOfBendingParts()
                << " parts), largest error " << 100.0 * worst << " % (centre "
                << f.At(Size / 2, Size / 2)[0] << " of " << expected << ")\n";
      // The bricks whose cells hold the sheet's (cell 13: 0 to 200 there).
      int bending = 0;
      for (int bk = 0; bk < bricks[2]; ++bk)
      {
        bending += (B - 1) * bk <= 13 && 13 < std::min((B - 1) * bk + B, n[2]) ? 1 : 0;
      }
      if (mapper->GetNumberOfBendingBricks() != bending)
      {
        std::cerr << what << ": " << mapper->GetNumberOfBendingBricks() << " bricks bend, not "
                  << bending << "\n";
        ok = false;
      }
      // Of each, the parts whose points hold the sheet's and a 0 beside it
      // (two of four along z: points 4 to 6 and 6 to 7 of the brick from
      // cell 7), every one across x and y: 32 of its 64.
      if (mapper->GetNumberOfBendingParts() != 32 * bending)
      {
        std::cerr << what << ": " << mapper->GetNumberOfBendingParts() << " parts bend, not "
                  << 32 * bending << "\n";
        ok = false;
      }
      // Parallel: the four samples a fine cell (within 1 % of the optical
      // depth here; 0.46 % measured on the cells); perspective: rays up to
      // 20 degrees off the axis.
      const double allowed = parallel ? 0.01 : 0.05;
      if (!(worst <= allowed))
      {
        std::cerr << what << ": " << 100.0 * worst << " % from 1 - exp(-tau), allowed "
                  << 100.0 * allowed << " %\n";
        ok = false;
      }
      if (offset == 0.0)
      {
        // Without the bends' samples, the samples on the cells' centres take
        // the tent's peak for a whole cell: 1.51 of its optical depth.
        mapper->SetBendSampling(false);
        const Frame g = Render({ volume }, parallel);
        mapper->SetBendSampling(true);
        const double without = std::abs(g.At(Size / 2, Size / 2)[0] - expected) / expected;
        std::cout << what << ", without the bends' samples: " << 100.0 * without << " %\n";
        if (!(without > 0.1))
        {
          std::cerr << what << ": without the bends' samples, within " << 100.0 * without
                    << " %; it should miss\n";
          ok = false;
        }
      }
    }
  }
  return ok;
}

bool ClassifiedExtinction()
{
  // Scalars s_i = i / 7 at the centres of 8 x 4 x 1 cells over the unit
  // cube (one brick), classified by a two-level step function: opacity 0.2
  // below s = 9/14, 0.8 from there (per unit distance 1). Classified after
  // interpolation, sigma_t steps where the interpolated scalar crosses 9/14,
  // x = 0.125, halfway between two centres; classifying the cells' values
  // before interpolating would ramp over the cell between them. Each pixel
  // is S (1 - exp(-sigma_t)) through the cube's depth of 1, its sigma_t the
  // level on its side of the step (the same step with nearest sampling: the
  // cells meet at x = 0.125).
  const double box[6] = { -0.5, 0.5, -0.5, 0.5, -0.5, 0.5 };
  const double step = 9.0 / 14.0, low = 0.2, high = 0.8;
  const RGB scale{ 1.5, 0.5, 3.0 };
  auto grid = vtkSmartPointer<vtkImageData>::New();
  grid->SetDimensions(9, 5, 2);
  grid->SetOrigin(box[0], box[2], box[4]);
  grid->SetSpacing(1.0 / 8.0, 1.0 / 4.0, 1.0);
  const int B = vtkBrumeSliceVolumeMapper::ExtinctionBrickSize;
  vtkNew<vtkIntArray> slots;
  slots->SetName(vtkBrumeNames::ExtinctionBrickSlots);
  slots->InsertNextValue(0);
  vtkNew<vtkFloatArray> values, samples, table;
  values->SetName(vtkBrumeNames::ExtinctionBrickValues);
  values->InsertNextValue(0.f);
  samples->SetName(vtkBrumeNames::ExtinctionBrickSamples);
  for (int k = 0; k < B; ++k)
    for (int j = 0; j < B; ++j)
      for (int i = 0; i < B; ++i)
      {
        samples->InsertNextValue(static_cast<float>(std::min(i, 7)) / 7.f);
      }
  // The function's extinction at 4096 scalars over [0, 1]: the step, or
  // a gentle ramp of opacity from `low` to `high`.
  table->SetName(vtkBrumeNames::ExtinctionTransferFunction);
  const int n = 4096;
  auto fill = [&](bool stepped)
  {
    table->SetNumberOfValues(n);
    for (int i = 0; i < n; ++i)
    {
      const double s = static_cast<double>(i) / (n - 1);
      const double alpha = stepped ? (s < step ? low : high) : low + (high - low) * s;
      table->SetValue(i, static_cast<float>(-std::log1p(-alpha)));
    }
    table->Modified();
  };
  fill(false);
  vtkNew<vtkDoubleArray> range, perUnit;
  range->SetName(vtkBrumeNames::ExtinctionTransferRange);
  range->SetNumberOfComponents(2);
  range->InsertNextTuple2(0.0, 1.0);
  perUnit->SetName(vtkBrumeNames::ExtinctionScale);
  perUnit->SetNumberOfComponents(3);
  perUnit->InsertNextTuple(scale.data());
  for (vtkDataArray* a : { static_cast<vtkDataArray*>(slots), static_cast<vtkDataArray*>(values),
         static_cast<vtkDataArray*>(samples), static_cast<vtkDataArray*>(table),
         static_cast<vtkDataArray*>(range), static_cast<vtkDataArray*>(perUnit) })
  {
    grid->GetFieldData()->AddArray(a);
  }
  const Layer coarse{ { 2.0, 1.0, 0.5 }, { 10.0, 10.0, 10.0 } }; // extinction ignored
  bool ok = vtkBrumeSliceVolumeMapper::ValidateExtinction(Medium(box, { coarse }), grid).empty();
  auto level = [&](double alpha)
  {
    const double sigma = -std::log1p(-alpha);
    return Layer{ coarse.Source, { sigma * scale[0], sigma * scale[1], sigma * scale[2] } };
  };
  {
    // The scalars' 16-bit values under the ramp keep within the default
    // tolerance of optical depth (its slope 3 per unit of scalar, times the
    // scale's 3 and the diagonal's sqrt(3), over 2 65,535 steps: 1.2e-4);
    // under the step they would not (its slope is 5,676), so the same
    // grid, modified, goes up again as floats.
    auto volume = Volume(Medium(box, { coarse }), 0.0, false);
    auto* mapper = vtkBrumeOpenGLSliceVolumeMapper::SafeDownCast(volume->GetMapper());
    if (!mapper)
    {
      std::cerr << "classified scalars: not an OpenGL slice mapper\n";
      return false;
    }
    mapper->SetExtinctionData(grid);
    Render({ volume }, true);
    const int rampBytes = mapper->GetExtinctionAtlasTexelBytes();
    const double rampError = mapper->GetExtinctionAtlasDepthError();
    fill(true);
    grid->Modified();
    const Frame f = Render({ volume }, true);
    std::cout << "classified scalars: under the ramp " << rampBytes << " bytes a texel (bound "
              << rampError << "), under the step " << mapper->GetExtinctionAtlasTexelBytes()
              << " (bound " << mapper->GetExtinctionAtlasDepthError() << "), "
              << mapper->GetNumberOfExtinctionAtlasUploads() << " uploads\n";
    if (rampBytes != 2 || !(rampError > 1e-4 && rampError < 1.3e-4) ||
      mapper->GetExtinctionAtlasTexelBytes() != 4 ||
      mapper->GetExtinctionAtlasDepthError() != 0.0 ||
      mapper->GetNumberOfExtinctionAtlasUploads() != 2)
    {
      std::cerr << "classified scalars: the ramp's atlas should be 16-bit within 1.2e-4, the "
                   "step's sent again as floats\n";
      ok = false;
    }
    for (int i = 0; i < Size; ++i)
    {
      const double x = Coordinate(i);
      if (std::abs(x) <= 0.45)
      {
        const RGB expected = Slab(level(x < 0.125 ? low : high), 1.0);
        ok = Near(f.At(i, Size / 2), expected, 0.01, "classified scalars, after the ramp") && ok;
      }
    }
  }
  for (bool nearest : { true, false })
  {
    auto volume = Volume(Medium(box, { coarse }), 0.0, nearest);
    vtkBrumeSliceVolumeMapper::SafeDownCast(volume->GetMapper())->SetExtinctionData(grid);
    const Frame f = Render({ volume }, true);
    const std::string what = std::string("classified scalars, ") + (nearest ? "nearest" : "linear");
    for (int i = 0; i < Size; ++i)
    {
      const double x = Coordinate(i);
      if (std::abs(x) > 0.45)
      {
        continue;
      }
      const RGB expected = Slab(level(x < 0.125 ? low : high), 1.0);
      ok = Near(f.At(i, Size / 2), expected, 0.01, what + " at x = " + std::to_string(x)) && ok;
    }
  }
  // A table with a negative value, or a range the wrong way round, is refused.
  table->SetValue(3, -1.f);
  ok = !vtkBrumeSliceVolumeMapper::ValidateExtinction(Medium(box, { coarse }), grid).empty() && ok;
  table->SetValue(3, 0.f);
  range->SetTuple2(0, 1.0, 0.0);
  ok = !vtkBrumeSliceVolumeMapper::ValidateExtinction(Medium(box, { coarse }), grid).empty() && ok;
  return ok;
}

bool FreeGPUMemory()
{
  // No window, or one before its context: -1. After a render, the driver's
  // figure where it has GL_NVX_gpu_memory_info or GL_ATI_meminfo, -1 where
  // it has neither (llvmpipe, which these tests run on without a GPU).
  bool ok = vtkBrumeOpenGLSliceVolumeMapper::GetFreeGPUMemory(nullptr) == -1;
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(8, 8);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  const vtkTypeInt64 before = vtkBrumeOpenGLSliceVolumeMapper::GetFreeGPUMemory(window);
  window->Render();
  // The extensions as VTK lists them (one a line).
  const std::string capabilities = window->ReportCapabilities();
  const bool reports = capabilities.find("GL_NVX_gpu_memory_info\n") != std::string::npos ||
    capabilities.find("GL_ATI_meminfo\n") != std::string::npos;
  const bool listed = capabilities.find("GL_ARB_") != std::string::npos;
  const vtkTypeInt64 after = vtkBrumeOpenGLSliceVolumeMapper::GetFreeGPUMemory(window);
  std::cout << "free GPU memory: " << before << " before the first render, " << after
            << " bytes after (" << (reports ? "a driver that reports it" : "a driver that does not")
            << ")\n";
  ok = ok && listed && before == -1 && (reports ? after > 0 : after == -1);
  if (!ok)
  {
    std::cerr << "free GPU memory: -1 without a context and "
              << (reports ? "a positive figure" : "-1") << " after a render were expected\n";
  }
  return ok;
}

int TestSliceVolumeMapper(int, char*[])
{
  bool ok = true;
  ok = Exactness() && ok;
  ok = Layers() && ok;
  // Coloured extinction: drawn at full resolution whatever the distance.
  const Layer fog{ { 1.0, 2.0, 0.5 }, { 2.0, 1.0, 3.0 } };
  ok = Occlusion(fog, 1.0, 1.0, 1.0) && ok;
  ok = Occlusion(fog, 2.5, 1.0, 1.0) && ok;
  ok = Occlusion(fog, 1.0, 2.0, 1.0) && ok;
  ok = DepthOrder() && ok;
  ok = BadInput() && ok;
  ok = Directional() && ok;
  ok = NativeExtinction() && ok;
  ok = SparseExtinction(0.0, 4, 0.0) && ok;   // floats, kept exactly
  ok = SparseExtinction(0.0, 2, 1e-3) && ok;  // floats rounded within the default tolerance
  ok = SparseExtinction(0.01, 2, 0.0) && ok;  // whole numbers up to 280 (8-bit data): 16 bits
  ok = SparseExtinction(0.001, 2, 0.0) && ok; // up to 2,800
  ok = SparseExtinction(1e-5, 4, 0.0) && ok;  // up to 280,000: floats when kept exactly
  ok = SparseExtinction(1e-5, 2, 1e-3) && ok; // or rounded to 16 bits within the tolerance
  ok = ClassifiedExtinction() && ok;
  ok = ThickSkin() && ok;
  ok = ThinSheet() && ok;
  ok = ClassifiedThinSheet() && ok;
  ok = FreeGPUMemory() && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
