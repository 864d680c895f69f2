// The pose merging shared by the sources (pose_source.h): the plausibility limits and checks,
// decoding NMEA 2000 frames and UDP pose messages into the merged pose, and its history.
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <variant>

#include "drivers/n2k/messages.h"
#include "drivers/pose/pose_message.h"
#include "emulator/pose_source.h"
#include "sim/vehicle/vehicle_desc.h"
#include "units/angles.h"

namespace sonarloop::emulator {
namespace {

// A UDP pose message whose sequence number is at most this far behind the last one is a late
// (reordered or duplicated) datagram and is dropped; further behind, the sender has restarted
// its counter and the message is taken.
constexpr std::int32_t kSequenceReorderWindow = 64;
// A forward jump of more sequence numbers than this is a sender that started again (or a sender
// of another stream), not that many messages lost: 22 minutes of a 50 Hz sender.
constexpr std::int32_t kSequenceRestartGap = 65536;

// How far the scene's relief reaches below its plane, in standard deviations of the
// large-scale elevation (Gaussian relief: 6 sigma is exceeded with probability ~1e-9).
constexpr double kReliefSigmas = 6.0;

// printf-style text for the rejection reasons
template <typename... Args>
std::string format(const char* pattern, Args... args) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, args...);
  return text;
}

}  // namespace

PoseSource::~PoseSource() = default;

double PoseLimits::default_max_speed_m_s() {
  return vehicle::limit_of("trajectory.speed_m_s").value_or(Limit::finite()).hi;
}

double PoseLimits::default_max_angle_rad(std::string_view vehicle_field) {
  return vehicle::limit_of(vehicle_field).value_or(Limit::finite()).hi;
}

PoseLimits pose_limits_for_scene(const scene::SceneDesc& scene) {
  // the deepest seabed: the mean depth, the plane's fall to the extent's farthest corner and
  // the large-scale relief (seabed_model.cpp: elevation = slope . (north, east) + noise, + up)
  const scene::SeabedDesc& s = scene.seabed;
  double fall_m = 0.0;
  for (const double n : {s.origin_m.x(), s.origin_m.x() + s.extent_m.x()})
    for (const double e : {s.origin_m.y(), s.origin_m.y() + s.extent_m.y()})
      fall_m = std::max(fall_m, -(s.elevation.slope.x() * n + s.elevation.slope.y() * e));
  PoseLimits limits;
  limits.max_depth_m = scene.water.depth_m + fall_m + kReliefSigmas * s.elevation.rms_m;
  limits.max_altitude_m = limits.max_depth_m + limits.above_surface_tolerance_m;
  return limits;
}

// ---- PoseMerger ----

PoseMerger::PoseMerger(const LocalTangentPlane& ltp, std::function<std::int64_t()> now_ns,
                       PoseLimits limits, std::function<void(const std::string&)> warn)
    : ltp_(ltp), now_ns_(std::move(now_ns)), limits_(limits), warn_(std::move(warn)) {
  if (!now_ns_) throw std::invalid_argument("pose source: now_ns function is empty");
}

std::string PoseMerger::check_depth_locked(double depth_m) const {
  if (depth_m < -limits_.above_surface_tolerance_m)
    return format("depth %.6g m is above the sea surface", depth_m);
  if (depth_m > limits_.max_depth_m)
    return format("depth %.6g m is below the scene's deepest seabed (%.1f m)", depth_m,
                  limits_.max_depth_m);
  return {};
}

std::string PoseMerger::check_altitude_locked(double altitude_m) const {
  if (altitude_m < 0.0) return format("altitude %.6g m is below the seabed", altitude_m);
  if (altitude_m > limits_.max_altitude_m)
    return format("altitude %.6g m is more than the scene's water column (%.1f m)", altitude_m,
                  limits_.max_altitude_m);
  return {};
}

