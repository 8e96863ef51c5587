// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeHitConversion.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedIntArray.h"
#include "vtkUnsignedShortArray.h"

#include <cmath>
#include <cstdint>

const char* const vtkBrumeHitConversion::DirectionName = vtkBrumeNames::Direction;
const char* const vtkBrumeHitConversion::FluxName = vtkBrumeNames::Flux;
const char* const vtkBrumeHitConversion::ObjectIdName = vtkBrumeNames::ObjectId;
const char* const vtkBrumeHitConversion::EmitterIdName = vtkBrumeNames::EmitterId;
const char* const vtkBrumeHitConversion::DepthName = vtkBrumeNames::Depth;
const char* const vtkBrumeHitConversion::TriangleIdName = vtkBrumeNames::TriangleId;
const char* const vtkBrumeHitConversion::AimName = vtkBrumeNames::Aim;
const char* const vtkBrumeHitConversion::AimWeightsName = vtkBrumeNames::AimWeights;
const char* const vtkBrumeHitConversion::TotalPowerName = vtkBrumeNames::TotalPower;
const char* const vtkBrumeHitConversion::NumberOfParticlesName = vtkBrumeNames::NumberOfParticles;
const char* const vtkBrumeHitConversion::FirstParticleName = vtkBrumeNames::FirstParticle;
const char* const vtkBrumeHitConversion::EndParticleName = vtkBrumeNames::EndParticle;
const char* const vtkBrumeHitConversion::SeedName = vtkBrumeNames::Seed;

namespace
{
// A float view of a 3-component array: the array itself, or a float copy.
const float* FloatView(vtkDataArray* a, std::vector<float>& copy)
{
  if (auto* f = vtkFloatArray::SafeDownCast(a))
  {
    return f->GetPointer(0);
  }
  copy.resize(static_cast<std::size_t>(a->GetNumberOfValues()));
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    copy[i] = static_cast<float>(a->GetVariantValue(i).ToDouble());
  }
  return copy.data();
}
}

vtkSmartPointer<vtkPolyData> vtkBrumeHitConversion::HitsToPolyData(
  const std::vector<brume::Hit>& hits, const brume::Vec3& totalPower, long long particles)
{
  const auto n = static_cast<vtkIdType>(hits.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(n);
  vtkNew<vtkFloatArray> direction;
  direction->SetName(DirectionName);
  direction->SetNumberOfComponents(3);
  direction->SetNumberOfTuples(n);
  vtkNew<vtkFloatArray> flux;
  flux->SetName(FluxName);
  flux->SetNumberOfComponents(3);
  flux->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedShortArray> object;
  object->SetName(ObjectIdName);
  object->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedShortArray> emitter;
  emitter->SetName(EmitterIdName);
  emitter->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedCharArray> depth;
  depth->SetName(DepthName);
  depth->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedIntArray> triangle;
  triangle->SetName(TriangleIdName);
  triangle->SetNumberOfTuples(n);
  auto* p = static_cast<float*>(points->GetVoidPointer(0));
  float* d = direction->GetPointer(0);
  float* f = flux->GetPointer(0);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const brume::Hit& h = hits[i];
    for (int c = 0; c < 3; ++c)
    {
      p[3 * i + c] = h.Position[c];
      d[3 * i + c] = h.Direction[c];
      f[3 * i + c] = h.Flux[c];
    }
    object->SetValue(i, h.Object);
    emitter->SetValue(i, h.Emitter);
    depth->SetValue(i, h.Depth);
    triangle->SetValue(i, h.Triangle);
  }
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->SetPoints(points);
  output->GetPointData()->AddArray(direction);
  output->GetPointData()->AddArray(flux);
  output->GetPointData()->AddArray(object);
  output->GetPointData()->AddArray(emitter);
  output->GetPointData()->AddArray(depth);
  output->GetPointData()->AddArray(triangle);
  vtkNew<vtkDoubleArray> power;
  power->SetName(TotalPowerName);
  power->SetNumberOfComponents(3);
  power->InsertNextTuple3(totalPower.x, totalPower.y, totalPower.z);
  output->GetFieldData()->AddArray(power);
  vtkNew<vtkDoubleArray> count;
  count->SetName(NumberOfParticlesName);
  count->InsertNextValue(static_cast<double>(particles));
  output->GetFieldData()->AddArray(count);
  return output;
}

