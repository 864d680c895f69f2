#pragma once
// The vehicle as plain data (docs/style.md habit 1): what a vehicle/mission YAML file says, after
// validation, with every default filled in. trajectory.h turns a TrajectoryDesc into a path;
// nav_sensor.h turns a NavNoiseDesc into a navigation sensor model.
//
// Units: SI throughout (metres, seconds, radians, m/s, rad/s). Angles are radians (frames.h);
// the YAML loader converts the YAML's degrees (heading_deg, ...) and knots if it offers them.
// Positions are (north, east) in the world frame W of frames.h. Each field's comment gives its
// default (the initialiser), its unit and a sensible range; validate() enforces the hard limits.
//
// Nothing here allocates or computes: see trajectory.h and nav_sensor.h for that.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sim/core/validation.h"

namespace sonarloop::vehicle {

// A horizontal position in W (metres north and east of the scenario origin).
struct NorthEast {
  double north_m = 0.0;
  double east_m = 0.0;
};

// The three kinds of mission path (YAML: "straight", "waypoints", "lawnmower").
enum class TrajectoryKind { kStraight, kWaypoints, kLawnmower };

// Side of a turn (YAML: "starboard" = right, heading increasing; "port" = left).
enum class TurnDirection { kStarboard, kPort };

// How the vertical is flown (YAML: "depth" = constant depth, "altitude" = terrain following).
enum class DepthMode { kConstantDepth, kAltitude };

// Lawnmower survey: `legs` parallel straight legs of leg_length_m, line_spacing_m apart, joined
// by U-turns of radius speed / max_turn_rate (trajectory.h: regular or keyhole U-turn). Leg 0
// starts at origin and runs along first_leg_heading; leg i is offset i·line_spacing_m to the
// side of first_turn and runs in the opposite direction to leg i-1 (turns alternate sides).
struct LawnmowerDesc {
  NorthEast origin;                // start of leg 0, m
  double first_leg_heading = 0.0;  // rad clockwise from north, any value (wrapped)
  double leg_length_m = 200.0;     // > 0; typically 100-5000 m
  double line_spacing_m = 50.0;    // > 0; typically 0.5-1.8 x the sonar's range per side
  int legs = 4;                    // 1-10000
  TurnDirection first_turn = TurnDirection::kStarboard;  // side of the first U-turn
};

// Vertical control.
struct DepthDesc {
  DepthMode mode = DepthMode::kConstantDepth;
  double depth_m = 20.0;     // kConstantDepth: depth of the vehicle origin, >= 0; 0-6000 m
  double altitude_m = 10.0;  // kAltitude: commanded height above the seabed, > 0; 2-50 m
                             // (sidescan flies at ~10 % of its range per side)
  // Vertical rate bound for both climbing and diving (terrain following), > 0; typically
  // 0.2-1 m/s (a glide of 6-30 degrees at 2 m/s).
  double max_climb_rate_m_s = 0.5;
  // How far ahead along the path the vehicle sees the seabed (a forward-looking sonar or a
  // mission-planned altitude profile): it starts climbing early enough to clear any rise within
  // this distance. 0 = purely reactive (it cannot anticipate; altitude drops on steep rises).
  // >= 0; typically 20-200 m.
  double look_ahead_m = 50.0;
  double min_depth_m = 1.0;  // the vehicle never rises above this depth (kAltitude), >= 0
  // Step along the path at which the seabed is sampled and the depth profile is precomputed
  // (trajectory.h), in [0.05, 10] m. Smaller = more memory (4 doubles per step) and set-up time.
  double profile_step_m = 0.5;
  // Width of the moving average that smooths the rate-limited profile (depth_profile.h): the
  // vertical acceleration is at most 2·speed·max_climb_rate / width (0.4 m/s² by default), the
  // pitch rate about that / speed. The price: the altitude departs from the command by about
  // width²/24 × the seabed's curvature, and by up to max_climb_rate·width / (4·speed) (0.31 m
  // by default) below it where a climb turns sharply into a dive over a crest.
  // Values below profile_step_m act as profile_step_m. In [0, 1000] m; typically 2-20 m.
  double vertical_smoothing_m = 5.0;
};

// Optional sinusoidal sway: a lateral offset y(t) = amplitude_m·sin(2π·t/period_s + phase),
// positive to starboard of the planned path (as from waves or a cross-track control loop).
// validate() checks every field whatever the amplitude, so that a description is valid or not
// independently of whether sway is switched on.
struct SwayDesc {
  double amplitude_m = 0.0;  // 0 = no sway; >= 0; typically 0-2 m
  double period_s = 10.0;    // > 0; typically 5-60 s
  double phase = 0.0;        // rad, any value
  // How far the heading follows the swaying track: yaw = path tangent + yaw_coupling·atan(ẏ/u).
  // 0 = pure sway (the vehicle crabs, heading stays on the path), 1 = the vehicle snakes (heading
  // follows its track). In [0, 1]. The yaw rate it adds, up to yaw_coupling·A·ω²/speed, comes on
  // top of max_turn_rate_rad_s (which bounds the planned path).
  double yaw_coupling = 0.0;
};

// Attitude model (trajectory.h): roll from the turn, pitch from the vertical velocity, plus an
// optional wave-induced oscillation of both.
struct AttitudeDesc {
  // Roll command = roll_gain·atan(u²·κ / g) = roll_gain·atan(u·ψ̇ / g) (coordinated-turn bank).
  // 1 = the coordinated-turn bank, starboard down in a starboard turn; negative = rolls outboard.
  // In [-10, 10]; typically 0.5-3.
  double roll_gain = 1.0;
  double max_roll = 0.35;             // |roll| limit, rad, in (0, π/2); default 20 degrees
  double roll_time_constant_s = 1.5;  // first-order lag of roll behind its command, >= 0 s
                                      // (0 = no lag: roll steps at segment joins); 0.5-5 s
  // Pitch = pitch_gain·atan2(-w, u) (nose up when climbing; 1 = zero angle of attack).
  // In [0, 10]; typically 1-2.
  double pitch_gain = 1.0;
  double max_pitch = 0.5;  // |pitch| limit, rad, in (0, π/2); default ~29 degrees
  // Wave-induced oscillation. A vehicle near the surface in a regular swell is rocked by the
  // wave's orbital motion at the wave encounter period (the wave period as the moving vehicle
  // meets the crests). Modelled as the first-order (linear) response to a single-frequency
  // wave: one sinusoid per angle at that period, added to the turn roll and the flight-path
  // pitch above, the sum then limited to ±max_roll / ±max_pitch:
  //   roll  += roll_amplitude·sin(2π·t / wave_period_s)
  //   pitch += pitch_amplitude·cos(2π·t / wave_period_s)
  // (t in s since the mission start). Pitch leads roll by a quarter period, so that the two are
  // not in phase (trajectory.h says why). validate() checks every field whatever the
  // amplitudes, so that a description is valid or not independently of whether waves are on.
  double roll_amplitude = 0.0;   // rad, in [0, π/4]; 0 = none; typically 0-0.1 (0-6 degrees)
  double pitch_amplitude = 0.0;  // rad, in [0, π/4]; 0 = none; typically 0-0.05 (0-3 degrees)
  double wave_period_s = 8.0;    // encounter period, s, in [1, 600]; typically 4-15 s
};

struct TrajectoryDesc {
  TrajectoryKind kind = TrajectoryKind::kStraight;