std::string PoseMerger::check_attitude_locked(double pitch_rad, double roll_rad) const {
  // open limits (vehicle_desc.h: |pitch|, |roll| < 90 degrees): beyond, the vehicle is upside
  // down or standing on its nose, and the sonar looks at the sky
  if (!(std::abs(pitch_rad) < limits_.max_pitch_rad) ||
      !(std::abs(roll_rad) < limits_.max_roll_rad)) {
    return format("pitch %.1f / roll %.1f degrees beyond +-%.0f / +-%.0f degrees",
                  pitch_rad * kDegPerRad, roll_rad * kDegPerRad, limits_.max_pitch_rad * kDegPerRad,
                  limits_.max_roll_rad * kDegPerRad);
  }
  return {};
}

bool PoseMerger::reanchor_due_locked(int& consecutive) {
  if (++consecutive < limits_.reanchor_after) return false;
  consecutive = 0;
  ++stats_.reanchors;
  return true;
}

std::string PoseMerger::check_jump_locked(std::int64_t t_ns, const Vec2& ne) {
  if (position_.empty()) return {};
  const PartSample<2>& last = position_.newest();
  const double dt_s = static_cast<double>(std::max<std::int64_t>(t_ns - last.t_ns, 0)) * 1e-9;
  const double moved_m = std::hypot(ne.x() - last.v[0], ne.y() - last.v[1]);
  const double reach_m = limits_.max_speed_m_s * dt_s + limits_.jump_tolerance_m;
  if (moved_m <= reach_m) {
    position_rejections_ = 0;
    return {};
  }
  const std::string why =
      format("position jumped %.6g m in %.3f s (at most %.1f m at %.0f m/s + %.0f m)", moved_m,
             dt_s, reach_m, limits_.max_speed_m_s, limits_.jump_tolerance_m);
  if (!reanchor_due_locked(position_rejections_)) return why;
  // the vehicle has really moved: no interpolation across the jump
  position_.clear();
  pending_note_ = why + ": accepted as the new position after " +
                  std::to_string(limits_.reanchor_after) + " such fixes in a row";
  return {};
}

std::string PoseMerger::check_stamp_locked(std::int64_t stamp_ns, std::int64_t arrival_ns) {
  if (!have_stamp_) return {};
  // in double: a hostile stamp may be anywhere in int64
  const double stamp_step_s =
      (static_cast<double>(stamp_ns) - static_cast<double>(last_stamp_ns_)) * 1e-9;
  const double arrival_step_s =
      (static_cast<double>(arrival_ns) - static_cast<double>(last_stamp_arrival_ns_)) * 1e-9;
  std::string why;
  if (stamp_step_s < 0.0) {
    why = format("time stamp went back %.6g s", -stamp_step_s);
  } else if (stamp_step_s >
             arrival_step_s + static_cast<double>(limits_.stamp_tolerance_ns) * 1e-9) {
    why =
        format("time stamp jumped ahead %.6g s while %.3f s passed", stamp_step_s, arrival_step_s);
  }
  if (why.empty()) {
    stamp_rejections_ = 0;
    return {};
  }
  if (!reanchor_due_locked(stamp_rejections_)) return why;
  // the sender's clock was stepped: a new time base, and no samples placed on the old one
  stamps_ = StampClock{};
  position_.clear();
  heading_.clear();
  attitude_.clear();
  depth_.clear();
  altitude_.clear();
  pending_note_ = why + ": the sender's clock was stepped; new time base after " +
                  std::to_string(limits_.reanchor_after) + " such messages in a row";
  return {};
}

bool PoseMerger::reject_and_warn(std::unique_lock<std::mutex>& lock, const std::string& what,
                                 std::int64_t now_ns) {
  ++stats_.rejected;
  stats_.last_error = what;
  ++unwarned_;
  std::string line;
  if (!warned_ || now_ns - last_warning_ns_ >= kRejectWarningIntervalNs) {
    line = "implausible pose rejected: " + what;
    if (unwarned_ > 1)
      line += " (and " + std::to_string(unwarned_ - 1) + " more since the last such warning)";
    warned_ = true;
    last_warning_ns_ = now_ns;
    unwarned_ = 0;
  }
  lock.unlock();
  if (!line.empty() && warn_) warn_(line);
  return false;
}

