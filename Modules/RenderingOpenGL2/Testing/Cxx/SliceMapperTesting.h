// SPDX-License-Identifier: BSD-3-Clause
// What the slice mapper's tests share: media of stacked layers, volumes,
// frames rendered into one shared window and read back as float radiance,
// and the slab's analytic radiance.
#ifndef SliceMapperTesting_h
#define SliceMapperTesting_h

#include "vtkActor.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeFloatImageCapture.h"
#include "vtkBrumeSliceVolumeMapper.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProp.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace SliceMapperTesting
{
using RGB = std::array<double, 3>;
constexpr int Size = 64;

struct Layer
{
  RGB Source;
  RGB SigmaT;
};

// A medium over the box, with `layers` stacked along z (first = lowest z).
inline vtkSmartPointer<vtkImageData> Medium(const double box[6], const std::vector<Layer>& layers)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  const int nz = static_cast<int>(layers.size());
  image->SetDimensions(2, 2, nz + 1);
  image->SetOrigin(box[0], box[2], box[4]);
  image->SetSpacing(box[1] - box[0], box[3] - box[2], (box[5] - box[4]) / nz);
  vtkNew<vtkFloatArray> source, extinction;
  source->SetName(vtkBrumeNames::SourceRadiance);
  source->SetNumberOfComponents(3);
  extinction->SetName(vtkBrumeNames::Extinction);
  extinction->SetNumberOfComponents(3);
  for (const Layer& l : layers)
  {
    source->InsertNextTuple(l.Source.data());
    extinction->InsertNextTuple(l.SigmaT.data());
  }
  image->GetCellData()->AddArray(source);
  image->GetCellData()->AddArray(extinction);
  return image;
}

inline vtkSmartPointer<vtkVolume> Volume(vtkImageData* image, double spacing, bool nearest)
{
  auto mapper = vtkSmartPointer<vtkBrumeSliceVolumeMapper>::New();
  mapper->SetInputData(image);
  mapper->SetSliceSpacing(spacing);
  auto volume = vtkSmartPointer<vtkVolume>::New();
  volume->SetMapper(mapper);
  if (nearest)
  {
    volume->GetProperty()->SetInterpolationTypeToNearest();
  }
  else
  {
    volume->GetProperty()->SetInterpolationTypeToLinear();
  }
  return volume;
}

struct Frame
{
  vtkSmartPointer<vtkImageData> Radiance;
  const float* At(int i, int j) const
  {
    return static_cast<vtkFloatArray*>(this->Radiance->GetPointData()->GetArray(0))
      ->GetPointer(3 * (j * Size + i));
  }
};

// Renders the props looking down -z from z = 5, parallel (scale 1: the
// window spans [-1, 1]^2) or perspective; returns the float radiance.
// One window for every frame: opening an X connection per frame is what
// intermittently fails under Xvfb, not what is under test.
inline vtkRenderWindow* SharedWindow()
{
  static vtkSmartPointer<vtkRenderWindow> window;
  if (!window)
  {
    window = vtkSmartPointer<vtkRenderWindow>::New();
    window->SetOffScreenRendering(1);
    window->SetMultiSamples(0);
    window->SetSize(Size, Size);
  }
  return window;
}

inline Frame Render(const std::vector<vtkSmartPointer<vtkProp>>& props, bool parallel)
{
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  vtkRenderWindow* window = SharedWindow();
  window->GetRenderers()->RemoveAllItems();
  window->AddRenderer(renderer);
  for (const auto& p : props)
  {
    renderer->AddViewProp(p);
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, 0, 5);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetParallelProjection(parallel);
  camera->SetParallelScale(1.0);
  camera->SetViewAngle(2.0 * std::atan(1.0 / 5.0) * 180.0 / M_PI); // [-1, 1] at z = 0
  camera->SetClippingRange(1.0, 10.0);
  vtkNew<vtkBrumeFloatImageCapture> capture;
  capture->Attach(renderer);
  window->Render();
  Frame frame{ capture->Capture() };
  window->RemoveRenderer(renderer);
  return frame;
}

// World (x, y) at the centre of pixel (i, j) on the plane z = 0.
inline double Coordinate(int i)
{
  return -1.0 + (i + 0.5) * 2.0 / Size;
}

inline bool Near(const float* got, const RGB& expected, double relative, const std::string& what)
{
  for (int c = 0; c < 3; ++c)
  {
    if (std::abs(got[c] - expected[c]) > relative * std::abs(expected[c]) + 1e-6)
    {
      std::cerr << what << ": channel " << c << " is " << got[c] << ", expected " << expected[c]
                << "\n";
      return false;
    }
  }
  return true;
}

inline RGB Slab(const Layer& l, double d)
{
  RGB r;
  for (int c = 0; c < 3; ++c)
  {
    r[c] = l.Source[c] * (1.0 - std::exp(-l.SigmaT[c] * d));
  }
  return r;
}

// Two grey volumes one behind the other (0.4 deep each, 0.2 apart), and
// the radiance through both: `Expected` composited in depth order,
// `Wrong` in the other.
struct StackedVolumes
{
  vtkSmartPointer<vtkVolume> Back, Front;
  RGB Expected, Wrong;
};

