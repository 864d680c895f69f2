#pragma once
// External pose sources for hardware in the loop (`sonarloop run --pose-from SPEC`): the emulator
// follows a vehicle outside it instead of its own trajectory, and renders pings from that pose.
//
// Specs (open_pose_source):
//   can:IFACE                        NMEA 2000 frames from a SocketCAN interface (vcan0, can0)
//   socketcand:HOST:PORT[:CHANNEL]   NMEA 2000 frames from a socketcand server: sonarloop connects
//                                    as a client (rawmode, channel default vcan0)
//   udp:HOST:PORT                    listens for the UDP pose message
//                                    (drivers/pose/pose_message.md)
//   imc:udp:HOST:PORT                listens for IMC EstimatedState (drivers/imc/imc_codec.h), as
//                                    DUNE publishes its navigation (its vehicle simulator too)
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
// matching has_* flag (altitude_m NaN = no bottom lock). So is an IMC EstimatedState
// (pose_message_from_imc): its position is lat/lon displaced by the NED offsets x, y; depth and
// alt when not negative (negative: invalid, not available); heading psi, pitch theta, roll phi;
// time its header's time stamp. IMC has no sequence numbers: lost and out_of_order stay 0, and a
// late packet is refused by its time stamp instead. Other IMC messages (Heartbeat, Announce,
// ...) are counted as ignored.
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
//
// Plausibility (PoseLimits). A pose that decodes but cannot be a vehicle's is rejected, counted
// in PoseSourceStats::rejected (not `updates`, not `malformed`) and said in a warning line, at
// most one per kRejectWarningIntervalNs (the lines in between are summed into the next): a
// depth above the sea surface or below the scene's deepest seabed, a negative altitude or one
// beyond that depth, |pitch| or |roll| of 90 degrees or more, a position that moved faster than
// a vehicle can (max_speed_m_s plus a navigation fix's jump_tolerance_m), and a UDP time stamp
// that went back or jumped ahead of its arrival. A rejected message changes nothing, so it does
// not refresh received_ns: a source that sends only absurd poses goes stale like a silent one,
// and pings pause until a plausible pose arrives. The relative checks (jump, time stamp) compare
// with the last accepted sample; after reanchor_after consecutive such rejections the source is
// taken to have really moved (or its clock to have been stepped): the next sample is accepted as
// the new reference and the samples before it are forgotten, so that one bad fix cannot lock a
// vehicle out for ever. A re-anchoring is said in a note, at most one per
// kRejectWarningIntervalNs too (a sender alternating two clocks re-anchors many times a second).
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
#include <string_view>
#include <thread>

#include "common/geodesy.h"
#include "drivers/can/can_transport.h"
#include "drivers/imc/imc_codec.h"
#include "drivers/net/host_port.h"
#include "drivers/net/udp_receiver.h"
#include "drivers/pose/pose_message.h"
#include "emulator/pose_history.h"
#include "sim/frames.h"
#include "sim/scene/scene_desc.h"

namespace sonarloop::emulator {

// The pose message is a wire format (drivers/pose/pose_message.h); the pose input reads it.
using pose::decode_pose_message;
using pose::encode_pose_message;
using pose::kPoseMessageBytes;
using pose::PoseMessage;

struct ExternalPose {
  std::int64_t received_ns = 0;  // now_ns() at the receipt of the last update
  Pose pose;                     // W frame (sim/frames.h); valid parts per the flags below
  bool has_position = false, has_heading = false, has_attitude = false, has_depth = false;
  double altitude_m = std::numeric_limits<double>::quiet_NaN();  // above the seabed; NaN unknown
};

// What a plausible external pose is (see "Plausibility" above). The defaults reuse the
// vehicle's hard limits (sim/vehicle/vehicle_desc.h validate(): speed, pitch and roll); the
// emulator sets the depths from the scene (pose_limits_for_scene below).
struct PoseLimits {
  double max_speed_m_s = default_max_speed_m_s();  // the vehicle speed limit, 20 m/s
  // Added to max_speed_m_s x dt: a USBL- or GPS-aided navigation fix resets the position by up
  // to a few metres (vehicle_desc.h: USBL-aided position noise 1-5 m).
  double jump_tolerance_m = 5.0;
  // A surfaced vehicle's pressure depth swings by the wave height: this much above the surface
  // is still taken as the surface.
  double above_surface_tolerance_m = 1.0;
  double max_depth_m = std::numeric_limits<double>::infinity();     // the deepest seabed
  double max_altitude_m = std::numeric_limits<double>::infinity();  // the same (water column)
  double max_pitch_rad = default_max_angle_rad("trajectory.attitude.max_pitch");  // π/2, open
  double max_roll_rad = default_max_angle_rad("trajectory.attitude.max_roll");    // π/2, open
  // A stamp may run ahead of the arrival clock by at most this (a message delayed in the
  // network and the next one on time); beyond it the sender's clock jumped.
  std::int64_t stamp_tolerance_ns = 1'000'000'000;
  int reanchor_after = 5;  // consecutive jump / time rejections before re-anchoring

