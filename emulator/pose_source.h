#pragma once
// External pose sources for hardware in the loop (`sonarloop run --pose-from SPEC`): the emulator
// follows a vehicle outside it instead of its own trajectory, and renders pings from that pose.
//
// Specs (open_pose_source):
//   can:IFACE                        NMEA 2000 frames from a SocketCAN interface (vcan0, can0)
//   socketcand:HOST:PORT[:CHANNEL]   NMEA 2000 frames from a socketcand server: sonarloop connects
//                                    as a client (rawmode, channel default vcan0)
//   udp:HOST:PORT                    listens for the UDP pose message (emulator/pose_message.md)
//
// Each source runs one background thread that receives and merges into the latest pose; latest()
// may be called from any thread at any time.
//
// Merging. NMEA 2000 PGNs (docs/formats.md §2.3) each update their part of the pose; frames from
// any source address are merged, other PGNs are ignored (counted):
//   129025 Position, Rapid Update  lat/long -> pose.position_W x (north), y (east) through the
//                                  LocalTangentPlane; has_position (both fields available)
//   127250 Vessel Heading          heading -> pose.yaw; has_heading. A magnetic heading is made
//                                  true by adding deviation and variation where available
//   127257 Attitude                pitch, roll -> pose.pitch, pose.roll (+ nose up, + starboard
//                                  down, sim/frames.h); has_attitude (both available). Its yaw is
//                                  not used: heading comes from 127250
//   128267 Water Depth             Depth (water below the transducer: for the vehicle's downward
//                                  transducer its altitude above the seabed) -> altitude_m (NaN
//                                  when not available: no bottom lock); Offset >= 0 (transducer
//                                  to surface, i.e. the transducer's depth) -> pose.position_W z
//                                  and has_depth; without such an Offset has_depth becomes
//                                  false (depth unknown, not the last one kept). N2K cannot
//                                  carry depths beyond the Offset field's 32.764 m; a deeper
//                                  vehicle sends its depth with the UDP message instead.
// A UDP pose message is a complete snapshot: it replaces the pose, and its NaN fields clear the
// matching has_* flag (altitude_m NaN = no bottom lock).
//
// Time. received_ns is what the injected now_ns() returned when the last frame or message that
// updated the pose was received; frames that change nothing (ignored PGNs, malformed data) leave
// it alone. A source that goes silent therefore keeps returning the same received_ns: the
// emulator compares it with its own now_ns() and reports the pose as stale beyond its limit.
// (received_ns covers the whole pose: a source that keeps sending heading but stops sending
// position is not detected by it.) Besides the latest pose, each part's recent samples are kept
// (emulator/pose_history.h): pose_at(τ) gives the pose of any time τ on the now_ns() clock,
// interpolated between them (UDP messages placed at their own time stamps), or extrapolated
// after the last.
//
// Failures. Opening throws std::invalid_argument for a malformed spec, std::runtime_error when
// the source cannot be opened (no kernel CAN, a refused connection, a UDP port in use), naming
// the spec. Later receive errors (e.g. the socketcand server goes away) are reported once as a
// warning and counted; the socketcand source reconnects every reconnect_interval_ms. Malformed
// messages are counted and dropped.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <thread>

#include "common/geodesy.h"
#include "drivers/can/can_transport.h"
#include "drivers/net/host_port.h"
#include "drivers/net/udp_receiver.h"
#include "emulator/pose_history.h"
#include "sim/frames.h"

namespace sonarloop::emulator {

struct ExternalPose {
  std::int64_t received_ns = 0;  // now_ns() at the receipt of the last update
  Pose pose;                     // W frame (sim/frames.h); valid parts per the flags below
  bool has_position = false, has_heading = false, has_attitude = false, has_depth = false;
  double altitude_m = std::numeric_limits<double>::quiet_NaN();  // above the seabed; NaN unknown
};

class PoseSource {
 public:
  virtual ~PoseSource();
  // The merged latest pose, or nullopt before the first update.
  virtual std::optional<ExternalPose> latest() const = 0;
  // The pose at τ (now_ns() clock) by the rule of emulator/pose_history.h, each part
  // extrapolated for at most max_extrapolation_ns; nullopt before the first update.
  // *extrapolated (if given): whether the position was extrapolated.
  virtual std::optional<ExternalPose> pose_at(std::int64_t tau_ns,
                                              std::int64_t max_extrapolation_ns,
                                              bool* extrapolated = nullptr) const = 0;
  // One line for logs, e.g. "udp pose on 127.0.0.1:5700 (120 messages, 0 malformed)".
  virtual std::string describe() const = 0;
};

std::unique_ptr<PoseSource> open_pose_source(const std::string& spec, const LocalTangentPlane& ltp,
                                             std::function<std::int64_t()> now_ns);

// ---- the concrete sources (for tests and for callers that want their counters) ----

struct PoseSourceStats {
  std::uint64_t updates = 0;         // frames/messages that updated the pose
  std::uint64_t ignored = 0;         // valid frames of PGNs that carry no pose (e.g. 129026)
  std::uint64_t malformed = 0;       // undecodable messages/frames, unavailable or invalid fields
  std::uint64_t lost = 0;            // UDP: messages missing according to the sequence numbers
  std::uint64_t out_of_order = 0;    // UDP: late messages (older sequence), dropped
  std::uint64_t receive_errors = 0;  // transport failures (connection lost, socket errors)
  std::uint64_t reconnects = 0;      // successful reconnections after a failure
  std::string last_error;            // text of the last malformed input or receive error
};

struct PoseSourceOptions {
  int receive_timeout_ms = 100;      // receive poll slice: bounds how long stopping takes
  int reconnect_interval_ms = 1000;  // between reconnection attempts
  // Called from the receiving thread for each receive error (not for malformed input, which is
  // only counted). Default: a "warning: ..." line on stderr.
  std::function<void(const std::string&)> on_warning;
};

// The merging state shared by the sources (thread-safe).
class PoseMerger {
 public:
  PoseMerger(const LocalTangentPlane& ltp, std::function<std::int64_t()> now_ns);
  // NMEA 2000 frame: updates the pose if it is one of the PGNs above (true), counts otherwise.
  bool merge_n2k(const can::CanFrame& frame);
  // UDP datagram: decodes a pose message and replaces the pose (true), counts otherwise.
  bool merge_pose_datagram(std::span<const std::uint8_t> datagram);
  void count_malformed(const std::string& what);
  void count_receive_error(const std::string& what);
  void count_reconnect();

