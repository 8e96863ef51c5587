// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeRadianceTextures' objects created: each object's texture sized
// from the run's hits (where they gather: the media's and the planar
// surfaces' pilot grids, summed across processes), each object's owner in
// a distributed run, and the output grids of the direct light.
#include "vtkBrumeRadianceTextures.h"

#include "vtkAlgorithm.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeProcesses.h"
#include "vtkBrumeQuotes.h"
#include "vtkBrumeSMP.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace
{

// The per-vertex texture coordinates of a scene surface, if it has some.
std::vector<std::array<float, 2>> TextureCoordinates(vtkPolyData* polyData)
{
  std::vector<std::array<float, 2>> tcoords;
  vtkDataArray* tc = polyData->GetPointData()->GetTCoords();
  if (tc && tc->GetNumberOfComponents() >= 2)
  {
    tcoords.resize(static_cast<std::size_t>(tc->GetNumberOfTuples()));
    for (vtkIdType i = 0; i < tc->GetNumberOfTuples(); ++i)
    {
      tcoords[i] = { static_cast<float>(tc->GetComponent(i, 0)),
        static_cast<float>(tc->GetComponent(i, 1)) };
    }
  }
  return tcoords;
}
}

std::array<int, 3> vtkBrumeRadianceTextures::FixedResolution(const brume::Vec3& extent, int n)
{
  const float longest = MaxComponent(extent);
  std::array<int, 3> res{ 1, 1, 1 };
  for (int a = 0; a < 3; ++a)
  {
    if (extent[a] > 0.f)
    {
      res[a] = std::max(1, static_cast<int>(std::lround(n * extent[a] / longest)));
    }
  }
  return res;
}

std::unique_ptr<brume::ObjectRadiance> vtkBrumeRadianceTextures::CreateObject(std::size_t o,
  std::size_t hitCount, double concentration, const vtkBrumeReconstructionSettings& settings)
{
  const auto& source = this->Sources[o];
  vtkDataObject* sceneObject =
    this->SceneCollection->GetPartitionedDataSet(source.CollectionIndex)->GetPartition(0);
  vtkDataArray* override = sceneObject->GetFieldData()->GetArray(vtkBrumeNames::TextureResolution);
  const int perObject =
    override && override->GetNumberOfTuples() > 0 ? static_cast<int>(override->GetTuple1(0)) : 0;
  // The object's own resolution, the filter's, or one chosen from its hits.
  bool tooLarge = false;
  auto resolution =
    [&](const brume::Vec3& extent, int global, int maximum, int automatic, double hitsPerTexel)
  {
    const int fixed = perObject > 0 ? perObject : global;
    if (fixed > maximum)
    {
      vtkErrorWithObjectMacro(this->Filter,
        "BrumeTextureResolution of '" << source.Name << "' exceeds " << maximum << ".");
      tooLarge = true;
      return std::array<int, 3>{ 0, 0, 0 };
    }
    return fixed > 0 ? FixedResolution(extent, fixed)
                     : brume::ChooseResolution(extent, hitCount, hitsPerTexel, 4, automatic);
  };
  std::unique_ptr<brume::ObjectRadiance> radiance;
  const int refinement = settings.HistogramRefinement;
  if (!this->Scene.IsMedium(o))
  {
    const brume::Surface& surface = this->Scene.Surfaces[o];
    const auto tcoords = TextureCoordinates(vtkPolyData::SafeDownCast(sceneObject));
    brume::SurfaceChart chart = brume::MakeChart(surface, tcoords.empty() ? nullptr : &tcoords);
    // Evenly lit surfaces keep their texels (brume::MinSurfaceConcentration).
    const double factor = concentration >= brume::MinSurfaceConcentration ? concentration : 1.0;
    const auto res = resolution(brume::Vec3(chart.Width, chart.Height, 0.f),
      settings.SurfaceResolution, MaxSurfaceResolution, 1024, settings.RadiosityThreshold / factor);
    if (!tooLarge)
    {
      radiance.reset(new brume::ObjectRadiance(surface, chart, { res[0], res[1] }, refinement));
    }
  }
  else
  {
    const brume::Medium& medium = this->Scene.Media[o - this->Scene.Surfaces.size()];
    const auto res =
      resolution(medium.Bounds.Extent(), settings.MediumResolution, MaxMediumResolution, 256,
        brume::MediumHitsPerTexel(medium, hitCount, settings.RadiosityThreshold) / concentration);
    if (!tooLarge)
    {
      radiance.reset(new brume::ObjectRadiance(medium, res, refinement));
    }
  }
  return radiance;
}

