// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeRadianceReconstruction.h"

#include "vtkBrumeSceneConversion.h"
#include "vtkCellData.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStringArray.h"

#include "brume/Reconstruction.h"

#include <cmath>
#include <sstream>

vtkStandardNewMacro(vtkBrumeRadianceReconstruction);

namespace
{
constexpr int MaxSurfaceResolution = 4096;
constexpr int MaxMediumResolution = 512;

void AddVec3(vtkFieldData* fd, const char* name, const brume::Vec3& v)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->InsertNextTuple3(v.x, v.y, v.z);
  fd->AddArray(a);
}

void AddKind(vtkFieldData* fd, const char* kind)
{
  vtkNew<vtkStringArray> a;
  a->SetName("BrumeObjectKind");
  a->InsertNextValue(kind);
  fd->AddArray(a);
}

vtkSmartPointer<vtkFloatArray> NewRGB(const char* name, vtkIdType tuples)
{
  auto a = vtkSmartPointer<vtkFloatArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->SetNumberOfTuples(tuples);
  return a;
}

// Resolution along the longer axis `n`, the others in proportion.
std::array<int, 3> FixedResolution(const brume::Vec3& extent, int n)
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
}

vtkBrumeRadianceReconstruction::vtkBrumeRadianceReconstruction()
{
  this->SetNumberOfInputPorts(2);
}

int vtkBrumeRadianceReconstruction::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(),
    port == 0 ? "vtkPartitionedDataSetCollection" : "vtkPolyData");
  return 1;
}

