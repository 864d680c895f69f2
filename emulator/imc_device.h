#pragma once
// IMC over UDP (`run --imc udp:HOST:PORT`; drivers/imc/imc_codec.h, docs/formats.md §7): the
// emulated vehicle as a DUNE vehicle appears to a Neptus console or to other IMC software. To
// the one address given (unicast, no discovery multicast) it sends:
//   SonarData (276)       every ping: type sidescan, the sonar's frequency, min_range 0 and
//                         max_range its slant range, one line across (the XTF channels' samples:
//                         port far to near, then starboard near to far), bits_per_point from the
//                         XTF sample size, scale_factor 1 (values are the recorder's counts;
//                         float samples: 16-bit units of the ping's peak / 65535);
//                         time stamp the ping's time
//   EstimatedState (350)  every navigation sample (10 Hz): the navigation solution (the same as
//                         the NMEA 2000 frames carry) as NED offsets x, y and depth z from the
//                         scenario's origin (lat, lon, height 0), roll / pitch / yaw, body and
//                         ground velocities, yaw rate, depth and altitude (-1: unknown)
//   Heartbeat (150)       every second of simulation time
//   Announce (151)        every 10 s of simulation time and first: the system's name, type UUV,
//                         its position, and `services` (where it listens, if anywhere)
// Every header carries the system's IMC address (default kDefaultImcSystem), entity
// kImcEntitySonar or kImcEntityNavigation, destination any, and the simulation time as UTC.
#include <cstdint>
#include <string>
#include <vector>

#include "common/geodesy.h"
#include "drivers/imc/imc_codec.h"
#include "drivers/net/host_port.h"
#include "drivers/net/udp_sender.h"
#include "emulator/device.h"
#include "sim/core/sim_time.h"

namespace sonarloop::emulator {

using imc::kDefaultImcSystem;
using imc::kImcEntityNavigation;
using imc::kImcEntitySonar;
inline constexpr double kImcHeartbeatS = 1.0;
inline constexpr double kImcAnnounceS = 10.0;

struct ImcDeviceOptions {
  net::HostPort destination;
  std::uint16_t system = kDefaultImcSystem;
  std::string system_name = "sonarloop";
  std::string services;  // Announce's services, e.g. "imc+udp://127.0.0.1:6002/" (may be empty)
  int send_buffer_bytes = 1 << 20;
};

// The sonar's description as SonarData gives it.
struct ImcSonarInfo {
  double frequency_hz = 0.0;
  double max_range_m = 0.0;
};

class ImcDevice final : public Device {
 public:
  // `origin`: the scenario's local tangent plane (EstimatedState's lat, lon). Throws
  // std::runtime_error when the socket cannot be opened.
  ImcDevice(const ImcDeviceOptions& options, const LocalTangentPlane& origin,
            const ImcSonarInfo& sonar);

  void ping(const PingSlot& slot, std::span<const std::uint8_t> packet) override;
  void nav_solution(const vehicle::NavSolution& solution, std::int64_t utc_ns) override;
  bool on_wire() const override { return true; }
  // imc_datagrams, imc_bytes, imc_dropped
  void add_stats(RunStats& stats) const override;
  std::vector<std::string> describe() const override;

 private:
  void send();  // the packet in buffer_
  void keep_alive(SimTime t, std::int64_t utc_ns);
  imc::Header header(std::int64_t utc_ns, std::uint8_t entity) const;

  ImcDeviceOptions options_;
  LocalTangentPlane origin_;
  ImcSonarInfo sonar_;
  net::UdpSender udp_;
  imc::SonarData sonar_data_;  // reused: no allocation per ping once warmed up
  std::vector<std::uint8_t> buffer_;
  bool started_ = false;
  SimTime next_heartbeat_t_ = 0, next_announce_t_ = 0;
  GeoPoint last_position_{};
  std::uint64_t datagrams_ = 0, bytes_ = 0;
};

// SonarData's sidescan line from an XTF ping of one port and one starboard channel: the samples
// as stored (port far to near, starboard near to far), little-endian; float samples as 16-bit
// units with the scale factor of the ping's peak. Reuses out.data.
void sonar_data_from_xtf(const xtf::XtfPing& ping, const ImcSonarInfo& sonar, imc::SonarData& out);

// EstimatedState from a navigation solution, as offsets from `origin`.
imc::EstimatedState estimated_state_of(const vehicle::NavSolution& s,
                                       const LocalTangentPlane& origin);

}  // namespace sonarloop::emulator