void PoseMerger::give_pending_note(std::unique_lock<std::mutex>& lock, std::int64_t now_ns) {
  std::string note = std::exchange(pending_note_, {});
  // at most one a kRejectWarningIntervalNs, as the rejections (a sender alternating between two
  // clocks would otherwise be said hundreds of times a second)
  if (!note.empty()) {
    if (noted_ && now_ns - last_note_ns_ < kRejectWarningIntervalNs) {
      ++unnoted_;
      note.clear();
    } else {
      if (unnoted_ > 0)
        note += " (and " + std::to_string(unnoted_) + " more since the last such note)";
      noted_ = true;
      last_note_ns_ = now_ns;
      unnoted_ = 0;
    }
  }
  lock.unlock();
  if (!note.empty() && warn_) warn_(note);
}

void PoseMerger::count_malformed_locked(std::string what) {
  ++stats_.malformed;
  stats_.last_error = std::move(what);
}

void PoseMerger::count_malformed(const std::string& what) {
  std::lock_guard lock(mu_);
  count_malformed_locked(what);
}

bool PoseMerger::merge_n2k(const can::CanFrame& frame) {
  const n2k::Decoded<n2k::N2kMessage> decoded = n2k::decode_any(frame);
  if (!decoded) {
    std::lock_guard lock(mu_);
    if (decoded.error() == n2k::DecodeError::kUnsupportedPgn) {
      ++stats_.ignored;  // some other PGN on the bus
    } else {
      char id[16];
      std::snprintf(id, sizeof id, "%08X", frame.id);
      count_malformed_locked(std::string("CAN frame ") + id + ": " +
                             n2k::to_string(decoded.error()));
    }
    return false;
  }
  const n2k::N2kMessage& message = *decoded;
  // what the frame says, checked before the time is taken and the lock held
  if (const auto* m = std::get_if<n2k::PositionRapidUpdate>(&message)) {
    if (!m->latitude_deg || !m->longitude_deg) {
      std::lock_guard lock(mu_);
      count_malformed_locked("129025 Position without latitude or longitude");
      return false;
    }
    const Vec2 ne = ltp_.to_local(GeoPoint{*m->latitude_deg, *m->longitude_deg});
    const std::int64_t t = now_ns_();
    std::unique_lock lock(mu_);
    if (const std::string why = check_jump_locked(t, ne); !why.empty())
      return reject_and_warn(lock, "129025 Position: " + why, t);
    pose_.pose.position_W.x() = ne.x();
    pose_.pose.position_W.y() = ne.y();
    pose_.has_position = true;
    position_.add(t, {ne.x(), ne.y()});
    pose_.received_ns = t;
    any_ = true;
    ++stats_.updates;
    give_pending_note(lock, t);
    return true;
  }
  if (const auto* m = std::get_if<n2k::VesselHeading>(&message)) {
    // True (and Null: reference not stated) headings are taken as they are; a magnetic one is
    // corrected with whatever deviation and variation the frame carries
    const bool usable = m->heading_rad && m->reference != n2k::DirectionReference::kError;
    if (!usable) {
      std::lock_guard lock(mu_);
      count_malformed_locked("127250 Heading not available or reference 'error'");
      return false;
    }
    double yaw = *m->heading_rad;
    if (m->reference == n2k::DirectionReference::kMagnetic)
      yaw += m->deviation_rad.value_or(0.0) + m->variation_rad.value_or(0.0);
    const std::int64_t t = now_ns_();
    std::lock_guard lock(mu_);
    pose_.pose.yaw = wrap_to_two_pi(yaw);
    pose_.has_heading = true;
    heading_.add(t, {pose_.pose.yaw});
    pose_.received_ns = t;
    any_ = true;
    ++stats_.updates;
    return true;
  }
  if (const auto* m = std::get_if<n2k::Attitude>(&message)) {
    if (!m->pitch_rad || !m->roll_rad) {
      std::lock_guard lock(mu_);
      count_malformed_locked("127257 Attitude without pitch or roll");
      return false;
    }
    const std::int64_t t = now_ns_();
    std::unique_lock lock(mu_);
    if (const std::string why = check_attitude_locked(*m->pitch_rad, *m->roll_rad); !why.empty())
      return reject_and_warn(lock, "127257 Attitude: " + why, t);
    pose_.pose.pitch = *m->pitch_rad;
    pose_.pose.roll = *m->roll_rad;
    pose_.has_attitude = true;
    attitude_.add(t, {pose_.pose.pitch, pose_.pose.roll});
    pose_.received_ns = t;
    any_ = true;
    ++stats_.updates;
    return true;
  }
  if (const auto* m = std::get_if<n2k::WaterDepth>(&message)) {
    // Depth below the transducer = altitude; Offset >= 0 (transducer to surface) = depth, as
    // emulator/nav_frames.cpp publishes it (a negative Offset is transducer to keel: no depth)
    const std::int64_t t = now_ns_();
    std::unique_lock lock(mu_);
    std::string why;
    if (m->depth_m) why = check_altitude_locked(*m->depth_m);
    if (why.empty() && m->offset_m && *m->offset_m >= 0.0) why = check_depth_locked(*m->offset_m);
    if (!why.empty()) return reject_and_warn(lock, "128267 Water Depth: " + why, t);
    pose_.altitude_m = m->depth_m.value_or(std::numeric_limits<double>::quiet_NaN());
    // 128267 is the only PGN with a depth: without a usable Offset the depth is unknown now (a
    // vehicle below the field's 32.764 m must not keep its last shallower depth)
    pose_.has_depth = m->offset_m && *m->offset_m >= 0.0;
    if (pose_.has_depth) pose_.pose.position_W.z() = *m->offset_m;
    if (pose_.has_depth) {
      depth_.add(t, {pose_.pose.position_W.z()});
    } else {
      depth_.clear();
    }
    if (std::isnan(pose_.altitude_m)) {
      altitude_.clear();
    } else {
      altitude_.add(t, {pose_.altitude_m});
    }
    pose_.received_ns = t;
    any_ = true;
    ++stats_.updates;
    return true;
  }
  std::lock_guard lock(mu_);
  ++stats_.ignored;  // a navigation PGN without pose content (COG/SOG, rate of turn, ...)
  return false;
}

