#include "emulator/nav_frames.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "drivers/n2k/messages.h"
#include "emulator/pacer.h"
#include "units/angles.h"

namespace sonarloop::emulator {

const std::array<NavPgnInfo, kNavPgnCount> kNavPgns = {{
    {n2k::PositionRapidUpdate::kPgn, n2k::PositionRapidUpdate::kDefaultPeriodNs, true, "position"},
    {n2k::VesselHeading::kPgn, n2k::VesselHeading::kDefaultPeriodNs, true, "heading"},
    {n2k::RateOfTurn::kPgn, n2k::RateOfTurn::kDefaultPeriodNs, true, "rate of turn"},
    {n2k::CogSogRapidUpdate::kPgn, n2k::CogSogRapidUpdate::kDefaultPeriodNs, true, "cog sog"},
    {n2k::Attitude::kPgn, n2k::Attitude::kDefaultPeriodNs, true, "attitude"},
    {n2k::SpeedWaterReferenced::kPgn, n2k::SpeedWaterReferenced::kDefaultPeriodNs, true, "speed"},
    {n2k::WaterDepth::kPgn, n2k::WaterDepth::kDefaultPeriodNs, true, "water depth"},
    {n2k::SystemTime::kPgn, n2k::SystemTime::kDefaultPeriodNs, false, "system time"},
}};

namespace {

// Largest positive value of 128267's Offset field (int16, 0.001 m; 0x7FFF/0x7FFE are the
// not-available and error sentinels).
constexpr double kMaxDepthOffsetM = 32.764;

std::optional<double> finite_or_none(double v) {
  if (std::isfinite(v)) return v;
  return std::nullopt;
}

}  // namespace

NavPgnMask pose_free_pgns() {
  NavPgnMask m = 0;
  for (int i = 0; i < kNavPgnCount; ++i)
    if (!kNavPgns[static_cast<std::size_t>(i)].from_pose) m |= 1u << i;
  return m;
}

NavSchedule::NavSchedule() {
  next_.fill(0);
}

SimTime NavSchedule::next_time() const {
  return *std::min_element(next_.begin(), next_.end());
}

NavSchedule::Sample NavSchedule::pop(SimTime now) {
  Sample s;
  s.t = next_time();
  for (int i = 0; i < kNavPgnCount; ++i) {
    auto& next = next_[static_cast<std::size_t>(i)];
    if (next != s.t) continue;
    s.due |= 1u << i;
    const SimTime period = kNavPgns[static_cast<std::size_t>(i)].period_ns;
    const SimTime after = next_deadline(s.t, period, std::max(now, s.t));
    s.skipped += deadlines_skipped(s.t, period, after);
    next = after;
  }
  return s;
}

std::size_t make_nav_frames(const vehicle::NavSolution& nav, const LocalTangentPlane& ltp,
                            std::int64_t utc_ns, std::uint8_t sid, NavPgnMask due,
                            std::span<can::CanFrame> out) {
  if (out.size() < static_cast<std::size_t>(kNavPgnCount)) {
    throw std::invalid_argument("make_nav_frames: the output must hold 8 frames");
  }
  std::size_t n = 0;
  const std::uint8_t sa = kNavSourceAddress;
  for (int i = 0; i < kNavPgnCount; ++i) {
    if (!(due & (1u << i))) continue;
    switch (kNavPgns[static_cast<std::size_t>(i)].pgn) {
      case n2k::PositionRapidUpdate::kPgn: {
        const GeoPoint g = ltp.to_geodetic(nav.north_m, nav.east_m);
        out[n++] = n2k::encode(n2k::PositionRapidUpdate{g.latitude_deg, g.longitude_deg}, sa);
        break;
      }
      case n2k::VesselHeading::kPgn: {
        n2k::VesselHeading m;
        m.sid = sid;
        m.heading_rad = finite_or_none(nav.heading);
        m.reference = n2k::DirectionReference::kTrue;
        out[n++] = n2k::encode(m, sa);
        break;
      }
      case n2k::RateOfTurn::kPgn: {
        n2k::RateOfTurn m;
        m.sid = sid;
        m.rate_rad_per_s = finite_or_none(nav.yaw_rate);
        out[n++] = n2k::encode(m, sa);
        break;
      }
      case n2k::CogSogRapidUpdate::kPgn: {
        n2k::CogSogRapidUpdate m;
        m.sid = sid;
        m.cog_reference = n2k::DirectionReference::kTrue;
        m.cog_rad = finite_or_none(nav.course_over_ground);
        m.sog_mps = finite_or_none(nav.speed_over_ground_m_s);
        out[n++] = n2k::encode(m, sa);
        break;
      }
      case n2k::Attitude::kPgn: {
        n2k::Attitude m;
        m.sid = sid;
        m.yaw_rad = finite_or_none(wrap_to_pi(nav.heading));
        m.pitch_rad = finite_or_none(nav.pitch);
        m.roll_rad = finite_or_none(nav.roll);
        out[n++] = n2k::encode(m, sa);
        break;
      }
      case n2k::SpeedWaterReferenced::kPgn: {
        n2k::SpeedWaterReferenced m;
        m.sid = sid;
        m.speed_water_mps = finite_or_none(nav.speed_over_ground_m_s);
        m.speed_ground_mps = finite_or_none(nav.speed_over_ground_m_s);
        m.speed_water_type = n2k::WaterReference::kDoppler;
        m.speed_direction = 0;
        out[n++] = n2k::encode(m, sa);
        break;
      }
      case n2k::WaterDepth::kPgn: {
        n2k::WaterDepth m;
        m.sid = sid;
        m.depth_m = finite_or_none(nav.altitude_m);
        if (std::isfinite(nav.depth_m) && nav.depth_m >= 0.0 && nav.depth_m <= kMaxDepthOffsetM) {
          m.offset_m = nav.depth_m;
        }
        out[n++] = n2k::encode(m, sa);
        break;
      }
      case n2k::SystemTime::kPgn: {
        out[n++] = n2k::encode(n2k::system_time_from_unix_ns(utc_ns, sid), sa);
        break;
      }
      default:
        break;
    }
  }
  return n;
}

}  // namespace sonarloop::emulator
