// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeOpenGLSliceVolumeMapper.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerKey.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include "vtkBrumeOpenGLSliceVolumeMapperInternals.h"
#include "vtkBrumeSliceVolumeShader.h"
#include "vtkBrumeSliceVolumeVS.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkBrumeOpenGLSliceVolumeMapper);
vtkInformationKeyMacro(vtkBrumeOpenGLSliceVolumeMapper, FRAME, Integer);
vtkInformationKeyMacro(vtkBrumeOpenGLSliceVolumeMapper, DRAWN_FRAME, Integer);

namespace
{
using Vec = std::array<double, 3>;

double Dot(const Vec& a, const Vec& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Vec Transform(vtkMatrix4x4* m, const Vec& p)
{
  const double in[4] = { p[0], p[1], p[2], 1.0 };
  double out[4];
  m->MultiplyPoint(in, out);
  return { out[0] / out[3], out[1] / out[3], out[2] / out[3] };
}

// The twelve edges of a box, as pairs of corner indices (bit i: upper on axis i).
// The most optical depths a slab of the automatic spacing holds at the
// largest sigma_t of an extinction grid of its own (CutSlices).
constexpr double MaxSlabDepth = 2.0;
// The most extinction samples a slab takes along a ray: its thickness over
// the extinction's own finest cell, so that structures one cell thin are
// integrated across the slab (the automatic spacing spans at most four).
constexpr int MaxSlabSamples = 8;
// The window's desired update rate (frames a second) from which a draw is
// interactive: one sample a slab.
constexpr double InteractiveUpdateRate = 1.0;

constexpr int BoxEdges[12][2] = { { 0, 1 }, { 2, 3 }, { 4, 5 }, { 6, 7 }, { 0, 2 }, { 1, 3 },
  { 4, 6 }, { 5, 7 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 } };

// Counts the renderer's frames in its information (StartEvent).
void CountFrame(vtkObject* caller, unsigned long, void*, void*)
{
  vtkInformation* info = static_cast<vtkRenderer*>(caller)->GetInformation();
  const int frame = info->Has(vtkBrumeOpenGLSliceVolumeMapper::FRAME())
    ? info->Get(vtkBrumeOpenGLSliceVolumeMapper::FRAME())
    : 0;
  info->Set(vtkBrumeOpenGLSliceVolumeMapper::FRAME(), frame + 1);
}

// A corner of a slice's polygon, and its angle about the polygon's centre.
struct SlicePoint
{
  Vec World, Data;
  double Angle;
};

// World units per data unit along data axis a.
double AxisScale(vtkMatrix4x4* model, int a)
{
  return std::sqrt(model->GetElement(0, a) * model->GetElement(0, a) +
    model->GetElement(1, a) * model->GetElement(1, a) +
    model->GetElement(2, a) * model->GetElement(2, a));
}

// A grid's smallest cell side, in world units.
double SmallestCell(vtkMatrix4x4* model, vtkImageData* grid)
{
  double cell = VTK_DOUBLE_MAX;
  const double* spacing = grid->GetSpacing();
  for (int a = 0; a < 3; ++a)
  {
    cell = std::min(cell, AxisScale(model, a) * spacing[a]);
  }
  return cell;
}

// The slices' spacing, in world units, when SliceSpacing is 0 (automatic).
// Slices half a voxel of the source apart but no closer than 1/40 of the
// medium's longest side, and at most four cells of the extinction's own
// grid apart. Each slab of the sum is exact for its sigma_t (sampled
// across the slice's plane at full resolution); only the source radiance
// is sampled along the view at the slices, and it is smooth along most
// rays. Fine source grids (direct light computed per texel) would
// otherwise cost hundreds of slices: god-rays.json, 64^3 source, 128x128
// supersampled 4x under llvmpipe, block error 4.74 % half a voxel apart
// (0.27 s a frame), 4.72 % two voxels (85 ms), 5.27 % eight (43 ms); at
// 1/40 of the side, 3.58 % against 3.60 % at 1/48 (threshold 64), a 512 x
// 512 view 103 against 120 ms, and the WDAS cloud 2.08 against 2.06 %,
// 69 against 77 ms. Sources of 20 voxels or fewer a side keep half a
// voxel. The
// WDAS cloud, 128x128: 3.77 % one fine cell apart, 3.79 % four, 3.80 %
// half a source voxel; a new 512x512 view 165, 53 and 46 ms.
// In an optically thick medium a slab several optical depths deep shows
// the source at its slice, up to half the slab inside the medium's lit
// skin, not at the skin itself: the dragon (sigma_t up to 20.4 per metre,
// 3.6 optical depths a slab by the rules above) came out too dark, its
// single scattering alone 1.73 % from the path tracer's. So slabs hold at
// most MaxSlabDepth optical depths at the largest sigma_t, but are no
// thinner than one fine cell: the dragon's are then one cell (1.08 %;
// half a cell or a quarter no better, 1.12 and 1.19 %). smoke.vdb (3.5
// optical depths a slab before), two seeds: block error 1.06, 1.12 % ->
// 0.99, 1.10 %, per-pixel 2.21, 2.28 % -> 2.04, 2.15 %, a 512x512 frame
// 152 -> 196 ms; one optical depth is no better (2.01, 2.12 %) at three
// times the frame's cost. The clouds stay under two optical depths a
// slab and keep their slices.
// `extinction` is the extinction's own grid (null without), `maxExtinction`
// its largest sigma_t per data unit.
double AutomaticSpacing(vtkMatrix4x4* model, vtkImageData* input, vtkImageData* extinction,
  double maxExtinction, const Vec cornersWC[8])
{
  auto axisScale = [&](int a) { return AxisScale(model, a); };
  auto smallestCell = [&](vtkImageData* grid) { return SmallestCell(model, grid); };
  double longest = 0.0; // the medium's longest side, in world units
  for (int a = 0; a < 3; ++a)
  {
    const Vec& far = cornersWC[1 << a];
    const Vec side{ far[0] - cornersWC[0][0], far[1] - cornersWC[0][1], far[2] - cornersWC[0][2] };
    longest = std::max(longest, std::sqrt(Dot(side, side)));
  }
  double automatic = std::max(0.5 * smallestCell(input), longest / 40.0);
  if (extinction)
  {
    const double fine = smallestCell(extinction);
    automatic = std::min(automatic, 4.0 * fine);
    // Optically thick media: slabs at most MaxSlabDepth deep at the
    // largest sigma_t, but no closer than one fine cell.
    // sigma_t per world unit: per data unit over the model's smallest scale.
    const double modelScale = std::min({ axisScale(0), axisScale(1), axisScale(2) });
    const double maxSigma = modelScale > 0.0 ? maxExtinction / modelScale : 0.0;
    if (maxSigma > 0.0)
    {
      automatic = std::min(automatic, std::max(fine, MaxSlabDepth / maxSigma));
    }
  }
  return automatic;
}

// The polygon where a slice's plane cuts the box of `corners` (data) and
// `cornersWC` (world), the corners' signed distances to the plane `f`: its
// corners in order of angle in the plane (axes u, v). Returns their count,
// under 3 when the plane misses the box.
int CutPolygon(const Vec corners[8], const Vec cornersWC[8], const double f[8], const Vec& u,
  const Vec& v, SlicePoint polygon[6])
{
  int n = 0;
  for (const auto& edge : BoxEdges)
  {
    const double fa = f[edge[0]], fb = f[edge[1]];
    if ((fa < 0.0) == (fb < 0.0) || n == 6)
    {
      continue;
    }
    const double t = fa / (fa - fb);
    SlicePoint& p = polygon[n++];
    for (int a = 0; a < 3; ++a)
    {
      p.World[a] = cornersWC[edge[0]][a] + t * (cornersWC[edge[1]][a] - cornersWC[edge[0]][a]);
      p.Data[a] = corners[edge[0]][a] + t * (corners[edge[1]][a] - corners[edge[0]][a]);
    }
  }
  if (n < 3)
  {
    return n;
  }
  Vec centre{ 0, 0, 0 };
  for (int i = 0; i < n; ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      centre[a] += polygon[i].World[a] / n;
    }
  }
  for (int i = 0; i < n; ++i)
  {
    const SlicePoint& p = polygon[i];
    const Vec r{ p.World[0] - centre[0], p.World[1] - centre[1], p.World[2] - centre[2] };
    polygon[i].Angle = std::atan2(Dot(r, v), Dot(r, u));
  }
  // By angle; stable, as std::sort is on so few points (which GCC 12 warns
  // about once inlined here).
  std::stable_sort(polygon, polygon + n,
    [](const SlicePoint& a, const SlicePoint& b) { return a.Angle < b.Angle; });
  return n;
}

// Appends the polygon as a fan of triangles: per vertex its world position,
// then its texture coordinates over the box (`bounds`, `extent`).
void EmitPolygon(const SlicePoint* polygon, int n, const double bounds[6], const Vec& extent,
  std::vector<float>& out)
{
  auto emit = [&](const SlicePoint& p)
  {
    for (int a = 0; a < 3; ++a)
    {
      out.push_back(static_cast<float>(p.World[a]));
    }
    for (int a = 0; a < 3; ++a)
    {
      out.push_back(static_cast<float>((p.Data[a] - bounds[2 * a]) / extent[a]));
    }
  };
  for (int i = 1; i + 1 < n; ++i)
  {
    emit(polygon[0]);
    emit(polygon[i]);
    emit(polygon[i + 1]);
  }
}
}

