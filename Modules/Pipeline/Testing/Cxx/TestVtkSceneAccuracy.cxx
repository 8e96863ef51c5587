// SPDX-License-Identifier: BSD-3-Clause
// A scene built the VTK way (a ground, a glossy sphere, VTK's Wavelet as a
// volume with its volume property, one positional vtkLight), lit by Brume
// through vtkBrumeRendererScene and vtkBrumePipeline at 2 x 10^6
// particles, against the reference path tracer over the same scene: the
// block error (relative MAE of 8 x 8-block means, as
// ../shared/tools/image-error.py computes it) is at most 3 % beyond what
// the reference's own noise adds to it (sqrt(2/pi) times its blocks'
// standard errors, summed over the blocks' sums).
//   TestVtkSceneAccuracy [OUTPUT_DIR]
#include "VtkSceneTesting.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumePipeline.h"
#include "vtkBrumeReferencePathTracer.h"
#include "vtkBrumeRendererScene.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSphereSource.h"
#include "vtkXMLImageDataWriter.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace
{
constexpr int Size = 128;
constexpr int Block = 8;
}

int TestVtkSceneAccuracy(int argc, char* argv[])
{
  vtkNew<vtkRenderer> renderer;
  AddPassScene(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();

  vtkNew<vtkBrumeRendererScene> scene;
  scene->SetRenderer(renderer);
  vtkNew<vtkBrumePipeline> pipeline;
  pipeline->SetInputConnection(scene->GetOutputPort());
  pipeline->SetCamera(camera);
  pipeline->SetSize(Size, Size);
  pipeline->GetTracer()->SetNumberOfParticles(2000000);
  pipeline->GetTracer()->SetSeed(3);
  if (!pipeline->Update())
  {
    std::fprintf(stderr, "FAILED: the pipeline runs\n");
    return 1;
  }
  vtkSmartPointer<vtkImageData> image = pipeline->RenderImage();
  vtkNew<vtkBrumeReferencePathTracer> reference;
  reference->SetInputConnection(scene->GetOutputPort());
  reference->SetCamera(camera);
  reference->SetSize(Size, Size);
  reference->SetSamplesPerPixel(2048);
  reference->SetSeed(11);
  reference->Update();
  vtkDataArray* got = image ? image->GetPointData()->GetArray("Radiance") : nullptr;
  vtkDataArray* want = reference->GetOutput()->GetPointData()->GetArray("Radiance");
  vtkDataArray* variance = reference->GetOutput()->GetPointData()->GetArray("Variance");
  if (!got || !want || !variance)
  {
    std::fprintf(stderr, "FAILED: both images have their radiance\n");
    return 1;
  }
  double difference = 0.0, total = 0.0, noise = 0.0;
  for (int by = 0; by < Size; by += Block)
  {
    for (int bx = 0; bx < Size; bx += Block)
    {
      for (int c = 0; c < 3; ++c)
      {
        double g = 0.0, w = 0.0, v = 0.0;
        for (int y = by; y < by + Block; ++y)
        {
          for (int x = bx; x < bx + Block; ++x)
          {
            g += got->GetComponent(y * Size + x, c);
            w += want->GetComponent(y * Size + x, c);
            v += variance->GetComponent(y * Size + x, c);
          }
        }
        difference += std::abs(g - w);
        total += std::abs(w);
        noise += std::sqrt(2.0 / 3.141592653589793 * v);
      }
    }
  }
  const double blockError = difference / total, referenceNoise = noise / total;
  std::printf("block error %.2f %% against the reference (its own noise adds about %.2f %%)\n",
    100.0 * blockError, 100.0 * referenceNoise);
  if (argc > 1)
  {
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName((std::string(argv[1]) + "/vtk-scene.vti").c_str());
    writer->Write();
    writer->SetInputData(reference->GetOutput());
    writer->SetFileName((std::string(argv[1]) + "/vtk-scene-reference.vti").c_str());
    writer->Write();
  }
  if (!(blockError <= 0.03 + referenceNoise))
  {
    std::fprintf(stderr, "FAILED: block error %.2f %% above 3 %% + %.2f %%\n", 100.0 * blockError,
      100.0 * referenceNoise);
    return 1;
  }
  std::printf("the VTK-built scene is within 3 %% of the reference path tracer: ok\n");
  return 0;
}
