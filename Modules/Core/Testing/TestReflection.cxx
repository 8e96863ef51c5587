// SPDX-License-Identifier: BSD-3-Clause
// Mirrors at display time (brume/Reflection.h) against analytic radiance:
// an emitter seen in a mirror, through an absorbing slab, two mirrors facing
// each other up to the bounded depth, a curved mirror's atlas, the mirrored
// eye, and the same texture whatever the threads.
#include "brume/Reconstruction.h"
#include "brume/Reflection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

using namespace brume;

namespace
{
// |x|, |y| <= half in the plane z, facing +z (up) or -z.
Surface Square(const std::string& name, float half, float z, bool up, const Material& m)
{
  Surface s;
  s.Name = name;
  s.Vertices = { { -half, -half, z }, { half, -half, z }, { half, half, z }, { -half, half, z } };
  s.Triangles = up ? std::vector<std::array<std::uint32_t, 3>>{ { 0, 1, 2 }, { 0, 2, 3 } }
                   : std::vector<std::array<std::uint32_t, 3>>{ { 0, 2, 1 }, { 0, 3, 2 } };
  s.Mat = m;
  return s;
}

Material MirrorOf(const Vec3& specular, const Vec3& emission = Vec3(0.f))
{
  Material m;
  m.Type = MaterialType::Mirror;
  m.Reflectance = Vec3(0.f);
  m.Specular = specular;
  m.Emission = emission;
  return m;
}

Material Emitter(const Vec3& emission)
{
  Material m;
  m.Reflectance = Vec3(0.f);
  m.Emission = emission;
  return m;
}

// Every object's texture from no particle at all: emission only (media: no
// source radiance), which the reflection must carry exactly.
struct Reconstructed
{
  std::vector<std::unique_ptr<ObjectRadiance>> Objects;
  std::vector<const ObjectRadiance*> Pointers;

  Reconstructed(const Scene& scene, const Vec3& eye)
  {
    const HitArrays none;
    for (const Surface& s : scene.Surfaces)
    {
      this->Objects.emplace_back(new ObjectRadiance(s, MakeChart(s, nullptr), { 8, 8 }, 2));
    }
    for (const Medium& m : scene.Media)
    {
      this->Objects.emplace_back(new ObjectRadiance(m, { 4, 4, 4 }, 2));
    }
    for (auto& o : this->Objects)
    {
      EXPECT_EQ(o->Build(none, nullptr, 0, eye, 1.0, SerialFor()), "");
      this->Pointers.push_back(o.get());
    }
  }
};

Vec3 TexelOf(const std::vector<float>& rgb, std::size_t t)
{
  return { rgb[3 * t], rgb[3 * t + 1], rgb[3 * t + 2] };
}
}

TEST(Reflection, EmitterSeenInAPlanarMirrorThroughAnAbsorbingSlab)
{
  // A mirror at z = 0 facing up, a large emitter at z = 2 facing it, and
  // (second case) an absorbing slab 0.5 thick between them: each texel
  // shows rho_s L_e exp(-sigma_t 0.5 / cos theta) along its reflected ray.
  const Vec3 rho(0.5f, 0.6f, 0.7f), Le(2.f, 3.f, 4.f), eye(0.3f, 0.2f, 1.5f);
  for (const bool slab : { false, true })
  {
    Scene scene;
    scene.Surfaces.push_back(Square("mirror", 1.f, 0.f, true, MirrorOf(rho)));
    scene.Surfaces.push_back(Square("sky", 8.f, 2.f, false, Emitter(Le)));
    const Vec3 sigmaA(0.3f, 0.7f, 1.1f);
    if (slab)
    {
      Medium m;
      m.Name = "slab";
      m.Bounds = { { -8.f, -8.f, 0.5f }, { 8.f, 8.f, 1.f } };
      m.SigmaA = sigmaA;
      m.SigmaS = Vec3(0.f);
      scene.Media.push_back(m);
    }
    ASSERT_EQ(scene.Validate(), "");
    const RayCaster caster(scene);
    const Reconstructed r(scene, eye);
    const MirrorReflection reflection(scene, caster, r.Pointers);
    std::vector<float> rgb;
    const int n = 16;
    reflection.Reflect(0, eye, { n, n }, rgb, SerialFor());
    ASSERT_EQ(rgb.size(), 3u * n * n);
    const PlanarFrame& f = r.Objects[0]->GetLayout().Chart.Frame;
    for (int t = 0; t < n * n; ++t)
    {
      const Vec3 x = f.Origin + f.U * ((t % n + 0.5f) / n) + f.V * ((t / n + 0.5f) / n);
      const Vec3 d = Reflect(Normalize(eye - x), Vec3(0.f, 0.f, 1.f));
      Vec3 want = rho * Le;
      if (slab)
      {
        for (int c = 0; c < 3; ++c)
        {
          want[c] *= std::exp(-sigmaA[c] * 0.5f / d.z);
        }
      }
      const Vec3 got = TexelOf(rgb, t);
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_NEAR(got[c], want[c], 2e-5f * want[c]) << "texel " << t << " channel " << c;
      }
    }
  }
}

