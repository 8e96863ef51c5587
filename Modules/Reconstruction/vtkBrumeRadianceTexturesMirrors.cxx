// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeRadianceTextures' mirrors and sharp glossy surfaces: which are
// cast (before the build), and their reflections toward each new eye
// (brume::MirrorReflection).
#include "vtkBrumeRadianceTextures.h"

#include "vtkAlgorithm.h"
#include "vtkBrumeSMP.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"

#include "brume/Reflection.h"

#include <algorithm>

bool vtkBrumeRadianceTextures::PlanReflections()
{
  // Mirrors and sharp glossy lobes are cast; a glossy lobe only where the
  // delta lights' direct light is computed (cast rays cannot meet them).
  this->Mirrors.clear();
  this->MirrorsCurrent = false;
  for (std::size_t s = 0; s < this->Scene.Surfaces.size(); ++s)
  {
    const brume::Surface& surface = this->Scene.Surfaces[s];
    if (!brume::MirrorReflection::Casts(surface))
    {
      continue;
    }
    const bool lobes = this->Scene.Lights.empty() || this->Objects[s]->GetDirect().IsEnabled();
    this->Objects[s]->Options().LobeCast = lobes;
    if (lobes || brume::MirrorReflection::HasMirror(surface))
    {
      this->Mirrors.push_back(s);
    }
  }
  if (this->Mirrors.empty() || this->Caster)
  {
    return true;
  }
  this->Caster = vtkBrumeSceneConversion::SharedRayCaster(this->Scene);
  if (!this->Caster->GetError().empty())
  {
    vtkErrorWithObjectMacro(
      this->Filter, "Cannot cast the mirrors' rays: " << this->Caster->GetError() << ".");
    this->Caster.reset();
    return false;
  }
  return true;
}

std::vector<bool> vtkBrumeRadianceTextures::ReflectMirrors(const brume::Vec3& eye)
{
  std::vector<bool> moved(this->Objects.size(), false);
  const brume::Vec3& last = this->MirrorEye;
  if (this->Mirrors.empty() ||
    (this->MirrorsCurrent && last.x == eye.x && last.y == eye.y && last.z == eye.z))
  {
    return moved;
  }
  const brume::ParallelFor parallelFor = vtkBrumeSMP::ParallelFor();
  std::vector<const brume::ObjectRadiance*> objects;
  for (const auto& object : this->Objects)
  {
    objects.push_back(object.get());
  }
  brume::MirrorReflection reflection(this->Scene, *this->Caster, objects);
  // View-dependent objects other than mirrors are looked up in textures
  // toward the point the reflected rays come from: a planar mirror's
  // mirrored eye (a curved one's: the eye itself).
  std::vector<std::size_t> seen;
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    if (this->Objects[o]->GetLayout().ViewDependent &&
      std::find(this->Mirrors.begin(), this->Mirrors.end(), o) == this->Mirrors.end())
    {
      seen.push_back(o);
    }
  }
  // A glossy surface casts LobeSamples rays per texel and blurs what it
  // reflects: half the texels along each axis.
  auto isMirror = [&](std::size_t s)
  { return brume::MirrorReflection::HasMirror(this->Scene.Surfaces[s]); };
  auto dimsOf = [&](std::size_t s)
  {
    const int n = isMirror(s) ? this->Settings.MirrorResolution
                              : std::max(1, this->Settings.MirrorResolution / 2);
    const brume::SurfaceChart& chart = this->Objects[s]->GetLayout().Chart;
    return FixedResolution(brume::Vec3(chart.Width, chart.Height, 0.f), n);
  };
  std::vector<std::vector<float>> views(this->Objects.size());
  // The rays a planar surface reflects come from the eye mirrored by its
  // plane: the view-dependent objects are looked up toward that point.
  auto lookFrom = [&](std::size_t s, const brume::Vec3& viewer)
  {
    brume::Vec3 from = viewer;
    brume::MirrorReflection::MirroredEye(this->Scene.Surfaces[s], viewer, from);
    for (const std::size_t o : seen)
    {
      this->Objects[o]->UpdateView(from, parallelFor);
      moved[o] = true;
      views[o] = this->Objects[o]->GetOutput().Radiance;
      reflection.SetTexture(o, { views[o].data(), this->Objects[o]->GetOutput().Dims });
    }
    return from;
  };
  for (const std::size_t m : this->Mirrors)
  {
    // Surfaces that cast start from their own texture (without what they
    // reflect); a mirror shows the sharp glossy ones with their lobes cast
    // toward its mirrored eye, their rays looking from that point mirrored
    // by their own plane.
    for (const std::size_t c : this->Mirrors)
    {
      const brume::ObjectRadiance& own = *this->Objects[c];
      reflection.SetTexture(c, { own.GetUnreflected().Radiance.data(), own.GetUnreflected().Dims });
    }
    brume::Vec3 mirrored = eye;
    brume::MirrorReflection::MirroredEye(this->Scene.Surfaces[m], eye, mirrored);
    if (isMirror(m))
    {
      for (const std::size_t c : this->Mirrors)
      {
        if (c == m || !this->Objects[c]->Options().LobeCast || isMirror(c))
        {
          continue;
        }
        lookFrom(c, mirrored);
        const std::array<int, 3> dims = dimsOf(c);
        reflection.Reflect(c, mirrored, { dims[0], dims[1] }, views[c], parallelFor);
        reflection.SetTexture(c, { views[c].data(), dims });
      }
    }
    lookFrom(m, eye);
    const std::array<int, 3> dims = dimsOf(m);
    std::vector<float> radiance;
    reflection.Reflect(m, eye, { dims[0], dims[1] }, radiance, parallelFor);
    this->Objects[m]->SetReflected(std::move(radiance), dims);
    this->Outputs[m] = nullptr;
  }
  this->MirrorEye = eye;
  this->MirrorsCurrent = true;
  return moved;
}