inline StackedVolumes Stacked()
{
  const double frontBox[6] = { -0.5, 0.5, -0.5, 0.5, 0.1, 0.5 };
  const double backBox[6] = { -0.5, 0.5, -0.5, 0.5, -0.5, -0.1 };
  const Layer front{ { 0.2, 0.2, 0.2 }, { 4.0, 4.0, 4.0 } };
  const Layer back{ { 5.0, 5.0, 5.0 }, { 3.0, 3.0, 3.0 } };
  StackedVolumes v;
  v.Back = Volume(Medium(backBox, { back }), 0.01, false);
  v.Front = Volume(Medium(frontBox, { front }), 0.01, false);
  const RGB lf = Slab(front, 0.4), lb = Slab(back, 0.4);
  for (int c = 0; c < 3; ++c)
  {
    v.Expected[c] = lf[c] + std::exp(-front.SigmaT[c] * 0.4) * lb[c];
    v.Wrong[c] = lb[c] + std::exp(-back.SigmaT[c] * 0.4) * lf[c];
  }
  return v;
}

// A sphere of radius 0.3 centred on the medium's side face x = 0.5: half
// inside. Unlit colour c; the medium between the front face z = 0.5 and the
// sphere is all that lies in front of it; nothing behind it shows. The
// mapper's RadianceScale multiplies the medium's radiance, not what it lets
// through. Drawn at ImageSampleDistance `distance`; the image sample
// distance the mapper reports must be `drawn`.
inline bool Occlusion(const Layer& fog, double scale, double distance, double drawn)
{
  const double box[6] = { -0.5, 0.5, -0.5, 0.5, -0.5, 0.5 };
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0.5, 0, 0);
  sphere->SetRadius(0.3);
  sphere->SetThetaResolution(256);
  sphere->SetPhiResolution(256);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->LightingOff();
  actor->GetProperty()->SetColor(0.25, 0.5, 0.75);
  const RGB c{ 0.25, 0.5, 0.75 };
  vtkSmartPointer<vtkVolume> volume = Volume(Medium(box, { fog }), 0.002, false);
  auto* sliceMapper = vtkBrumeSliceVolumeMapper::SafeDownCast(volume->GetMapper());
  sliceMapper->SetRadianceScale(scale);
  sliceMapper->SetImageSampleDistance(distance);
  const Frame f = Render({ actor, volume }, true);
  bool ok = sliceMapper->GetLastImageSampleDistance() == drawn;
  if (!ok)
  {
    std::cerr << "occlusion: drawn at image sample distance "
              << sliceMapper->GetLastImageSampleDistance() << ", expected " << drawn << "\n";
  }
  // What pixel (i, j) shows: 1 on the sphere, 2 the medium alone, 0 not
  // checked (the sphere's silhouette, the medium's side face, the edges).
  auto expectedAt = [&](int i, int j, RGB& expected)
  {
    const double x = Coordinate(i), y = Coordinate(j);
    const double rho2 = (x - 0.5) * (x - 0.5) + y * y;
    if (std::abs(y) > 0.45 || x < -0.45 || x > 0.95)
    {
      return 0;
    }
    if (rho2 < 0.28 * 0.28)
    {
      // On the sphere: its front surface at z_s; medium from 0.5 to z_s (if x < 0.5).
      const double zs = std::sqrt(0.09 - rho2);
      const double d = x < 0.5 ? std::max(0.0, 0.5 - zs) : 0.0;
      if (std::abs(x - 0.5) < 0.03 * distance)
      {
        return 0; // the medium's side face crosses these pixels
      }
      const RGB l = Slab(fog, d);
      for (int k = 0; k < 3; ++k)
      {
        expected[k] = scale * l[k] + std::exp(-fog.SigmaT[k] * d) * c[k];
      }
      return 1;
    }
    if (rho2 > 0.32 * 0.32 && x < 0.45)
    {
      expected = Slab(fog, 1.0);
      for (double& e : expected)
      {
        e *= scale;
      }
      return 2;
    }
    return 0; // the sphere's silhouette
  };
  // At a reduced resolution the medium in front of the sphere is sampled
  // coarsely: a pixel there shows what the sphere shows within a coarse
  // pixel and a half of it (never the medium beside the sphere); the medium
  // beside the sphere, uniform, stays exact up to the silhouette.
  const int reach = distance > 1.0 ? static_cast<int>(std::ceil(1.5 * distance)) : 0;
  int checked = 0;
  for (int j = 0; j < Size; ++j)
    for (int i = 0; i < Size; ++i)
    {
      RGB expected;
      const int region = expectedAt(i, j, expected);
      if (region == 0)
      {
        continue;
      }
      const std::string what = "sphere half inside, image sample distance " +
        std::to_string(distance) + ", pixel " + std::to_string(i) + "," + std::to_string(j);
      if (region == 2 || reach == 0)
      {
        ok = Near(f.At(i, j), expected, 0.02, what) && ok;
      }
      else
      {
        RGB low = expected, high = expected, other;
        for (int v = std::max(0, j - reach); v <= std::min(Size - 1, j + reach); ++v)
          for (int u = std::max(0, i - reach); u <= std::min(Size - 1, i + reach); ++u)
          {
            if (expectedAt(u, v, other) == 1)
            {
              for (int k = 0; k < 3; ++k)
              {
                low[k] = std::min(low[k], other[k]);
                high[k] = std::max(high[k], other[k]);
              }
            }
          }
        for (int k = 0; k < 3; ++k)
        {
          const float got = f.At(i, j)[k];
          if (got < 0.98 * low[k] - 1e-6 || got > 1.02 * high[k] + 1e-6)
          {
            std::cerr << what << ": channel " << k << " is " << got << ", outside what the sphere "
                      << "shows within " << reach << " pixels, [" << low[k] << ", " << high[k]
                      << "]\n";
            ok = false;
          }
        }
      }
      ++checked;
    }
  std::cout << "occlusion, radiance scale " << scale << ", image sample distance " << distance
            << ": " << checked << " pixels checked\n";
  return ok && checked > 500;
}
}

#endif
