#pragma once
// The emulator's output devices: what the publisher (emulator.h) hands out, in simulation time
// order, on its own thread, as ArduPilot's SITL and Gazebo's sensor plugins hand simulated
// sensors' data to their outputs. One class and file per device, each behind this narrow
// interface:
//
//   SonarUdpDevice   (sonar_udp_device.h)  pings -> XTF datagrams over UDP (--udp)
//   NavCanDevice     (nav_can_device.h)    NMEA 2000 frames -> one CAN transport (--can, each)
//   RecorderDevice   (recorder_device.h)   pings, frames and truth -> files (--record)
//   ImcDevice        (imc_device.h)        pings and navigation -> IMC over UDP (--imc)
//   McapDevice       (mcap_device.h)       pings, navigation, truth, contacts -> MCAP (--record)
//
// The inputs are not devices: the external pose (--pose-from) is read through
// ExternalPoseInput (external_pose.h) by the render workers and the publisher alike.
//
// A layer above the emulator adds its own with Emulator::add_device: the in-process onboard
// consumer of `run --classify` (mission/onboard_device.h) and the live view of `run --web`
// (web/emulator_device.h), which this layer cannot build.
//
// Timing. A device on the wire (on_wire()) gets each event first; the publisher measures a
// ping's lateness once they have all sent it, then hands it to the others (the recorder), whose
// disk writes are not the stream's lateness. Adding a device touches no other device: the
// emulator's own are built in Emulator::Impl::open_transports, the others added before run().
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "drivers/can/can_frame.h"
#include "emulator/render_queue.h"
#include "emulator/run_stats.h"
#include "sim/vehicle/nav_sensor.h"

namespace sonarloop::emulator {

class Device {
 public:
  virtual ~Device();
  // A ping: its slot (truth, lines) and its encoded XTF packet.
  virtual void ping(const PingSlot& slot, std::span<const std::uint8_t> packet);
  // One navigation sample's NMEA 2000 frames, at UTC utc_ns.
  virtual void nav(std::span<const can::CanFrame> frames, std::int64_t utc_ns);
  // The same sample's navigation solution, for devices that publish navigation in their own
  // terms (IMC's EstimatedState, MCAP's fix and pose); called before nav(), for the samples that
  // carry the position (129025, every 100 ms; not while an external pose is stale).
  virtual void nav_solution(const vehicle::NavSolution& solution, std::int64_t utc_ns);
  // Whether the device sends on the wire (timed) rather than records.
  virtual bool on_wire() const = 0;
  // Its counters into the run's statistics (called with every statistics update).
  virtual void add_stats(RunStats& stats) const;
  // The run's statistics, at the live statistics' interval (EmulatorOptions::stats_interval_s).
  virtual void stats(const RunStats& stats);
  // Lines for the run's set-up report.
  virtual std::vector<std::string> describe() const = 0;
  // The end of the run: flush and close (may be called again); throws std::exception on failure.
  // Devices are closed in the reverse order of their adding: the emulator's own last.
  virtual void close();
};

}  // namespace sonarloop::emulator
