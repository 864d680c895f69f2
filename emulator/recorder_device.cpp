#include "emulator/recorder_device.h"

#include <utility>

namespace sonarloop::emulator {

RecorderDevice::RecorderDevice(std::unique_ptr<Recording> recording,
                               std::function<void(const std::string&)> on_warning)
    : recording_(std::move(recording)), on_warning_(std::move(on_warning)) {}

void RecorderDevice::ping(const PingSlot& slot, std::span<const std::uint8_t>) {
  recording_->write_ping(slot);
  check();
}

void RecorderDevice::nav(std::span<const can::CanFrame> frames, std::int64_t utc_ns) {
  for (const can::CanFrame& f : frames)
    recording_->write_nav(f, utc_ns);
  check();
}

void RecorderDevice::check() {
  if (!error_.empty() || recording_->error().empty()) return;
  error_ = recording_->error();
  if (on_warning_) {
    on_warning_("warning: --record stopped: " + error_ +
                " (the run goes on; the recordings end with whole lines and packets)");
  }
}

void RecorderDevice::add_stats(RunStats& stats) const {
  stats.recorded_pings = recording_->pings();
  stats.recording_error = error_;
}

std::vector<std::string> RecorderDevice::describe() const {
  return {"record: " + recording_->dir() + "/{pings.xtf, nav.log, truth.csv}"};
}

void RecorderDevice::close() {
  recording_->close();
}

}  // namespace sonarloop::emulator