TEST(Reflection, SharpGlossyLobeUnderAUniformSkyIsRhoSCosTheta)
{
  // A Phong floor of exponent 1000 under a uniform emitting sky: the lobe
  // about the mirror direction r holds cos(alpha) with mean (e + 1)/(e + 2),
  // and the azimuths cancel, so the cast lobe is rho_s L_e (r . n) exactly
  // in expectation. What a texel's 16 rays leave is the azimuthal term
  // sin(alpha) sin(theta_r) cos(phi), |.| < 0.1 sin(theta_r) for 99.3 % of
  // the lobe (alpha < 0.1): each texel within 2 %, and the mean over the 64
  // texels' 1,024 independent rays within 0.2 %. The particles' part (none
  // here) would add the diffuse.
  const Vec3 rho(0.6f), Le(2.f, 1.f, 0.5f), eye(0.2f, -0.3f, 1.2f);
  Material glossy;
  glossy.Type = MaterialType::Phong;
  glossy.Reflectance = Vec3(0.2f);
  glossy.Specular = rho;
  glossy.Exponent = 1000.f;
  Scene scene;
  scene.Surfaces.push_back(Square("floor", 1.f, 0.f, true, glossy));
  scene.Surfaces.push_back(Square("sky", 30.f, 2.f, false, Emitter(Le)));
  ASSERT_EQ(scene.Validate(), "");
  EXPECT_TRUE(MirrorReflection::Casts(scene.Surfaces[0]));
  const RayCaster caster(scene);
  Reconstructed r(scene, eye);
  r.Objects[0]->Options().LobeCast = true;
  const MirrorReflection reflection(scene, caster, r.Pointers);
  std::vector<float> rgb;
  const int n = 8;
  reflection.Reflect(0, eye, { n, n }, rgb, SerialFor());
  const PlanarFrame& f = r.Objects[0]->GetLayout().Chart.Frame;
  double sumGot = 0.0, sumWant = 0.0;
  for (int t = 0; t < n * n; ++t)
  {
    const Vec3 x = f.Origin + f.U * ((t % n + 0.5f) / n) + f.V * ((t / n + 0.5f) / n);
    const float cosR = Reflect(Normalize(eye - x), Vec3(0.f, 0.f, 1.f)).z;
    const Vec3 got = TexelOf(rgb, static_cast<std::size_t>(t));
    for (int c = 0; c < 3; ++c)
    {
      const float want = rho[c] * Le[c] * cosR;
      EXPECT_NEAR(got[c], want, 0.02f * want) << "texel " << t << " channel " << c;
    }
    sumGot += got.x;
    sumWant += rho.x * Le.x * cosR;
  }
  EXPECT_NEAR(sumGot / sumWant, 1.0, 2e-3);
  // Without ObjectOptions::LobeCast the texture is the particles' alone.
  r.Objects[0]->Options().LobeCast = false;
  reflection.Reflect(0, eye, { n, n }, rgb, SerialFor());
  EXPECT_EQ(TexelOf(rgb, 0).x, 0.f);
}

