// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneActors.h"

#include "vtkActor.h"
#include "vtkBrumeArrayBytes.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeSliceVolumeMapper.h"
#include "vtkBrumeSurfaceAtlas.h"
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
#include <cmath>
#include <unordered_map>

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
    if (!vtkBrumeArrayBytes::Same(x, x->GetName() ? b->GetArray(x->GetName()) : nullptr))
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
  return vtkBrumeArrayBytes::Same(surface->GetPoints()->GetData(), other->GetPoints()->GetData()) &&
    vtkBrumeArrayBytes::Same(
      surface->GetPolys()->GetConnectivityArray(), other->GetPolys()->GetConnectivityArray()) &&
    vtkBrumeArrayBytes::Same(
      surface->GetPolys()->GetOffsetsArray(), other->GetPolys()->GetOffsetsArray());
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
  vtkSmartPointer<vtkTexture> Texture;               // surfaces with an actor of their own
  vtkSmartPointer<vtkPolyDataMapper> Surface;        // surfaces with an actor of their own
  vtkSmartPointer<vtkBrumeSliceVolumeMapper> Slices; // media
  vtkSmartPointer<vtkVolume> Volume;                 // media
  int Atlas = -1;                                    // surfaces in an atlas: which,
  std::size_t Member = 0;                            // and their place in it
};