struct vtkBrumeOpenGLSliceVolumeMapper::Slice
{
  vtkBrumeOpenGLSliceVolumeMapper* Owner;
  double Depth;
  float Spacing;
  std::size_t First; // in floats, into the collected vertices
  std::size_t Floats;
};

vtkBrumeOpenGLSliceVolumeMapper::vtkBrumeOpenGLSliceVolumeMapper()
  : Impl(new Internals)
{
}

vtkBrumeOpenGLSliceVolumeMapper::~vtkBrumeOpenGLSliceVolumeMapper() = default;

vtkTypeInt64 vtkBrumeOpenGLSliceVolumeMapper::GetFreeGPUMemory(vtkRenderWindow* window)
{
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!gl)
  {
    return -1;
  }
  gl->MakeCurrent(); // nothing to make current before the context is
  if (!gl->IsCurrent())
  {
    return -1;
  }
  bool nvx = false, ati = false;
  GLint extensions = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &extensions);
  for (GLint e = 0; e < extensions; ++e)
  {
    const auto* name = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, e));
    const std::string extension = name ? name : "";
    nvx = nvx || extension == "GL_NVX_gpu_memory_info";
    ati = ati || extension == "GL_ATI_meminfo";
  }
  // Kilobytes: GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, or the
  // first of GL_TEXTURE_FREE_MEMORY_ATI's four (the pool's free total).
  constexpr GLenum CurrentAvailableNVX = 0x9049, TextureFreeATI = 0x87FC;
  GLint kilobytes[4] = { -1, -1, -1, -1 };
  if (nvx)
  {
    glGetIntegerv(CurrentAvailableNVX, kilobytes);
  }
  else if (ati)
  {
    glGetIntegerv(TextureFreeATI, kilobytes);
  }
  while (glGetError() != GL_NO_ERROR)
  {
  }
  return kilobytes[0] >= 0 ? static_cast<vtkTypeInt64>(kilobytes[0]) * 1024 : -1;
}

void vtkBrumeOpenGLSliceVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Impl->Source->ReleaseGraphicsResources(window);
  this->Impl->Extinction->ReleaseGraphicsResources(window);
  this->Impl->BrickTable->ReleaseGraphicsResources(window);
  this->Impl->BendMask->ReleaseGraphicsResources(window);
  this->Impl->TransferTable->ReleaseGraphicsResources(window);
  for (auto& texture : this->Impl->Coefficients)
  {
    texture->ReleaseGraphicsResources(window);
  }
  this->Impl->VAO->ReleaseGraphicsResources();
  this->Impl->VBO->ReleaseGraphicsResources();
  this->Impl->FullDepth->ReleaseGraphicsResources(window);
  this->Impl->CoarseDepth->ReleaseGraphicsResources(window);
  this->Impl->CoarseMedia->ReleaseGraphicsResources(window);
  this->Impl->CoarseFramebuffer->ReleaseGraphicsResources(window);
  this->Impl->CoarseDepthPass.reset();
  this->Impl->UpsamplePass.reset();
  this->Impl->ReducedFailed = false;
  this->Impl->Context = nullptr;
  this->Impl->TextureTime = vtkTimeStamp();
  this->Impl->ExtinctionGrid = nullptr;
  this->Impl->AtlasSamples = nullptr;
  this->Impl->AtlasSlots = nullptr;
}

