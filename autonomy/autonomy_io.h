#pragma once
// The wires of `sonarloop autonomy` (tools/cmd_autonomy.cpp): navigation read from CAN (NMEA 2000),
// contacts read from UDP (JSON lines of the onboard consumer), the pose published to the emulator
// (UDP pose message, drivers/pose/pose_message.md), and the agent's report as JSON.
#include <atomic>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "atr/contact.h"
#include "autonomy/agent.h"
#include "common/geodesy.h"
#include "drivers/can/can_transport.h"
#include "drivers/net/udp_receiver.h"
#include "drivers/net/udp_sender.h"

namespace sonarloop::autonomy {

// The latest navigation read from the bus, in the mission frame.
struct NavFix {
  std::optional<autonomy::Point2> position;  // PGN 129025
  std::optional<double> heading_rad;         // PGN 127250
  std::optional<double> seabed_depth_m;      // PGN 128267: transducer depth (Offset) + Depth
  std::optional<double> altitude_m;          // PGN 128267 Depth
  std::uint64_t frames = 0, decoded = 0, position_updates = 0, depth_updates = 0;
};

// Reads NMEA 2000 frames on a thread. spec: socketcand:HOST:PORT[:CHANNEL] (a client of the
// emulator's `--can socketcand:` server; connection retried until `connect_timeout_s`) or a
// SocketCAN interface (vcan0). Throws std::runtime_error when it cannot connect.
class NavListener {
 public:
  NavListener(const std::string& spec, const LocalTangentPlane& ltp, double connect_timeout_s);
  ~NavListener();
  NavListener(const NavListener&) = delete;
  NavListener& operator=(const NavListener&) = delete;
  NavFix latest() const;
  std::string describe() const { return describe_; }

 private:
  void run();
  LocalTangentPlane ltp_;
  std::unique_ptr<can::CanTransport> bus_;
  std::string describe_;
  mutable std::mutex mu_;
  NavFix fix_;
  std::atomic<bool> stop_{false};
  std::string error_;
  std::thread thread_;
};

// Receives contact datagrams on a thread; take() hands over those received since the last call.
// A step's share of the contacts, and how many may wait (beyond: dropped, counted).
inline constexpr std::size_t kMaxContactsPerTake = 64;
inline constexpr std::size_t kMaxQueuedContacts = 4096;

class ContactListener {
 public:
  explicit ContactListener(const net::HostPort& address);
  ~ContactListener();
  ContactListener(const ContactListener&) = delete;
  ContactListener& operator=(const ContactListener&) = delete;
  // The contacts received since the last call, oldest first, at most `max` (the rest stay for the
  // next call): a burst is handed over a step at a time, never all at once.
  std::deque<atr::Contact> take(std::size_t max = kMaxContactsPerTake);
  std::uint64_t received() const { return received_.load(); }
  // lines that are not a valid contact (contact_decision.h: malformed or out of range)
  std::uint64_t malformed() const { return malformed_.load(); }
  // contacts dropped because kMaxQueuedContacts were waiting (a flood)
  std::uint64_t dropped() const { return dropped_.load(); }
  std::string describe() const { return rx_.describe(); }
  std::uint16_t port() const { return rx_.bound_port(); }  // the one bound (port 0: any free)

 private:
  void run();
  net::UdpReceiver rx_;
  std::mutex mu_;
  std::deque<atr::Contact> queue_;
  std::atomic<std::uint64_t> received_{0}, malformed_{0}, dropped_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// Sends the vehicle's pose as UDP pose messages (latitude/longitude through `ltp`, depth,
// heading, pitch; altitude not available: the emulator takes it from its seabed).
class PosePublisher {
 public:
  PosePublisher(const net::HostPort& destination, const LocalTangentPlane& ltp);
  void publish(const autonomy::VehicleState& s, std::int64_t time_unix_ns);
  std::uint64_t sent() const { return sequence_; }

 private:
  net::UdpSender tx_;
  LocalTangentPlane ltp_;
  std::uint32_t sequence_ = 0;
};

// What the report says besides the agent's own state.
struct AgentRunInfo {
  // flown in lock-step (mission/lockstep.h): no wall clock, no wire; the report then leaves out
  // what depends on them (rate, wall times, poses sent, the navigation read from the bus), so
  // that it is a function of the scenario and seed alone
  bool lockstep = false;
  double rate = 1.0;
  double threshold = 0.0;
  bool relooks = true;
  double wall_time_s = 0.0;
  double survey_plan_m = 0.0;
  bool stopped = false;  // by SIGINT / SIGTERM
  std::uint64_t contacts_received = 0, contacts_malformed = 0, contacts_dropped = 0, poses_sent = 0;
  NavFix nav;
  double nav_offset_mean_m = 0.0, nav_offset_max_m = 0.0;  // |nav - model| on receipt
};

// The report: the run, every object with its looks and final state, every re-look with its
// geometry and timing (docs/autonomy.md).
std::string agent_report_json(const autonomy::Agent& agent, const AgentRunInfo& info);

}  // namespace sonarloop::autonomy