std::string vtkBrumeHitConversion::HitsFromPolyData(
  vtkPolyData* data, std::vector<brume::Hit>& hits)
{
  hits.clear();
  if (!data)
  {
    return "no particle hits were given";
  }
  const vtkIdType n = data->GetNumberOfPoints();
  vtkPointData* pd = data->GetPointData();
  auto* direction = vtkFloatArray::SafeDownCast(pd->GetArray(DirectionName));
  auto* flux = vtkFloatArray::SafeDownCast(pd->GetArray(FluxName));
  auto* object = vtkUnsignedShortArray::SafeDownCast(pd->GetArray(ObjectIdName));
  auto* emitter = vtkUnsignedShortArray::SafeDownCast(pd->GetArray(EmitterIdName));
  auto* depth = vtkUnsignedCharArray::SafeDownCast(pd->GetArray(DepthName));
  auto* triangle = vtkUnsignedIntArray::SafeDownCast(pd->GetArray(TriangleIdName));
  auto* aim = vtkUnsignedCharArray::SafeDownCast(pd->GetArray(AimName));
  if (n > 0 &&
    (!direction || !flux || !object || direction->GetNumberOfComponents() != 3 ||
      flux->GetNumberOfComponents() != 3))
  {
    return "the particle hits lack the float[3] 'Direction' and 'Flux' or the unsigned short "
           "'ObjectId' point arrays";
  }
  hits.resize(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    brume::Hit& h = hits[i];
    double p[3];
    data->GetPoint(i, p);
    for (int c = 0; c < 3; ++c)
    {
      h.Position[c] = static_cast<float>(p[c]);
      h.Direction[c] = direction->GetValue(3 * i + c);
      h.Flux[c] = flux->GetValue(3 * i + c);
    }
    h.Object = object->GetValue(i);
    h.Emitter = emitter ? emitter->GetValue(i) : 0;
    h.Depth = depth ? depth->GetValue(i) : 0;
    h.Aim = aim && aim->GetNumberOfTuples() == n ? aim->GetValue(i) : 0;
    h.Padding[0] = h.Padding[1] = 0;
    h.Triangle = triangle ? triangle->GetValue(i) : 0;
  }
  return {};
}