void vtkBrumeOpenGLSliceVolumeMapper::Render(vtkRenderer* ren, vtkVolume*)
{
  if (!vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow()))
  {
    vtkErrorMacro("Not an OpenGL render window: nothing drawn.");
    return;
  }
  // The first slice mapper called in a frame draws every slice volume of the
  // renderer, their slices merged in depth order; the others have nothing
  // left to do. Each volume's own problems are reported by its mapper.
  vtkInformation* info = ren->GetInformation();
  if (!info->Has(FRAME()))
  {
    vtkNew<vtkCallbackCommand> counter;
    counter->SetCallback(CountFrame);
    ren->AddObserver(vtkCommand::StartEvent, counter);
    info->Set(FRAME(), 1);
    info->Set(DRAWN_FRAME(), 0);
  }
  if (info->Get(DRAWN_FRAME()) == info->Get(FRAME()))
  {
    return;
  }
  info->Set(DRAWN_FRAME(), info->Get(FRAME()));
  this->DrawAll(ren);
}

bool vtkBrumeOpenGLSliceVolumeMapper::PrepareSlices(
  vtkRenderer* ren, vtkVolume* vol, std::vector<Slice>& slices)
{
  this->LastNumberOfSlices = 0;
  if (this->GetInputAlgorithm())
  {
    this->GetInputAlgorithm()->Update();
  }
  auto* input = vtkImageData::SafeDownCast(this->GetInput());
  std::string problem = ValidateInput(input);
  if (problem.empty() && this->ExtinctionData)
  {
    problem = ValidateExtinction(input, this->ExtinctionData);
  }
  else if (problem.empty() && IsSparseSource(input))
  {
    problem = "a medium image in the sparse form (SourceBrickSlots) needs its extinction "
              "grid (SetExtinctionData)";
  }
  if (!problem.empty())
  {
    vtkErrorMacro("Cannot draw this medium: " << problem << ".");
    return false;
  }
  if (this->SliceSpacing < 0.0 || !std::isfinite(this->SliceSpacing))
  {
    vtkErrorMacro("SliceSpacing must be >= 0, not " << this->SliceSpacing << ": nothing drawn.");
    return false;
  }
  auto* renWin = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  Internals& impl = *this->Impl;
  if (impl.Context != renWin)
  {
    this->ReleaseGraphicsResources(impl.Context ? impl.Context : renWin);
    impl.Context = renWin;
  }
  int pointDims[3];
  input->GetDimensions(pointDims);
  const int dims[3] = { pointDims[0] - 1, pointDims[1] - 1, pointDims[2] - 1 };
  const int interpolation =
    vol->GetProperty() ? vol->GetProperty()->GetInterpolationType() : VTK_LINEAR_INTERPOLATION;

  // Two RGB float 3D textures: source radiance and extinction.
  if (impl.TextureTime < input->GetMTime() || impl.TextureTime < this->GetMTime() ||
    !impl.Source->GetHandle() || impl.Interpolation != interpolation)
  {
    if (!this->UploadTextures(input, renWin, dims, interpolation))
    {
      return false;
    }
  }
  vtkCamera* camera = ren->GetActiveCamera();
  vtkMatrix4x4* model = vol->GetMatrix();
  const double* eyePtr = camera->GetPosition();
  const Vec eye{ eyePtr[0], eyePtr[1], eyePtr[2] };
  double bounds[6];
  input->GetBounds(bounds);
  {
    // The eye in data coordinates, where the directions of directional
    // radiance are expressed.
    vtkNew<vtkMatrix4x4> inverse;
    vtkMatrix4x4::Invert(model, inverse);
    const Vec eyeData = Transform(inverse, eye);
    for (int a = 0; a < 3; ++a)
    {
      impl.EyeData[a] = static_cast<float>(eyeData[a]);
      impl.BoundsLower[a] = static_cast<float>(bounds[2 * a]);
      impl.BoundsExtent[a] = static_cast<float>(bounds[2 * a + 1] - bounds[2 * a]);
      // Texture coordinate a per world unit along each world axis.
      const double extent = bounds[2 * a + 1] - bounds[2 * a];
      for (int w = 0; w < 3; ++w)
      {
        impl.TextureFromWorld[a][w] =
          extent > 0.0 ? static_cast<float>(inverse->GetElement(a, w) / extent) : 0.f;
      }
    }
  }
  {
    double e[6] = { bounds[0], bounds[1], bounds[2], bounds[3], bounds[4], bounds[5] };
    if (this->ExtinctionData)
    {
      this->ExtinctionData->GetBounds(e);
    }
    for (int a = 0; a < 3; ++a)
    {
      const double extent = e[2 * a + 1] - e[2 * a];
      impl.ExtinctionScale[a] = static_cast<float>((bounds[2 * a + 1] - bounds[2 * a]) / extent);
      impl.ExtinctionOffset[a] = static_cast<float>((bounds[2 * a] - e[2 * a]) / extent);
    }
    vtkDataArray* factor = input->GetFieldData()->GetArray(vtkBrumeNames::ExtinctionFactor);
    for (int c = 0; c < 3; ++c)
    {
      const double f =
        factor && factor->GetNumberOfComponents() == 3 ? factor->GetComponent(0, c) : 1.0;
      impl.ExtinctionFactor[c] = f > 0.0 && f <= 1.0 ? static_cast<float>(f) : 1.f;
    }
    vtkDataArray* forward = input->GetFieldData()->GetArray(vtkBrumeNames::ForwardFraction);
    const double fraction =
      forward && forward->GetNumberOfTuples() > 0 ? forward->GetTuple1(0) : 0.0;
    impl.ForwardFraction = fraction > 0.0 && fraction < 1.0 ? static_cast<float>(fraction) : 0.f;
  }
  if (!this->EvaluateTowardEye(renWin, dims, interpolation))
  {
    return false;
  }
  this->CutSlices(camera, model, input, slices);
  // While an interaction asks for frames (VTK's interactor styles raise the
  // window's desired update rate from the still one, 0.0001, to 15 while the
  // camera moves; at least one frame a second here), one sample a slab, as
  // vtkGPUVolumeRayCastMapper samples more coarsely then.
  if (renWin->GetDesiredUpdateRate() >= InteractiveUpdateRate)
  {
    impl.SlabSamples = 1;
  }
  return true;
}

