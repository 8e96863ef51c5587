// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneActors.h"

#include "vtkActor.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeSliceVolumeMapper.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerKey.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkStringArray.h"
#include "vtkTexture.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cstring>

vtkStandardNewMacro(vtkBrumeSceneActors);

namespace
{
// A medium's extinction at the density's own resolution (partition 1 of a
// heterogeneous medium), or null.
vtkImageData* NativeExtinction(vtkPartitionedDataSet* pds)
{
  return pds->GetNumberOfPartitions() >= 2 ? vtkImageData::SafeDownCast(pds->GetPartition(1))
                                           : nullptr;
}

bool SameArray(vtkDataArray* x, vtkDataArray* y)
{
  return x && y && x->GetDataType() == y->GetDataType() &&
    x->GetNumberOfComponents() == y->GetNumberOfComponents() &&
    x->GetNumberOfTuples() == y->GetNumberOfTuples() &&
    (x->GetNumberOfValues() == 0 ||
      std::memcmp(x->GetVoidPointer(0), y->GetVoidPointer(0),
        static_cast<std::size_t>(x->GetNumberOfValues()) * x->GetDataTypeSize()) == 0);
}

bool SameArrays(vtkFieldData* a, vtkFieldData* b)
{
  if (!a || !b || a->GetNumberOfArrays() != b->GetNumberOfArrays())
  {
    return a == b;
  }
  for (int i = 0; i < a->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* x = a->GetArray(i);
    if (!x)
    {
      continue; // string arrays (the objects' kinds) are the layout's
    }
    if (!SameArray(x, x->GetName() ? b->GetArray(x->GetName()) : nullptr))
    {
      return false;
    }
  }
  return true;
}

// Whether two data sets of a texture collection hold the same geometry
// and the same bytes (images: extent, origin, spacing; surfaces: points
// and polygons; every point, cell and field data array).
bool SameDataSet(vtkDataObject* a, vtkDataObject* b)
{
  if (a == b)
  {
    return true;
  }
  auto* x = vtkDataSet::SafeDownCast(a);
  auto* y = vtkDataSet::SafeDownCast(b);
  if (!x || !y || x->GetDataObjectType() != y->GetDataObjectType() ||
    !SameArrays(x->GetPointData(), y->GetPointData()) ||
    !SameArrays(x->GetCellData(), y->GetCellData()) ||
    !SameArrays(x->GetFieldData(), y->GetFieldData()))
  {
    return false;
  }
  if (auto* image = vtkImageData::SafeDownCast(x))
  {
    auto* other = vtkImageData::SafeDownCast(y);
    for (int i = 0; i < 6; ++i)
    {
      if (image->GetExtent()[i] != other->GetExtent()[i] ||
        (i < 3 &&
          (image->GetOrigin()[i] != other->GetOrigin()[i] ||
            image->GetSpacing()[i] != other->GetSpacing()[i])))
      {
        return false;
      }
    }
    return true;
  }
  auto* surface = vtkPolyData::SafeDownCast(x);
  auto* other = vtkPolyData::SafeDownCast(y);
  if (!surface || !surface->GetPoints() || !other->GetPoints() || !surface->GetPolys() ||
    !other->GetPolys())
  {
    return false;
  }
  return SameArray(surface->GetPoints()->GetData(), other->GetPoints()->GetData()) &&
    SameArray(
      surface->GetPolys()->GetConnectivityArray(), other->GetPolys()->GetConnectivityArray()) &&
    SameArray(surface->GetPolys()->GetOffsetsArray(), other->GetPolys()->GetOffsetsArray());
}

std::string KindOf(vtkDataObject* data)
{
  return vtkBrumeSceneActors::GetObjectKind(data);
}
}

// What AddToRenderer() made for one object of the input.
struct vtkBrumeSceneActors::Entry
{
  unsigned int Index;
  vtkSmartPointer<vtkTexture> Texture;               // surfaces
  vtkSmartPointer<vtkPolyDataMapper> Surface;        // surfaces
  vtkSmartPointer<vtkBrumeSliceVolumeMapper> Slices; // media
  vtkSmartPointer<vtkVolume> Volume;                 // media
};