// An atlas of surfaces and its actor.
struct vtkBrumeSceneActors::Atlas
{
  vtkBrumeSceneActorsInternals::SurfaceAtlas Data;
  vtkSmartPointer<vtkTexture> Texture;
  vtkSmartPointer<vtkPolyDataMapper> Mapper;
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

vtkActor* vtkBrumeSceneActors::AddSurfaceActor(vtkRenderer* renderer, vtkImageData* image,
  vtkPolyData* surface, vtkTexture* texture, vtkPolyDataMapper* mapper)
{
  texture->SetInputData(image);
  texture->SetInterpolate(this->Interpolate);
  texture->RepeatOff();
  texture->EdgeClampOn();
  // Float radiance goes to the texture unchanged (no lookup table).
  texture->SetColorModeToDirectScalars();
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
  return actor;
}

bool vtkBrumeSceneActors::AddToRenderer(vtkRenderer* renderer)
{
  this->Props->RemoveAllItems();
  this->Entries.clear();
  this->Atlases.clear();
  this->Renderer = renderer;
  if (!this->Input || !renderer)
  {
    vtkErrorMacro("AddToRenderer needs an input collection and a renderer.");
    return false;
  }
  // Surfaces share atlases when the scene has many that can.
  const unsigned int objects = this->Input->GetNumberOfPartitionedDataSets();
  auto surfaceData = [this](unsigned int i, vtkImageData*& image, vtkPolyData*& surface)
  {
    vtkPartitionedDataSet* pds = this->Input->GetPartitionedDataSet(i);
    vtkDataObject* first = pds && pds->GetNumberOfPartitions() > 0 ? pds->GetPartition(0) : nullptr;
    image = vtkImageData::SafeDownCast(first);
    surface = KindOf(first) == "surface" && pds->GetNumberOfPartitions() >= 2
      ? vtkPolyData::SafeDownCast(pds->GetPartition(1))
      : nullptr;
    return KindOf(first);
  };
  int shareable = 0;
  for (unsigned int i = 0; i < objects; ++i)
  {
    vtkImageData* image;
    vtkPolyData* surface;
    surfaceData(i, image, surface);
    shareable += vtkBrumeSceneActorsInternals::SurfaceAtlas::Accepts(image, surface) ? 1 : 0;
  }
  const bool atlases = shareable > 0 && shareable >= this->SurfaceAtlasMinimum;
  std::vector<vtkBrumeSceneActorsInternals::AtlasMember> members;
  for (unsigned int i = 0; i < objects; ++i)
  {
    vtkPartitionedDataSet* pds = this->Input->GetPartitionedDataSet(i);
    vtkImageData* image;
    vtkPolyData* surface;
    const std::string kind = surfaceData(i, image, surface);
    if (kind == "surface" && pds->GetNumberOfPartitions() >= 2)
    {
      if (!image || !surface)
      {
        vtkErrorMacro("Object " << i << " is not a reconstructed surface texture.");
        return false;
      }
      Entry entry{ i, nullptr, nullptr, nullptr, nullptr };
      if (atlases && vtkBrumeSceneActorsInternals::SurfaceAtlas::Accepts(image, surface))
      {
        members.push_back({ i, image, surface });
        entry.Atlas = -2; // placed below
      }
      else
      {
        entry.Texture = vtkSmartPointer<vtkTexture>::New();
        entry.Surface = vtkSmartPointer<vtkPolyDataMapper>::New();
        this->AddSurfaceActor(renderer, image, surface, entry.Texture, entry.Surface);
      }
      this->Entries.push_back(entry);
    }
    else if (kind == "medium")
    {
      if (!this->ShowMedia)
      {
        continue;
      }
      vtkNew<vtkBrumeSliceVolumeMapper> mapper;
      mapper->SetInputData(image);
      mapper->SetExtinctionData(NativeExtinction(pds));
      mapper->SetSliceSpacing(this->SliceSpacing);
      mapper->SetSliceSpacingScale(this->SliceSpacingScale);
      mapper->SetSlabSampling(this->SlabSampling);
      mapper->SetExtinctionDepthTolerance(this->ExtinctionDepthTolerance);
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
  // Each atlas is one actor; the entries learn where their surface went.
  std::unordered_map<unsigned int, std::size_t> entryOf;
  for (std::size_t e = 0; e < this->Entries.size(); ++e)
  {
    entryOf[this->Entries[e].Index] = e;
  }
  for (auto& data : vtkBrumeSceneActorsInternals::SurfaceAtlas::Pack(std::move(members)))
  {
    Atlas atlas{ std::move(data), vtkSmartPointer<vtkTexture>::New(),
      vtkSmartPointer<vtkPolyDataMapper>::New() };
    this->AddSurfaceActor(
      renderer, atlas.Data.GetImage(), atlas.Data.GetGeometry(), atlas.Texture, atlas.Mapper);
    for (std::size_t k = 0; k < atlas.Data.GetMembers().size(); ++k)
    {
      Entry& entry = this->Entries[entryOf[atlas.Data.GetMembers()[k].Index]];
      entry.Atlas = static_cast<int>(this->Atlases.size());
      entry.Member = k;
    }
    this->Atlases.push_back(std::move(atlas));
  }
  return true;
}

int vtkBrumeSceneActors::GetNumberOfSurfaceAtlases()
{
  return static_cast<int>(this->Atlases.size());
}

vtkImageData* vtkBrumeSceneActors::GetSurfaceAtlas(int k)
{
  return k >= 0 && k < static_cast<int>(this->Atlases.size()) ? this->Atlases[k].Data.GetImage()
                                                              : nullptr;
}

int vtkBrumeSceneActors::FirstMismatch(vtkPartitionedDataSetCollection* textures)
{
  const unsigned int objects = textures->GetNumberOfPartitionedDataSets();
  auto kind = [](vtkPartitionedDataSetCollection* c, unsigned int i)
  {
    vtkPartitionedDataSet* pds =
      i < c->GetNumberOfPartitionedDataSets() ? c->GetPartitionedDataSet(i) : nullptr;
    return KindOf(pds && pds->GetNumberOfPartitions() > 0 ? pds->GetPartition(0) : nullptr);
  };
  // Objects without props (media not shown) keep their kind too.
  if (this->Input && this->Input != textures)
  {
    const unsigned int before = this->Input->GetNumberOfPartitionedDataSets();
    for (unsigned int i = 0; i < std::max(objects, before); ++i)
    {
      if (i >= objects || i >= before || kind(textures, i) != kind(this->Input, i))
      {
        return static_cast<int>(i);
      }
    }
  }
  for (const Entry& e : this->Entries)
  {
    vtkPartitionedDataSet* pds =
      e.Index < objects ? textures->GetPartitionedDataSet(e.Index) : nullptr;
    vtkDataObject* first = pds && pds->GetNumberOfPartitions() > 0 ? pds->GetPartition(0) : nullptr;
    const bool surface = (e.Texture || e.Atlas >= 0) && KindOf(first) == "surface" &&
      pds->GetNumberOfPartitions() >= 2 && vtkImageData::SafeDownCast(first) &&
      vtkPolyData::SafeDownCast(pds->GetPartition(1));
    const bool medium = e.Slices && KindOf(first) == "medium" && vtkImageData::SafeDownCast(first);
    if (!surface && !medium)
    {
      return static_cast<int>(e.Index);
    }
  }
  return -1;
}

vtkBrumeSliceVolumeMapper* vtkBrumeSceneActors::GetMediumMapper(unsigned int index)
{
  for (const Entry& e : this->Entries)
  {
    if (e.Index == index && e.Slices)
    {
      return e.Slices;
    }
  }
  return nullptr;
}

bool vtkBrumeSceneActors::CanUpdateInputs(vtkPartitionedDataSetCollection* textures)
{
  return textures && this->Renderer && this->FirstMismatch(textures) < 0;
}

bool vtkBrumeSceneActors::UpdateInputs(vtkPartitionedDataSetCollection* textures)
{
  if (!textures)
  {
    vtkErrorMacro("UpdateInputs needs a texture collection.");
    return false;
  }
  // Check every object first: a mismatch changes nothing.
  const int mismatch = this->FirstMismatch(textures);
  if (mismatch >= 0)
  {
    vtkErrorMacro("Object " << mismatch << " does not match the props made by AddToRenderer().");
    return false;
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
  // Surfaces in an atlas: new texels are copied into their slots; a new
  // size or surface builds the props again.
  bool rebuild = false;
  std::vector<std::pair<const Entry*, vtkImageData*>> texels;
  for (const Entry& e : this->Entries)
  {
    vtkPartitionedDataSet* pds = textures->GetPartitionedDataSet(e.Index);
    auto* image = vtkImageData::SafeDownCast(pds->GetPartition(0));
    if (e.Atlas >= 0)
    {
      const auto& member = this->Atlases[e.Atlas].Data.GetMembers()[e.Member];
      auto* surface = vtkPolyData::SafeDownCast(pds->GetPartition(1));
      const bool newTexels = take(member.Image, image);
      if (take(member.Surface, surface) ||
        (newTexels &&
          (!std::equal(
             image->GetDimensions(), image->GetDimensions() + 3, member.Image->GetDimensions()) ||
            !vtkBrumeSceneActorsInternals::SurfaceAtlas::Accepts(image, surface))))
      {
        rebuild = true;
      }
      else if (newTexels)
      {
        texels.emplace_back(&e, image);
      }
    }
    else if (e.Texture)
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
  if (rebuild)
  {
    if (!this->Renderer)
    {
      vtkErrorMacro("The renderer the props were added to is gone.");
      return false;
    }
    vtkRenderer* renderer = this->Renderer;
    this->RemoveFromRenderer(renderer);
    this->Input = textures;
    if (!this->AddToRenderer(renderer))
    {
      return false;
    }
  }
  else
  {
    for (const auto& [e, image] : texels)
    {
      this->Atlases[e->Atlas].Data.SetTexels(e->Member, image);
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

void vtkBrumeSceneActors::SetSliceSpacingScale(double scale)
{
  scale = std::isnan(scale) ? 1.0 : std::min(16.0, std::max(1.0, scale));
  if (this->SliceSpacingScale != scale)
  {
    this->SliceSpacingScale = scale;
    this->ApplyToMedia([=](vtkBrumeSliceVolumeMapper* m) { m->SetSliceSpacingScale(scale); });
  }
}

void vtkBrumeSceneActors::SetExtinctionDepthTolerance(double tolerance)
{
  tolerance = tolerance > 0.0 ? tolerance : 0.0; // NaN too: floats kept exactly
  if (this->ExtinctionDepthTolerance != tolerance)
  {
    this->ExtinctionDepthTolerance = tolerance;
    this->ApplyToMedia(
      [=](vtkBrumeSliceVolumeMapper* m) { m->SetExtinctionDepthTolerance(tolerance); });
    this->Modified();
  }
}

void vtkBrumeSceneActors::SetSlabSampling(bool sampling)
{
  if (this->SlabSampling != sampling)
  {
    this->SlabSampling = sampling;
    this->ApplyToMedia([=](vtkBrumeSliceVolumeMapper* m) { m->SetSlabSampling(sampling); });
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
  for (const Atlas& atlas : this->Atlases)
  {
    atlas.Texture->SetInterpolate(interpolate);
  }
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
  this->Atlases.clear();
  if (renderer == this->Renderer)
  {
    this->Renderer = nullptr;
  }
}

void vtkBrumeSceneActors::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ShowMedia: " << this->ShowMedia << "\n";
  os << indent << "BackfaceCulling: " << this->BackfaceCulling << "\n";
  os << indent << "SliceSpacing: " << this->SliceSpacing << "\n";
  os << indent << "SliceSpacingScale: " << this->SliceSpacingScale << "\n";
  os << indent << "SlabSampling: " << this->SlabSampling << "\n";
  os << indent << "ExtinctionDepthTolerance: " << this->ExtinctionDepthTolerance << "\n";
  os << indent << "MediaWriteDepth: " << this->MediaWriteDepth << "\n";
  os << indent << "ImageSampleDistance: " << this->ImageSampleDistance << "\n";
  os << indent << "Interpolate: " << this->Interpolate << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
  os << indent << "SurfaceAtlasMinimum: " << this->SurfaceAtlasMinimum << "\n";
  os << indent << "Surface atlases: " << this->Atlases.size() << "\n";
  os << indent << "Input: " << this->Input.Get() << "\n";
}
