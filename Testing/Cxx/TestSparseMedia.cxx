// SPDX-License-Identifier: BSD-3-Clause
// A heterogeneous medium's texture in the sparse form (source radiance only
// in the bricks the slice mapper reads, no texture-resolution extinction)
// draws the very image of the dense form, per view and directional (per
// voxel and per fragment), and costs less where the medium fills little of
// its box.
//   TestSparseMedia DIR
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeFloatImageCapture.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeSceneActors.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkBrumeSceneReader.h"
#include "vtkBrumeSliceVolumeMapper.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPropCollection.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkVolume.h"

#include "BrumeVdbWriter.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <string>

namespace
{
int failures = 0;
void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++failures;
  }
}

// A ball of radius 6 voxels at each end of a long box (voxels of 1 m): most
// of the box is empty.
void WriteBalls(const std::string& path)
{
  brume::vdbwriter::Write(path, { brume::vdbwriter::Balls({ 0, 60 }, 6, 0.9f) });
}

void WriteScene(const std::string& path, const std::string& vdb)
{
  std::ofstream out(path);
  out << R"({ "brume_scene": 1, "name": "balls",
  "camera": { "position": [30, 0, 120], "focal_point": [30, 0, 0], "view_up": [0, 1, 0], "view_angle": 45 },
  "media": [ { "name": "balls", "density": { "vdb": ")"
      << vdb << R"(" }, "sigma_a": [0.02, 0.03, 0.04], "sigma_s": [0.5, 0.4, 0.3], "g": 0.5 } ],
  "lights": [ { "type": "directional", "direction": [-0.3, -1, -0.2], "irradiance": [1, 1, 1] } ] })";
}

struct Result
{
  vtkSmartPointer<vtkImageData> Texture; // the medium's partition 0
  vtkSmartPointer<vtkImageData> Image;   // the float capture
};