std::string vtkBrumeSceneActors::GetObjectKind(vtkDataObject* texture)
{
  auto* kind = texture ? vtkStringArray::SafeDownCast(
                           texture->GetFieldData()->GetAbstractArray(vtkBrumeNames::ObjectKind))
                       : nullptr;
  return kind && kind->GetNumberOfValues() > 0 ? kind->GetValue(0) : std::string();
}

vtkBrumeSceneActors::vtkBrumeSceneActors()
  : Props(vtkSmartPointer<vtkPropCollection>::New())
{
}

vtkBrumeSceneActors::~vtkBrumeSceneActors() = default;

void vtkBrumeSceneActors::SetInputData(vtkPartitionedDataSetCollection* textures)
{
  if (this->Input != textures)
  {
    this->Input = textures;
    this->Modified();
  }
}

vtkPartitionedDataSetCollection* vtkBrumeSceneActors::GetInputData()
{
  return this->Input;
}

vtkInformationKeyMacro(vtkBrumeSceneActors, RADIANCE_PROP, Integer);

namespace
{
// Marks a prop as showing Brume's radiance (RADIANCE_PROP).
void MarkRadiance(vtkProp* prop)
{
  vtkNew<vtkInformation> keys;
  keys->Set(vtkBrumeSceneActors::RADIANCE_PROP(), 1);
  prop->SetPropertyKeys(keys);
}
}

vtkPropCollection* vtkBrumeSceneActors::GetProps()
{
  return this->Props;
}

bool vtkBrumeSceneActors::AddToRenderer(vtkRenderer* renderer)
{
  this->Props->RemoveAllItems();
  this->Entries.clear();
  if (!this->Input || !renderer)
  {
    vtkErrorMacro("AddToRenderer needs an input collection and a renderer.");
    return false;
  }
  for (unsigned int i = 0; i < this->Input->GetNumberOfPartitionedDataSets(); ++i)
  {
    vtkPartitionedDataSet* pds = this->Input->GetPartitionedDataSet(i);
    vtkDataObject* first = pds && pds->GetNumberOfPartitions() > 0 ? pds->GetPartition(0) : nullptr;
    const std::string kind = KindOf(first);
    if (kind == "surface" && pds->GetNumberOfPartitions() >= 2)
    {
      auto* image = vtkImageData::SafeDownCast(first);
      auto* surface = vtkPolyData::SafeDownCast(pds->GetPartition(1));
      if (!image || !surface)
      {
        vtkErrorMacro("Object " << i << " is not a reconstructed surface texture.");
        return false;
      }
      vtkNew<vtkTexture> texture;
      texture->SetInputData(image);
      texture->SetInterpolate(this->Interpolate);
      texture->RepeatOff();
      texture->EdgeClampOn();
      // Float radiance goes to the texture unchanged (no lookup table).
      texture->SetColorModeToDirectScalars();
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(surface);
      mapper->ScalarVisibilityOff();
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      actor->SetTexture(texture);
      // Unlit: the fragment is the texture's radiance.
      actor->GetProperty()->LightingOff();
      actor->GetProperty()->SetColor(this->Exposure, this->Exposure, this->Exposure);
      actor->GetProperty()->SetAmbient(1.0);
      actor->GetProperty()->SetDiffuse(0.0);
      actor->GetProperty()->SetSpecular(0.0);
      // The texture holds the light leaving the front (winding) side: seen
      // from behind, a surface is cut away rather than shown wrongly lit.
      actor->GetProperty()->SetBackfaceCulling(this->BackfaceCulling);
      MarkRadiance(actor);
      renderer->AddActor(actor);
      this->Props->AddItem(actor);
      this->Entries.push_back({ i, texture.Get(), mapper.Get(), nullptr, nullptr });
    }
    else if (kind == "medium")
    {
      if (!this->ShowMedia)
      {
        continue;
      }
      auto* image = vtkImageData::SafeDownCast(first);
      vtkNew<vtkBrumeSliceVolumeMapper> mapper;
      mapper->SetInputData(image);
      mapper->SetExtinctionData(NativeExtinction(pds));
      mapper->SetSliceSpacing(this->SliceSpacing);
      mapper->SetRadianceScale(this->Exposure);
      mapper->SetWriteDepth(this->MediaWriteDepth);
      mapper->SetImageSampleDistance(this->ImageSampleDistance);
      vtkNew<vtkVolume> volume;
      volume->SetMapper(mapper);
      volume->GetProperty()->SetInterpolationType(
        this->Interpolate ? VTK_LINEAR_INTERPOLATION : VTK_NEAREST_INTERPOLATION);
      MarkRadiance(volume);
      renderer->AddVolume(volume);
      this->Props->AddItem(volume);
      this->Entries.push_back({ i, nullptr, nullptr, mapper.Get(), volume.Get() });
    }
    else
    {
      vtkErrorMacro("Object " << i << " is not a Brume radiance texture (no BrumeObjectKind).");
      return false;
    }
  }
  return true;
}