bool PoseMerger::merge_pose_datagram(std::span<const std::uint8_t> datagram) {
  std::string error;
  const std::optional<PoseMessage> m = decode_pose_message(datagram, error);
  if (!m) {
    std::lock_guard lock(mu_);
    count_malformed_locked(std::move(error));
    return false;
  }
  return merge_snapshot(*m, true, "pose message " + std::to_string(m->sequence));
}

std::optional<PoseMessage> pose_message_from_imc(const imc::EstimatedState& e, double timestamp_s,
                                                 std::string& error) {
  const double lat_deg = e.lat_rad * kDegPerRad;
  const double lon_deg = e.lon_rad * kDegPerRad;
  if (!std::isfinite(lat_deg) || !std::isfinite(lon_deg) || std::fabs(lat_deg) > 90.0 ||
      std::fabs(lon_deg) > 180.0) {
    error = "IMC EstimatedState: lat/lon not on the Earth";
    return std::nullopt;
  }
  for (float v : {e.x_m, e.y_m, e.depth_m, e.alt_m, e.phi_rad, e.theta_rad, e.psi_rad}) {
    if (!std::isfinite(v)) {
      error = "IMC EstimatedState: a field is not finite";
      return std::nullopt;
    }
  }
  PoseMessage m;
  // the NED offsets displace the reference point; beyond a tangent plane's reach it is not a
  // position (the checks below refuse it)
  try {
    const GeoPoint at = LocalTangentPlane(GeoPoint{lat_deg, lon_deg}).to_geodetic(e.x_m, e.y_m);
    m.latitude_deg = at.latitude_deg;
    m.longitude_deg = at.longitude_deg;
  } catch (const std::invalid_argument& x) {
    error = std::string("IMC EstimatedState: ") + x.what();
    return std::nullopt;
  }
  if (e.depth_m >= 0.0f) m.depth_m = e.depth_m;
  if (e.alt_m >= 0.0f) m.altitude_m = e.alt_m;
  m.heading_rad = e.psi_rad;
  m.pitch_rad = e.theta_rad;
  m.roll_rad = e.phi_rad;
  if (std::isfinite(timestamp_s) && timestamp_s > 0.0 && timestamp_s < 9.2e9)
    m.time_unix_ns = static_cast<std::int64_t>(std::llround(timestamp_s * 1e9));
  return m;
}