  static double default_max_speed_m_s();
  static double default_max_angle_rad(std::string_view vehicle_field);
};

// At most one warning line about rejected poses per this long (now_ns() clock): a sender that
// streams absurd poses at 50 Hz must not flood the log.
inline constexpr std::int64_t kRejectWarningIntervalNs = 1'000'000'000;

struct PoseSourceOptions {
  int receive_timeout_ms = 100;      // receive poll slice: bounds how long stopping takes
  int reconnect_interval_ms = 1000;  // between reconnection attempts
  // Called from the receiving thread for each receive error and (rate-limited) for rejected
  // poses (not for malformed input, which is only counted). Default: a "warning: ..." line on
  // stderr.
  std::function<void(const std::string&)> on_warning;
  PoseLimits limits;
};

// What a pose source counted (PoseSource::stats()).
struct PoseSourceStats {
  std::uint64_t updates = 0;    // frames/messages that updated the pose
  std::uint64_t rejected = 0;   // decoded but implausible poses (PoseLimits), dropped
  std::uint64_t reanchors = 0;  // new reference accepted after reanchor_after rejections
  std::uint64_t ignored = 0;    // valid frames of PGNs that carry no pose (e.g. 129026)
  std::uint64_t malformed = 0;  // undecodable messages/frames, unavailable or invalid fields
  std::uint64_t lost = 0;       // UDP: messages missing according to the sequence numbers
  // UDP: sequence jumps taken as a sender restart (back by more than 64, ahead by more than
  // 65536), not counted as lost
  std::uint64_t sequence_restarts = 0;
  std::uint64_t out_of_order = 0;    // UDP: late messages (older sequence), dropped
  std::uint64_t receive_errors = 0;  // transport failures (connection lost, socket errors)
  std::uint64_t reconnects = 0;      // successful reconnections after a failure
  std::string last_error;            // text of the last malformed input or receive error
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
  // The counters so far (PoseSourceStats, below).
  virtual PoseSourceStats stats() const = 0;
};

// The limits of a plausible pose over `scene`: its deepest seabed (the mean water depth, the
// plane's fall to the extent's farthest corner and 6 sigma of the large-scale relief) bounds the
// depth and the altitude; speed and attitude keep the vehicle limits.
PoseLimits pose_limits_for_scene(const scene::SceneDesc& scene);

// `options`: the plausibility limits (the emulator's come from the scene, pose_limits_for_scene)
// and where warnings go; the poll timings keep their defaults.
std::unique_ptr<PoseSource> open_pose_source(const std::string& spec, const LocalTangentPlane& ltp,
                                             std::function<std::int64_t()> now_ns,
                                             PoseSourceOptions options = {});

// ---- the concrete sources (for tests and for callers that want their counters) ----

// The merging state shared by the sources (thread-safe).
class PoseMerger {
 public:
  // `warn` (may be empty: silent) receives the rate-limited lines about rejected poses; it is
  // called without the merger's lock held.
  PoseMerger(const LocalTangentPlane& ltp, std::function<std::int64_t()> now_ns,
             PoseLimits limits = {}, std::function<void(const std::string&)> warn = {});
  // NMEA 2000 frame: updates the pose if it is one of the PGNs above (true), counts otherwise.
  bool merge_n2k(const can::CanFrame& frame);
  // UDP datagram: decodes a pose message and replaces the pose (true), counts otherwise.
  bool merge_pose_datagram(std::span<const std::uint8_t> datagram);
  // UDP datagram of IMC: an EstimatedState replaces the pose (true); other messages are
  // counted as ignored, undecodable packets as malformed.
  bool merge_imc_datagram(std::span<const std::uint8_t> datagram);
  void count_ignored();
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
  // Plausibility (mu_ held): the reason a value is absurd, or empty.
  std::string check_depth_locked(double depth_m) const;
  std::string check_altitude_locked(double altitude_m) const;
  std::string check_attitude_locked(double pitch_rad, double roll_rad) const;
  // The relative checks (mu_ held): a position jump from the last accepted position sample, and
  // a UDP stamp against the last accepted one. Empty when plausible or re-anchored.
  std::string check_jump_locked(std::int64_t t_ns, const Vec2& ne);
  std::string check_stamp_locked(std::int64_t stamp_ns, std::int64_t arrival_ns);
  // After a relative rejection: true when reanchor_after of them came in a row (then the
  // caller accepts the sample as the new reference).
  bool reanchor_due_locked(int& consecutive);
  // A decoded snapshot (a pose message, or an IMC EstimatedState made one: no sequence number):
  // checked, then the pose. `what` names it in a rejection's warning.
  bool merge_snapshot(const PoseMessage& m, bool sequenced, const std::string& what);
  // The absolute and relative checks of a decoded UDP snapshot (mu_ held).
  std::string check_snapshot_locked(const ExternalPose& p, const PoseMessage& m,
                                    std::int64_t arrival_ns);
  // Gives a re-anchoring note, if one is pending, after unlocking.
  // Says a pending re-anchoring (at most one line per kRejectWarningIntervalNs); unlocks.
  void give_pending_note(std::unique_lock<std::mutex>& lock, std::int64_t now_ns);
  // Counts a rejection, unlocks, and gives the warning line if its turn has come; false.
  bool reject_and_warn(std::unique_lock<std::mutex>& lock, const std::string& what,
                       std::int64_t now_ns);