bool vtkBrumeSceneActors::UpdateInputs(vtkPartitionedDataSetCollection* textures)
{
  if (!textures)
  {
    vtkErrorMacro("UpdateInputs needs a texture collection.");
    return false;
  }
  // Check every object first: a mismatch changes nothing.
  for (const Entry& e : this->Entries)
  {
    vtkPartitionedDataSet* pds = e.Index < textures->GetNumberOfPartitionedDataSets()
      ? textures->GetPartitionedDataSet(e.Index)
      : nullptr;
    vtkDataObject* first = pds && pds->GetNumberOfPartitions() > 0 ? pds->GetPartition(0) : nullptr;
    const bool surface = e.Texture && KindOf(first) == "surface" &&
      pds->GetNumberOfPartitions() >= 2 && vtkImageData::SafeDownCast(first) &&
      vtkPolyData::SafeDownCast(pds->GetPartition(1));
    const bool medium = e.Slices && KindOf(first) == "medium" && vtkImageData::SafeDownCast(first);
    if (!surface && !medium)
    {
      vtkErrorMacro("Object " << e.Index << " does not match the props made by AddToRenderer().");
      return false;
    }
  }
  // A prop keeps the data set it shows when the new one holds the same
  // geometry and bytes (textures delivered from a ParaView server are new
  // objects every time): only changed data sets are uploaded again.
  int changed = 0;
  auto take = [&changed](vtkDataObject* shown, vtkDataObject* next)
  {
    if (shown != next && !(shown && next && SameDataSet(next, shown)))
    {
      ++changed;
      return true;
    }
    return false;
  };
  for (const Entry& e : this->Entries)
  {
    vtkPartitionedDataSet* pds = textures->GetPartitionedDataSet(e.Index);
    auto* image = vtkImageData::SafeDownCast(pds->GetPartition(0));
    if (e.Texture)
    {
      if (take(e.Texture->GetInput(), image))
      {
        e.Texture->SetInputData(image);
      }
      auto* surface = vtkPolyData::SafeDownCast(pds->GetPartition(1));
      if (take(e.Surface->GetInput(), surface))
      {
        e.Surface->SetInputData(surface);
      }
    }
    else
    {
      if (take(e.Slices->GetInput(), image))
      {
        e.Slices->SetInputData(image);
      }
      vtkImageData* extinction = NativeExtinction(pds);
      if (take(e.Slices->GetExtinctionData(), extinction))
      {
        e.Slices->SetExtinctionData(extinction);
      }
    }
  }
  this->NumberOfChangedDataSets = changed;
  this->Input = textures;
  return true;
}

void vtkBrumeSceneActors::SetMediaVisibility(bool visible)
{
  for (const Entry& e : this->Entries)
  {
    if (e.Volume)
    {
      e.Volume->SetVisibility(visible);
    }
  }
}

void vtkBrumeSceneActors::SetSurfaceVisibility(bool visible)
{
  // The surfaces' props are the actors; the media's are volumes.
  this->Props->InitTraversal();
  while (vtkProp* prop = this->Props->GetNextProp())
  {
    if (vtkActor::SafeDownCast(prop))
    {
      prop->SetVisibility(visible);
    }
  }
}

