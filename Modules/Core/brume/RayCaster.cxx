// SPDX-License-Identifier: BSD-3-Clause
#include "brume/RayCaster.h"

#include <embree3/rtcore.h>

#include <limits>

namespace brume
{

struct RayCaster::Internals
{
  RTCDevice Device = nullptr;
  RTCScene Scene = nullptr;
};

namespace
{
void ErrorCallback(void* userPtr, RTCError code, const char* message)
{
  auto* error = static_cast<std::string*>(userPtr);
  if (error->empty())
  {
    *error = "Embree error " + std::to_string(static_cast<int>(code)) + ": " +
      (message ? message : "(no message)");
  }
}
}

RayCaster::RayCaster(const Scene& scene)
  : Impl(new Internals)
{
  this->Bounds = { Vec3(std::numeric_limits<float>::max()),
    Vec3(-std::numeric_limits<float>::max()) };
  this->Impl->Device = rtcNewDevice(nullptr);
  if (!this->Impl->Device)
  {
    this->Error = "Embree could not create a device";
    return;
  }
  rtcSetDeviceErrorFunction(this->Impl->Device, ErrorCallback, &this->Error);
  this->Impl->Scene = rtcNewScene(this->Impl->Device);
  rtcSetSceneBuildQuality(this->Impl->Scene, RTC_BUILD_QUALITY_HIGH);
  for (std::size_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    const Surface& surface = scene.Surfaces[s];
    RTCGeometry geom = rtcNewGeometry(this->Impl->Device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
      RTC_FORMAT_FLOAT3, 3 * sizeof(float), surface.Vertices.size()));
    auto* indices = static_cast<unsigned int*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX,
      0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned int), surface.Triangles.size()));
    if (!vertices || !indices)
    {
      rtcReleaseGeometry(geom);
      return;
    }
    for (std::size_t i = 0; i < surface.Vertices.size(); ++i)
    {
      const Vec3& v = surface.Vertices[i];
      vertices[3 * i + 0] = v.x;
      vertices[3 * i + 1] = v.y;
      vertices[3 * i + 2] = v.z;
      for (int a = 0; a < 3; ++a)
      {
        this->Bounds.lower[a] = std::min(this->Bounds.lower[a], v[a]);
        this->Bounds.upper[a] = std::max(this->Bounds.upper[a], v[a]);
      }
    }
    for (std::size_t i = 0; i < surface.Triangles.size(); ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        indices[3 * i + k] = surface.Triangles[i][k];
      }
    }
    rtcCommitGeometry(geom);
    // Geometry ids are the surface indices.
    rtcAttachGeometryByID(this->Impl->Scene, geom, static_cast<unsigned int>(s));
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(this->Impl->Scene);
}

RayCaster::~RayCaster()
{
  if (this->Impl->Scene)
  {
    rtcReleaseScene(this->Impl->Scene);
  }
  if (this->Impl->Device)
  {
    rtcReleaseDevice(this->Impl->Device);
  }
}

bool RayCaster::Intersect(
  const Vec3& o, const Vec3& d, float tnear, float tfar, SurfaceHit& hit) const
{
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray.org_x = o.x;
  rh.ray.org_y = o.y;
  rh.ray.org_z = o.z;
  rh.ray.dir_x = d.x;
  rh.ray.dir_y = d.y;
  rh.ray.dir_z = d.z;
  rh.ray.tnear = tnear;
  rh.ray.tfar = tfar;
  rh.ray.time = 0.f;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(this->Impl->Scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
  {
    return false;
  }
  hit.T = rh.ray.tfar;
  hit.Surface = rh.hit.geomID;
  hit.Triangle = rh.hit.primID;
  hit.Ng = { rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z };
  return true;
}

} // namespace brume