bool vtkBrumeRadianceTextures::CreateObjects(const vtkBrumeReconstructionSettings& settings,
  const brume::HitArrays& hits, const brume::ObjectHits& groups,
  const vtkBrumeHitConversion::RunInfo& run)
{
  // Resolutions follow the hits of the whole run, on every process; from
  // the first batch of a run traced in batches, its hits scaled to the run
  // (or to the planned count, where more: a progressive run's last step).
  // Then the hits of the media and of the planar surfaces counted over
  // their pilot grids (where the hits are, brume::HitConcentration; a
  // surface's without those the direct light replaces).
  const double scale =
    std::max(run.Particles, settings.PlannedParticles) / (run.EndParticle - run.FirstParticle);
  const std::size_t objects = this->Scene.NumberOfObjects();
  const std::size_t surfaces = this->Scene.Surfaces.size();
  // Where lights were aimed, a hit counts for its particle's emission
  // weight: an object's texels follow the particles a uniform emission
  // would have sent it (as many texels, as much work), and the particles
  // aimed at it lower its noise instead.
  std::vector<vtkTypeInt64> counts(objects);
  for (std::size_t o = 0; o < objects; ++o)
  {
    double hitsOfObject = static_cast<double>(groups.Offset[o + 1] - groups.Offset[o]);
    if (hits.Aim)
    {
      hitsOfObject = 0.0;
      for (std::size_t k = groups.Offset[o]; k < groups.Offset[o + 1]; ++k)
      {
        hitsOfObject += 1.0 / hits.GrowthScale(groups.Index[k]);
      }
    }
    counts[o] = static_cast<vtkTypeInt64>(std::llround(scale * hitsOfObject));
  }
  if (this->Distributed())
  {
    vtkBrumeProcesses::Sum(this->Controller, counts);
  }
  // Surfaces only where the direct light of delta lights is computed: their
  // scattered light gathers around its patches. Lit by emissive surfaces
  // alone (the default scene), walls are lit evenly and skip the pass.
  // Objects no particle reached skip it too (a scene of 65,000 tiles
  // would count 2 GB of empty grids); the counts above are every
  // process's, so every process sizes the same grids.
  const std::size_t deltaLights = settings.DirectLightResolution > 0 && hits.Emitter && hits.Depth
    ? this->Scene.Lights.size()
    : 0;
  const brume::ParallelFor parallelFor = vtkBrumeSMP::ParallelFor();
  std::vector<vtkTypeInt64> pilots;
  std::vector<std::size_t> pilotStart(objects + 1, 0);
  for (std::size_t o = 0; o < objects; ++o)
  {
    const std::uint32_t* index = groups.Index.data() + groups.Offset[o];
    const std::size_t count = groups.Offset[o + 1] - groups.Offset[o];
    std::vector<std::int64_t> pilot;
    brume::PlanarFrame frame;
    if (counts[o] == 0)
    {
      // No hit on any process: no grid (its concentration is 1).
    }
    else if (o >= surfaces)
    {
      brume::CountHitsOverPilotGrid(
        hits, index, count, this->Scene.Media[o - surfaces].Bounds, pilot, parallelFor);
    }
    else if (deltaLights > 0 && this->Scene.Surfaces[o].ComputePlanarFrame(frame))
    {
      brume::CountHitsOverPilotGrid(
        hits, index, count, frame, this->Scene.LightEmitterId(0), deltaLights, pilot, parallelFor);
    }
    pilots.insert(pilots.end(), pilot.begin(), pilot.end());
    pilotStart[o + 1] = pilotStart[o] + pilot.size();
  }
  if (this->Distributed())
  {
    vtkBrumeProcesses::Sum(this->Controller, pilots);
    this->Reduction.reset(new vtkBrumeHistogramReduction(this->Controller));
  }
  // Objects no particle reached, named in one warning (a scene of
  // thousands of small objects would print a line each).
  std::vector<std::string> unlit;
  for (std::size_t o = 0; o < objects; ++o)
  {
    if (counts[o] == 0)
    {
      unlit.push_back(this->Sources[o].Name);
    }
  }
  if (unlit.size() == 1)
  {
    vtkWarningWithObjectMacro(this->Filter,
      << vtkBrumeBoundQuotes("Object '" + unlit[0] +
           "' received no particle: its texture holds only its emission (more particles, or a "
           "light that reaches it)."));
  }
  else if (!unlit.empty())
  {
    std::string names;
    for (std::size_t k = 0; k < std::min<std::size_t>(unlit.size(), 3); ++k)
    {
      names += (k ? ", '" : "'") + unlit[k] + "'";
    }
    if (unlit.size() > 3)
    {
      names += " and " + std::to_string(unlit.size() - 3) + " more";
    }
    vtkWarningWithObjectMacro(
      this->Filter, << vtkBrumeBoundQuotes(std::to_string(unlit.size()) +
                      " objects received no particle (" + names +
                      "): their textures hold only their emission (more particles, or a light that "
                      "reaches them)."));
  }
  for (std::size_t o = 0; o < objects; ++o)
  {
    const double concentration = pilotStart[o + 1] > pilotStart[o]
      ? brume::HitConcentration(
          std::vector<std::int64_t>(pilots.begin() + static_cast<std::ptrdiff_t>(pilotStart[o]),
            pilots.begin() + static_cast<std::ptrdiff_t>(pilotStart[o + 1])))
      : 1.0;
    auto radiance =
      this->CreateObject(o, static_cast<std::size_t>(counts[o]), concentration, settings);
    if (!radiance)
    {
      return false;
    }
    radiance->Distribution().SetReduction(this->Reduction.get());
    radiance->Options().CentroidMatching = settings.CentroidMatching;
    radiance->Options().NativeMemory = static_cast<std::size_t>(settings.NativeMemory);
    this->NativeMemoryOfGPU = settings.NativeMemoryOfGPU;
    this->Objects.push_back(std::move(radiance));
    this->Outputs.push_back(nullptr);
  }
  if (this->Reduction)
  {
    // Each texture estimated by one process, the work shared out evenly:
    // the same resolutions give the same owners on every process.
    std::vector<double> costs;
    for (const auto& object : this->Objects)
    {
      costs.push_back(object->GetLayout().EstimateCost());
    }
    const std::vector<int> owners =
      brume::AssignOwners(costs, this->Reduction->NumberOfProcesses());
    for (std::size_t o = 0; o < objects; ++o)
    {
      this->Objects[o]->Distribution().SetOwner(owners[o]);
    }
  }
  return true;
}

