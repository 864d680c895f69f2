#include "emulator/pose_source.h"

#include <array>
#include <chrono>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "drivers/can/socketcan.h"
#include "drivers/can/socketcand_client.h"
#include "emulator/stderr_warning.h"

// The sources (pose_source.h): the CAN and UDP receivers on their threads, and the spec parser;
// the merging they share is pose_merger.cpp.
namespace sonarloop::emulator {
namespace {

// Receive buffer for UDP datagrams: larger than a pose message, so that a longer datagram is seen
// (and counted) as the wrong size instead of being truncated to a plausible one.
constexpr std::size_t kUdpBufferBytes = 2048;

std::string counters(const PoseSourceStats& s) {
  std::string text = std::to_string(s.updates) + " updates, " + std::to_string(s.malformed) +
                     " malformed, " + std::to_string(s.ignored) + " ignored";
  if (s.rejected) text += ", " + std::to_string(s.rejected) + " rejected as implausible";
  if (s.reanchors) text += ", " + std::to_string(s.reanchors) + " re-anchored";
  if (s.lost) text += ", " + std::to_string(s.lost) + " lost";
  if (s.sequence_restarts) text += ", " + std::to_string(s.sequence_restarts) + " sender restarts";
  if (s.out_of_order) text += ", " + std::to_string(s.out_of_order) + " out of order";
  if (s.receive_errors) text += ", " + std::to_string(s.receive_errors) + " receive errors";
  return text;
}

}  // namespace

// ---- CanPoseSource ----

CanPoseSource::CanPoseSource(std::string name, Connect connect, const LocalTangentPlane& ltp,
                             std::function<std::int64_t()> now_ns, PoseSourceOptions options)
    : name_(std::move(name)),
      connect_(std::move(connect)),
      options_(std::move(options)),
      merger_(ltp, std::move(now_ns), options_.limits,
              [this](const std::string& w) { options_.on_warning(name_ + ": " + w); }) {
  if (!options_.on_warning) options_.on_warning = warn_on_stderr;
  transport_ = connect_();
  if (!transport_ || !transport_->can_receive())
    throw std::invalid_argument(name_ + ": the transport cannot receive frames");
  connected_ = true;
  thread_ = std::thread([this] { run(); });
}

CanPoseSource::~CanPoseSource() {
  {
    std::lock_guard lock(stop_mu_);
    stopping_ = true;
  }
  stop_cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

bool CanPoseSource::wait_stop(int ms) {
  std::unique_lock lock(stop_mu_);
  return stop_cv_.wait_for(lock, std::chrono::milliseconds(ms), [this] { return stopping_; });
}

void CanPoseSource::run() {
  bool reported_retry_failure = false;
  for (;;) {
    {
      std::lock_guard lock(stop_mu_);
      if (stopping_) return;
    }
    if (!transport_) {
      // the connection was lost: try again every reconnect_interval_ms until stopped
      if (wait_stop(options_.reconnect_interval_ms)) return;
      try {
        transport_ = connect_();
        connected_ = true;
        reported_retry_failure = false;
        merger_.count_reconnect();
        options_.on_warning(name_ + ": reconnected");
      } catch (const std::exception& e) {
        if (!reported_retry_failure) {
          options_.on_warning(name_ + ": reconnecting failed (retrying every " +
                              std::to_string(options_.reconnect_interval_ms) + " ms): " + e.what());
          reported_retry_failure = true;
        }
      }
      continue;
    }
    try {
      const std::optional<can::CanFrame> frame = transport_->receive(options_.receive_timeout_ms);
      if (frame) merger_.merge_n2k(*frame);
    } catch (const std::exception& e) {
      merger_.count_receive_error(e.what());
      options_.on_warning(name_ +
                          ": receive failed, pose updates stop until reconnected: " + e.what());
      transport_.reset();
      connected_ = false;
    }
  }
}

std::string CanPoseSource::describe() const {
  return name_ + " (" + counters(merger_.stats()) + (connected_ ? ")" : "; disconnected)");
}

// ---- UdpPoseSource ----

UdpPoseSource::UdpPoseSource(const net::HostPort& local, const LocalTangentPlane& ltp,
                             std::function<std::int64_t()> now_ns, PoseSourceOptions options,
                             UdpPoseFormat format)
    : options_(std::move(options)),
      format_(format),
      merger_(ltp, std::move(now_ns), options_.limits,
              [this](const std::string& w) {
                options_.on_warning(std::string(format_ == UdpPoseFormat::kImc ? "imc" : "udp") +
                                    " pose on " + net::to_string(receiver_.bound_address()) + ": " +
                                    w);
              }),
      receiver_(local) {
  if (!options_.on_warning) options_.on_warning = warn_on_stderr;
  thread_ = std::thread([this] { run(); });
}

UdpPoseSource::~UdpPoseSource() {
  stopping_ = true;
  if (thread_.joinable()) thread_.join();
}

void UdpPoseSource::run() {
  std::array<std::uint8_t, kUdpBufferBytes> buffer{};
  while (!stopping_) {
    try {
      const auto got = receiver_.receive(buffer, options_.receive_timeout_ms);
      if (!got) continue;
      if (format_ == UdpPoseFormat::kImc) {
        // an IMC packet larger than the buffer is no EstimatedState (110 bytes): another
        // message of the sender's (a SonarData), ignored
        if (got->truncated)
          merger_.count_ignored();
        else
          merger_.merge_imc_datagram(std::span<const std::uint8_t>(buffer.data(), got->size));
        continue;
      }
      if (got->truncated) {
        merger_.count_malformed("datagram of " + std::to_string(got->datagram_size) +
                                " bytes is not a pose message (" +
                                std::to_string(kPoseMessageBytes) + " bytes)");
        continue;
      }
      merger_.merge_pose_datagram(std::span<const std::uint8_t>(buffer.data(), got->size));
    } catch (const std::exception& e) {
      merger_.count_receive_error(e.what());
      options_.on_warning(describe() + ": " + e.what());
      // do not spin on a persistent socket error
      std::this_thread::sleep_for(std::chrono::milliseconds(options_.receive_timeout_ms));
    }
  }
}

std::string UdpPoseSource::describe() const {
  return std::string(format_ == UdpPoseFormat::kImc ? "imc pose (EstimatedState)" : "udp pose") +
         " on " + net::to_string(receiver_.bound_address()) + " (" + counters(merger_.stats()) +
         ")";
}

// ---- open_pose_source ----

std::unique_ptr<PoseSource> open_pose_source(const std::string& spec, const LocalTangentPlane& ltp,
                                             std::function<std::int64_t()> now_ns,
                                             PoseSourceOptions options) {
  constexpr std::string_view kCan = "can:";
  constexpr std::string_view kSocketcand = "socketcand:";
  constexpr std::string_view kUdp = "udp:";
  constexpr std::string_view kImcUdp = "imc:udp:";
  const std::string what = "--pose-from " + spec;
  try {
    const bool imc = spec.starts_with(kImcUdp);
    if (imc || spec.starts_with(kUdp)) {
      net::HostPort hp;
      try {
        hp = net::parse_host_port(spec.substr(imc ? kImcUdp.size() : kUdp.size()));
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(what + ": " + e.what());
      }
      return std::make_unique<UdpPoseSource>(
          hp, ltp, std::move(now_ns), options,
          imc ? UdpPoseFormat::kImc : UdpPoseFormat::kPoseMessage);
    }
    if (spec.starts_with(kCan)) {
      const std::string iface = spec.substr(kCan.size());
      if (iface.empty())
        throw std::invalid_argument(what + ": missing interface name (can:IFACE, e.g. can:vcan0)");
      return std::make_unique<CanPoseSource>(
          "socketcan pose from " + iface,
          [iface] { return std::make_unique<can::SocketCanTransport>(iface); }, ltp,
          std::move(now_ns), options);
    }
    if (spec.starts_with(kSocketcand)) {
      // HOST:PORT or HOST:PORT:CHANNEL (an IPv6 host is bracketed, so the last ':' splits)
      const std::string rest = spec.substr(kSocketcand.size());
      net::HostPort hp;
      can::SocketcandClientOptions client;
      try {
        hp = net::parse_host_port(rest);
      } catch (const std::invalid_argument&) {
        const std::size_t colon = rest.rfind(':');
        if (colon == std::string::npos || colon + 1 == rest.size())
          throw std::invalid_argument(
              what + ": expected socketcand:HOST:PORT[:CHANNEL], e.g. socketcand:127.0.0.1:29536");
        client.channel = rest.substr(colon + 1);
        try {
          hp = net::parse_host_port(rest.substr(0, colon));
        } catch (const std::invalid_argument& e) {
          throw std::invalid_argument(what + ": " + e.what());
        }
      }
      const std::string name =
          "socketcand pose from " + net::to_string(hp) + " (" + client.channel + ")";
      return std::make_unique<CanPoseSource>(
          name, [hp, client] { return std::make_unique<can::SocketcandClient>(hp, client); }, ltp,
          std::move(now_ns), options);
    }
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error(what + ": " + e.what());
  }
  throw std::invalid_argument(what +
                              ": not a pose source: use can:IFACE, "
                              "socketcand:HOST:PORT[:CHANNEL], udp:HOST:PORT or "
                              "imc:udp:HOST:PORT");
}

}  // namespace sonarloop::emulator