  std::optional<ExternalPose> latest() const;
  std::optional<ExternalPose> pose_at(std::int64_t tau_ns, std::int64_t max_extrapolation_ns,
                                      bool* extrapolated) const;
  PoseSourceStats stats() const;

 private:
  void count_malformed_locked(std::string what);   // mu_ held
  void record_snapshot_locked(std::int64_t t_ns);  // all of pose_'s parts at t_ns (mu_ held)

  LocalTangentPlane ltp_;
  std::function<std::int64_t()> now_ns_;
  mutable std::mutex mu_;
  ExternalPose pose_;
  // each part's recent samples (pose_at)
  PartTrack<2> position_;
  PartTrack<1> heading_{true};
  PartTrack<2> attitude_;
  PartTrack<1> depth_;
  PartTrack<1> altitude_;
  StampClock stamps_;
  bool any_ = false;
  bool have_sequence_ = false;
  std::uint32_t last_sequence_ = 0;
  PoseSourceStats stats_;
};

// NMEA 2000 pose from a CAN transport that can receive (SocketCAN, socketcand client).
class CanPoseSource final : public PoseSource {
 public:
  using Connect = std::function<std::unique_ptr<can::CanTransport>()>;
  // Calls connect() once (its exceptions propagate), then receives in a background thread;
  // after a receive error it calls connect() again every reconnect_interval_ms. `name` starts
  // describe(), e.g. "socketcand pose from 127.0.0.1:29536 (vcan0)".
  CanPoseSource(std::string name, Connect connect, const LocalTangentPlane& ltp,
                std::function<std::int64_t()> now_ns, PoseSourceOptions options = {});
  ~CanPoseSource() override;
  CanPoseSource(const CanPoseSource&) = delete;
  CanPoseSource& operator=(const CanPoseSource&) = delete;

  std::optional<ExternalPose> latest() const override { return merger_.latest(); }
  std::optional<ExternalPose> pose_at(std::int64_t tau_ns, std::int64_t max_extrapolation_ns,
                                      bool* extrapolated = nullptr) const override {
    return merger_.pose_at(tau_ns, max_extrapolation_ns, extrapolated);
  }
  std::string describe() const override;
  PoseSourceStats stats() const { return merger_.stats(); }
  bool connected() const { return connected_.load(); }

 private:
  void run();
  // Waits up to ms or until stopping; true if stopping.
  bool wait_stop(int ms);

  std::string name_;
  Connect connect_;
  PoseSourceOptions options_;
  PoseMerger merger_;
  std::unique_ptr<can::CanTransport> transport_;  // receiving thread only after construction
  std::atomic<bool> connected_{false};
  std::mutex stop_mu_;
  std::condition_variable stop_cv_;
  bool stopping_ = false;
  std::thread thread_;
};

// The UDP pose message on a bound UDP port.
class UdpPoseSource final : public PoseSource {
 public:
  // Binds `local` (port 0: ephemeral, see bound_port()). Throws std::runtime_error naming the
  // address if it cannot (e.g. the port is in use).
  UdpPoseSource(const net::HostPort& local, const LocalTangentPlane& ltp,
                std::function<std::int64_t()> now_ns, PoseSourceOptions options = {});
  ~UdpPoseSource() override;
  UdpPoseSource(const UdpPoseSource&) = delete;
  UdpPoseSource& operator=(const UdpPoseSource&) = delete;

  std::optional<ExternalPose> latest() const override { return merger_.latest(); }
  std::optional<ExternalPose> pose_at(std::int64_t tau_ns, std::int64_t max_extrapolation_ns,
                                      bool* extrapolated = nullptr) const override {
    return merger_.pose_at(tau_ns, max_extrapolation_ns, extrapolated);
  }
  std::string describe() const override;
  PoseSourceStats stats() const { return merger_.stats(); }
  std::uint16_t bound_port() const { return receiver_.bound_port(); }

 private:
  void run();

  PoseSourceOptions options_;
  PoseMerger merger_;
  net::UdpReceiver receiver_;
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

}  // namespace sonarloop::emulator
