#pragma once
// The process-wide Embree device (created on first use; Embree devices are thread-safe and
// meant to be shared). Embree errors become exceptions.
#include <embree3/rtcore.h>

#include <string>

#include "sim/frames.h"

namespace sonarloop::scene {

RTCDevice embree_device();

// Throws std::runtime_error("<what>: <Embree error>") if the device has a pending error.
void check_embree(const std::string& what);

// Fills `rh` with the ray from origin (in the Embree scene's coordinates) along dir over
// [tnear, tfar], not yet hit: every field Embree reads is set.
inline void set_ray(RTCRayHit& rh, const Vec3& origin, const Vec3& dir, double tnear, double tfar,
                    unsigned id = 0) {
  rh.ray.org_x = static_cast<float>(origin.x());
  rh.ray.org_y = static_cast<float>(origin.y());
  rh.ray.org_z = static_cast<float>(origin.z());
  rh.ray.dir_x = static_cast<float>(dir.x());
  rh.ray.dir_y = static_cast<float>(dir.y());
  rh.ray.dir_z = static_cast<float>(dir.z());
  rh.ray.tnear = static_cast<float>(tnear);
  rh.ray.tfar = static_cast<float>(tfar);
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = id;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

// The first hit of one ray (rtcIntersect1); rh.hit.geomID is RTC_INVALID_GEOMETRY_ID if none.
inline RTCRayHit intersect_one(RTCScene scene, const Vec3& origin, const Vec3& dir, double tnear,
                               double tfar) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  set_ray(rh, origin, dir, tnear, tfar);
  rtcIntersect1(scene, &ctx, &rh);
  return rh;
}

}  // namespace sonarloop::scene
