#pragma once
// The recorder (--record DIR; recording.h): pings.xtf, nav.log (candump format) and truth.csv.
// A write error (a full disk) stops the recording, not the run: it is said once, when it
// happens (`on_warning`), and reported in the run's statistics (recording_error).
#include <functional>
#include <memory>
#include <string>

#include "emulator/device.h"
#include "emulator/recording.h"

namespace sonarloop::emulator {

class RecorderDevice final : public Device {
 public:
  RecorderDevice(std::unique_ptr<Recording> recording,
                 std::function<void(const std::string&)> on_warning);

  void ping(const PingSlot& slot, std::span<const std::uint8_t> packet) override;
  void nav(std::span<const can::CanFrame> frames, std::int64_t utc_ns) override;
  bool on_wire() const override { return false; }
  // recorded_pings, recording_error
  void add_stats(RunStats& stats) const override;
  std::vector<std::string> describe() const override;
  void close() override;

 private:
  void check();  // a new write error: said once

  std::unique_ptr<Recording> recording_;
  std::function<void(const std::string&)> on_warning_;
  std::string error_;
};

}  // namespace sonarloop::emulator