void vtkBrumeOpenGLSliceVolumeMapper::CutSlices(
  vtkCamera* camera, vtkMatrix4x4* model, vtkImageData* input, std::vector<Slice>& slices)
{
  const double* eyePtr = camera->GetPosition();
  const Vec eye{ eyePtr[0], eyePtr[1], eyePtr[2] };
  double dopPtr[3];
  camera->GetDirectionOfProjection(dopPtr);
  const Vec dop{ dopPtr[0], dopPtr[1], dopPtr[2] };
  double bounds[6];
  input->GetBounds(bounds);
  Vec corners[8], cornersWC[8];
  double dmin = VTK_DOUBLE_MAX, dmax = -VTK_DOUBLE_MAX;
  for (int c = 0; c < 8; ++c)
  {
    corners[c] = { bounds[(c & 1) ? 1 : 0], bounds[(c & 2) ? 3 : 2], bounds[(c & 4) ? 5 : 4] };
    cornersWC[c] = Transform(model, corners[c]);
    const double d =
      Dot({ cornersWC[c][0] - eye[0], cornersWC[c][1] - eye[1], cornersWC[c][2] - eye[2] }, dop);
    dmin = std::min(dmin, d);
    dmax = std::max(dmax, d);
  }
  // The camera may be inside the medium: start at the near plane.
  const double nearPlane = camera->GetClippingRange()[0];
  dmin = std::max(dmin, nearPlane * (1.0 + 1e-6));
  if (!(dmax > dmin))
  {
    return; // entirely behind the camera
  }
  const double automatic =
    AutomaticSpacing(model, input, this->ExtinctionData, this->Impl->MaxExtinction, cornersWC);
  const double unscaled = this->SliceSpacing > 0.0 ? this->SliceSpacing : automatic;
  const double requested = unscaled * this->SliceSpacingScale;
  // Samples of the extinction's own grid across a slab: one per fine cell
  // of the spacing, one without such a grid or in a quick draw (thicker
  // slabs asked for speed).
  this->Impl->SlabSamples = 1;
  this->Impl->BendParts = 1;
  this->Impl->SlabsWanted =
    this->ExtinctionData && this->SlabSampling && this->SliceSpacingScale <= 1.0;
  if (this->Impl->SlabsWanted)
  {
    const double fine = SmallestCell(model, this->ExtinctionData);
    if (fine > 0.0)
    {
      this->Impl->SlabSamples = static_cast<int>(
        std::clamp(std::ceil(unscaled / fine - 1e-6), 1.0, static_cast<double>(MaxSlabSamples)));
      // Where the transfer function bends, four samples a fine cell: each
      // sample split in as many parts as that takes (none where the slices
      // lie a quarter of a cell apart or closer).
      const double apart = requested / this->Impl->SlabSamples;
      this->Impl->BendParts =
        static_cast<int>(std::clamp(std::ceil(4.0 * apart / fine - 1e-6), 1.0, 4.0));
    }
  }
  const int count =
    static_cast<int>(std::min(8192.0, std::max(1.0, std::ceil((dmax - dmin) / requested))));
  // An exact partition of [dmin, dmax] into slabs; each slice at its slab's centre.
  const double delta = (dmax - dmin) / count;

  const Vec extent{ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] };
  Vec u;
  {
    Vec e{ 0, 0, 0 };
    e[std::abs(dop[0]) < 0.9 ? 0 : 1] = 1;
    const double k = Dot(e, dop);
    u = { e[0] - k * dop[0], e[1] - k * dop[1], e[2] - k * dop[2] };
    const double n = std::sqrt(Dot(u, u));
    u = { u[0] / n, u[1] / n, u[2] / n };
  }
  const Vec v{ dop[1] * u[2] - dop[2] * u[1], dop[2] * u[0] - dop[0] * u[2],
    dop[0] * u[1] - dop[1] * u[0] };
  std::vector<float>& out = this->Impl->Collected;
  for (int k = 0; k < count; ++k)
  {
    const double d = dmin + (k + 0.5) * delta;
    double f[8];
    for (int c = 0; c < 8; ++c)
    {
      f[c] =
        Dot({ cornersWC[c][0] - eye[0], cornersWC[c][1] - eye[1], cornersWC[c][2] - eye[2] }, dop) -
        d;
    }
    SlicePoint polygon[6];
    const int n = CutPolygon(corners, cornersWC, f, u, v, polygon);
    if (n < 3)
    {
      continue;
    }
    Slice slice{ this, d, static_cast<float>(delta), out.size(), 0 };
    EmitPolygon(polygon, n, bounds, extent, out);
    slice.Floats = out.size() - slice.First;
    slices.push_back(slice);
    ++this->LastNumberOfSlices;
  }
}