int vtkBrumeRadianceReconstruction::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  auto* sceneData = vtkPartitionedDataSetCollection::GetData(inputVector[0], 0);
  auto* hitData = vtkPolyData::GetData(inputVector[1], 0);
  auto* output = vtkPartitionedDataSetCollection::GetData(outputVector, 0);

  if (!(this->RadiosityThreshold > 0.0) || !std::isfinite(this->RadiosityThreshold))
  {
    vtkErrorMacro(
      "RadiosityThreshold must be positive and finite, not " << this->RadiosityThreshold << ".");
    return 0;
  }
  if (this->SurfaceResolution < 0 || this->SurfaceResolution > MaxSurfaceResolution ||
    this->MediumResolution < 0 || this->MediumResolution > MaxMediumResolution)
  {
    vtkErrorMacro("SurfaceResolution must be in [0, "
      << MaxSurfaceResolution << "] and MediumResolution in [0, " << MaxMediumResolution << "].");
    return 0;
  }
  if (this->HistogramRefinement < 1 || this->HistogramRefinement > 16)
  {
    vtkErrorMacro(
      "HistogramRefinement must be in [1, 16], not " << this->HistogramRefinement << ".");
    return 0;
  }
  const brume::Vec3 eye(static_cast<float>(this->EyePosition[0]),
    static_cast<float>(this->EyePosition[1]), static_cast<float>(this->EyePosition[2]));
  if (!brume::IsFinite(eye))
  {
    vtkErrorMacro("EyePosition must be finite.");
    return 0;
  }

  brume::Scene scene;
  std::vector<vtkBrumeSceneConversion::ObjectSource> sources;
  std::string error = vtkBrumeSceneConversion::ToScene(sceneData, scene, &sources);
  if (!error.empty())
  {
    vtkErrorMacro("Invalid scene: " << error << ".");
    return 0;
  }
  std::vector<brume::Hit> hits;
  error = vtkBrumeSceneConversion::HitsFromPolyData(hitData, hits);
  if (!error.empty())
  {
    vtkErrorMacro("Invalid particle hits: " << error << ".");
    return 0;
  }
  vtkFieldData* hitFields = hitData->GetFieldData();
  vtkDataArray* powerArray = hitFields ? hitFields->GetArray("TotalPower") : nullptr;
  vtkDataArray* countArray = hitFields ? hitFields->GetArray("NumberOfParticles") : nullptr;
  if (!powerArray || !countArray || powerArray->GetNumberOfComponents() != 3 ||
    powerArray->GetNumberOfTuples() < 1 || countArray->GetNumberOfTuples() < 1 ||
    !(countArray->GetTuple1(0) >= 1.0))
  {
    vtkErrorMacro("The particle hits lack the 'TotalPower' and 'NumberOfParticles' field arrays.");
    return 0;
  }
  const double* power = powerArray->GetTuple3(0);
  const double particleFlux = (power[0] + power[1] + power[2]) / 3.0 / countArray->GetTuple1(0);
  const double threshold = this->RadiosityThreshold * particleFlux;

  // Group the hits by object (counting sort, stable).
  const std::size_t objects = scene.NumberOfObjects();
  std::vector<std::size_t> offsets(objects + 1, 0);
  for (const brume::Hit& h : hits)
  {
    if (h.Object >= objects)
    {
      vtkErrorMacro("A particle hit refers to object " << h.Object << " but the scene has "
                                                       << objects << " objects.");
      return 0;
    }
    ++offsets[h.Object + 1];
  }
  for (std::size_t o = 0; o < objects; ++o)
  {
    offsets[o + 1] += offsets[o];
  }
  std::vector<brume::Hit> sorted(hits.size());
  {
    std::vector<std::size_t> cursor(offsets.begin(), offsets.end() - 1);
    for (const brume::Hit& h : hits)
    {
      sorted[cursor[h.Object]++] = h;
    }
  }
  std::vector<brume::Hit>().swap(hits);

  output->SetNumberOfPartitionedDataSets(sceneData->GetNumberOfPartitionedDataSets());
  const int refinement = this->HistogramRefinement;
  for (std::size_t o = 0; o < objects; ++o)
  {
    const brume::Hit* objectHits = sorted.data() + offsets[o];
    const std::size_t count = offsets[o + 1] - offsets[o];
    vtkNew<vtkPartitionedDataSet> pds;
    if (!scene.IsMedium(o))
    {
      const brume::Surface& surface = scene.Surfaces[o];
      brume::PlanarFrame frame;
      if (!surface.ComputePlanarFrame(frame))
      {
        vtkErrorMacro("Surface '" << surface.Name
                                  << "' is not planar: only planar surfaces are supported yet.");
        return 0;
      }
      const brume::Vec3 extent(Length(frame.U), Length(frame.V), 0.f);
      const auto res = this->SurfaceResolution > 0
        ? FixedResolution(extent, this->SurfaceResolution)
        : brume::ChooseResolution(extent, count, this->RadiosityThreshold, 4, 1024);
      brume::SurfaceRadiance radiance(surface, frame, { res[0], res[1] }, refinement);
      radiance.AddHits(objectHits, count);
      radiance.Finalize();
      const vtkIdType texels = static_cast<vtkIdType>(res[0]) * res[1];
      auto values = NewRGB("Radiance", texels);
      float* out = values->GetPointer(0);
      vtkSMPTools::For(0, res[1],
        [&](vtkIdType begin, vtkIdType end)
        {
          radiance.Estimate(static_cast<std::size_t>(begin) * res[0],
            static_cast<std::size_t>(end) * res[0], threshold, out + 3 * begin * res[0]);
        });
      vtkNew<vtkImageData> texture;
      texture->SetDimensions(res[0], res[1], 1);
      texture->SetSpacing(1.0 / res[0], 1.0 / res[1], 1.0);
      texture->SetOrigin(0.5 / res[0], 0.5 / res[1], 0.0);
      texture->GetPointData()->SetScalars(values);
      AddVec3(texture->GetFieldData(), "BrumeTextureOrigin", frame.Origin);
      AddVec3(texture->GetFieldData(), "BrumeTextureU", frame.U);
      AddVec3(texture->GetFieldData(), "BrumeTextureV", frame.V);
      AddKind(texture->GetFieldData(), "surface");

      // The surface itself, with coordinates that map the texture.
      auto* source = vtkPolyData::SafeDownCast(
        sceneData->GetPartitionedDataSet(sources[o].CollectionIndex)->GetPartition(0));
      vtkNew<vtkPolyData> mapped;
      mapped->ShallowCopy(source);
      vtkNew<vtkFloatArray> tcoords;
      tcoords->SetName("TextureCoordinates");
      tcoords->SetNumberOfComponents(2);
      tcoords->SetNumberOfTuples(mapped->GetNumberOfPoints());
      const float uu = Dot(frame.U, frame.U), vv = Dot(frame.V, frame.V);
      for (vtkIdType i = 0; i < mapped->GetNumberOfPoints(); ++i)
      {
        double p[3];
        mapped->GetPoint(i, p);
        const brume::Vec3 d = brume::Vec3(static_cast<float>(p[0]), static_cast<float>(p[1]),
                                static_cast<float>(p[2])) -
          frame.Origin;
        tcoords->SetTuple2(i, Dot(d, frame.U) / uu, Dot(d, frame.V) / vv);
      }
      mapped->GetPointData()->SetTCoords(tcoords);
      AddKind(mapped->GetFieldData(), "surface");
      pds->SetNumberOfPartitions(2);
      pds->SetPartition(0, texture);
      pds->SetPartition(1, mapped);
    }
    else
    {
      const brume::Medium& medium = scene.Media[o - scene.Surfaces.size()];
      const brume::Vec3 extent = medium.Bounds.Extent();
      const auto res = this->MediumResolution > 0
        ? FixedResolution(extent, this->MediumResolution)
        : brume::ChooseResolution(extent, count, this->RadiosityThreshold, 4, 256);
      brume::MediumRadiance radiance(medium, res, refinement);
      radiance.AddHits(objectHits, count, eye);
      radiance.Finalize();
      const vtkIdType slice = static_cast<vtkIdType>(res[0]) * res[1];
      const vtkIdType voxels = slice * res[2];
      auto values = NewRGB("SourceRadiance", voxels);
      auto extinction = NewRGB("Extinction", voxels);
      float* out = values->GetPointer(0);
      float* sigma = extinction->GetPointer(0);
      vtkSMPTools::For(0, res[2],
        [&](vtkIdType begin, vtkIdType end)
        {
          radiance.Estimate(static_cast<std::size_t>(begin * slice),
            static_cast<std::size_t>(end * slice), threshold, out + 3 * begin * slice,
            sigma + 3 * begin * slice);
        });
      vtkNew<vtkImageData> texture;
      texture->SetDimensions(res[0] + 1, res[1] + 1, res[2] + 1);
      texture->SetOrigin(medium.Bounds.lower.x, medium.Bounds.lower.y, medium.Bounds.lower.z);
      texture->SetSpacing(extent.x / res[0], extent.y / res[1], extent.z / res[2]);
      texture->GetCellData()->SetScalars(values);
      texture->GetCellData()->AddArray(extinction);
      AddKind(texture->GetFieldData(), "medium");
      pds->SetNumberOfPartitions(1);
      pds->SetPartition(0, texture);
    }
    const unsigned int index = sources[o].CollectionIndex;
    output->SetPartitionedDataSet(index, pds);
    output->GetMetaData(index)->Set(vtkCompositeDataSet::NAME(), sources[o].Name.c_str());
    this->UpdateProgress(static_cast<double>(o + 1) / static_cast<double>(objects));
  }
  return 1;
}

void vtkBrumeRadianceReconstruction::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EyePosition: (" << this->EyePosition[0] << ", " << this->EyePosition[1] << ", "
     << this->EyePosition[2] << ")\n";
  os << indent << "RadiosityThreshold: " << this->RadiosityThreshold << "\n";
  os << indent << "SurfaceResolution: " << this->SurfaceResolution << "\n";
  os << indent << "MediumResolution: " << this->MediumResolution << "\n";
  os << indent << "HistogramRefinement: " << this->HistogramRefinement << "\n";
}
