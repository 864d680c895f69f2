#include "emulator/imc_device.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "units/angles.h"

namespace sonarloop::emulator {
namespace {

std::uint16_t clamp_u16(double v) {
  if (!(v > 0.0)) return 0;
  return v >= 65535.0 ? std::uint16_t{65535} : static_cast<std::uint16_t>(std::lround(v));
}

template <class T>
void append_le(std::vector<std::uint8_t>& out, const std::vector<T>& samples) {
  for (T v : samples)
    for (std::size_t b = 0; b < sizeof(T); ++b)
      out.push_back(static_cast<std::uint8_t>((static_cast<std::uint64_t>(v) >> (8 * b)) & 0xFF));
}

}  // namespace

void sonar_data_from_xtf(const xtf::XtfPing& ping, const ImcSonarInfo& sonar, imc::SonarData& out) {
  if (ping.channels.size() != 2)
    throw std::invalid_argument(
        "IMC SonarData: a sidescan ping has two channels (port, starboard)");
  const std::size_t bytes = ping.channels[0].bytes_per_sample();
  if (ping.channels[1].bytes_per_sample() != bytes ||
      ping.channels[0].num_samples() != ping.channels[1].num_samples())
    throw std::invalid_argument("IMC SonarData: port and starboard differ in sample size or count");
  out.type = imc::SonarData::kSidescan;
  out.frequency_hz = static_cast<std::uint32_t>(std::lround(sonar.frequency_hz));
  out.min_range_m = 0;
  out.max_range_m = clamp_u16(sonar.max_range_m);
  out.bits_per_point = static_cast<std::uint8_t>(8 * bytes);
  out.scale_factor = 1.0f;
  out.beam_config.clear();
  out.data.clear();
  if (std::holds_alternative<std::vector<float>>(ping.channels[0].samples)) {
    // IMC's units are integers: float samples go as 16-bit units of the ping's peak / 65535
    // (value = unit x scale_factor)
    float peak = 0.0f;
    for (const xtf::XtfPingChannel& c : ping.channels)
      for (const float v : std::get<std::vector<float>>(c.samples))
        if (std::isfinite(v)) peak = std::max(peak, v);
    const float scale = peak > 0.0f ? peak / 65535.0f : 1.0f;
    out.bits_per_point = 16;
    out.scale_factor = scale;
    for (const xtf::XtfPingChannel& c : ping.channels) {
      for (const float v : std::get<std::vector<float>>(c.samples)) {
        const float u =
            std::isfinite(v) && v > 0.0f ? std::min(65535.0f, std::round(v / scale)) : 0.0f;
        const auto unit = static_cast<std::uint16_t>(u);
        out.data.push_back(static_cast<std::uint8_t>(unit & 0xFF));
        out.data.push_back(static_cast<std::uint8_t>(unit >> 8));
      }
    }
    return;
  }
  // XTF stores port far range first and starboard near range first: the line across as is
  for (const xtf::XtfPingChannel& c : ping.channels)
    std::visit([&](const auto& v) { append_le(out.data, v); }, c.samples);
}

imc::EstimatedState estimated_state_of(const vehicle::NavSolution& s,
                                       const LocalTangentPlane& origin) {
  imc::EstimatedState e;
  e.lat_rad = origin.origin().latitude_deg * kRadPerDeg;
  e.lon_rad = origin.origin().longitude_deg * kRadPerDeg;
  e.height_m = 0.0f;
  e.x_m = static_cast<float>(s.north_m);
  e.y_m = static_cast<float>(s.east_m);
  e.z_m = static_cast<float>(s.depth_m);
  e.phi_rad = static_cast<float>(s.roll);
  e.theta_rad = static_cast<float>(s.pitch);
  e.psi_rad = static_cast<float>(wrap_to_pi(s.heading));
  // no current is modelled: the water-relative velocity is the ground velocity, along the body
  // x axis as far as the solution tells
  const double sog = s.speed_over_ground_m_s;
  e.u_m_s = static_cast<float>(sog * std::cos(s.course_over_ground - s.heading));
  e.v_m_s = static_cast<float>(sog * std::sin(s.course_over_ground - s.heading));
  e.w_m_s = 0.0f;
  e.vx_m_s = static_cast<float>(sog * std::cos(s.course_over_ground));
  e.vy_m_s = static_cast<float>(sog * std::sin(s.course_over_ground));
  e.vz_m_s = 0.0f;
  e.p_rad_s = 0.0f;
  e.q_rad_s = 0.0f;
  e.r_rad_s = static_cast<float>(s.yaw_rate);
  e.depth_m = static_cast<float>(s.depth_m);
  e.alt_m = std::isfinite(s.altitude_m) ? static_cast<float>(s.altitude_m) : -1.0f;
  return e;
}

ImcDevice::ImcDevice(const ImcDeviceOptions& options, const LocalTangentPlane& origin,
                     const ImcSonarInfo& sonar)
    : options_(options),
      origin_(origin),
      sonar_(sonar),
      udp_(options.destination, options.send_buffer_bytes),
      last_position_(origin.origin()) {}

imc::Header ImcDevice::header(std::int64_t utc_ns, std::uint8_t entity) const {
  imc::Header h;
  h.timestamp_s = static_cast<double>(utc_ns) * 1e-9;
  h.src = options_.system;
  h.src_ent = entity;
  return h;
}

void ImcDevice::send() {
  udp_.send(buffer_);
  ++datagrams_;
  bytes_ += buffer_.size();
}

// Announce first and every kImcAnnounceS, Heartbeat every kImcHeartbeatS (simulation time).
void ImcDevice::keep_alive(SimTime t, std::int64_t utc_ns) {
  if (!started_ || t >= next_announce_t_) {
    imc::Announce a;
    a.sys_name = options_.system_name;
    a.lat_rad = last_position_.latitude_deg * kRadPerDeg;
    a.lon_rad = last_position_.longitude_deg * kRadPerDeg;
    a.services = options_.services;
    const imc::Header h = header(utc_ns, kImcEntityNavigation);
    imc::encode(h, a, buffer_);
    send();
    next_announce_t_ = t + from_seconds(kImcAnnounceS);
  }
  if (!started_ || t >= next_heartbeat_t_) {
    const imc::Header h = header(utc_ns, kImcEntityNavigation);
    imc::encode(h, imc::Heartbeat{}, buffer_);
    send();
    next_heartbeat_t_ = t + from_seconds(kImcHeartbeatS);
  }
  started_ = true;
}

void ImcDevice::ping(const PingSlot& slot, std::span<const std::uint8_t>) {
  keep_alive(slot.truth.t, slot.truth.time_utc_ns);
  sonar_data_from_xtf(slot.xtf, sonar_, sonar_data_);
  const imc::Header h = header(slot.truth.time_utc_ns, kImcEntitySonar);
  imc::encode(h, sonar_data_, buffer_);
  send();
}

void ImcDevice::nav_solution(const vehicle::NavSolution& solution, std::int64_t utc_ns) {
  keep_alive(solution.t, utc_ns);
  last_position_ = origin_.to_geodetic(solution.north_m, solution.east_m);
  const imc::Header h = header(utc_ns, kImcEntityNavigation);
  imc::encode(h, estimated_state_of(solution, origin_), buffer_);
  send();
}

void ImcDevice::add_stats(RunStats& stats) const {
  stats.imc_datagrams = datagrams_;
  stats.imc_bytes = bytes_;
  stats.imc_dropped = udp_.dropped();
}

std::vector<std::string> ImcDevice::describe() const {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "imc %s: SonarData per ping, EstimatedState per navigation sample, Heartbeat "
                "every %.0f s, Announce every %.0f s, as IMC system 0x%04X \"%s\"",
                udp_.describe().c_str(), kImcHeartbeatS, kImcAnnounceS, options_.system,
                options_.system_name.c_str());
  return {buf};
}

}  // namespace sonarloop::emulator
