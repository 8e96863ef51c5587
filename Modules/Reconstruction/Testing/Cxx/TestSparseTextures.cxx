// SPDX-License-Identifier: BSD-3-Clause
// A medium's extinction at its own resolution costs memory in proportion to
// where its density is, not to its box: two OpenVDB grids with the same
// active voxels, one in a box eight times as large, cost the same (within
// 10 %), and the sparse grid expands to the density's own values.
//   TestSparseTextures DIR
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeRadianceConversion.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeSceneReader.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkSmartPointer.h"

#include "BrumeVdbWriter.h"

#include <array>
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

// Two balls of radius 6 voxels (density falling to 0 at the edge), their
// centres `apart` voxels apart along x; voxels of 1 m.
void WriteBalls(const std::string& path, int apart)
{
  brume::vdbwriter::Write(path, { brume::vdbwriter::Balls({ 0, apart }, 6, 0.5f) });
}

void WriteScene(const std::string& path, const std::string& vdb)
{
  std::ofstream out(path);
  out << R"({ "brume_scene": 1, "name": "balls",
  "camera": { "position": [0, 0, 400], "focal_point": [0, 0, 0], "view_up": [0, 1, 0], "view_angle": 30 },
  "render": { "particles": 20000, "size": [64, 64], "threshold": 32 },
  "media": [ { "name": "balls", "density": { "vdb": ")"
      << vdb << R"(" }, "sigma_a": [0.01, 0.01, 0.01], "sigma_s": [0.3, 0.3, 0.3] } ],
  "lights": [ { "type": "directional", "direction": [0, -1, 0], "irradiance": [1, 1, 1] } ] })";
}

struct Textures
{
  vtkSmartPointer<vtkImageData> Extinction;
  vtkIdType Bytes = 0; // the extinction grid's arrays, as brume render --timings counts them
};

// A scene file read, traced (20,000 particles) and reconstructed.
struct Chain
{
  vtkNew<vtkBrumeSceneReader> Reader;
  vtkNew<vtkBrumeLightTracer> Tracer;
  vtkNew<vtkBrumeRadianceReconstruction> Reconstruction;
  Chain()
  {
    this->Tracer->SetInputConnection(this->Reader->GetOutputPort());
    this->Tracer->SetNumberOfParticles(20000);
    this->Reconstruction->SetInputConnection(0, this->Reader->GetOutputPort());
    this->Reconstruction->SetInputConnection(1, this->Tracer->GetOutputPort());
  }
};

Textures Reconstruct(const std::string& scene)
{
  Chain chain;
  chain.Reader->SetFileName(scene.c_str());
  vtkBrumeRadianceReconstruction* reconstruction = chain.Reconstruction;
  Textures t;
  if (!reconstruction->GetExecutive()->Update())
  {
    Check(false, scene + ": reconstruction");
    return t;
  }
  auto* out = vtkPartitionedDataSetCollection::SafeDownCast(reconstruction->GetOutputDataObject(0));
  vtkPartitionedDataSet* medium = out->GetPartitionedDataSet(0);
  t.Extinction = vtkImageData::SafeDownCast(medium->GetPartition(1));
  Check(t.Extinction != nullptr, scene + ": the medium's extinction at its own resolution");
  if (t.Extinction)
  {
    t.Bytes = t.Extinction->GetActualMemorySize();
  }
  return t;
}
}

