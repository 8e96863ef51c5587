// SPDX-License-Identifier: BSD-3-Clause
// The slice mapper's media at a reduced resolution
// (vtkBrumeSliceVolumeMapper::ImageSampleDistance): the slices are drawn
// into a buffer `distance` times coarser along each axis, holding per pixel
// the media's radiance and, for grey media, their transmittance, then
// upsampled over the window with the window's depth. A slice costs its
// fragments, so a distance of 2 draws a quarter of them.
#include "vtkBrumeOpenGLSliceVolumeMapperInternals.h"

#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtk_glew.h"

#include "vtkBrumeSliceVolumeCoarseDepthFS.h"
#include "vtkBrumeSliceVolumeUpsampleFS.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{
// (Re)allocates a 2D texture of `width` x `height` unless it has that size.
bool Size2D(
  vtkTextureObject* texture, vtkOpenGLRenderWindow* window, int width, int height, bool depth)
{
  if (texture->GetHandle() && static_cast<int>(texture->GetWidth()) == width &&
    static_cast<int>(texture->GetHeight()) == height)
  {
    return true;
  }
  texture->ReleaseGraphicsResources(window);
  texture->SetContext(window);
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
  texture->SetMinificationFilter(vtkTextureObject::Nearest);
  texture->SetMagnificationFilter(vtkTextureObject::Nearest);
  return depth ? texture->AllocateDepth(static_cast<unsigned int>(width),
                   static_cast<unsigned int>(height), vtkTextureObject::Float32)
               : texture->Allocate2D(static_cast<unsigned int>(width),
                   static_cast<unsigned int>(height), 4, VTK_FLOAT);
}

// The pixels of the viewport (width x height) that `volumes` can cover:
// their bounds' corners projected, [rect[0], rect[2]) x [rect[1], rect[3]);
// the whole viewport when a corner lies behind the eye.
void ScreenRectangle(
  vtkRenderer* ren, const std::vector<vtkVolume*>& volumes, int width, int height, int rect[4])
{
  rect[0] = width;
  rect[1] = height;
  rect[2] = 0;
  rect[3] = 0;
  vtkMatrix4x4* project = ren->GetActiveCamera()->GetCompositeProjectionTransformMatrix(
    ren->GetTiledAspectRatio(), -1, 1);
  for (vtkVolume* volume : volumes)
  {
    const double* b = volume->GetBounds();
    for (int c = 0; c < 8; ++c)
    {
      const double corner[4] = { b[(c & 1) ? 1 : 0], b[(c & 2) ? 3 : 2], b[(c & 4) ? 5 : 4], 1.0 };
      double clip[4];
      project->MultiplyPoint(corner, clip);
      if (!(clip[3] > 1e-9 * (std::abs(clip[0]) + std::abs(clip[1]) + std::abs(clip[2]))))
      {
        rect[0] = rect[1] = 0;
        rect[2] = width;
        rect[3] = height;
        return;
      }
      const double x = (clip[0] / clip[3] + 1.0) * 0.5 * width;
      const double y = (clip[1] / clip[3] + 1.0) * 0.5 * height;
      rect[0] = std::min(rect[0], static_cast<int>(std::floor(std::max(x, 0.0))));
      rect[1] = std::min(rect[1], static_cast<int>(std::floor(std::max(y, 0.0))));
      rect[2] = std::max(rect[2], static_cast<int>(std::ceil(std::min(x, 1.0 * width))));
      rect[3] = std::max(rect[3], static_cast<int>(std::ceil(std::min(y, 1.0 * height))));
    }
  }
}

// Drops the errors OpenGL has recorded so far; true if there were none.
bool ClearErrors()
{
  bool none = true;
  while (glGetError() != GL_NO_ERROR)
  {
    none = false;
  }
  return none;
}

// Copies the window's depth (what the opaque props left) under `depthRect`
// into `fullDepth`, read from the framebuffer being drawn; the viewport's
// origin is (x, y).
void CopyWindowDepth(
  vtkOpenGLState* state, vtkTextureObject* fullDepth, int x, int y, const int depthRect[4])
{
  unsigned int drawBinding = 0, drawBuffer = 0;
  state->GetCurrentDrawFramebufferState(drawBinding, drawBuffer);
  state->PushReadFramebufferBinding();
  state->vtkglBindFramebuffer(GL_READ_FRAMEBUFFER, drawBinding);
  // (vtkTextureObject::CopyFromFrameBuffer ignores the destination corner.)
  fullDepth->Activate();
  glCopyTexSubImage2D(GL_TEXTURE_2D, 0, depthRect[0], depthRect[1], x + depthRect[0],
    y + depthRect[1], depthRect[2] - depthRect[0], depthRect[3] - depthRect[1]);
  fullDepth->Deactivate();
  state->PopReadFramebufferBinding();
}
}

