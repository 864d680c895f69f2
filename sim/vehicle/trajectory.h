#pragma once
// The vehicle's true motion: a TrajectoryDesc turned into a continuous, deterministic function
// of time, state_at(t). Everything is computed once in the constructor (the path, the depth
// profile, the roll lag at each segment start); state_at is then a pure, thread-safe lookup,
// closed form within each piece, so the same t always gives the same state whatever the order
// or thread of the queries.
//
// Horizontal: the path of path.h, flown at constant horizontal speed u = speed_m_s, so the arc
// length is s = u·t. Turns are arcs of radius R = u / max_turn_rate_rad_s: the path's turn rate
// is u·κ, never more than the bound (sway adds its own, below).
//
// Sway (SwayDesc, optional): a lateral offset y(t) = A·sin(ωt + φ0), ω = 2π/period, along the
// path's starboard normal n. With the path tangent τ and turn rate r = u·κ (dn/dt = -r·τ):
//   p = p_path(s) + y·n,   v = (u - r·y)·τ + ẏ·n          (exact on lines and arcs)
//   yaw = ψ_path + k·atan(ẏ/u),  yaw rate = r + k·(ÿ/u) / (1 + (ẏ/u)²)   (k = yaw_coupling)
//
// Vertical (depth_profile.h): constant depth, or terrain following precomputed every
// profile_step_m with a look-ahead and a climb/dive rate bound, then smoothed over
// vertical_smoothing_m (bounded vertical acceleration); w = u·dz/ds (continuous).
//
// Attitude:
// * yaw: the path tangent plus the sway term above; continuous (the path is C1).
// * pitch = clamp(pitch_gain·atan2(-w, u), ±max_pitch): the flight-path angle (zero angle of
//   attack when pitch_gain = 1), nose up when climbing (w < 0). Continuous because w is.
// * roll: the coordinated-turn bank, tan φ = u·ψ̇ / g = u²·κ / g (lift balances weight and the
//   centripetal force; standard flight mechanics, valid for any speed and turn rate), times
//   roll_gain, limited to ±max_roll; starboard down in a starboard turn for roll_gain > 0. The
//   command is constant on each segment (only the path's turn rate rolls the vehicle; sway does
//   not), and roll follows it through a first-order lag of time constant τ = roll_time_constant_s:
//     φ(t) = φ_cmd + (φ(t_i) - φ_cmd)·exp(-(t - t_i)/τ)   on segment i starting at t_i,
//   with φ = 0 before the start (the vehicle was flying straight) and φ_cmd = 0 after the end.
//   So roll is continuous (no steps at segment joins) and reaches 95 % of a new bank in 3τ.
//   g = 9.80665 m/s² (standard gravity, 3rd CGPM 1901).
// * waves (optional; AttitudeDesc roll_amplitude, pitch_amplitude, wave_period_s): a vehicle
//   near the surface in a regular swell is rocked by the wave's orbital motion, the water
//   particles' velocity and the sea surface slope, at the wave encounter period T: the period at
//   which the moving vehicle meets crests (the wave period Doppler-shifted by its speed along
//   the wave direction; given directly here, so it does not change with the heading). The
//   response is modelled as first order, linear and at a single frequency: first-order (Airy)
//   wave theory gives a sinusoidal forcing of amplitude proportional to the wave height, and a
//   linear vehicle answers it with a sinusoid at the same period, of amplitude the forcing times
//   its response amplitude operator (here given directly as the angle amplitudes), with no
//   harmonics and no transient. Its phase depends on how the forcing period compares with each
//   mode's natural period and damping (in phase well below resonance, a quarter period behind
//   at resonance, in antiphase well above), and roll and pitch have different natural periods,
//   so the two are in general not in phase. The model takes pitch a quarter period ahead of
//   roll: the two are then uncorrelated over a period (the mean of sin·cos is 0) and the vehicle
//   axis traces an ellipse rather than rocking in one plane. With ω = 2π/T and t = t_s, the
//   seconds since the mission start that the rest of state_at uses (also outside [0, duration]):
//     roll  = clamp(φ_turn(t) + roll_amplitude·sin(ω·t), ±max_roll)
//     pitch = clamp(θ_path(t) + pitch_amplitude·cos(ω·t), ±max_pitch)
//   where φ_turn is the lagged turn roll and θ_path the flight-path pitch (gain applied) above.
//   The waves add up to amplitude·ω to the roll and pitch rates; they do not move the vehicle
//   (sway, above, is separate). An amplitude of 0 adds nothing: the state is then bit for bit
//   that of the model without waves.
//
// Outside [0, duration_s()] the vehicle keeps going straight along the first / last heading at
// the same speed; altitude is then unknown (NaN). In terrain following the depth profile is
// also computed over a margin of the straight run-in and run-out (a few smoothing widths: so
// that the smoothing has no end effects on the path) and held constant beyond it.
#include <cstddef>
#include <functional>
#include <vector>