std::array<int, 3> vtkBrumeRadianceTextures::DirectResolution(std::size_t o, int n) const
{
  // n texels along the longest axis, at most the density's own resolution,
  // at most MaxDirectTexels in all, and at most MaxDirectArrivals over the
  // scene's lights. A medium drawn at its own resolution whose mean free
  // path is shorter than its voxels has them cut as far as its particles'
  // texture resolves (brume::MediumVoxelRefinement), with as many texels a
  // voxel in its limit.
  std::array<int, 3> res{ 1, 1, 1 };
  const double lights = static_cast<double>(std::max<std::size_t>(1, this->Scene.Lights.size()));
  double texelLimit = MaxDirectTexels;
  if (this->Scene.IsMedium(o))
  {
    const brume::Medium& medium = this->Scene.Media[o - this->Scene.Surfaces.size()];
    res = FixedResolution(medium.Bounds.Extent(), n);
    if (medium.Density)
    {
      const std::array<int, 3> native = medium.Density->NativeResolution();
      for (int a = 0; a < 3; ++a)
      {
        res[a] = std::max(1, std::min(res[a], native[a]));
      }
      const int cut =
        brume::MediumVoxelRefinement(medium, this->Objects[o]->GetLayout().Resolution);
      if (cut > 1 && res == native &&
        static_cast<double>(res[0]) * res[1] * res[2] <= MaxDirectTexels)
      {
        for (int a = 0; a < 3; ++a)
        {
          res[a] *= cut;
        }
        texelLimit *= static_cast<double>(cut) * cut * cut;
      }
    }
  }
  else
  {
    const brume::SurfaceChart& chart = this->Objects[o]->GetLayout().Chart;
    res = FixedResolution(brume::Vec3(chart.Width, chart.Height, 0.f), n);
  }
  const double limit = std::min(texelLimit, MaxDirectArrivals / lights);
  const double texels = static_cast<double>(res[0]) * res[1] * res[2];
  if (texels > limit)
  {
    const int used = this->Scene.IsMedium(o) ? 3 : 2;
    const double scale = std::pow(limit / texels, 1.0 / used);
    for (int a = 0; a < used; ++a)
    {
      res[a] = std::max(1, static_cast<int>(std::floor(res[a] * scale)));
    }
  }
  return res;
}