void vtkBrumeOpenGLSliceVolumeMapper::DrawAll(vtkRenderer* ren)
{
  Internals& impl = *this->Impl;
  std::vector<Slice> slices;
  std::vector<vtkBrumeOpenGLSliceVolumeMapper*> mappers;
  std::vector<vtkVolume*> drawn;
  vtkVolumeCollection* volumes = this->GetDrawnVolumes(ren);
  vtkCollectionSimpleIterator it;
  volumes->InitTraversal(it);
  while (vtkVolume* volume = volumes->GetNextVolume(it))
  {
    auto* mapper = vtkBrumeOpenGLSliceVolumeMapper::SafeDownCast(volume->GetMapper());
    if (!mapper || !volume->GetVisibility())
    {
      continue;
    }
    mapper->Impl->Collected.clear();
    if (mapper->PrepareSlices(ren, volume, slices))
    {
      mappers.push_back(mapper);
      drawn.push_back(volume);
    }
  }
  if (slices.empty())
  {
    return;
  }
  // Far to near over all volumes.
  std::stable_sort(
    slices.begin(), slices.end(), [](const Slice& a, const Slice& b) { return a.Depth > b.Depth; });
  std::vector<Internals::Run>& runs = impl.Runs;
  runs.clear();
  impl.Sorted.clear();
  for (const Slice& s : slices)
  {
    const float* src = s.Owner->Impl->Collected.data() + s.First;
    const int first = static_cast<int>(impl.Sorted.size() / 6);
    impl.Sorted.insert(impl.Sorted.end(), src, src + s.Floats);
    const int vertices = static_cast<int>(s.Floats / 6);
    if (!runs.empty() && runs.back().Owner == s.Owner && runs.back().Spacing == s.Spacing)
    {
      runs.back().Vertices += vertices;
    }
    else
    {
      runs.push_back({ s.Owner, s.Spacing, first, vertices });
    }
  }
  impl.VBO->Upload(impl.Sorted, vtkOpenGLBufferObject::ArrayBuffer);

  // The media at a reduced resolution where every one of them asks for it
  // (the largest ImageSampleDistance wins) and can be drawn so; otherwise,
  // or if that fails, at full resolution.
  double distance = 1.0;
  bool reducible = true;
  for (auto* mapper : mappers)
  {
    distance = std::max(distance, mapper->ImageSampleDistance);
    reducible = reducible && !mapper->WriteDepth && mapper->Impl->GreyExtinction();
  }
  this->LastImageSampleDistance = 1.0;
  if (distance > 1.0 && reducible && this->DrawReduced(ren, distance, drawn))
  {
    this->LastImageSampleDistance = distance;
  }
  else
  {
    this->DrawRuns(ren, false);
  }
  for (auto* mapper : mappers)
  {
    mapper->LastImageSampleDistance = this->LastImageSampleDistance;
  }
}

