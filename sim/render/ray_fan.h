#pragma once
// The ray fan of a ping, shared by both renderers: the ray tracer casts all of it at the scene,
// the profile renderer only the part of it that a target can be in.
//
// Vertical edges: rays are placed where a flat seabed at the measured nadir altitude a would put
// `rays_per_bin` of them in every range bin (depression δ = asin(a/r)), from the start of the
// range window (or the altitude) to kRangeMargin beyond its end. Edge m has sin(world
// depression) = a / (r_start + m·bin/rays_per_bin).
//
// Along track: one fan per along-track sample j of the EchoModel (strip offset or beam angle ψ).
// A FanPlane turns the world depressions of the edges into the vehicle-frame depression of the
// sample's beam plane (tilted with roll and pitch), and makes the ray of each tube with its solid
// angle and two-way vertical pattern. Each ray carries its own solid angle, so uneven terrain
// changes how many rays a bin gets but not the energy it receives.
#include <embree3/rtcore.h>

#include <vector>

#include "sim/frames.h"
#include "sim/render/echo_model.h"

namespace sonarloop::render {

// Rays are fanned to 5 % beyond the maximum range on a flat seabed, so that rising terrain at
// far range is still reached.
inline constexpr double kRangeMargin = 1.05;

struct FanEdges {
  int n_vert = 0;      // tubes (edges = n_vert + 1); 0: nothing to render
  double r_max = 0.0;  // end of the rendered window (slant range)
};

// Fills edge_sin (sin of world depression at each vertical edge) for a ping at nadir altitude a.
FanEdges fan_edges(const SonarSetup& sonar, int rays_per_bin, double altitude,
                   const RenderOptions& options, std::vector<float>& edge_sin);

class FanPlane {
 public:
  // Along-track sample j of `echo` on side (0 port, 1 starboard) for a sonar at `pose`;
  // origin_local is the sonar's position in the coordinates of the Embree scene the rays go to.
  FanPlane(const EchoModel& echo, const Mat3& R_WV, int side, int j, const Vec3& origin_local);

  // Vehicle-frame depression of the ray of this plane whose world direction has z component
  // sin_world_depression.
  double depression_v(double sin_world_depression) const;
  // The ray of the tube between vehicle-frame depressions d_lo and d_hi (tfar = r_max).
  void make_ray(double d_lo, double d_hi, double r_max, unsigned id, RTCRayHit& rh,
                RayMeta& meta) const;
  // World direction of the ray at vehicle-frame depression d.
  Vec3 direction(double d) const;

 private:
  const EchoModel& echo_;
  Mat3 R_;
  double sign_;
  double sin_psi_, cos_psi_;
  Vec3 origin_;
  double a_coef_, b_coef_, c0_, amp_, phase_;
  double cos_dep_, sin_dep_;
  float weight_;
  std::uint8_t side_;
};

}  // namespace sonarloop::render