// Where DrawReduced's passes draw: the viewport's size and origin, the
// coarse buffer's size, the media's rectangle on screen (full pixels) and
// the coarse pixels it touches and one more around.
struct vtkBrumeOpenGLSliceVolumeMapper::ReducedLayout
{
  double Distance;
  int Width, Height, X, Y;
  int Coarse[2];
  int Rect[4], CoarseRect[4];
};

bool vtkBrumeOpenGLSliceVolumeMapper::FailReduced(const char* what)
{
  vtkWarningMacro("Media drawn at full resolution: " << what << ".");
  this->Impl->ReducedFailed = true;
  return false;
}

bool vtkBrumeOpenGLSliceVolumeMapper::DrawReduced(
  vtkRenderer* ren, double distance, const std::vector<vtkVolume*>& volumes)
{
  Internals& impl = *this->Impl;
  if (impl.ReducedFailed)
  {
    return false;
  }
  auto* renWin = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  vtkOpenGLState* state = renWin->GetState();
  int width, height, x, y;
  ren->GetTiledSizeAndOrigin(&width, &height, &x, &y);
  const int coarse[2] = { std::max(1, static_cast<int>(std::ceil(width / distance))),
    std::max(1, static_cast<int>(std::ceil(height / distance))) };
  if (width < 1 || height < 1)
  {
    return false;
  }
  // Only where the media can be: their rectangle on screen (full pixels),
  // the coarse pixels it touches and one more around (the upsampling's
  // reach), and the full pixels under those.
  int rect[4];
  ScreenRectangle(ren, volumes, width, height, rect);
  if (rect[2] <= rect[0] || rect[3] <= rect[1])
  {
    return true; // nothing on screen
  }
  const int coarseRect[4] = { std::max(0, static_cast<int>(rect[0] / distance) - 1),
    std::max(0, static_cast<int>(rect[1] / distance) - 1),
    std::min(coarse[0], static_cast<int>(std::ceil(rect[2] / distance)) + 1),
    std::min(coarse[1], static_cast<int>(std::ceil(rect[3] / distance)) + 1) };
  const int depthRect[4] = { static_cast<int>(coarseRect[0] * distance),
    static_cast<int>(coarseRect[1] * distance),
    std::min(width, static_cast<int>(std::ceil(coarseRect[2] * distance))),
    std::min(height, static_cast<int>(std::ceil(coarseRect[3] * distance))) };
  ClearErrors();
  if (!Size2D(impl.FullDepth, renWin, width, height, true) ||
    !Size2D(impl.CoarseDepth, renWin, coarse[0], coarse[1], true) ||
    !Size2D(impl.CoarseMedia, renWin, coarse[0], coarse[1], false))
  {
    return this->FailReduced("its buffers could not be allocated");
  }
  CopyWindowDepth(state, impl.FullDepth, x, y, depthRect);
  if (!ClearErrors())
  {
    return this->FailReduced("the window's depth could not be read");
  }

  if (!impl.CoarseDepthPass)
  {
    impl.CoarseDepthPass.reset(
      new vtkOpenGLQuadHelper(renWin, nullptr, vtkBrumeSliceVolumeCoarseDepthFS, ""));
    impl.UpsamplePass.reset(
      new vtkOpenGLQuadHelper(renWin, nullptr, vtkBrumeSliceVolumeUpsampleFS, ""));
  }
  if (!impl.CoarseDepthPass->Program || !impl.UpsamplePass->Program)
  {
    return this->FailReduced("its shaders could not be built");
  }

  const ReducedLayout layout{ distance, width, height, x, y, { coarse[0], coarse[1] },
    { rect[0], rect[1], rect[2], rect[3] },
    { coarseRect[0], coarseRect[1], coarseRect[2], coarseRect[3] } };
  if (!this->DrawCoarse(ren, layout))
  {
    return false;
  }
  this->Upsample(ren, layout);
  return true;
}