void vtkBrumeOpenGLSliceVolumeMapper::DrawRuns(vtkRenderer* ren, bool reduced)
{
  auto* renWin = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  Internals& impl = *this->Impl;
  vtkCamera* camera = ren->GetActiveCamera();
  vtkMatrix4x4* wcvc;
  vtkMatrix3x3* normals;
  vtkMatrix4x4* vcdc;
  vtkMatrix4x4* wcdc;
  static_cast<vtkOpenGLCamera*>(camera)->GetKeyMatrices(ren, wcvc, normals, vcdc, wcdc);
  const double* eye = camera->GetPosition();
  double dop[3];
  camera->GetDirectionOfProjection(dop);
  const float eyeF[3] = { static_cast<float>(eye[0]), static_cast<float>(eye[1]),
    static_cast<float>(eye[2]) };
  const float dopF[3] = { static_cast<float>(dop[0]), static_cast<float>(dop[1]),
    static_cast<float>(dop[2]) };

  vtkOpenGLState* state = renWin->GetState();
  vtkOpenGLState::ScopedglEnableDisable blendSaver(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthSaver(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable cullSaver(state, GL_CULL_FACE);
  vtkOpenGLState::ScopedglDepthMask depthMaskSaver(state);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFuncSaver(state);
  state->vtkglEnable(GL_BLEND);
  // Dual-source blending: C = C_slice + T * C_behind, T per channel. On
  // screen the alpha is the opacity, a = (1 - T) + T a; in a reduced
  // resolution's buffer (grey media only) it is the transmittance, a = T a.
  state->vtkglBlendFuncSeparate(GL_ONE, GL_SRC1_COLOR, reduced ? GL_ZERO : GL_ONE, GL_SRC1_ALPHA);
  state->vtkglEnable(GL_DEPTH_TEST);
  // Back to front, each slice nearer than the last: written depths never
  // hide a later slice, only what comes after the media.
  state->vtkglDepthMask(this->WriteDepth && !reduced ? GL_TRUE : GL_FALSE);
  state->vtkglDisable(GL_CULL_FACE);
  // One program per kind of volume (plain, or directional of an order).
  vtkShaderProgram* bound = nullptr;
  const size_t stride = 6 * sizeof(float);
  for (const Internals::Run& run : impl.Runs)
  {
    Internals& owner = *run.Owner->Impl;
    vtkBrumeSliceVolumeShader::Kind kind;
    kind.Order = owner.FragmentOrder;
    kind.SourceIsRadiance = owner.SourceIsRadiance;
    kind.Classified = owner.Bricked && owner.Classified;
    kind.Albedo = kind.Classified && owner.Albedo;
    // A reduced resolution is a quick draw: one sample a slab.
    const int samples = reduced ? 1 : owner.SlabSamples;
    run.Owner->LastSlabSamples = samples;
    // Classified bricks may bend: their samples take four each (slabs of
    // one sample too).
    kind.Bends = !reduced && kind.Classified && owner.SlabsWanted && run.Owner->GetBendSampling() &&
      owner.BendingBricks > 0 && owner.BendParts > 1;
    kind.Slabs = !reduced && (samples > 1 || kind.Bends);
    kind.Extinction = owner.Bricked ? vtkBrumeSliceVolumeShader::ExtinctionBricks
      : owner.ConstantExtinction    ? vtkBrumeSliceVolumeShader::ExtinctionConstant
                                    : vtkBrumeSliceVolumeShader::ExtinctionTexture;
    vtkShaderProgram* program = renWin->GetShaderCache()->ReadyShaderProgram(
      vtkBrumeSliceVolumeVS, vtkBrumeSliceVolumeShader::Fragment(kind).c_str(), "");
    if (!program)
    {
      vtkErrorMacro("Could not build the slice shaders: nothing drawn.");
      break;
    }
    if (program != bound)
    {
      impl.VAO->ShaderProgramChanged();
      impl.VAO->Bind();
      if (!impl.VAO->AddAttributeArray(
            program, impl.VBO, "vertexWC", 0, stride, VTK_FLOAT, 3, false) ||
        !impl.VAO->AddAttributeArray(
          program, impl.VBO, "textureCoordinate", 3 * sizeof(float), stride, VTK_FLOAT, 3, false))
      {
        vtkErrorMacro("Could not bind the slice vertex attributes: nothing drawn.");
        break;
      }
      program->SetUniformMatrix("WCDCMatrix", wcdc);
      program->SetUniform3f("eyeWC", eyeF);
      program->SetUniform3f("viewDirectionWC", dopF);
      program->SetUniformi("perspective", camera->GetParallelProjection() ? 0 : 1);
      bound = program;
    }
    owner.Source->Activate();
    // Every sampler the shader declares is given a 3D texture's unit, used or not.
    owner.Extinction->Activate();
    program->SetUniformi("sourceTexture", owner.Source->GetTextureUnit());
    program->SetUniformi("extinctionTexture", owner.Extinction->GetTextureUnit());
    program->SetUniformf("sliceSpacing", run.Spacing);
    if (kind.Bends)
    {
      program->SetUniformi("bendParts", owner.BendParts);
      owner.BendMask->Activate();
      program->SetUniformi("bendMask", owner.BendMask->GetTextureUnit());
    }
    if (kind.Slabs)
    {
      program->SetUniformi("slabSamples", samples);
      program->SetUniform3f("textureFromWorldX", owner.TextureFromWorld[0]);
      program->SetUniform3f("textureFromWorldY", owner.TextureFromWorld[1]);
      program->SetUniform3f("textureFromWorldZ", owner.TextureFromWorld[2]);
    }
    program->SetUniform3f("extinctionScale", owner.ExtinctionScale);
    program->SetUniform3f("extinctionOffset", owner.ExtinctionOffset);
    program->SetUniform3f("extinctionFactor", owner.ExtinctionFactor);
    if (kind.Extinction == vtkBrumeSliceVolumeShader::ExtinctionBricks)
    {
      owner.BrickTable->Activate();
      program->SetUniformi("brickTable", owner.BrickTable->GetTextureUnit());
      program->SetUniform3f("gridCells", owner.GridCells);
      program->SetUniform3f("brickCount", owner.BrickCount);
      program->SetUniform3f("atlasSize", owner.AtlasSize);
      program->SetUniform3f("brickScale", owner.BrickScale);
      if (kind.Classified)
      {
        owner.TransferTable->Activate();
        program->SetUniformi("transferTexture", owner.TransferTable->GetTextureUnit());
        program->SetUniform2f("transferRange", owner.TransferRange);
        program->SetUniformf("transferSamples", owner.TransferSamples);
        if (kind.Albedo)
        {
          program->SetUniformf("forwardFraction", owner.ForwardFraction);
        }
      }
    }
    else if (kind.Extinction == vtkBrumeSliceVolumeShader::ExtinctionConstant)
    {
      program->SetUniform3f("constantExtinction", owner.Constant);
    }
    program->SetUniformf("radianceScale", static_cast<float>(run.Owner->GetRadianceScale()));
    if (owner.FragmentOrder > 0)
    {
      for (std::size_t t = 0; t < owner.Coefficients.size(); ++t)
      {
        owner.Coefficients[t]->Activate();
        program->SetUniformi(
          ("shTexture" + std::to_string(t)).c_str(), owner.Coefficients[t]->GetTextureUnit());
      }
      program->SetUniformf("phaseG", owner.G);
      program->SetUniform3f("eyeData", owner.EyeData);
      program->SetUniform3f("boundsLower", owner.BoundsLower);
      program->SetUniform3f("boundsExtent", owner.BoundsExtent);
    }
    glDrawArrays(GL_TRIANGLES, run.FirstVertex, run.Vertices);
    owner.Source->Deactivate();
    owner.Extinction->Deactivate();
    if (owner.Bricked)
    {
      owner.BrickTable->Deactivate();
    }
    if (kind.Bends)
    {
      owner.BendMask->Deactivate();
    }
    if (kind.Classified)
    {
      owner.TransferTable->Deactivate();
    }
    if (owner.FragmentOrder > 0)
    {
      for (auto& texture : owner.Coefficients)
      {
        texture->Deactivate();
      }
    }
  }
  impl.VAO->Release();
}

void vtkBrumeOpenGLSliceVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