TEST(Reflection, MirrorsFacingEachOtherStopAtTheBoundedDepth)
{
  // Mirror A (z = 0, rho_A) faces mirror B (z = 1, rho_B, emitting L_e): a
  // ray leaving A bounces between them; B's emission reaches A's texel at
  // odd depths, weighted by the mirrors it met, up to MaxDepth bounces.
  const Vec3 rhoA(0.5f), rhoB(0.8f, 0.6f, 0.4f), Le(1.f, 2.f, 3.f);
  Scene scene;
  scene.Surfaces.push_back(Square("A", 40.f, 0.f, true, MirrorOf(rhoA)));
  scene.Surfaces.push_back(Square("B", 40.f, 1.f, false, MirrorOf(rhoB, Le)));
  ASSERT_EQ(scene.Validate(), "");
  const Vec3 eye(0.f, 0.f, 0.5f);
  const RayCaster caster(scene);
  const Reconstructed r(scene, eye);
  const MirrorReflection reflection(scene, caster, r.Pointers);
  std::vector<float> rgb;
  // 41 x 41 texels: the nine around the centre reflect rays that stay
  // between the mirrors for MaxDepth bounces.
  const int n = 41;
  reflection.Reflect(0, eye, { n, n }, rgb, SerialFor());
  Vec3 want(0.f), weight = rhoA;
  for (int depth = 1; depth <= MirrorReflection::MaxDepth; ++depth)
  {
    const bool onB = depth % 2 == 1;
    want += weight * (onB ? Le : Vec3(0.f));
    weight *= onB ? rhoB : rhoA;
  }
  for (int j = n / 2 - 1; j <= n / 2 + 1; ++j)
  {
    for (int i = n / 2 - 1; i <= n / 2 + 1; ++i)
    {
      const Vec3 got = TexelOf(rgb, static_cast<std::size_t>(j * n + i));
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_NEAR(got[c], want[c], 1e-5f * want[c]) << "texel " << i << ", " << j;
      }
    }
  }
}

TEST(Reflection, CurvedMirrorAtlasTexelsAreReflectionsUpToTheSeams)
{
  // A mirror folded by 20 degrees along y = 0 (not planar: an atlas of one
  // chart per triangle) under a large emitter: every texel the atlas gives a
  // triangle, the gutters' next to it included, shows rho_s L_e, and the
  // others keep the mirror's own texture (0): none is a blend.
  const Vec3 rho(0.9f), Le(1.f);
  Surface fold;
  fold.Name = "fold";
  const float rise = 0.17633f; // tan(10 degrees)
  fold.Vertices = { { -1, -1, rise }, { 1, -1, rise }, { 1, 0, 0 }, { -1, 0, 0 }, { 1, 1, rise },
    { -1, 1, rise } };
  fold.Triangles = { { 0, 1, 2 }, { 0, 2, 3 }, { 3, 2, 4 }, { 3, 4, 5 } };
  fold.Mat = MirrorOf(rho);
  Scene scene;
  scene.Surfaces.push_back(fold);
  scene.Surfaces.push_back(Square("sky", 50.f, 3.f, false, Emitter(Le)));
  ASSERT_EQ(scene.Validate(), "");
  const Vec3 eye(0.1f, 0.2f, 2.f);
  const RayCaster caster(scene);
  const Reconstructed r(scene, eye);
  ASSERT_EQ(r.Objects[0]->GetLayout().Chart.Type, SurfaceChart::Kind::Atlas);
  const MirrorReflection reflection(scene, caster, r.Pointers);
  std::vector<float> rgb;
  const int n = 64;
  reflection.Reflect(0, eye, { n, n }, rgb, SerialFor());
  std::size_t reflected = 0;
  for (int t = 0; t < n * n; ++t)
  {
    const float v = TexelOf(rgb, t).x;
    const bool full = std::abs(v - 0.9f) < 1e-5f;
    EXPECT_TRUE(full || v == 0.f) << "texel " << t << " holds " << v;
    reflected += full ? 1 : 0;
  }
  // The four triangles' charts cover part of the atlas.
  EXPECT_GT(reflected, static_cast<std::size_t>(n * n / 8));
}

