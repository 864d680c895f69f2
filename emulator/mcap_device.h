#pragma once
// The run as an MCAP recording for ROS 2 tools (`run --record DIR` writes DIR/run.mcap, `run
// --mcap FILE` that file alone; drivers/mcap/mcap_writer.h, docs/formats.md §8): profile ros2,
// messages in CDR with their ros2msg definitions, time stamps (log, publish and header) the
// simulation time on the run's UTC epoch. Topics:
//   /sidescan/port, /sidescan/starboard   marine_acoustic_msgs/msg/RawSonarImage, every ping: one
//                                         beam of the XTF channel's samples near to far (dtype
//                                         from the sample size), sample_rate c / (2 bin),
//                                         rx_angles -pi/2 (port) or +pi/2 (starboard), frequency
//                                         and sound speed; frame_id "sonar"
//   /sidescan/waterfall                   sensor_msgs/msg/Image, mono8, every kMcapWaterfallEvery
//                                         pings: the last kMcapWaterfallRows pings, newest on
//                                         top, port on the left, samples averaged to at most
//                                         kMcapWaterfallWidth columns, 0..255 over the 60 dB below
//                                         full scale
//   /nav/fix                              sensor_msgs/msg/NavSatFix, every navigation sample
//                                         (10 Hz): the navigation solution's latitude, longitude
//                                         and -depth (the solution the NMEA 2000 frames carry)
//   /nav/pose                             geometry_msgs/msg/PoseStamped, the same solution in the
//                                         frame "map" (REP 103: x east, y north, z up from the
//                                         scenario's origin; orientation of the body frame
//                                         forward-left-up)
//   /truth/pose                           geometry_msgs/msg/PoseStamped, every ping: the true pose
//                                         it was rendered from, in "map"
//   /contacts                             std_msgs/msg/String (with record_contacts(): `run
//                                         --classify`): each contact's JSON line as the contacts
//                                         file holds it (docs/formats.md §6)
//   /contacts/fix                         sensor_msgs/msg/NavSatFix, the same contact's position
//                                         (altitude NaN: unknown), for a map panel
// The contacts are kept and written at close(), ordered by (time, id), with the log time of
// the ping they were detected on: the consumer's thread reports them when it gets there, and
// the file is the same bytes whatever that timing.
#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "common/geodesy.h"
#include "drivers/mcap/mcap_writer.h"
#include "drivers/ros2/ros2_messages.h"
#include "emulator/device.h"
#include "sim/frames.h"

namespace sonarloop::emulator {

inline constexpr int kMcapWaterfallEvery = 16;
inline constexpr int kMcapWaterfallRows = 256;
inline constexpr int kMcapWaterfallWidth = 1024;

struct McapSonarInfo {
  double frequency_hz = 0.0;
  double sound_speed_m_s = 1500.0;
  double bin_size_m = 0.0;
};

// The quaternion (x, y, z, w) of a pose's attitude (NED world, forward-right-down body:
// sim/frames.h) as ROS's ENU world and forward-left-up body see it (REP 103).
std::array<double, 4> enu_flu_quaternion(double yaw, double pitch, double roll);

// A contact as the MCAP recording keeps it (what the onboard layer reports; this layer does not
// know its type).
struct McapContact {
  std::optional<std::int64_t> time_utc_ns;  // the ping's; none: recorded at the last ping's
  std::uint64_t id = 0;
  double north_m = 0.0, east_m = 0.0;  // in the scenario's frame
  std::string json;                    // one line, without its newline
};

class McapDevice final : public Device {
 public:
  // Creates `path` (std::runtime_error naming it when it cannot). `origin`: the scenario's.
  McapDevice(const std::string& path, const LocalTangentPlane& origin, const McapSonarInfo& sonar,
             mcap::WriterOptions options = {});

  void ping(const PingSlot& slot, std::span<const std::uint8_t> packet) override;
  void nav_solution(const vehicle::NavSolution& solution, std::int64_t utc_ns) override;
  bool on_wire() const override { return false; }
  void add_stats(RunStats& stats) const override;  // mcap_messages, mcap_error
  std::vector<std::string> describe() const override;
  void close() override;

  // Adds the /contacts channels (before run(); `run --classify`).
  void record_contacts();
  // One contact, from any thread (needs record_contacts()); written at close().
  void add_contact(McapContact contact);

 private:
  // Runs `write`; the first write error stops the recording (said once, counted in the stats).
  template <class F>
  void guarded(F&& write);
  void waterfall_row(const xtf::XtfPing& ping);
  void write_waterfall(std::int64_t utc_ns);
  void write_fix(std::uint16_t channel, std::int64_t utc_ns, double north_m, double east_m,
                 double altitude_m);
  void write_contacts();
  std::uint16_t add_schema(const ros2::MessageSchema& s);
  void write_pose(std::uint16_t channel, std::int64_t utc_ns, double north_m, double east_m,
                  double depth_m, double yaw, double pitch, double roll);

  LocalTangentPlane origin_;
  McapSonarInfo sonar_;
  std::unique_ptr<mcap::Writer> writer_;
  std::uint16_t port_ = 0, stbd_ = 0, waterfall_ = 0, fix_ = 0, nav_pose_ = 0, truth_ = 0;
  std::uint32_t seq_ = 0;
  std::vector<std::uint8_t> buffer_, samples_;
  // the waterfall: rows of width_ pixels, a ring of kMcapWaterfallRows
  int width_ = 0;
  std::vector<std::uint8_t> rows_, image_;
  int rows_filled_ = 0, next_row_ = 0, pings_ = 0;
  std::string error_;
  std::int64_t last_ping_utc_ns_ = 0;
  std::uint16_t contacts_ = 0, contact_fix_ = 0, fix_schema_ = 0;
  bool record_contacts_ = false;
  std::mutex contacts_mutex_;
  std::vector<McapContact> pending_;
};

}  // namespace sonarloop::emulator