std::string vtkBrumeHitConversion::ReadHits(
  vtkPolyData* data, brume::HitArrays& hits, RunInfo& run, std::vector<float>& positionCopy)
{
  hits = brume::HitArrays();
  run = RunInfo();
  if (!data)
  {
    return "No particle hits were given";
  }
  vtkPointData* pd = data->GetPointData();
  auto* direction = vtkFloatArray::SafeDownCast(pd->GetArray(DirectionName));
  auto* flux = vtkFloatArray::SafeDownCast(pd->GetArray(FluxName));
  auto* objectIds = vtkUnsignedShortArray::SafeDownCast(pd->GetArray(ObjectIdName));
  auto* triangleIds = vtkUnsignedIntArray::SafeDownCast(pd->GetArray(TriangleIdName));
  auto* emitterIds = vtkUnsignedShortArray::SafeDownCast(pd->GetArray(EmitterIdName));
  auto* depths = vtkUnsignedCharArray::SafeDownCast(pd->GetArray(DepthName));
  const vtkIdType n = data->GetNumberOfPoints();
  if (n > 0 &&
    (!direction || !flux || !objectIds || direction->GetNumberOfComponents() != 3 ||
      flux->GetNumberOfComponents() != 3 || direction->GetNumberOfTuples() != n ||
      flux->GetNumberOfTuples() != n || objectIds->GetNumberOfTuples() != n))
  {
    return "Invalid particle hits: they lack the float[3] 'Direction' and 'Flux' or the "
           "unsigned short 'ObjectId' point arrays";
  }
  if (n > static_cast<vtkIdType>(UINT32_MAX))
  {
    return "More than 2^32 particle hits: reconstruct them in parts";
  }
  vtkFieldData* fields = data->GetFieldData();
  vtkDataArray* power = fields ? fields->GetArray(TotalPowerName) : nullptr;
  vtkDataArray* count = fields ? fields->GetArray(NumberOfParticlesName) : nullptr;
  if (!power || !count || power->GetNumberOfComponents() != 3 || power->GetNumberOfTuples() < 1 ||
    count->GetNumberOfTuples() < 1 || !(count->GetTuple1(0) >= 1.0))
  {
    return "The particle hits lack the 'TotalPower' and 'NumberOfParticles' field arrays";
  }
  power->GetTuple(0, run.TotalPower);
  run.Particles = count->GetTuple1(0);
  auto fieldValue = [&](const char* name)
  {
    vtkDataArray* a = fields->GetArray(name);
    return a && a->GetNumberOfTuples() > 0 ? a->GetTuple1(0) : 0.0;
  };
  run.FirstParticle = fieldValue(FirstParticleName);
  run.EndParticle = fields->GetArray(EndParticleName) ? fieldValue(EndParticleName) : run.Particles;
  if (!(run.FirstParticle >= 0.0 && run.FirstParticle < run.EndParticle &&
        run.EndParticle <= run.Particles))
  {
    return "The particle hits' 'FirstParticle' and 'EndParticle' do not make a range of "
           "[0, NumberOfParticles]";
  }
  run.Seed = fieldValue(SeedName);
  hits.Count = static_cast<std::size_t>(n);
  if (n > 0)
  {
    hits.Position = FloatView(data->GetPoints()->GetData(), positionCopy);
    hits.Direction = direction->GetPointer(0);
    hits.Flux = flux->GetPointer(0);
    hits.Object = objectIds->GetPointer(0);
    hits.Triangle =
      triangleIds && triangleIds->GetNumberOfTuples() == n ? triangleIds->GetPointer(0) : nullptr;
    hits.Emitter =
      emitterIds && emitterIds->GetNumberOfTuples() == n ? emitterIds->GetPointer(0) : nullptr;
    hits.Depth = depths && depths->GetNumberOfTuples() == n ? depths->GetPointer(0) : nullptr;
  }
  auto* aim = vtkUnsignedCharArray::SafeDownCast(pd->GetArray(AimName));
  if (n > 0 && aim)
  {
    // Every hit's class must have its weight: emitters in range, classes 0-2.
    vtkDataArray* weights = fields->GetArray(AimWeightsName);
    if (aim->GetNumberOfTuples() != n || !emitterIds || emitterIds->GetNumberOfTuples() != n ||
      !weights || weights->GetNumberOfComponents() != 3)
    {
      return "The particle hits' 'Aim' needs one value per hit, with 'EmitterId' and the "
             "double[3] field array 'AimWeights'";
    }
    const vtkIdType emitters = weights->GetNumberOfTuples();
    run.GrowthScales.resize(3 * static_cast<std::size_t>(emitters));
    for (vtkIdType e = 0; e < emitters; ++e)
    {
      for (int c = 0; c < 3; ++c)
      {
        const double w = weights->GetComponent(e, c);
        if (!(w > 0.0) || !std::isfinite(w))
        {
          return "The particle hits' 'AimWeights' holds a weight that is not positive and finite";
        }
        run.GrowthScales[3 * e + c] = 1.0 / w;
      }
    }
    const unsigned char* a = aim->GetPointer(0);
    const unsigned short* e = emitterIds->GetPointer(0);
    for (vtkIdType i = 0; i < n; ++i)
    {
      if (a[i] > 2 || e[i] >= emitters)
      {
        return "The particle hits' 'Aim' or 'EmitterId' has a value without its 'AimWeights'";
      }
    }
    hits.Aim = a;
    hits.GrowthScales = run.GrowthScales.data();
  }
  return {};
}