bool PoseMerger::merge_imc_datagram(std::span<const std::uint8_t> datagram) {
  imc::Packet packet;
  const imc::DecodeStatus status = imc::decode(datagram, packet);
  if (status == imc::DecodeStatus::kUnknownMessage ||
      (status == imc::DecodeStatus::kOk &&
       !std::holds_alternative<imc::EstimatedState>(packet.message))) {
    count_ignored();
    return false;
  }
  std::string error;
  std::optional<PoseMessage> m;
  if (status != imc::DecodeStatus::kOk) {
    error = std::string("IMC packet: ") + imc::decode_status_name(status);
  } else {
    m = pose_message_from_imc(std::get<imc::EstimatedState>(packet.message),
                              packet.header.timestamp_s, error);
  }
  if (!m) {
    std::lock_guard lock(mu_);
    count_malformed_locked(std::move(error));
    return false;
  }
  return merge_snapshot(*m, false, "IMC EstimatedState");
}

void PoseMerger::count_ignored() {
  std::lock_guard lock(mu_);
  ++stats_.ignored;
}

bool PoseMerger::merge_snapshot(const PoseMessage& msg, bool sequenced, const std::string& what) {
  const PoseMessage* m = &msg;
  ExternalPose p;
  p.has_position = !std::isnan(m->latitude_deg);
  if (p.has_position) {
    const Vec2 ne = ltp_.to_local(GeoPoint{m->latitude_deg, m->longitude_deg});
    p.pose.position_W.x() = ne.x();
    p.pose.position_W.y() = ne.y();
  }
  p.has_depth = !std::isnan(m->depth_m);
  if (p.has_depth) p.pose.position_W.z() = m->depth_m;
  p.altitude_m = m->altitude_m;
  p.has_heading = !std::isnan(m->heading_rad);
  if (p.has_heading) p.pose.yaw = wrap_to_two_pi(m->heading_rad);
  p.has_attitude = !std::isnan(m->pitch_rad) && !std::isnan(m->roll_rad);
  if (p.has_attitude) {
    p.pose.pitch = m->pitch_rad;
    p.pose.roll = m->roll_rad;
  }
  const std::int64_t t = now_ns_();
  std::unique_lock lock(mu_);
  if (sequenced && have_sequence_) {
    // serial-number arithmetic: the signed distance from the last accepted message
    const auto d = static_cast<std::int32_t>(m->sequence - last_sequence_);
    if (d <= 0 && d >= -kSequenceReorderWindow) {
      ++stats_.out_of_order;
      return false;
    }
    if (d < -kSequenceReorderWindow || d > kSequenceRestartGap) {
      ++stats_.sequence_restarts;  // a jump back, or far ahead: the sender started again
    } else if (d > 1) {
      stats_.lost += static_cast<std::uint64_t>(d - 1);
    }
  }
  // received, whatever its content: a rejected message is not lost
  if (sequenced) {
    have_sequence_ = true;
    last_sequence_ = m->sequence;
  }
  if (const std::string why = check_snapshot_locked(p, *m, t); !why.empty())
    return reject_and_warn(lock, what + ": " + why, t);
  if (m->time_unix_ns != 0) {
    have_stamp_ = true;
    last_stamp_ns_ = m->time_unix_ns;
    last_stamp_arrival_ns_ = t;
  }
  p.received_ns = t;
  pose_ = p;
  // the sample's time: the sender's stamp on our clock, else its arrival
  record_snapshot_locked(m->time_unix_ns != 0 ? stamps_.place(m->time_unix_ns, t) : t);
  any_ = true;
  ++stats_.updates;
  give_pending_note(lock, t);
  return true;
}