  LocalTangentPlane ltp_;
  std::function<std::int64_t()> now_ns_;
  PoseLimits limits_;
  std::function<void(const std::string&)> warn_;
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
  bool have_stamp_ = false;  // last accepted UDP stamp and its arrival
  std::int64_t last_stamp_ns_ = 0, last_stamp_arrival_ns_ = 0;
  int position_rejections_ = 0;  // consecutive position jumps rejected
  int stamp_rejections_ = 0;     // consecutive time stamp jumps rejected
  std::string pending_note_;     // a re-anchoring, said once the lock is released
  // rate limit of the rejection warnings
  bool warned_ = false;
  std::int64_t last_warning_ns_ = 0;
  std::uint64_t unwarned_ = 0;  // rejections since the last warning line
  // rate limit of the re-anchoring notes
  bool noted_ = false;
  std::int64_t last_note_ns_ = 0;
  std::uint64_t unnoted_ = 0;  // re-anchorings since the last note
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
  PoseSourceStats stats() const override { return merger_.stats(); }
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

// An IMC EstimatedState as a pose snapshot (see "Merging" above); nullopt with `error` set when
// a value is not finite or the position is not on the Earth. time_unix_ns: the time stamp
// (0 when it is not positive).
std::optional<PoseMessage> pose_message_from_imc(const imc::EstimatedState& e, double timestamp_s,
                                                 std::string& error);

// What a UdpPoseSource listens for.
enum class UdpPoseFormat { kPoseMessage, kImc };

// The UDP pose message, or IMC, on a bound UDP port.
class UdpPoseSource final : public PoseSource {
 public:
  // Binds `local` (port 0: ephemeral, see bound_port()). Throws std::runtime_error naming the
  // address if it cannot (e.g. the port is in use).
  UdpPoseSource(const net::HostPort& local, const LocalTangentPlane& ltp,
                std::function<std::int64_t()> now_ns, PoseSourceOptions options = {},
                UdpPoseFormat format = UdpPoseFormat::kPoseMessage);
  ~UdpPoseSource() override;
  UdpPoseSource(const UdpPoseSource&) = delete;
  UdpPoseSource& operator=(const UdpPoseSource&) = delete;

  std::optional<ExternalPose> latest() const override { return merger_.latest(); }
  std::optional<ExternalPose> pose_at(std::int64_t tau_ns, std::int64_t max_extrapolation_ns,
                                      bool* extrapolated = nullptr) const override {
    return merger_.pose_at(tau_ns, max_extrapolation_ns, extrapolated);
  }
  std::string describe() const override;
  PoseSourceStats stats() const override { return merger_.stats(); }
  std::uint16_t bound_port() const { return receiver_.bound_port(); }

 private:
  void run();

  PoseSourceOptions options_;
  UdpPoseFormat format_;
  PoseMerger merger_;
  net::UdpReceiver receiver_;
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

}  // namespace sonarloop::emulator