void vtkBrumeRadianceTextures::SampleMedia(vtkBrumeReconstructionWork& work)
{
  // Objects are built concurrently, one thread each (ForEachObject): a
  // medium's grid at its own resolution, independent of the particles, is
  // sampled before, on every thread, one medium after the other.
  const brume::ParallelFor parallelFor = vtkBrumeSMP::ParallelFor();
  const std::size_t surfaces = this->Scene.Surfaces.size();
  // The replaced textures' grids that no medium here can take from (a new
  // time step, another volume) go before any is sampled: a large volume's
  // next grid is not made beside the last one.
  auto offers = [](const brume::NativeMediumGrid& grid, const brume::Medium& medium)
  { return grid.SameDensity(medium) || grid.SameField(medium); };
  for (brume::NativeMediumGrid& previous : this->PreviousNatives)
  {
    if (std::none_of(this->Scene.Media.begin(), this->Scene.Media.end(),
          [&](const brume::Medium& medium) { return offers(previous, medium); }))
    {
      previous = brume::NativeMediumGrid();
    }
  }
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    brume::ObjectRadiance& object = *this->Objects[o];
    // The grid of the same density, or of the same scalar field, in the
    // textures replaced.
    for (brume::NativeMediumGrid& previous : this->PreviousNatives)
    {
      if (this->Scene.IsMedium(o) && !previous.Empty() &&
        offers(previous, this->Scene.Media[o - surfaces]))
      {
        object.OfferNative(std::move(previous));
        previous = brume::NativeMediumGrid();
        break;
      }
    }
    object.SampleMedium(parallelFor);
    const brume::NativeMediumGrid& native = object.GetNative();
    work.NativeBricksSampled += static_cast<vtkIdType>(native.GetSampledBricks());
    work.NativeBricksReused += static_cast<vtkIdType>(native.GetReusedBricks());
    if (native.GetCoarsening() > 1)
    {
      const auto& field = native.GetFieldResolution();
      const auto& kept = native.GetResolution();
      vtkWarningWithObjectMacro(
        this->Filter, << vtkBrumeBoundQuotes("Medium '" + this->Sources[o].Name + "' is drawn at " +
                        std::to_string(kept[0]) + " x " + std::to_string(kept[1]) + " x " +
                        std::to_string(kept[2]) + ", its own " + std::to_string(field[0]) + " x " +
                        std::to_string(field[1]) + " x " + std::to_string(field[2]) +
                        " coarsened by " + std::to_string(native.GetCoarsening()) +
                        ": its grids at its own resolution would take more than the " +
                        std::to_string(object.Options().NativeMemory >> 20) +
                        (this->NativeMemoryOfGPU
                            ? " MB the GPU has free for them (GPUMemoryLimit; an explicit "
                              "NativeMemoryLimit, brume: --native-memory, overrides it)."
                            : " MB NativeMemoryLimit (brume: --native-memory).")));
    }
  }
  this->PreviousNatives.clear();
}
