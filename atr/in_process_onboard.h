#pragma once
// The onboard consumer in the emulator's process (`run --classify`): the pipeline on a thread of
// its own, fed through a packet queue, contacts to a ContactWriter.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <thread>

#include "atr/contact_writer.h"
#include "atr/onboard_pipeline.h"
#include "atr/packet_queue.h"
#include "atr/subspace_classifier.h"

namespace sonarloop::atr {

// `run --classify`: the onboard pipeline on a thread of its own, fed with the emulator's pings
// (mission/onboard_device.h) through a queue, contacts to a file or stderr. Lossless: with
// --rate max the emulator waits for a free queue slot (the output then depends only on the
// scenario); paced, a full queue drops the ping (counted) rather than delay the emulator.
class InProcessOnboard {
 public:
  // Also told every contact (on the consumer's thread, or in finish()), e.g. `run --web`.
  using ContactObserver = std::function<void(const Contact&)>;
  // Starts the consumer thread; feeds `file_header` (the emulator's XTF file header) first.
  InProcessOnboard(Model model, const OnboardOptions& options,
                   const std::optional<std::string>& contacts_path,
                   std::span<const std::uint8_t> file_header, std::size_t packet_bytes,
                   bool lossless, ContactObserver observer = {});
  ~InProcessOnboard();
  InProcessOnboard(const InProcessOnboard&) = delete;
  InProcessOnboard& operator=(const InProcessOnboard&) = delete;

  // The hook: copies the packet into the queue.
  void on_ping(std::span<const std::uint8_t> packet) { queue_.push(packet, lossless_); }
  // Drains the queue, ends the thread, decides the objects still open; returns the statistics.
  // Called again, returns them again (the consumer's error thrown again).
  OnboardStats finish();
  const PacketQueue& queue() const { return queue_; }
  std::string contacts_destination() const { return contacts_.describe(); }

 private:
  ContactWriter contacts_;
  ContactObserver observer_;
  OnboardPipeline pipeline_;
  PacketQueue queue_;
  bool lossless_;
  std::thread thread_;
  std::string error_;
  bool finished_ = false;
};

}  // namespace sonarloop::atr