// A scene file's OpenVDB medium edited between two executions of the same
// filters: its grid is read once (the conversions find it again while the
// textures hold it), so an albedo edit keeps the medium's shadow rays and
// an opacity edit of a classified grid keeps the bricks it left alone.
void TestEdits(const std::string& dir)
{
  auto write = [&](const std::string& name, const std::string& medium)
  {
    std::ofstream out(dir + "/" + name);
    out << R"({ "brume_scene": 1, "name": "edited balls",
  "camera": { "position": [0, 0, 400], "focal_point": [0, 0, 0], "view_up": [0, 1, 0], "view_angle": 30 },
  "render": { "particles": 20000, "size": [64, 64], "threshold": 32 },
  "media": [ { "name": "balls", "density": { "vdb": ")"
        << dir << "/near.vdb\"" << medium << R"( } ],
  "lights": [ { "type": "directional", "direction": [0, -1, 0], "irradiance": [1, 1, 1] } ] })";
  };
  write("albedo-1.json", R"( }, "sigma_a": [0.01, 0.01, 0.01], "sigma_s": [0.3, 0.3, 0.3])");
  write("albedo-2.json", R"( }, "sigma_a": [0.11, 0.11, 0.11], "sigma_s": [0.2, 0.2, 0.2])");
  const std::string function = R"(, "transfer_function": { "unit_distance": 1, "opacity": )";
  write("opacity-1.json",
    function + R"([[0, 0], [0.1, 0.2], [0.4, 0.9]] } }, "albedo": [0.9, 0.9, 0.9])");
  write("opacity-2.json",
    function + R"([[0, 0], [0.1, 0.2], [0.4, 0.5]] } }, "albedo": [0.9, 0.9, 0.9])");
  for (const std::string kind : { "albedo", "opacity" })
  {
    Chain chain;
    vtkBrumeRadianceReconstruction* reconstruction = chain.Reconstruction;
    bool ran = true;
    for (const char* step : { "-1.json", "-2.json" })
    {
      chain.Reader->SetFileName((dir + "/" + kind + step).c_str());
      ran = ran && reconstruction->GetExecutive()->Update();
    }
    Check(ran, kind + " edit: both scenes reconstruct");
    std::cout << kind << " edit: " << reconstruction->GetNumberOfNativeBricksSampled()
              << " bricks sampled, " << reconstruction->GetNumberOfNativeBricksReused() << " kept, "
              << reconstruction->GetNumberOfDirectLightsKept() << " direct lights kept\n";
    if (kind == "albedo")
    {
      Check(reconstruction->GetNumberOfDirectLightsKept() == 1,
        "an albedo edit of an OpenVDB medium keeps its shadow rays");
    }
    else
    {
      Check(reconstruction->GetNumberOfNativeBricksReused() > 0 &&
          reconstruction->GetNumberOfDirectLightsKept() == 0,
        "an opacity edit of a classified OpenVDB grid keeps the bricks it left alone");
    }
  }
}

// A ball whose mean free path is half a voxel at its densest (sigma_t 4
// at density 0.5, voxels of 1 m) has its voxels cut in two along each axis
// in the source radiance's grid, its direct light's and the particles'
// texture's, where the particles' texture is finer than its voxels (many
// particles, a low threshold): the light changes within its lit skin. With
// few particles, or a thin ball, the grid is its voxels'.
void TestDenseVoxelsCut(const std::string& dir)
{
  auto sourceDims = [&](const std::string& name, const char* sigmaS, int particles)
  {
    std::ofstream(dir + "/" + name) << R"({ "brume_scene": 1, "name": "one ball",
  "camera": { "position": [0, 0, 80], "focal_point": [0, 0, 0], "view_up": [0, 1, 0], "view_angle": 30 },
  "render": { "particles": 20000, "size": [64, 64], "threshold": 8 },
  "media": [ { "name": "ball", "density": { "vdb": ")"
                                    << dir << R"(/one.vdb" }, "sigma_a": [0, 0, 0], "sigma_s": [)"
                                    << sigmaS << ", " << sigmaS << ", " << sigmaS << R"(] } ],
  "lights": [ { "type": "directional", "direction": [0, -1, 0], "irradiance": [1, 1, 1] } ] })";
    Chain chain;
    chain.Reader->SetFileName((dir + "/" + name).c_str());
    chain.Tracer->SetNumberOfParticles(particles);
    std::array<int, 6> dims{};
    if (!chain.Reconstruction->GetExecutive()->Update())
    {
      Check(false, name + ": reconstruction");
      return dims;
    }
    auto* out =
      vtkPartitionedDataSetCollection::SafeDownCast(chain.Reconstruction->GetOutputDataObject(0));
    auto* source = vtkImageData::SafeDownCast(out->GetPartitionedDataSet(0)->GetPartition(0));
    auto* extinction = vtkImageData::SafeDownCast(out->GetPartitionedDataSet(0)->GetPartition(1));
    if (source && extinction)
    {
      source->GetDimensions(dims.data());
      extinction->GetDimensions(dims.data() + 3);
    }
    std::cout << name << ", " << particles << " particles: source radiance " << dims[0] - 1 << " x "
              << dims[1] - 1 << " x " << dims[2] - 1 << " cells, extinction " << dims[3] - 1
              << " x " << dims[4] - 1 << " x " << dims[5] - 1 << "\n";
    return dims;
  };
  brume::vdbwriter::Write(dir + "/one.vdb", { brume::vdbwriter::Balls({ 0 }, 6, 0.5f) });
  auto cut = [](const std::array<int, 6>& d, int by)
  {
    return d[5] > 1 && d[0] - 1 == by * (d[3] - 1) && d[1] - 1 == by * (d[4] - 1) &&
      d[2] - 1 == by * (d[5] - 1);
  };
  const std::array<int, 6> dense = sourceDims("dense.json", "4", 400000);
  Check(cut(dense, 2), "a dense ball's voxels are cut in two where the particles resolve them");
  const std::array<int, 6> few = sourceDims("dense.json", "4", 2000);
  Check(cut(few, 1), "a dense ball's voxels are whole where its particles' texels are larger");
  const std::array<int, 6> thin = sourceDims("thin.json", "0.3", 400000);
  Check(cut(thin, 1), "a thin ball's voxels are whole");
}

int TestSparseTextures(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::cerr << "usage: TestSparseTextures DIR\n";
    return 2;
  }
  const std::string dir = argv[1];
  WriteBalls(dir + "/near.vdb", 28);
  WriteBalls(dir + "/far.vdb", 28 * 12);
  WriteScene(dir + "/near.json", dir + "/near.vdb");
  WriteScene(dir + "/far.json", dir + "/far.vdb");
  const Textures near = Reconstruct(dir + "/near.json");
  const Textures far = Reconstruct(dir + "/far.json");
  if (!near.Extinction || !far.Extinction)
  {
    return 1;
  }
  int nd[3], fd[3];
  near.Extinction->GetDimensions(nd);
  far.Extinction->GetDimensions(fd);
  const double boxRatio = static_cast<double>(fd[0] - 1) * (fd[1] - 1) * (fd[2] - 1) /
    (static_cast<double>(nd[0] - 1) * (nd[1] - 1) * (nd[2] - 1));
  std::cout << "cells in the box: near " << (nd[0] - 1) * (nd[1] - 1) * (nd[2] - 1) << ", far "
            << (fd[0] - 1) * (fd[1] - 1) * (fd[2] - 1) << " (" << boxRatio << "x); extinction "
            << near.Bytes << " KiB and " << far.Bytes << " KiB\n";
  Check(boxRatio > 8.0, "the far grid's box is many times the near one's");
  const double ratio = static_cast<double>(far.Bytes) / static_cast<double>(near.Bytes);
  Check(std::abs(ratio - 1.0) <= 0.10,
    "the same active voxels cost the same within 10 % (far / near = " + std::to_string(ratio) +
      ")");

  // The sparse grid holds the density's own values: at the ball's centre
  // voxel, sigma_t = 0.31 * 0.5; far from both balls, 0.
  vtkSmartPointer<vtkImageData> dense = vtkBrumeRadianceConversion::DenseExtinction(far.Extinction);
  Check(dense != nullptr, "the sparse grid expands");
  if (dense)
  {
    double centre[3] = { 0.0, 0.0, 0.0 };
    int ijk[3];
    double pcoords[3];
    Check(dense->ComputeStructuredCoordinates(centre, ijk, pcoords) != 0, "the centre is inside");
    const vtkIdType id = dense->ComputeCellId(ijk);
    vtkDataArray* sigmaT = dense->GetCellData()->GetArray(vtkBrumeNames::Extinction);
    Check(std::abs(sigmaT->GetComponent(id, 0) - 0.31 * 0.5) < 1e-6,
      "sigma_t at a ball's centre voxel is 0.31 * 0.5, not " +
        std::to_string(sigmaT->GetComponent(id, 0)));
    double middle[3] = { 168.0, 0.0, 0.0 };
    Check(dense->ComputeStructuredCoordinates(middle, ijk, pcoords) != 0, "the middle is inside");
    Check(
      sigmaT->GetComponent(dense->ComputeCellId(ijk), 0) == 0.0, "sigma_t between the balls is 0");
    Check(static_cast<vtkIdType>(dense->GetActualMemorySize()) > 8 * far.Bytes,
      "the dense grid costs many times the sparse one");
  }
  TestEdits(dir);
  TestDenseVoxelsCut(dir);
  return failures == 0 ? 0 : 1;
}