void vtkBrumeSceneActors::ApplyToMedia(const std::function<void(vtkBrumeSliceVolumeMapper*)>& apply)
{
  for (const Entry& e : this->Entries)
  {
    if (e.Slices)
    {
      apply(e.Slices);
    }
  }
  this->Modified();
}

void vtkBrumeSceneActors::SetSliceSpacing(double spacing)
{
  if (this->SliceSpacing != spacing)
  {
    this->SliceSpacing = spacing;
    this->ApplyToMedia([=](vtkBrumeSliceVolumeMapper* m) { m->SetSliceSpacing(spacing); });
  }
}

void vtkBrumeSceneActors::SetMediaWriteDepth(bool write)
{
  if (this->MediaWriteDepth != write)
  {
    this->MediaWriteDepth = write;
    this->ApplyToMedia([=](vtkBrumeSliceVolumeMapper* m) { m->SetWriteDepth(write); });
  }
}

double vtkBrumeSceneActors::GetLastImageSampleDistance()
{
  double distance = 1.0;
  for (const Entry& e : this->Entries)
  {
    if (e.Slices)
    {
      distance = std::max(distance, e.Slices->GetLastImageSampleDistance());
    }
  }
  return distance;
}

void vtkBrumeSceneActors::SetImageSampleDistance(double distance)
{
  distance = std::min(16.0, std::max(1.0, distance));
  if (this->ImageSampleDistance != distance)
  {
    this->ImageSampleDistance = distance;
    this->ApplyToMedia([=](vtkBrumeSliceVolumeMapper* m) { m->SetImageSampleDistance(distance); });
  }
}

void vtkBrumeSceneActors::SetInterpolate(bool interpolate)
{
  if (this->Interpolate == interpolate)
  {
    return;
  }
  this->Interpolate = interpolate;
  for (const Entry& e : this->Entries)
  {
    if (e.Texture)
    {
      e.Texture->SetInterpolate(interpolate);
    }
    if (e.Volume)
    {
      e.Volume->GetProperty()->SetInterpolationType(
        interpolate ? VTK_LINEAR_INTERPOLATION : VTK_NEAREST_INTERPOLATION);
    }
  }
  this->Modified();
}

void vtkBrumeSceneActors::SetBackfaceCulling(bool cull)
{
  if (this->BackfaceCulling == cull)
  {
    return;
  }
  this->BackfaceCulling = cull;
  this->Props->InitTraversal();
  while (vtkProp* prop = this->Props->GetNextProp())
  {
    if (auto* actor = vtkActor::SafeDownCast(prop))
    {
      actor->GetProperty()->SetBackfaceCulling(cull);
    }
  }
  this->Modified();
}

void vtkBrumeSceneActors::SetExposure(double exposure)
{
  exposure = exposure > 0.0 ? exposure : 0.0;
  if (this->Exposure == exposure)
  {
    return;
  }
  this->Exposure = exposure;
  this->Props->InitTraversal();
  while (vtkProp* prop = this->Props->GetNextProp())
  {
    if (auto* actor = vtkActor::SafeDownCast(prop))
    {
      actor->GetProperty()->SetColor(exposure, exposure, exposure);
    }
  }
  for (const Entry& e : this->Entries)
  {
    if (e.Slices)
    {
      e.Slices->SetRadianceScale(exposure);
    }
  }
  this->Modified();
}

void vtkBrumeSceneActors::RemoveFromRenderer(vtkRenderer* renderer)
{
  if (renderer)
  {
    this->Props->InitTraversal();
    while (vtkProp* prop = this->Props->GetNextProp())
    {
      renderer->RemoveViewProp(prop);
    }
  }
  this->Props->RemoveAllItems();
  this->Entries.clear();
}

void vtkBrumeSceneActors::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ShowMedia: " << this->ShowMedia << "\n";
  os << indent << "BackfaceCulling: " << this->BackfaceCulling << "\n";
  os << indent << "SliceSpacing: " << this->SliceSpacing << "\n";
  os << indent << "MediaWriteDepth: " << this->MediaWriteDepth << "\n";
  os << indent << "ImageSampleDistance: " << this->ImageSampleDistance << "\n";
  os << indent << "Interpolate: " << this->Interpolate << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
  os << indent << "Input: " << this->Input.Get() << "\n";
}
