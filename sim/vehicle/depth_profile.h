#pragma once
// The vertical profile z(s) (depth, m, down) along the path, and terrain following.
//
// Terrain following is precomputed once, at fixed steps Δs along the path (DepthDesc::
// profile_step_m, default 0.5 m, i.e. Δt = Δs/u = 0.25 s at 2 m/s), so that the vehicle state at
// any time is a pure lookup: no integration state, no dependence on the order of queries.
//
// Knots (terrain_following_depths), with z_d(j) = max(seabed(j) - altitude, min_depth) the
// commanded depth and c = w_max·Δt the most the depth may change in one step:
//   1. look-ahead (backward rate limit): to be no deeper than z_d(j) at step j, the vehicle must
//      be no deeper than z_d(j) + (j - k)·c at step k <= j. Over the steps it can see,
//      j in [k, k + L/Δs] (L = look_ahead_m), the target is the shallowest of these:
//        target(k) = min_j (z_d(j) + (j - k)·c)          (a sliding-window minimum, O(n))
//      With an unlimited look-ahead this is the largest depth profile that never goes below the
//      commanded altitude and never climbs faster than w_max (the lower rate-limited envelope).
//   2. forward rate limit: z(0) = target(0), z(k) = clamp(target(k), z(k-1) - c, z(k-1) + c).
//      The vehicle dives at no more than w_max when the seabed falls away, and climbs at no more
//      than w_max if the look-ahead was too short to start in time (then the altitude drops below
//      the command: Trajectory::min_altitude_m reports it).
// So both the climb and the dive rate are bounded by w_max, and with enough look-ahead the
// knots never fall below the commanded altitude (they are higher over hollows too narrow or
// steep to dive into, and where min_depth stops the vehicle).
//
// Evaluation (DepthProfile): the knots joined by straight lines, z_l(s), have a vertical rate
// that steps at the knots. They are smoothed by a moving average over a width W >= Δs
// (DepthDesc::vertical_smoothing_m):
//   z(s) = (1/W)·∫_{s-W/2}^{s+W/2} z_l,   dz/ds = (z_l(s + W/2) - z_l(s - W/2)) / W.
// * The rate bound survives exactly: dz/ds is a difference quotient of z_l, whose |slope| is at
//   most w_max/u, so |w| <= w_max.
// * The slope is continuous (pitch has no steps) and changes by at most 2·(w_max/u)/W per metre:
//   |dw/dt| <= 2·u·w_max/W (0.4 m/s² by default), the vehicle's vertical acceleration bound.
// * Straight stretches of z_l are unchanged (the vehicle keeps its altitude on a steady slope).
//   Where the slope of z_l changes by Δσ, z departs from z_l by up to |Δσ|·W/8: shallower where
//   the vehicle levels off after a dive (safe), deeper where it stops climbing over a crest.
//   The worst case, a climb at w_max turning into a dive at w_max over a sharp crest, brings the
//   vehicle w_max·W/(4u) (0.31 m by default) below the commanded altitude; over a smooth seabed
//   of curvature κ_b the departure is about κ_b·W²/24.
// Outside the knots the profile is extended by its end values; within smoothing_margin_steps()
// of the ends the average sees that extension, so Trajectory pads the knots by that many steps
// beyond both ends of the path (on its straight run-in and run-out).
#include <cstddef>
#include <span>
#include <vector>

namespace sonarloop::vehicle {

class DepthProfile {
 public:
  // A constant depth.
  explicit DepthProfile(double depth_m = 0.0) : z_{depth_m}, integral_{0.0} {}
  // Knots z_k at s = origin_m + k·step_m, k = 0..n-1 (n >= 1, step_m > 0), smoothed over
  // max(smoothing_m, step_m).
  DepthProfile(std::vector<double> knot_depths_m, double step_m, double smoothing_m,
               double origin_m = 0.0);

  // Steps at each end over which the smoothing is affected by the end of the knots.
  static std::size_t smoothing_margin_steps(double step_m, double smoothing_m);

  double depth_at(double s_m) const;  // smoothed z(s), m
  double slope_at(double s_m) const;  // dz/ds (dimensionless; w = u·dz/ds)

  const std::vector<double>& knots() const { return z_; }  // before smoothing
  double step_m() const { return step_m_; }
  double smoothing_m() const { return width_m_; }
  double origin_m() const { return origin_m_; }

 private:
  double linear_at(double s_m) const;    // z_l(s)
  double integral_to(double s_m) const;  // ∫ z_l from the first knot to s

  std::vector<double> z_;         // rate-limited knots
  std::vector<double> integral_;  // ∫ z_l from the first knot to each knot
  double step_m_ = 1.0;
  double width_m_ = 1.0;
  double origin_m_ = 0.0;
};

// Terrain-following knot depths (steps 1 and 2 above) for seabed depths sampled every step_m
// along the path (flown at speed_m_s). All arguments > 0 except look_ahead_m, min_depth_m >= 0.
std::vector<double> terrain_following_depths(std::span<const double> seabed_depth_m, double step_m,
                                             double speed_m_s, double altitude_m,
                                             double max_climb_rate_m_s, double look_ahead_m,
                                             double min_depth_m);

}  // namespace sonarloop::vehicle