  // kStraight and kWaypoints: the start point and heading (kLawnmower starts at its origin).
  NorthEast start;
  double start_heading = 0.0;  // rad clockwise from north, any value

  double straight_length_m = 1000.0;  // kStraight: length of the line, > 0

  // kWaypoints: visited in order, starting from `start`; at least 1; consecutive points (the
  // start included) at least 0.01 m apart. The vehicle flies over each waypoint (path.h).
  std::vector<NorthEast> waypoints;

  LawnmowerDesc lawnmower;  // kLawnmower

  // Horizontal speed along the path (over ground; no current), > 0 and <= 20; AUV surveys
  // typically 1-2.5 m/s (2 m/s = 3.9 kn).
  double speed_m_s = 2.0;
  DepthDesc depth;
  // Turn-rate bound of the planned path, (0, 2] rad/s; typically 0.05-0.3 rad/s (3-17 deg/s).
  // The turn radius is speed_m_s / max_turn_rate_rad_s (default 20 m).
  double max_turn_rate_rad_s = 0.1;
  SwayDesc sway;
  AttitudeDesc attitude;
};

// Navigation sensor errors (nav_sensor.h). Every field defaults to 0: all zero = perfect nav
// (published = truth). White noises are independent per axis and per time step; random walks
// start at 0 at t = 0 and their standard deviation grows as drift·sqrt(t).
struct NavNoiseDesc {
  // Horizontal position, per axis (north and east independently).
  double position_noise_sd_m = 0.0;          // white, >= 0; INS+DVL 0-1 m, USBL-aided 1-5 m
  double position_drift_m_per_sqrt_s = 0.0;  // random walk, >= 0; 0-0.5 (0.1 = 6 m after 1 h)
  // Heading.
  double heading_bias = 0.0;                  // rad, constant, |.| <= π; 0-0.03 (2 degrees)
  double heading_noise_sd = 0.0;              // rad, white, >= 0; 0-0.02
  double heading_drift_rad_per_sqrt_s = 0.0;  // rad/sqrt(s), random walk, >= 0; 0-1e-3
  // Pitch and roll (each).
  double attitude_noise_sd = 0.0;  // rad, white, >= 0; 0-0.01
  // Speed over ground: measured velocity = (1 + scale)·R(heading error)·true velocity + noise.
  double speed_noise_sd_m_s = 0.0;        // white, per horizontal axis, >= 0; 0-0.05
  double speed_scale_factor_error = 0.0;  // dimensionless, |.| < 0.5; 0-0.005 (DVL 0.2-0.5 %)
  double yaw_rate_noise_sd_rad_s = 0.0;   // white, >= 0; 0-0.005
  // Vertical.
  double depth_noise_sd_m = 0.0;     // white, >= 0; pressure sensor 0-0.1 m
  double altitude_noise_sd_m = 0.0;  // white, >= 0; DVL/altimeter 0-0.2 m
  // Time structure of the noise (nav_sensor.h): white noise is constant within each step of
  // noise_step_s and independent between steps; random walks are exact at multiples of
  // drift_step_s and linearly interpolated between. Both > 0 and <= 3600 s.
  double noise_step_s = 0.01;
  double drift_step_s = 1.0;
};

struct VehicleDesc {
  TrajectoryDesc trajectory;
  NavNoiseDesc nav;
};

// Names used in YAML (lower case) and their parsers; nullopt for an unknown name.
std::string_view to_string(TrajectoryKind kind);
std::string_view to_string(TurnDirection direction);
std::string_view to_string(DepthMode mode);
std::optional<TrajectoryKind> trajectory_kind_from_string(std::string_view name);
std::optional<TurnDirection> turn_direction_from_string(std::string_view name);
std::optional<DepthMode> depth_mode_from_string(std::string_view name);

// Every violation of the hard limits above, one Problem each (sim/core/validation.h): the field's
// dotted path from the struct with `prefix` in front (e.g. "trajectory.lawnmower.leg_length_m"),
// its value and the allowed range, in SI units. Empty = valid. Only the fields of the selected
// kind and depth mode are checked. Geometry that can only be judged on the planned path (its
// length) is checked by Trajectory's constructor.
std::vector<Problem> validate(const TrajectoryDesc& desc, std::string_view prefix = "trajectory");
std::vector<Problem> validate(const NavNoiseDesc& desc, std::string_view prefix = "nav");
std::vector<Problem> validate(const VehicleDesc& desc);

// The hard limit validate() applies to a number field, by the path it reports for a VehicleDesc
// ("trajectory.attitude.max_roll", "trajectory.lawnmower.legs", "nav.noise_step_s"); nullopt for
// a field without one (a waypoint, an enum). Lets a loader say what is allowed before it has a
// whole description, e.g. when a value is not a number at all.
std::optional<Limit> limit_of(std::string_view field);

}  // namespace sonarloop::vehicle
