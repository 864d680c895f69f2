#include "tools/onboard_output.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "atr/model_file.h"
#include "drivers/json/json_writer.h"
#include "mission/default_model.h"
#include "tools/args.h"
#include "tools/chip_options.h"
#include "tools/cli_helpers.h"

namespace sonarloop::tools {
namespace {

// Pings queued between the emulator and the in-process consumer: 4096 (4.5 KB each for the
// default sonar: 18 MB), about 4.5 minutes of pings at 15 per second.
constexpr std::size_t kInProcessQueueSlots = 4096;
// ContactWriter's destination prefix for UDP.
constexpr const char* kUdpPrefix = "udp:";

}  // namespace

ContactWriter::ContactWriter(const std::optional<std::string>& path, std::FILE* fallback) {
  if (path && path->rfind(kUdpPrefix, 0) == 0) {
    udp_ = std::make_unique<net::UdpSender>(
        net::parse_host_port(std::string_view(*path).substr(std::strlen(kUdpPrefix))));
    name_ = *path;
  } else if (path) {
    f_ = std::fopen(path->c_str(), "wb");
    if (!f_) {
      throw std::runtime_error("cannot create contacts file '" + *path +
                               "': " + std::strerror(errno));
    }
    owned_ = true;
    name_ = *path;
  } else {
    f_ = fallback;
    name_ = fallback == stdout ? "stdout" : "stderr";
  }
}

ContactWriter::~ContactWriter() {
  if (owned_ && f_) std::fclose(f_);
}

void ContactWriter::write(const atr::Contact& c) {
  const std::string line = atr::contact_json(c);
  if (udp_) {
    // a missing receiver is counted by the sender, never an error
    udp_->send(std::span(reinterpret_cast<const std::uint8_t*>(line.data()), line.size()));
    return;
  }
  if (std::fprintf(f_, "%s\n", line.c_str()) < 0 || std::fflush(f_) != 0) {
    throw std::runtime_error("cannot write to " + name_ + ": " + std::strerror(errno));
  }
}

std::string ContactWriter::describe() const {
  return name_;
}

std::optional<atr::Model> load_model_if(const std::optional<std::string>& path) {
  if (!path) return std::nullopt;
  // "default": the default model, built and cached the first time (mission/default_model.h)
  if (mission::is_default_model(*path))
    return load_model_with_metadata(
        mission::ensure_default_model(false, [] { return stop_requested(); }));
  return load_model_with_metadata(*path);  // older model files: heights of simulated types
}

void set_gate_threshold(std::optional<atr::Model>& model, std::optional<double> threshold) {
  if (!threshold) return;
  if (!model || !model->classification_gate) {
    throw UsageError(
        "--gate-threshold: the model has no classification gate (a model of "
        "`train --surveys`, or the default model, has one)");
  }
  model->classification_gate->threshold = *threshold;
}

void print_onboard_stats(const char* who, const atr::OnboardStats& s,
                         const atr::PacketQueue* queue) {
  const atr::ReceiverStats& r = s.receiver;
  std::fprintf(stderr,
               "%s: %llu datagrams (%llu file headers), %llu pings; lost %llu, late %llu, "
               "duplicated %llu, reordered %llu, malformed %llu, before a header %llu\n",
               who, ull(r.datagrams), ull(r.file_headers), ull(r.pings), ull(r.lost), ull(r.late),
               ull(r.duplicates), ull(r.reordered), ull(r.malformed), ull(r.before_header));
  if (r.other_packets || r.restarts || r.header_changes || r.unconfirmed || s.waterfall_unusable) {
    std::fprintf(stderr,
                 "  also: %llu other XTF packets, %llu stream restarts, %llu header changes, "
                 "%llu unconfirmed ping-number jumps (junk), %llu unusable pings\n",
                 ull(r.other_packets), ull(r.restarts), ull(r.header_changes), ull(r.unconfirmed),
                 ull(s.waterfall_unusable));
  }
  if (queue) {
    std::fprintf(stderr,
                 "  queue: %llu datagrams, %llu dropped (queue full), %llu oversize; high water "
                 "%zu of %zu\n",
                 ull(queue->pushed()), ull(queue->dropped_full()), ull(queue->dropped_oversize()),
                 queue->high_water(), queue->capacity());
  }
  const atr::DetectorStats& d = s.detector;
  std::fprintf(stderr,
               "  detector: %llu ping detections, %llu objects, %llu rejected by the gates, %llu "
               "suppressed, %llu reported\n",
               ull(d.ping_detections), ull(d.objects), ull(d.rejected), ull(d.suppressed),
               ull(d.reported));
  std::fprintf(stderr, "  contacts: %llu (%llu classified, %llu not)", ull(s.contacts),
               ull(s.classified), ull(s.unclassified));
  if (s.windows) {
    std::fprintf(stderr,
                 "; %llu chips classified in %.3f s: %.3f ms per chip, %.1f ms per contact "
                 "(max %.1f ms)",
                 ull(s.windows), s.classify_total_s, s.seconds_per_chip() * 1e3,
                 s.seconds_per_contact() * 1e3, s.classify_max_s * 1e3);
  }
  std::fprintf(stderr, "\n");
}

std::string onboard_stats_json(const atr::OnboardStats& s, const atr::PacketQueue* queue) {
  const atr::ReceiverStats& r = s.receiver;
  json::Writer w;
  w.begin_object();
  w.key("receiver").begin_object();
  w.field("datagrams", r.datagrams).field("bytes", r.bytes).field("file_headers", r.file_headers);
  w.field("header_changes", r.header_changes).field("pings", r.pings).field("lost", r.lost);
  w.field("late", r.late).field("duplicates", r.duplicates).field("reordered", r.reordered);
  w.field("malformed", r.malformed).field("before_header", r.before_header);
  w.field("other_packets", r.other_packets).field("restarts", r.restarts);
  w.field("unconfirmed", r.unconfirmed);
  w.end_object();
  if (queue) {
    w.key("queue").begin_object();
    w.field("pushed", queue->pushed()).field("dropped_full", queue->dropped_full());
    w.field("dropped_oversize", queue->dropped_oversize());
    w.field("high_water", static_cast<std::uint64_t>(queue->high_water()));
    w.end_object();
  }
  w.field("unusable_pings", s.waterfall_unusable).field("waterfall_resets", s.waterfall_resets);
  const atr::DetectorStats& d = s.detector;
  w.key("detector").begin_object();
  w.field("pings", d.pings).field("pings_no_altitude", d.pings_no_altitude);
  w.field("ping_detections", d.ping_detections).field("objects", d.objects);
  w.field("rejected", d.rejected).field("suppressed", d.suppressed);
  w.field("reported", d.reported).field("overflows", d.overflows);
  w.end_object();
  w.field("contacts", s.contacts).field("classified", s.classified);
  w.field("unclassified", s.unclassified).field("chips", s.windows);
  w.field("classify_total_s", s.classify_total_s, 6);
  w.field("ms_per_chip", s.seconds_per_chip() * 1e3, 6);
  w.field("ms_per_contact", s.seconds_per_contact() * 1e3, 6);
  w.field("ms_max_contact", s.classify_max_s * 1e3, 6);
  w.end_object();
  return w.str();
}

InProcessOnboard::InProcessOnboard(atr::Model model, const atr::OnboardOptions& options,
                                   const std::optional<std::string>& contacts_path,
                                   std::span<const std::uint8_t> file_header,
                                   std::size_t packet_bytes, bool lossless,
                                   ContactObserver observer)
    : contacts_(contacts_path, stderr),
      observer_(std::move(observer)),
      pipeline_(std::move(model), options,
                [this](const atr::Contact& c) {
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

atr::OnboardStats InProcessOnboard::finish() {
  queue_.close();  // pop() drains what is queued, then returns false
  if (thread_.joinable()) thread_.join();
  if (!error_.empty()) throw std::runtime_error("onboard consumer: " + error_);
  pipeline_.finish();
  return pipeline_.stats();
}

}  // namespace sonarloop::tools
