#pragma once
// The vehicle's navigation as NMEA 2000 frames (docs/formats.md §2): which PGNs, when, and what
// each carries. Pure: no clock, no I/O.
//
// Schedule (docs/formats.md §2.1 "default interval"): each PGN is sampled on its own grid from
// t = 0:
//   100 ms   129025 Position Rapid Update, 127250 Vessel Heading, 127251 Rate of Turn
//   250 ms   129026 COG & SOG Rapid Update
//   1000 ms  127257 Attitude, 128259 Speed, 128267 Water Depth, 126992 System Time
// PGNs due at the same instant form one sample: one navigation solution, one SID (docs/formats.md
// §2.2: "ties together PGNs sampled at the same instant"), frames in the order of kNavPgns.
// After an overrun each PGN resynchronises on its own grid (pacer.h next_deadline): missed
// samples are skipped and counted, never sent in a burst.
//
// Content, from a vehicle::NavSolution (the navigation sensor model's output), source address
// kNavSourceAddress, default priorities:
//   129025  latitude/longitude of (north, east) through the scenario's LocalTangentPlane
//   129026  COG (true) and SOG
//   127250  heading (true); deviation and variation not available
//   127251  yaw rate
//   127257  yaw (the heading, as ±π), pitch (+ nose up), roll (+ starboard down)
//   128259  speed through water = speed over ground (no current is modelled), type Doppler
//           (a DVL); speed over ground also filled
//   128267  depth = the altitude (water below the vehicle's downward transducer; not available
//           when the altitude is unknown), offset = + the vehicle's depth (transducer to
//           surface; not available beyond the field's 32.764 m); range not available
//   126992  source GPS, date and time of day of epoch + t (UTC)
#include <array>
#include <cstdint>
#include <span>

#include "common/geodesy.h"
#include "drivers/can/can_frame.h"
#include "sim/core/sim_time.h"
#include "sim/vehicle/nav_sensor.h"

namespace sonarloop::emulator {

// NMEA 2000 source address of the emulated navigation system (the address of docs/formats.md §2.4's
// reference frames).
inline constexpr std::uint8_t kNavSourceAddress = 0x23;

struct NavPgnInfo {
  std::uint32_t pgn;
  SimTime period_ns;
  bool from_pose;  // carries pose-derived values (withheld while an external pose is stale)
  const char* name;
};

inline constexpr int kNavPgnCount = 8;
// In frame order within a sample.
extern const std::array<NavPgnInfo, kNavPgnCount> kNavPgns;

// A bit per kNavPgns entry.
using NavPgnMask = std::uint32_t;
inline constexpr NavPgnMask kAllNavPgns = (1u << kNavPgnCount) - 1;
// The PGNs that do not depend on the pose (System Time).
NavPgnMask pose_free_pgns();
// The bit of 129025 Position, Rapid Update (kNavPgns[0]): a sample with it is a 10 Hz fix.
inline constexpr NavPgnMask kPositionPgnBit = 1u << 0;

class NavSchedule {
 public:
  NavSchedule();

  // Time of the next sample (the earliest due time over all PGNs).
  SimTime next_time() const;

  struct Sample {
    SimTime t = 0;
    NavPgnMask due = 0;        // PGNs sampled at t
    std::int64_t skipped = 0;  // PGN deadlines skipped by the resynchronisation
  };
  // Takes the sample at next_time() and moves each of its PGNs to its next deadline given the
  // current time `now` (next_deadline: pass now = next_time() when unpaced, never skipping).
  Sample pop(SimTime now);

 private:
  std::array<SimTime, kNavPgnCount> next_{};
};

// The frames of one sample: for every PGN in `due` (kNavPgns order) one frame into out[0..n).
// out must hold kNavPgnCount frames; returns n. utc_ns = epoch + nav.t (for System Time).
std::size_t make_nav_frames(const vehicle::NavSolution& nav, const LocalTangentPlane& ltp,
                            std::int64_t utc_ns, std::uint8_t sid, NavPgnMask due,
                            std::span<can::CanFrame> out);

}  // namespace sonarloop::emulator
