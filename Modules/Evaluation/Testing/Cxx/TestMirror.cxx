// SPDX-License-Identifier: BSD-3-Clause
// Mirrors at display time against the reference path tracer: the default
// scene with its floor a mirror (the room and its fog seen in the floor),
// with its side walls mirrors facing each other (reflections of
// reflections, up to brume::MirrorReflection::MaxDepth bounces), with its
// floor a sharp glossy Phong surface (exponent 1000, its lobe cast), and
// with a mirror floor showing a sharp glossy back wall.
// Density estimation alone shows a black floor for the mirror (its texture
// holds only what it emits) and coloured speckles for the lobe. Over blocks of 4 x 4 pixels, the
// pipeline's image and the reference's agree within four standard errors of the reference plus 4 %
// for the pipeline's own noise and smoothing. Left out: the outer ring of blocks (the room's
// silhouette, where a block mixes a wall and the space beyond it pixel by pixel) and the blocks
// where the light panel itself is seen (a pixel brighter than 1: its edges cross pixels that the
// rasterizer samples at their centres and the path tracer over their area,
// mirrors or not).
//   TestMirror [OUTPUT_DIR]
#include "EvaluationTestScenes.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeReferencePathTracer.h"
#include "vtkBrumeRenderWindowSelection.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkBrumeTimedPipeline.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPointData.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{
constexpr int Size = 32;
constexpr int Block = 4;

// The default scene (or `scene`) with the named surfaces of `type`
// ("mirror" or "phong"), diffuse reflectance rhoD, specular rhoS and Phong
// exponent e.
vtkSmartPointer<vtkPartitionedDataSetCollection> MirrorScene(
  const std::vector<std::string>& mirrors, const char* type, double rhoD, double rhoS, double e,
  vtkSmartPointer<vtkPartitionedDataSetCollection> scene = nullptr)
{
  if (!scene)
  {
    vtkNew<vtkBrumeDefaultSceneSource> source;
    source->Update();
    scene = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
    scene->DeepCopy(source->GetOutput());
  }
  for (unsigned int i = 0; i < scene->GetNumberOfPartitionedDataSets(); ++i)
  {
    const char* name =
      scene->HasMetaData(i) ? scene->GetMetaData(i)->Get(vtkCompositeDataSet::NAME()) : nullptr;
    if (!name || std::find(mirrors.begin(), mirrors.end(), name) == mirrors.end())
    {
      continue;
    }
    vtkFieldData* fd = scene->GetPartitionedDataSet(i)->GetPartition(0)->GetFieldData();
    vtkNew<vtkStringArray> material;
    material->SetName(vtkBrumeNames::Material);
    material->InsertNextValue(type);
    fd->RemoveArray(vtkBrumeNames::Material);
    fd->AddArray(material);
    const double diffuse[3] = { rhoD, rhoD, rhoD }, specular[3] = { rhoS, rhoS, rhoS };
    fd->RemoveArray(vtkBrumeNames::Reflectance);
    fd->RemoveArray(vtkBrumeNames::Specular);
    fd->RemoveArray(vtkBrumeNames::Exponent);
    vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::Reflectance, diffuse, 3);
    vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::Specular, specular, 3);
    vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::Exponent, &e, 1);
  }
  return scene;
}

// Whether a pixel of the block is brighter than `level` (channel mean).
bool Brighter(vtkImageData* image, int bx, int by, double level)
{
  vtkDataArray* radiance = image->GetPointData()->GetArray(vtkBrumeNames::Radiance);
  for (int y = by; y < by + Block; ++y)
  {
    for (int x = bx; x < bx + Block; ++x)
    {
      const vtkIdType p = y * Size + x;
      const double mean = (radiance->GetComponent(p, 0) + radiance->GetComponent(p, 1) +
                            radiance->GetComponent(p, 2)) /
        3.0;
      if (mean > level)
      {
        return true;
      }
    }
  }
  return false;
}

bool Compare(
  const char* name, vtkPartitionedDataSetCollection* scene, int argc, char* argv[], int spp = 2048)
{
  vtkNew<vtkBrumeReferencePathTracer> reference;
  reference->SetInputData(scene);
  reference->SetSize(Size, Size);
  reference->SetSamplesPerPixel(spp);
  reference->SetSeed(3);
  vtkNew<vtkBrumeTimedPipeline> pipeline;
  pipeline->SetInputData(scene);
  pipeline->SetSize(Size, Size);
  pipeline->SetNumberOfParticles(1000000);
  pipeline->MeasureNewViewOff();
  if (reference->GetExecutive()->Update() != 1 || pipeline->GetExecutive()->Update() != 1)
  {
    std::cerr << "FAILED: the images of '" << name << "' were not made\n";
    return false;
  }
  if (argc > 1)
  {
    SaveImage(argv[1], std::string("mirror-") + name + "-reference", reference->GetOutput());
    SaveImage(argv[1], std::string("mirror-") + name, pipeline->GetOutput());
  }
  bool ok = true;
  double worst = 0.0;
  std::printf("%s\n%6s %6s %12s %12s %12s\n", name, "x", "y", "reference", "pipeline", "band");
  for (int by = Block; by < Size - Block; by += Block)
  {
    for (int bx = Block; bx < Size - Block; bx += Block)
    {
      if (Brighter(reference->GetOutput(), bx, by, 1.0))
      {
        continue; // the light panel itself
      }
      double error = 0.0;
      const double want = BlockMean(reference->GetOutput(), bx, by, Block, &error);
      const double got = BlockMean(pipeline->GetOutput(), bx, by, Block, nullptr);
      const double band = 4.0 * error + 0.04 * want;
      const bool pass = std::abs(got - want) <= band;
      ok = ok && pass;
      worst = std::max(worst, std::abs(got - want) / want);
      std::printf(
        "%6d %6d %12.5g %12.5g %12.3g%s\n", bx, by, want, got, band, pass ? "" : "  FAIL");
    }
  }
  std::printf("%s: largest block difference %.2f %%\n", name, 100.0 * worst);
  return ok;
}
}

int TestMirror(int argc, char* argv[])
{
  if (!*vtkBrumeRenderWindowSelection::GetInstalled())
  {
    std::cerr << "no render window (no X display and no EGL): skipped\n";
    return 125;
  }
  const bool floor = Compare("floor", MirrorScene({ "floor" }, "mirror", 0, 0.9, 1), argc, argv);
  const bool walls =
    Compare("walls", MirrorScene({ "left", "right" }, "mirror", 0, 0.8, 1), argc, argv);
  const bool glossy =
    Compare("glossy", MirrorScene({ "floor" }, "phong", 0.2, 0.6, 1000), argc, argv);
  // A mirror floor showing a sharp glossy back wall (Data/scenes/mirror-fog.json):
  // the wall's lobe is cast toward the eye mirrored by the floor, its rays
  // looking at the fog from that point mirrored by the wall. The path
  // tracer's glossy paths are noisy: 8,192 spp bring its error under what
  // a fog looked up from the wrong point costs (17.5 % in a block).
  const bool both = Compare("mirror and glossy",
    MirrorScene({ "back" }, "phong", 0.3, 0.5, 1000, MirrorScene({ "floor" }, "mirror", 0, 0.9, 1)),
    argc, argv, 8192);
  if (!floor || !walls || !glossy || !both)
  {
    std::cerr << "FAILED: a block is outside the reference's band\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