bool vtkBrumeOpenGLSliceVolumeMapper::DrawCoarse(vtkRenderer* ren, const ReducedLayout& layout)
{
  // The coarse buffer: its depth, then the slices.
  Internals& impl = *this->Impl;
  auto* renWin = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  vtkOpenGLState* state = renWin->GetState();
  vtkOpenGLState::ScopedglViewport viewportSaver(state);
  vtkOpenGLState::ScopedglEnableDisable blendSaver(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthSaver(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglDepthMask depthMaskSaver(state);
  vtkOpenGLState::ScopedglDepthFunc depthFuncSaver(state);
  vtkOpenGLState::ScopedglEnableDisable scissorSaver(state, GL_SCISSOR_TEST);
  state->PushFramebufferBindings();
  impl.CoarseFramebuffer->SetContext(renWin);
  impl.CoarseFramebuffer->Bind();
  impl.CoarseFramebuffer->AddColorAttachment(0, impl.CoarseMedia);
  impl.CoarseFramebuffer->AddDepthAttachment(impl.CoarseDepth);
  impl.CoarseFramebuffer->ActivateDrawBuffer(0);
  if (!impl.CoarseFramebuffer->CheckFrameBufferStatus(GL_FRAMEBUFFER))
  {
    state->PopFramebufferBindings();
    return this->FailReduced("its framebuffer is incomplete");
  }
  const int* coarseRect = layout.CoarseRect;
  vtkOpenGLState::ScopedglScissor scissorBoxSaver(state);
  state->vtkglEnable(GL_SCISSOR_TEST);
  state->vtkglScissor(
    coarseRect[0], coarseRect[1], coarseRect[2] - coarseRect[0], coarseRect[3] - coarseRect[1]);
  state->vtkglViewport(0, 0, layout.Coarse[0], layout.Coarse[1]);
  state->vtkglDisable(GL_BLEND);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDepthFunc(GL_ALWAYS);
  state->vtkglDepthMask(GL_TRUE);
  renWin->GetShaderCache()->ReadyShaderProgram(impl.CoarseDepthPass->Program);
  impl.FullDepth->Activate();
  vtkShaderProgram* program = impl.CoarseDepthPass->Program;
  program->SetUniformi("fullDepth", impl.FullDepth->GetTextureUnit());
  const int fullSize[2] = { layout.Width, layout.Height };
  program->SetUniform2i("fullSize", fullSize);
  program->SetUniform2i("coarseSize", layout.Coarse);
  program->SetUniformf("sampleDistance", static_cast<float>(layout.Distance));
  impl.CoarseDepthPass->Render();
  impl.FullDepth->Deactivate();
  // The slices are tested against the coarse depth as against the window's.
  state->vtkglDepthFunc(GL_LEQUAL);
  this->DrawRuns(ren, true);
  state->PopFramebufferBindings();
  return true;
}

void vtkBrumeOpenGLSliceVolumeMapper::Upsample(vtkRenderer* ren, const ReducedLayout& layout)
{
  // Upsampled over the window: C = L + T C_behind.
  Internals& impl = *this->Impl;
  auto* renWin = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  vtkOpenGLState* state = renWin->GetState();
  const int* rect = layout.Rect;
  vtkOpenGLState::ScopedglEnableDisable scissorSaver(state, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglScissor scissorBoxSaver(state);
  state->vtkglEnable(GL_SCISSOR_TEST);
  state->vtkglScissor(layout.X + rect[0], layout.Y + rect[1], rect[2] - rect[0], rect[3] - rect[1]);
  vtkOpenGLState::ScopedglEnableDisable blendSaver(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthSaver(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFuncSaver(state);
  state->vtkglEnable(GL_BLEND);
  state->vtkglBlendFuncSeparate(GL_ONE, GL_SRC1_COLOR, GL_ONE, GL_SRC1_ALPHA);
  state->vtkglDisable(GL_DEPTH_TEST);
  renWin->GetShaderCache()->ReadyShaderProgram(impl.UpsamplePass->Program);
  vtkShaderProgram* program = impl.UpsamplePass->Program;
  impl.FullDepth->Activate();
  impl.CoarseDepth->Activate();
  impl.CoarseMedia->Activate();
  program->SetUniformi("fullDepth", impl.FullDepth->GetTextureUnit());
  program->SetUniformi("coarseDepth", impl.CoarseDepth->GetTextureUnit());
  program->SetUniformi("coarseMedia", impl.CoarseMedia->GetTextureUnit());
  const int fullSize[2] = { layout.Width, layout.Height };
  program->SetUniform2i("fullSize", fullSize);
  program->SetUniform2i("coarseSize", layout.Coarse);
  program->SetUniformf("sampleDistance", static_cast<float>(layout.Distance));
  vtkCamera* camera = ren->GetActiveCamera();
  const double* range = camera->GetClippingRange();
  const float clipping[2] = { static_cast<float>(range[0]), static_cast<float>(range[1]) };
  program->SetUniform2f("clippingRange", clipping);
  program->SetUniformi("perspective", camera->GetParallelProjection() ? 0 : 1);
  impl.UpsamplePass->Render();
  impl.FullDepth->Deactivate();
  impl.CoarseDepth->Deactivate();
  impl.CoarseMedia->Deactivate();
}
