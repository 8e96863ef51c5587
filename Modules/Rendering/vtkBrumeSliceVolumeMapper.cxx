// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSliceVolumeMapper.h"

#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
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
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtk_glew.h"

#include "vtkBrumeSliceVolumeFS.h"
#include "vtkBrumeSliceVolumeVS.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkBrumeSliceVolumeMapper);

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
constexpr int BoxEdges[12][2] = { { 0, 1 }, { 2, 3 }, { 4, 5 }, { 6, 7 }, { 0, 2 }, { 1, 3 },
  { 4, 6 }, { 5, 7 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 } };
}

struct vtkBrumeSliceVolumeMapper::Internals
{
  vtkNew<vtkTextureObject> Texture;
  vtkNew<vtkOpenGLVertexArrayObject> VAO;
  vtkNew<vtkOpenGLBufferObject> VBO;
  vtkTimeStamp TextureTime;
  vtkOpenGLRenderWindow* Context = nullptr;
  std::vector<float> Vertices; // x, y, z (world), s, t, r (texture)
};

vtkBrumeSliceVolumeMapper::vtkBrumeSliceVolumeMapper()
  : Impl(new Internals)
{
}

vtkBrumeSliceVolumeMapper::~vtkBrumeSliceVolumeMapper() = default;

int vtkBrumeSliceVolumeMapper::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

void vtkBrumeSliceVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Impl->Texture->ReleaseGraphicsResources(window);
  this->Impl->VAO->ReleaseGraphicsResources();
  this->Impl->VBO->ReleaseGraphicsResources();
  this->Impl->Context = nullptr;
  this->Impl->TextureTime = vtkTimeStamp();
}

void vtkBrumeSliceVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  this->LastNumberOfSlices = 0;
  if (this->GetInputAlgorithm())
  {
    this->GetInputAlgorithm()->Update();
  }
  vtkImageData* input = vtkImageData::SafeDownCast(this->GetInput());
  auto* renWin = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!input || !renWin)
  {
    vtkErrorMacro("No input image, or not an OpenGL render window: nothing drawn.");
    return;
  }
  if (this->SliceSpacing < 0.0 || !std::isfinite(this->SliceSpacing))
  {
    vtkErrorMacro("SliceSpacing must be >= 0, not " << this->SliceSpacing << ": nothing drawn.");
    return;
  }
  int pointDims[3];
  input->GetDimensions(pointDims);
  const int dims[3] = { pointDims[0] - 1, pointDims[1] - 1, pointDims[2] - 1 };
  const double* spacing = input->GetSpacing();
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1 || !(spacing[0] > 0.0) || !(spacing[1] > 0.0) ||
    !(spacing[2] > 0.0))
  {
    vtkErrorMacro("The medium image must have at least one cell along each axis and a "
                  "positive spacing: nothing drawn.");
    return;
  }
  const vtkIdType cells = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  vtkDataArray* source = input->GetCellData()->GetArray("SourceRadiance");
  vtkDataArray* extinction = input->GetCellData()->GetArray("Extinction");
  if (!source || !extinction || source->GetNumberOfComponents() != 3 ||
    (extinction->GetNumberOfComponents() != 1 && extinction->GetNumberOfComponents() != 3) ||
    source->GetNumberOfTuples() != cells || extinction->GetNumberOfTuples() != cells)
  {
    vtkErrorMacro("The medium image needs the cell arrays 'SourceRadiance' (3 components) and "
                  "'Extinction' (1 or 3 components), one tuple per cell: nothing drawn.");
    return;
  }

  Internals& impl = *this->Impl;
  if (impl.Context != renWin)
  {
    this->ReleaseGraphicsResources(impl.Context ? impl.Context : renWin);
    impl.Context = renWin;
  }

  // 3D texture: rgb = source radiance, a = extinction.
  if (impl.TextureTime < input->GetMTime() || impl.TextureTime < this->GetMTime() ||
    !impl.Texture->GetHandle())
  {
    std::vector<float> texels(static_cast<std::size_t>(4 * cells));
    const int ne = extinction->GetNumberOfComponents();
    for (vtkIdType i = 0; i < cells; ++i)
    {
      double s[3], e[3];
      source->GetTuple(i, s);
      extinction->GetTuple(i, e);
      const double sigmaT = e[0];
      if (ne == 3 &&
        (std::abs(e[1] - e[0]) > 1e-6 * std::abs(e[0]) ||
          std::abs(e[2] - e[0]) > 1e-6 * std::abs(e[0])))
      {
        vtkErrorMacro("Colour-dependent extinction is not supported yet: nothing drawn.");
        return;
      }
      if (!(sigmaT >= 0.0) || !std::isfinite(sigmaT))
      {
        vtkErrorMacro("Extinction must be finite and non-negative: nothing drawn.");
        return;
      }
      texels[4 * i + 0] = static_cast<float>(s[0]);
      texels[4 * i + 1] = static_cast<float>(s[1]);
      texels[4 * i + 2] = static_cast<float>(s[2]);
      texels[4 * i + 3] = static_cast<float>(sigmaT);
    }
    impl.Texture->SetContext(renWin);
    impl.Texture->SetWrapS(vtkTextureObject::ClampToEdge);
    impl.Texture->SetWrapT(vtkTextureObject::ClampToEdge);
    impl.Texture->SetWrapR(vtkTextureObject::ClampToEdge);
    impl.Texture->SetMinificationFilter(vtkTextureObject::Linear);
    impl.Texture->SetMagnificationFilter(vtkTextureObject::Linear);
    if (!impl.Texture->Create3DFromRaw(static_cast<unsigned int>(dims[0]),
          static_cast<unsigned int>(dims[1]), static_cast<unsigned int>(dims[2]), 4, VTK_FLOAT,
          texels.data()))
    {
      vtkErrorMacro("Could not create the 3D texture (" << dims[0] << " x " << dims[1] << " x "
                                                        << dims[2] << "): nothing drawn.");
      return;
    }
    impl.TextureTime.Modified();
  }

  // Slice planes perpendicular to the view direction, through the medium's box.
  vtkCamera* camera = ren->GetActiveCamera();
  vtkMatrix4x4* model = vol->GetMatrix();
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
  double worldSpacing = VTK_DOUBLE_MAX;
  for (int a = 0; a < 3; ++a)
  {
    const double axis = std::sqrt(model->GetElement(0, a) * model->GetElement(0, a) +
      model->GetElement(1, a) * model->GetElement(1, a) +
      model->GetElement(2, a) * model->GetElement(2, a));
    worldSpacing = std::min(worldSpacing, axis * spacing[a]);
  }
  const double requested = this->SliceSpacing > 0.0 ? this->SliceSpacing : 0.5 * worldSpacing;
  const int slices =
    static_cast<int>(std::min(8192.0, std::max(1.0, std::ceil((dmax - dmin) / requested))));
  // Exact slab partition of [dmin, dmax]: slice k sits at the centre of its slab.
  const double delta = (dmax - dmin) / slices;

  impl.Vertices.clear();
  const Vec extent{ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] };
  // In-plane axes for ordering the polygon's vertices.
  Vec u{ 0, 0, 0 };
  {
    const int a = std::abs(dop[0]) < 0.9 ? 0 : 1;
    Vec e{ 0, 0, 0 };
    e[a] = 1;
    const double k = Dot(e, dop);
    u = { e[0] - k * dop[0], e[1] - k * dop[1], e[2] - k * dop[2] };
    const double n = std::sqrt(Dot(u, u));
    u = { u[0] / n, u[1] / n, u[2] / n };
  }
  const Vec v{ dop[1] * u[2] - dop[2] * u[1], dop[2] * u[0] - dop[0] * u[2],
    dop[0] * u[1] - dop[1] * u[0] };
  for (int k = slices - 1; k >= 0; --k)
  {
    const double d = dmin + (k + 0.5) * delta;
    // Plane crossings of the box edges (world-space signed distances).
    double f[8];
    for (int c = 0; c < 8; ++c)
    {
      f[c] =
        Dot({ cornersWC[c][0] - eye[0], cornersWC[c][1] - eye[1], cornersWC[c][2] - eye[2] }, dop) -
        d;
    }
    struct Point
    {
      Vec World, Data;
      double Angle;
    };
    std::vector<Point> polygon;
    for (const auto& edge : BoxEdges)
    {
      const double fa = f[edge[0]], fb = f[edge[1]];
      if ((fa < 0.0) == (fb < 0.0))
      {
        continue;
      }
      const double t = fa / (fa - fb);
      Point p;
      for (int a = 0; a < 3; ++a)
      {
        p.World[a] = cornersWC[edge[0]][a] + t * (cornersWC[edge[1]][a] - cornersWC[edge[0]][a]);
        p.Data[a] = corners[edge[0]][a] + t * (corners[edge[1]][a] - corners[edge[0]][a]);
      }
      polygon.push_back(p);
    }
    if (polygon.size() < 3)
    {
      continue;
    }
    Vec centre{ 0, 0, 0 };
    for (const Point& p : polygon)
    {
      for (int a = 0; a < 3; ++a)
      {
        centre[a] += p.World[a] / polygon.size();
      }
    }
    for (Point& p : polygon)
    {
      const Vec r{ p.World[0] - centre[0], p.World[1] - centre[1], p.World[2] - centre[2] };
      p.Angle = std::atan2(Dot(r, v), Dot(r, u));
    }
    std::sort(polygon.begin(), polygon.end(),
      [](const Point& a, const Point& b) { return a.Angle < b.Angle; });
    auto emit = [&](const Point& p)
    {
      for (int a = 0; a < 3; ++a)
      {
        impl.Vertices.push_back(static_cast<float>(p.World[a]));
      }
      for (int a = 0; a < 3; ++a)
      {
        impl.Vertices.push_back(static_cast<float>((p.Data[a] - bounds[2 * a]) / extent[a]));
      }
    };
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
    {
      emit(polygon[0]);
      emit(polygon[i]);
      emit(polygon[i + 1]);
    }
    ++this->LastNumberOfSlices;
  }
  if (impl.Vertices.empty())
  {
    return;
  }

  vtkShaderProgram* program =
    renWin->GetShaderCache()->ReadyShaderProgram(vtkBrumeSliceVolumeVS, vtkBrumeSliceVolumeFS, "");
  if (!program)
  {
    vtkErrorMacro("Could not build the slice shaders: nothing drawn.");
    return;
  }
  impl.VBO->Upload(impl.Vertices, vtkOpenGLBufferObject::ArrayBuffer);
  impl.VAO->Bind();
  const size_t stride = 6 * sizeof(float);
  if (!impl.VAO->AddAttributeArray(program, impl.VBO, "vertexWC", 0, stride, VTK_FLOAT, 3, false) ||
    !impl.VAO->AddAttributeArray(
      program, impl.VBO, "textureCoordinate", 3 * sizeof(float), stride, VTK_FLOAT, 3, false))
  {
    vtkErrorMacro("Could not bind the slice vertex attributes: nothing drawn.");
    impl.VAO->Release();
    return;
  }

  vtkMatrix4x4* wcvc;
  vtkMatrix3x3* normals;
  vtkMatrix4x4* vcdc;
  vtkMatrix4x4* wcdc;
  static_cast<vtkOpenGLCamera*>(camera)->GetKeyMatrices(ren, wcvc, normals, vcdc, wcdc);
  program->SetUniformMatrix("WCDCMatrix", wcdc);
  const float eyeF[3] = { static_cast<float>(eye[0]), static_cast<float>(eye[1]),
    static_cast<float>(eye[2]) };
  const float dopF[3] = { static_cast<float>(dop[0]), static_cast<float>(dop[1]),
    static_cast<float>(dop[2]) };
  program->SetUniform3f("eyeWC", eyeF);
  program->SetUniform3f("viewDirectionWC", dopF);
  program->SetUniformf("sliceSpacing", static_cast<float>(delta));
  program->SetUniformi("perspective", camera->GetParallelProjection() ? 0 : 1);
  impl.Texture->Activate();
  program->SetUniformi("mediumTexture", impl.Texture->GetTextureUnit());

  vtkOpenGLState* state = renWin->GetState();
  vtkOpenGLState::ScopedglEnableDisable blendSaver(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthSaver(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable cullSaver(state, GL_CULL_FACE);
  vtkOpenGLState::ScopedglDepthMask depthMaskSaver(state);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFuncSaver(state);
  state->vtkglEnable(GL_BLEND);
  // Premultiplied "over": C = C_slice + (1 - alpha) C_behind.
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_FALSE);
  state->vtkglDisable(GL_CULL_FACE);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(impl.Vertices.size() / 6));
  impl.Texture->Deactivate();
  impl.VAO->Release();
}

void vtkBrumeSliceVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SliceSpacing: " << this->SliceSpacing << "\n";
  os << indent << "LastNumberOfSlices: " << this->LastNumberOfSlices << "\n";
}