std::string PoseMerger::check_snapshot_locked(const ExternalPose& p, const PoseMessage& m,
                                              std::int64_t arrival_ns) {
  // NaN is "not available" by the message's definition (that part then comes from the
  // scenario's trajectory); infinities were refused by the decoder as malformed
  if (p.has_depth) {
    if (std::string why = check_depth_locked(m.depth_m); !why.empty()) return why;
  }
  if (!std::isnan(m.altitude_m)) {
    if (std::string why = check_altitude_locked(m.altitude_m); !why.empty()) return why;
  }
  if (!std::isnan(m.pitch_rad) || !std::isnan(m.roll_rad)) {
    const double pitch = std::isnan(m.pitch_rad) ? 0.0 : m.pitch_rad;
    const double roll = std::isnan(m.roll_rad) ? 0.0 : m.roll_rad;
    if (std::string why = check_attitude_locked(pitch, roll); !why.empty()) return why;
  }
  // the relative checks last, so that an absurd value never counts towards a re-anchoring
  if (m.time_unix_ns != 0) {
    if (std::string why = check_stamp_locked(m.time_unix_ns, arrival_ns); !why.empty()) return why;
  }
  if (p.has_position) {
    const Vec2 ne(p.pose.position_W.x(), p.pose.position_W.y());
    if (std::string why = check_jump_locked(arrival_ns, ne); !why.empty()) return why;
  }
  return {};
}

void PoseMerger::count_receive_error(const std::string& what) {
  std::lock_guard lock(mu_);
  ++stats_.receive_errors;
  stats_.last_error = what;
}

void PoseMerger::count_reconnect() {
  std::lock_guard lock(mu_);
  ++stats_.reconnects;
}

std::optional<ExternalPose> PoseMerger::latest() const {
  std::lock_guard lock(mu_);
  if (!any_) return std::nullopt;
  return pose_;
}

void PoseMerger::record_snapshot_locked(std::int64_t t_ns) {
  const Pose& q = pose_.pose;
  if (pose_.has_position) {
    position_.add(t_ns, {q.position_W.x(), q.position_W.y()});
  } else {
    position_.clear();
  }
  if (pose_.has_heading) {
    heading_.add(t_ns, {q.yaw});
  } else {
    heading_.clear();
  }
  if (pose_.has_attitude) {
    attitude_.add(t_ns, {q.pitch, q.roll});
  } else {
    attitude_.clear();
  }
  if (pose_.has_depth) {
    depth_.add(t_ns, {q.position_W.z()});
  } else {
    depth_.clear();
  }
  if (std::isnan(pose_.altitude_m)) {
    altitude_.clear();
  } else {
    altitude_.add(t_ns, {pose_.altitude_m});
  }
}

std::optional<ExternalPose> PoseMerger::pose_at(std::int64_t tau_ns,
                                                std::int64_t max_extrapolation_ns,
                                                bool* extrapolated) const {
  std::lock_guard lock(mu_);
  if (extrapolated) *extrapolated = false;
  if (!any_) return std::nullopt;
  ExternalPose p = pose_;  // flags, received_ns; each known part from its samples
  Pose& q = p.pose;
  if (const auto v = position_.value_at(tau_ns, max_extrapolation_ns)) {
    q.position_W.x() = v->v[0];
    q.position_W.y() = v->v[1];
    if (extrapolated) *extrapolated = v->extrapolated;
  }
  if (const auto v = heading_.value_at(tau_ns, max_extrapolation_ns)) q.yaw = v->v[0];
  if (const auto v = attitude_.value_at(tau_ns, max_extrapolation_ns)) {
    q.pitch = v->v[0];
    q.roll = v->v[1];
  }
  if (const auto v = depth_.value_at(tau_ns, max_extrapolation_ns)) q.position_W.z() = v->v[0];
  if (const auto v = altitude_.value_at(tau_ns, max_extrapolation_ns)) p.altitude_m = v->v[0];
  return p;
}

PoseSourceStats PoseMerger::stats() const {
  std::lock_guard lock(mu_);
  return stats_;
}

}  // namespace sonarloop::emulator