#include "sim/core/sim_time.h"
#include "sim/vehicle/depth_profile.h"
#include "sim/vehicle/path.h"
#include "sim/vehicle/vehicle_desc.h"
#include "sim/vehicle/vehicle_state.h"

namespace sonarloop::vehicle {

// Depth of the seabed (z_W, m, positive down) at (north, east); e.g. scene::Scene::seabed_z.
// Called only from Trajectory's constructor, on the constructing thread.
using SeabedDepthFn = std::function<double(double north_m, double east_m)>;

// Start-up progress of the seabed sampling along the path (knots done of total), called every
// kPlanProgressKnots knots and once at the end, on the constructing thread. It may throw to
// abandon the construction (the emulator does on a stop request); the exception propagates.
using PlanProgressFn = std::function<void(std::size_t knots_done, std::size_t knots_total)>;
inline constexpr std::size_t kPlanProgressKnots = 4096;

inline constexpr double kStandardGravityMPerS2 = 9.80665;

class Trajectory {
 public:
  // Throws std::invalid_argument listing every problem (validate() of vehicle_desc.h, a missing
  // seabed in altitude mode, a non-finite seabed depth, a path too long for profile_step_m).
  // The seabed is sampled along the path every profile_step_m in both modes when given (for the
  // altitude in the state); it is required in altitude mode.
  // A long path sampled finely can take minutes: `progress` (optional) reports it.
  explicit Trajectory(const TrajectoryDesc& desc, const SeabedDepthFn& seabed_depth_m = {},
                      const PlanProgressFn& progress = {});

  // The true state at time t (ns since the scenario epoch; the mission starts at t = 0).
  VehicleState state_at(SimTime t) const;

  double duration_s() const { return duration_s_; }  // path length / speed
  SimTime end_time() const { return end_time_; }     // duration_s() in ns (rounded)
  double length_m() const { return path_.length_m(); }
  double turn_radius_m() const { return radius_m_; }
  const Path& path() const { return path_; }
  const DepthProfile& depth_profile() const { return profile_; }
  const TrajectoryDesc& desc() const { return desc_; }

  // Lowest altitude over the precomputed profile knots (m); NaN when the seabed is unknown.
  // Below the commanded altitude when the look-ahead was too short, or the seabed too steep,
  // for the climb-rate bound; negative = the vehicle would hit the seabed.
  double min_altitude_m() const { return min_altitude_m_; }

  // The roll command of a segment of curvature κ (rad; before the lag).
  double roll_command(double curvature_per_m) const;

  // Paths with more profile steps than this are refused (memory: 4 doubles per step).
  static constexpr double kMaxProfileSteps = 2e7;

 private:
  double roll_at(int segment, double s_m) const;
  Vec2 horizontal_position(double s_m, double t_s) const;
  double sway_offset_m(double t_s) const;

  TrajectoryDesc desc_;
  Path path_;
  DepthProfile profile_;
  double speed_m_s_ = 0.0;
  double radius_m_ = 0.0;
  double duration_s_ = 0.0;
  double sway_omega_ = 0.0;       // rad/s, 0 = no sway
  double wave_omega_ = 0.0;       // rad/s, 0 = no wave-induced roll or pitch
  std::vector<double> seabed_m_;  // seabed depth at the profile knots (empty = unknown)
  double knot_step_m_ = 1.0;
  std::size_t pad_steps_ = 0;  // knots before s = 0 (and after the path end)
  SimTime end_time_ = 0;
  double min_altitude_m_;
  std::vector<double> roll_start_;    // roll at the start of each segment (after the lag)
  std::vector<double> roll_command_;  // roll command of each segment
  double roll_end_ = 0.0;             // roll at the end of the path
};

}  // namespace sonarloop::vehicle