Result Render(const std::string& scene, bool sparse, bool directional, int evaluation)
{
  vtkNew<vtkBrumeSceneReader> reader;
  reader->SetFileName(scene.c_str());
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputConnection(reader->GetOutputPort());
  tracer->SetNumberOfParticles(30000);
  tracer->SetSeed(3);
  vtkNew<vtkBrumeRadianceReconstruction> reconstruction;
  reconstruction->SetInputConnection(0, reader->GetOutputPort());
  reconstruction->SetInputConnection(1, tracer->GetOutputPort());
  reconstruction->SetEyePosition(30, 0, 120);
  reconstruction->SetRadiosityThreshold(16);
  reconstruction->SetDirectionalRadiance(directional);
  reconstruction->SetSparseMedia(sparse);
  Result r;
  vtkPartitionedDataSetCollection* textures =
    reconstruction->GetExecutive()->Update() ? reconstruction->GetOutput() : nullptr;
  if (!textures || textures->GetNumberOfPartitionedDataSets() < 1)
  {
    return r;
  }
  r.Texture = vtkImageData::SafeDownCast(textures->GetPartitionedDataSet(0)->GetPartition(0));

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(128, 48);
  window->AddRenderer(renderer);
  vtkNew<vtkBrumeSceneActors> actors;
  actors->SetInputData(reconstruction->GetOutput());
  actors->AddToRenderer(renderer);
  vtkPropCollection* props = actors->GetProps();
  props->InitTraversal();
  while (vtkProp* prop = props->GetNextProp())
  {
    if (auto* volume = vtkVolume::SafeDownCast(prop))
    {
      vtkBrumeSliceVolumeMapper::SafeDownCast(volume->GetMapper())
        ->SetDirectionalEvaluation(evaluation);
    }
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(30, 4, 60);
  camera->SetFocalPoint(30, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(30);
  renderer->ResetCameraClippingRange();
  vtkNew<vtkBrumeFloatImageCapture> capture;
  capture->Attach(renderer);
  window->Render();
  r.Image = capture->Capture();
  return r;
}
}

int TestSparseMedia(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::cerr << "usage: TestSparseMedia DIR\n";
    return 2;
  }
  const std::string dir = argv[1];
  WriteBalls(dir + "/balls.vdb");
  WriteScene(dir + "/balls.json", dir + "/balls.vdb");
  const std::string scene = dir + "/balls.json";
  {
    // The reader's check of its scene, the tracer and the reconstruction
    // find one grid: the file is read once a run, not three times.
    const std::size_t loads = vtkBrumeSceneConversion::GetNumberOfOpenVDBLoads();
    const Result once = Render(scene, true, false, vtkBrumeSliceVolumeMapper::PerVoxel);
    const std::size_t read = vtkBrumeSceneConversion::GetNumberOfOpenVDBLoads() - loads;
    Check(once.Texture && read == 1,
      "one run reads the OpenVDB file once, not " + std::to_string(read) + " times");
  }
  struct Case
  {
    const char* Name;
    bool Directional;
    int Evaluation;
  };
  for (const Case& c : { Case{ "per view", false, vtkBrumeSliceVolumeMapper::PerVoxel },
         Case{ "directional, per voxel", true, vtkBrumeSliceVolumeMapper::PerVoxel },
         Case{ "directional, per fragment", true, vtkBrumeSliceVolumeMapper::PerFragment } })
  {
    const std::string name = c.Name;
    const Result dense = Render(scene, false, c.Directional, c.Evaluation);
    const Result sparse = Render(scene, true, c.Directional, c.Evaluation);
    if (!dense.Texture || !sparse.Texture || !dense.Image || !sparse.Image)
    {
      Check(false, name + ": textures and images");
      continue;
    }
    Check(!vtkBrumeSliceVolumeMapper::IsSparseSource(dense.Texture) &&
        dense.Texture->GetCellData()->GetArray(vtkBrumeNames::Extinction) != nullptr,
      name + ": SparseMedia off gives the cell arrays");
    Check(vtkBrumeSliceVolumeMapper::IsSparseSource(sparse.Texture) &&
        sparse.Texture->GetCellData()->GetNumberOfArrays() == 0,
      name + ": SparseMedia on gives the sparse form, no cell arrays");
    Check(vtkBrumeSliceVolumeMapper::ValidateInput(sparse.Texture).empty(),
      name + ": the sparse form is valid input: " +
        vtkBrumeSliceVolumeMapper::ValidateInput(sparse.Texture));

    // The same image, to the bit.
    auto* a = vtkFloatArray::SafeDownCast(dense.Image->GetPointData()->GetScalars());
    auto* b = vtkFloatArray::SafeDownCast(sparse.Image->GetPointData()->GetScalars());
    Check(a && b && a->GetNumberOfValues() == b->GetNumberOfValues(), name + ": image sizes");
    double differing = 0.0, lit = 0.0;
    for (vtkIdType i = 0; a && b && i < std::min(a->GetNumberOfValues(), b->GetNumberOfValues());
         ++i)
    {
      differing += a->GetValue(i) != b->GetValue(i) ? 1.0 : 0.0;
      lit += a->GetValue(i) > 0.f ? 1.0 : 0.0;
    }
    Check(lit > 0.02 * static_cast<double>(a ? a->GetNumberOfValues() : 0),
      name + ": the medium is in the picture");
    Check(differing == 0.0,
      name + ": sparse and dense draw the same image (" + std::to_string(differing) +
        " values differ)");

    // The expanded source radiance is the dense one wherever a brick is
    // stored; bricks between the balls are dropped.
    for (const char* array : { vtkBrumeNames::SourceRadiance, vtkBrumeNames::SourceRadianceSH })
    {
      vtkDataArray* full = dense.Texture->GetCellData()->GetArray(array);
      if (!full)
      {
        Check(std::string(array) == vtkBrumeNames::SourceRadianceSH && !c.Directional,
          name + ": the dense form's " + array);
        continue;
      }
      vtkSmartPointer<vtkDataArray> expanded =
        vtkBrumeSliceVolumeMapper::DenseSourceArray(sparse.Texture, array);
      Check(expanded && expanded->GetNumberOfTuples() == full->GetNumberOfTuples() &&
          expanded->GetNumberOfComponents() == full->GetNumberOfComponents(),
        name + ": " + array + " expands to one tuple per cell");
      if (!expanded || expanded->GetNumberOfValues() != full->GetNumberOfValues())
      {
        continue;
      }
      int pointDims[3];
      sparse.Texture->GetDimensions(pointDims);
      const int cells[3] = { pointDims[0] - 1, pointDims[1] - 1, pointDims[2] - 1 };
      const int bricksX = vtkBrumeSliceVolumeMapper::SourceBricksAlong(cells[0]);
      const int bricksY = vtkBrumeSliceVolumeMapper::SourceBricksAlong(cells[1]);
      int edge[3];
      for (int e = 0; e < 3; ++e)
      {
        edge[e] = vtkBrumeSliceVolumeMapper::SourceBrickEdge(cells[e]);
      }
      vtkDataArray* slots =
        sparse.Texture->GetFieldData()->GetArray(vtkBrumeNames::SourceBrickSlots);
      vtkIdType wrong = 0, dropped = 0, cell = 0;
      for (int k = 0; k < cells[2]; ++k)
        for (int j = 0; j < cells[1]; ++j)
          for (int i = 0; i < cells[0]; ++i, ++cell)
          {
            const vtkIdType brick =
              (static_cast<vtkIdType>(k / edge[2]) * bricksY + j / edge[1]) * bricksX + i / edge[0];
            const bool stored = slots->GetTuple1(brick) >= 0.0;
            dropped += stored ? 0 : 1;
            for (int n = 0; n < full->GetNumberOfComponents(); ++n)
            {
              const double want = stored ? full->GetComponent(cell, n) : 0.0;
              wrong += expanded->GetComponent(cell, n) != want ? 1 : 0;
            }
          }
      Check(wrong == 0,
        name + ": " + array + " expanded is the dense one in stored bricks, 0 elsewhere (" +
          std::to_string(wrong) + " values differ)");
      Check(dropped > 0, name + ": bricks between the balls are dropped");
    }
    const double ratio = static_cast<double>(sparse.Texture->GetActualMemorySize()) /
      static_cast<double>(dense.Texture->GetActualMemorySize());
    std::cout << name << ": sparse texture " << sparse.Texture->GetActualMemorySize()
              << " KiB, dense " << dense.Texture->GetActualMemorySize() << " KiB (" << ratio
              << ")\n";
  }

  // Sparse arrays that do not fit the grid are refused with a reason.
  const Result r = Render(scene, true, false, vtkBrumeSliceVolumeMapper::PerVoxel);
  if (r.Texture)
  {
    vtkNew<vtkImageData> bad;
    bad->DeepCopy(r.Texture);
    vtkDataArray* slots = bad->GetFieldData()->GetArray(vtkBrumeNames::SourceBrickSlots);
    slots->SetTuple1(0, 1e6);
    Check(vtkBrumeSliceVolumeMapper::ValidateInput(bad).find("slot") != std::string::npos,
      "a slot past the samples is refused: " + vtkBrumeSliceVolumeMapper::ValidateInput(bad));
    Check(
      vtkBrumeSliceVolumeMapper::DenseSourceArray(bad, vtkBrumeNames::SourceRadiance) == nullptr,
      "and is not expanded");
    bad->DeepCopy(r.Texture);
    bad->GetFieldData()->GetArray(vtkBrumeNames::SourceBrickSlots)->SetNumberOfTuples(1);
    Check(!vtkBrumeSliceVolumeMapper::ValidateInput(bad).empty(),
      "too few slots for the grid are refused");
    bad->DeepCopy(r.Texture);
    bad->GetFieldData()->RemoveArray(vtkBrumeNames::SourceRadianceBrickSamples);
    Check(
      !vtkBrumeSliceVolumeMapper::ValidateInput(bad).empty(), "slots without samples are refused");
  }
  return failures == 0 ? 0 : 1;
}
