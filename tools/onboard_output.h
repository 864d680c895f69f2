#pragma once
// What `sonarloop onboard` and `sonarloop run --classify` share: the contacts file (JSON Lines,
// atr/contact.h) and the end-of-run statistics of the onboard pipeline.
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "atr/contact.h"
#include "atr/onboard_pipeline.h"
#include "atr/packet_queue.h"
#include "atr/subspace_classifier.h"
#include "drivers/net/udp_sender.h"
#include "emulator/device.h"

namespace sonarloop::tools {

// Contact reports, one JSON line each, flushed line by line (a reader sees them live). To a file
// (created or truncated), to an already open stream (stdout, stderr), or with a path
// "udp:HOST:PORT" as UDP datagrams there, one contact's JSON line (no newline) per datagram
// (atr/contact.h; what `sonarloop autonomy --contacts` reads).
class ContactWriter {
 public:
  // Throws std::runtime_error naming the file if it cannot be created, std::invalid_argument
  // for a malformed udp:HOST:PORT.
  explicit ContactWriter(const std::optional<std::string>& path, std::FILE* fallback);
  ~ContactWriter();
  ContactWriter(const ContactWriter&) = delete;
  ContactWriter& operator=(const ContactWriter&) = delete;

  void write(const atr::Contact& c);
  std::string describe() const;  // the file name, "stdout" / "stderr", or "udp:HOST:PORT"

 private:
  std::unique_ptr<net::UdpSender> udp_;
  std::FILE* f_ = nullptr;
  bool owned_ = false;
  std::string name_;
};

// Loads a model file (older formats: class heights from the simulator, tools/chip_options.h),
// or nullopt when no path is given; "default" is the default model (mission/default_model.h),
// built and cached the first time.
std::optional<atr::Model> load_model_if(const std::optional<std::string>& path);

// --gate-threshold P: the classification gate's operating point (its target probability, 0 to
// 1) instead of the one training chose; a point of the mission report's gate_froc.csv. Throws
// UsageError when `model` has no classification gate (a model of `train --surveys` has one).
void set_gate_threshold(std::optional<atr::Model>& model, std::optional<double> threshold);

// The end-of-run statistics on stderr, a few lines (`who` prefixes the first).
void print_onboard_stats(const char* who, const atr::OnboardStats& s,
                         const atr::PacketQueue* queue);

// The statistics as one JSON object.
std::string onboard_stats_json(const atr::OnboardStats& s, const atr::PacketQueue* queue);

// `run --classify`: the onboard pipeline on a thread of its own, fed with the emulator's pings
// (OnboardDevice, below) through a queue, contacts to a file or stderr. Lossless: with
// --rate max the emulator waits for a free queue slot (the output then depends only on the
// scenario); paced, a full queue drops the ping (counted) rather than delay the emulator.
class InProcessOnboard {
 public:
  // Also told every contact (on the consumer's thread, or in finish()), e.g. `run --web`.
  using ContactObserver = std::function<void(const atr::Contact&)>;
  // Starts the consumer thread; feeds `file_header` (the emulator's XTF file header) first.
  InProcessOnboard(atr::Model model, const atr::OnboardOptions& options,
                   const std::optional<std::string>& contacts_path,
                   std::span<const std::uint8_t> file_header, std::size_t packet_bytes,
                   bool lossless, ContactObserver observer = {});
  ~InProcessOnboard();
  InProcessOnboard(const InProcessOnboard&) = delete;
  InProcessOnboard& operator=(const InProcessOnboard&) = delete;

  // The hook: copies the packet into the queue.
  void on_ping(std::span<const std::uint8_t> packet) { queue_.push(packet, lossless_); }
  // Drains the queue, ends the thread, decides the objects still open; returns the statistics.
  atr::OnboardStats finish();
  const atr::PacketQueue& queue() const { return queue_; }
  std::string contacts_destination() const { return contacts_.describe(); }

 private:
  ContactWriter contacts_;
  ContactObserver observer_;
  atr::OnboardPipeline pipeline_;
  atr::PacketQueue queue_;
  bool lossless_;
  std::thread thread_;
  std::string error_;
};

// `run --classify`: the in-process consumer as one of the emulator's devices
// (emulator/device.h): every ping's packet copied into its queue. `onboard` must outlive the
// emulator.
class OnboardDevice final : public emulator::Device {
 public:
  explicit OnboardDevice(InProcessOnboard& onboard) : onboard_(onboard) {}
  void ping(const emulator::PingSlot&, std::span<const std::uint8_t> packet) override {
    onboard_.on_ping(packet);
  }
  bool on_wire() const override { return true; }
  std::vector<std::string> describe() const override { return {}; }  // said by run itself

 private:
  InProcessOnboard& onboard_;
};

}  // namespace sonarloop::tools
