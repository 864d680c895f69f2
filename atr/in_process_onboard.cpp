#include "atr/in_process_onboard.h"

#include <algorithm>
#include <stdexcept>

namespace sonarloop::atr {
namespace {

// Pings queued between the emulator and the in-process consumer: 4096 (4.5 KB each for the
// default sonar: 18 MB), about 4.5 minutes of pings at 15 per second.
constexpr std::size_t kInProcessQueueSlots = 4096;

}  // namespace

InProcessOnboard::InProcessOnboard(Model model, const OnboardOptions& options,
                                   const std::optional<std::string>& contacts_path,
                                   std::span<const std::uint8_t> file_header,
                                   std::size_t packet_bytes, bool lossless,
                                   ContactObserver observer)
    : contacts_(contacts_path, stderr),
      observer_(std::move(observer)),
      pipeline_(std::move(model), options,
                [this](const Contact& c) {
                  contacts_.write(c);
                  if (observer_) observer_(c);
                }),
      queue_(kInProcessQueueSlots, std::max(packet_bytes, file_header.size())),
      lossless_(lossless) {
  queue_.push(file_header, true);
  thread_ = std::thread([this] {
    try {
      while (queue_.pop([this](std::span<const std::uint8_t> p) { pipeline_.feed(p); }, -1)) {
      }
    } catch (const std::exception& e) {
      error_ = e.what();
      queue_.close();
    }
  });
}

InProcessOnboard::~InProcessOnboard() {
  queue_.close();
  if (thread_.joinable()) thread_.join();
}

OnboardStats InProcessOnboard::finish() {
  if (!finished_) {
    finished_ = true;
    queue_.close();  // pop() drains what is queued, then returns false
    if (thread_.joinable()) thread_.join();
    if (error_.empty()) pipeline_.finish();
  }
  if (!error_.empty()) throw std::runtime_error("onboard consumer: " + error_);
  return pipeline_.stats();
}

}  // namespace sonarloop::atr
