// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeDisplayPass.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkRenderState.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkBrumeDisplayPass);

struct vtkBrumeDisplayPass::Internals
{
  vtkSmartPointer<vtkOpenGLFramebufferObject> Framebuffer;
  vtkSmartPointer<vtkTextureObject> Color;
  vtkSmartPointer<vtkTextureObject> Depth;
  std::unique_ptr<vtkOpenGLQuadHelper> Quad;
};

vtkBrumeDisplayPass::vtkBrumeDisplayPass()
  : Impl(new Internals)
{
  vtkNew<vtkRenderStepsPass> steps;
  this->SetDelegatePass(steps);
}

vtkBrumeDisplayPass::~vtkBrumeDisplayPass() = default;

namespace
{
// The radiance the display transform (exposure, clamp, sRGB curve) shows
// as the display value `shown` (each channel in [0, 1]).
void BackgroundRadiance(const double shown[3], double exposure, double radiance[3])
{
  for (int c = 0; c < 3; ++c)
  {
    const double v = std::min(1.0, std::max(0.0, shown[c]));
    const double linear = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    radiance[c] = exposure > 0.0 ? linear / exposure : 0.0;
  }
}
}

void vtkBrumeDisplayPass::Render(const vtkRenderState* s)
{
  this->NumberOfRenderedProps = 0;
  if (!this->DelegatePass)
  {
    vtkErrorMacro("No delegate pass: nothing drawn.");
    return;
  }
  vtkRenderer* renderer = s->GetRenderer();
  auto* window = static_cast<vtkOpenGLRenderWindow*>(renderer->GetRenderWindow());
  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable blendSaver(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthSaver(state, GL_DEPTH_TEST);
  Internals& impl = *this->Impl;

  // The delegate draws radiance into a float texture.
  int x, y, w, h;
  renderer->GetTiledSizeAndOrigin(&w, &h, &x, &y);
  if (!impl.Color)
  {
    impl.Color = vtkSmartPointer<vtkTextureObject>::New();
    impl.Color->SetContext(window);
    impl.Color->SetMinificationFilter(vtkTextureObject::Nearest);
    impl.Color->SetMagnificationFilter(vtkTextureObject::Nearest);
    impl.Color->Allocate2D(w, h, 4, VTK_FLOAT);
  }
  impl.Color->Resize(w, h);
  // The delegate's depth, as a texture the transform below writes on to
  // the window: ParaView composites parallel processes' images by depth,
  // and counts a pixel at the far plane as empty, so what is drawn there
  // (a medium over the sky, whose slices write no depth) is written just
  // before it.
  if (!impl.Depth)
  {
    impl.Depth = vtkSmartPointer<vtkTextureObject>::New();
    impl.Depth->SetContext(window);
    impl.Depth->SetMinificationFilter(vtkTextureObject::Nearest);
    impl.Depth->SetMagnificationFilter(vtkTextureObject::Nearest);
    impl.Depth->AllocateDepth(w, h, vtkTextureObject::Float32);
  }
  impl.Depth->Resize(w, h);
  if (!impl.Framebuffer)
  {
    impl.Framebuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
    impl.Framebuffer->SetContext(window);
    // Attached once; the delegate's render keeps an attached depth.
    state->PushFramebufferBindings();
    impl.Framebuffer->Bind();
    impl.Framebuffer->AddDepthAttachment(impl.Depth);
    state->PopFramebufferBindings();
  }
  // The background as radiance that the transform below shows as the
  // renderer's own colours (sRGB values, as VTK's views show them): a
  // view's background looks the same with Brume as without.
  double background[3], background2[3], radiance[3], radiance2[3];
  renderer->GetBackground(background);
  renderer->GetBackground2(background2);
  BackgroundRadiance(background, this->Exposure, radiance);
  BackgroundRadiance(background2, this->Exposure, radiance2);
  renderer->SetBackground(radiance);
  renderer->SetBackground2(radiance2);
  state->PushFramebufferBindings();
  this->RenderDelegate(s, w, h, w, h, impl.Framebuffer, impl.Color);
  state->PopFramebufferBindings();
  renderer->SetBackground(background);
  renderer->SetBackground2(background2);

  // Then exposure, clamp and the sRGB curve, as vtkBrumeFloatImageCapture::ToneMap.
  if (!impl.Quad)
  {
    std::string fs = vtkOpenGLRenderUtilities::GetFullScreenQuadFragmentShaderTemplate();
    vtkShaderProgram::Substitute(fs, "//VTK::FSQ::Decl",
      "uniform sampler2D radiance;\nuniform sampler2D depth;\nuniform float exposure;\n");
    vtkShaderProgram::Substitute(fs, "//VTK::FSQ::Impl",
      "  vec3 x = clamp(exposure * texture2D(radiance, texCoord).rgb, 0.0, 1.0);\n"
      "  vec3 low = 12.92 * x;\n"
      "  vec3 high = 1.055 * pow(x, vec3(1.0 / 2.4)) - 0.055;\n"
      "  gl_FragData[0] = vec4(mix(high, low, vec3(lessThanEqual(x, vec3(0.0031308)))), "
      "texture2D(radiance, texCoord).a);\n"
      "  float d = texture2D(depth, texCoord).r;\n"
      "  gl_FragDepth = texture2D(radiance, texCoord).a > 0.0 && d >= 1.0 ? 0.99999988 : d;\n");
    impl.Quad.reset(new vtkOpenGLQuadHelper(
      window, vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(), fs.c_str(), ""));
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(impl.Quad->Program);
  }
  if (!impl.Quad->Program || !impl.Quad->Program->GetCompiled())
  {
    vtkErrorMacro("Could not build the display shader: nothing drawn.");
    return;
  }
  impl.Color->Activate();
  impl.Depth->Activate();
  impl.Quad->Program->SetUniformi("radiance", impl.Color->GetTextureUnit());
  impl.Quad->Program->SetUniformi("depth", impl.Depth->GetTextureUnit());
  impl.Quad->Program->SetUniformf("exposure", static_cast<float>(this->Exposure));
  state->vtkglDisable(GL_BLEND);
  // Depth written as it is, whatever the window held.
  vtkOpenGLState::ScopedglDepthFunc depthFuncSaver(state);
  vtkOpenGLState::ScopedglDepthMask depthMaskSaver(state);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDepthFunc(GL_ALWAYS);
  state->vtkglDepthMask(GL_TRUE);
  state->vtkglViewport(x, y, w, h);
  state->vtkglScissor(x, y, w, h);
  impl.Quad->Render();
  impl.Depth->Deactivate();
  impl.Color->Deactivate();
}

void vtkBrumeDisplayPass::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Superclass::ReleaseGraphicsResources(w);
  this->Impl->Quad.reset();
  if (this->Impl->Framebuffer)
  {
    this->Impl->Framebuffer->ReleaseGraphicsResources(w);
  }
  this->Impl->Framebuffer = nullptr;
  if (this->Impl->Color)
  {
    this->Impl->Color->ReleaseGraphicsResources(w);
  }
  this->Impl->Color = nullptr;
  if (this->Impl->Depth)
  {
    this->Impl->Depth->ReleaseGraphicsResources(w);
  }
  this->Impl->Depth = nullptr;
}

void vtkBrumeDisplayPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Exposure: " << this->Exposure << "\n";
}