TEST(Reflection, AnEyeOnTheMirrorGivesFiniteTexels)
{
  // The eye exactly at a texel's centre: no direction to reflect there, and
  // no index may come of a NaN (a fog above the mirror would be marched
  // along it). The texel shows the mirror's own texture (0), the others
  // their reflection.
  Scene scene;
  scene.Surfaces.push_back(Square("mirror", 1.f, 0.f, true, MirrorOf(Vec3(0.9f))));
  scene.Surfaces.push_back(Square("sky", 8.f, 2.f, false, Emitter(Vec3(1.f))));
  Medium fog;
  fog.Name = "fog";
  fog.Bounds = { { -0.5f, -0.5f, 0.2f }, { 0.5f, 0.5f, 0.8f } };
  scene.Media.push_back(fog);
  const RayCaster caster(scene);
  const PlanarFrame frame = [&]
  {
    PlanarFrame f;
    scene.Surfaces[0].ComputePlanarFrame(f);
    return f;
  }();
  const int n = 4;
  const Vec3 eye = frame.Origin + frame.U * (1.5f / n) + frame.V * (2.5f / n);
  const Reconstructed r(scene, eye);
  const MirrorReflection reflection(scene, caster, r.Pointers);
  std::vector<float> rgb;
  reflection.Reflect(0, eye, { n, n }, rgb, SerialFor());
  for (float v : rgb)
  {
    EXPECT_TRUE(std::isfinite(v));
  }
  EXPECT_EQ(TexelOf(rgb, 2 * n + 1).x, 0.f);
}

TEST(Reflection, MirroredEyeAndThreads)
{
  const Vec3 eye(0.3f, -0.4f, 2.5f);
  Scene scene;
  scene.Surfaces.push_back(Square("mirror", 1.f, -1.f, true, MirrorOf(Vec3(0.9f))));
  scene.Surfaces.push_back(Square("sky", 8.f, 2.f, false, Emitter(Vec3(1.f, 0.5f, 0.25f))));
  Medium fog;
  fog.Name = "fog";
  fog.Bounds = { { -0.5f, -0.5f, -0.5f }, { 0.5f, 0.5f, 0.5f } };
  fog.SigmaA = Vec3(0.4f);
  fog.SigmaS = Vec3(0.f);
  scene.Media.push_back(fog);
  Vec3 mirrored;
  ASSERT_TRUE(MirrorReflection::MirroredEye(scene.Surfaces[0], eye, mirrored));
  EXPECT_NEAR(mirrored.x, 0.3f, 1e-6f);
  EXPECT_NEAR(mirrored.y, -0.4f, 1e-6f);
  EXPECT_NEAR(mirrored.z, -4.5f, 1e-5f);
  EXPECT_TRUE(MirrorReflection::Casts(scene.Surfaces[0]));
  EXPECT_FALSE(MirrorReflection::Casts(scene.Surfaces[1]));

  // Rows handed out in reverse, in uneven ranges: the same texture.
  const RayCaster caster(scene);
  const Reconstructed r(scene, eye);
  const MirrorReflection reflection(scene, caster, r.Pointers);
  std::vector<float> serial, scrambled;
  reflection.Reflect(0, eye, { 37, 23 }, serial, SerialFor());
  const ParallelFor reversed = [](std::size_t begin, std::size_t end,
                                 const std::function<void(std::size_t, std::size_t)>& body)
  {
    for (std::size_t e = end; e > begin;)
    {
      const std::size_t b = e >= begin + 3 ? e - 3 : begin;
      body(b, e);
      e = b;
    }
  };
  reflection.Reflect(0, eye, { 37, 23 }, scrambled, reversed);
  EXPECT_EQ(serial, scrambled);
}
