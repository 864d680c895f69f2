#include "web/web_hub.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "atr/stream_receiver.h"
#include "atr/waterfall.h"
#include "drivers/json/json_writer.h"
#include "web/web_events.h"

namespace sonarloop::web {
namespace {

// The worker waits this long for a datagram before it looks at the stats and hands over pings
// held for reordering: stats reach the browsers within 100 ms of a push.
constexpr int kWorkerPollMs = 100;
// Contacts kept for the catch-up of a new client (a long mission reports a few hundred).
constexpr std::size_t kMaxContactsKept = 1000;
// Track points kept for the catch-up (20 km of track at one point per metre); the oldest half
// is thinned out to every other point when full.
constexpr std::size_t kMaxTrackPoints = 20000;

void field_count(json::Writer& w, std::string_view key, std::int64_t v) {
  if (v < 0) {
    w.key(key).null();
  } else {
    w.field(key, v);
  }
}

}  // namespace

// ---- WebClient ----

void WebClient::push(const Event& e) {
  {
    std::lock_guard lock(mutex_);
    if (closed_) return;
    if (queue_.size() >= capacity_) {
      queue_.pop_front();
      ++dropped_;
    }
    queue_.push_back(e);
  }
  cv_.notify_one();
  if (wake_) wake_();
}

WebClient::Next WebClient::next(Event& out, std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  cv_.wait_for(lock, timeout, [this] { return closed_ || !queue_.empty(); });
  if (queue_.empty()) return closed_ ? Next::kClosed : Next::kTimeout;
  out = std::move(queue_.front());
  queue_.pop_front();
  ++delivered_;
  return Next::kEvent;
}

void WebClient::close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  cv_.notify_all();
  if (wake_) wake_();
}

std::uint64_t WebClient::delivered() const {
  std::lock_guard lock(mutex_);
  return delivered_;
}

std::uint64_t WebClient::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

// ---- the worker's decoder: datagrams -> ordered pings -> levels -> line events ----

struct WebHub::Decoder {
  Decoder(WebHub& owner, int pixels, const std::optional<GeoPoint>& frame_origin)
      : hub(owner),
        receiver(atr::ReceiverOptions{},
                 [this](const xtf::XtfFileHeader& h, const xtf::XtfPing& p) { on_ping(h, p); }),
        waterfall(2, frame_origin),
        port(static_cast<std::size_t>(pixels)),
        stbd(static_cast<std::size_t>(pixels)) {}

  void on_ping(const xtf::XtfFileHeader& header, const xtf::XtfPing& ping) {
    if (waterfall.add(header, ping) == atr::AddResult::kUnusable) return;
    const std::uint64_t seq = waterfall.newest_seq();
    const atr::PingRecord& r = waterfall.record(seq);
    reduce_line(waterfall.levels(seq, 0), port);
    reduce_line(waterfall.levels(seq, 1), stbd);
    // positions in the stream's metres, as contact reports give theirs (atr/contact.h)
    const Vec2 ne = waterfall.stream_metres(r.north_m, r.east_m);
    json::Writer w;
    w.begin_object();
    w.field("seq", seq).field("ping", static_cast<std::uint64_t>(r.ping_number));
    if (r.time_utc_ns) {
      w.field("t_utc_ns", *r.time_utc_ns);
    } else {
      w.key("t_utc_ns").null();
    }
    w.field("north_m", ne.x(), 9).field("east_m", ne.y(), 9);
    w.field("heading_deg", r.heading_deg, 5);
    w.field("r0_m", waterfall.range_start_m(), 6);
    w.field("r1_m", waterfall.range_start_m() + waterfall.bins() * waterfall.bin_size_m(), 6);
    w.field("db0", static_cast<double>(kDisplayMinDb), 4);
    w.field("db1", static_cast<double>(kDisplayMaxDb), 4);
    w.field("port", base64(port)).field("stbd", base64(stbd));
    w.end_object();
    hub.publish_line(w.str(), ne.x(), ne.y());
  }

  WebHub& hub;
  atr::StreamReceiver receiver;
  atr::Waterfall waterfall;
  std::vector<std::uint8_t> port, stbd;
};

// ---- WebHub ----

WebHub::WebHub(const WebHubOptions& options)
    : options_(options), datagrams_(options.datagram_slots, options.slot_bytes) {
  if (options.client_queue_events == 0 || options.line_pixels <= 0 || options.max_clients <= 0) {
    throw std::invalid_argument("web hub: queue sizes, pixels and clients must be positive");
  }
  decoder_ = std::make_unique<Decoder>(*this, options.line_pixels, options.frame_origin);
  worker_ = std::thread([this] { run_worker(); });
}

WebHub::~WebHub() {
  close();
}

void WebHub::close() {
  datagrams_.close();
  if (worker_.joinable()) worker_.join();
  std::vector<std::shared_ptr<WebClient>> clients;
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
    clients = clients_;
  }
  for (auto& c : clients)
    c->close();
}

bool WebHub::push_datagram(std::span<const std::uint8_t> datagram, bool wait_when_full) {
  return datagrams_.push(datagram, wait_when_full);
}

void WebHub::push_stats(const WebStats& stats) {
  std::lock_guard lock(mutex_);
  stats_ = stats;
  have_stats_ = true;
  stats_pending_ = true;
}

void WebHub::push_contact(const atr::Contact& contact) {
  const Event e =
      std::make_shared<const std::string>(sse_event("contact", atr::contact_json(contact)));
  std::lock_guard lock(mutex_);
  if (contacts_.size() >= kMaxContactsKept) contacts_.erase(contacts_.begin());
  contacts_.push_back(e);
  deliver(e);
}

void WebHub::broadcast(std::string_view name, std::string_view data) {
  const Event e = std::make_shared<const std::string>(sse_event(name, data));
  std::lock_guard lock(mutex_);
  deliver(e);
}

void WebHub::deliver(const Event& e) {
  ++counters_.events;
  for (auto& c : clients_)
    c->push(e);
}

void WebHub::run_worker() {
  for (;;) {
    bool got = false;
    try {
      got = datagrams_.pop([this](std::span<const std::uint8_t> d) { decoder_->receiver.feed(d); },
                           kWorkerPollMs);
      // a quiet moment: hand over the pings held for reordering
      if (!got) decoder_->receiver.flush();
    } catch (const std::exception&) {
      // a ping the waterfall cannot take is not shown; the stream goes on
    }
    publish_pending_stats();
    if (!got && datagrams_.closed()) break;
  }
}

void WebHub::publish_line(const std::string& json, double north_m, double east_m) {
  const Event e = std::make_shared<const std::string>(sse_event("line", json));
  std::lock_guard lock(mutex_);
  ++counters_.lines;
  const std::size_t n = track_ne_.size();
  if (n == 0 || std::hypot(north_m - track_ne_[n - 2], east_m - track_ne_[n - 1]) >= kTrackStepM) {
    if (n / 2 >= kMaxTrackPoints) {
      // thin the older half to every other point
      std::vector<double> thinned;
      thinned.reserve(n);
      for (std::size_t i = 0; i < n / 2; i += 4) {
        thinned.push_back(track_ne_[i]);
        thinned.push_back(track_ne_[i + 1]);
      }
      thinned.insert(thinned.end(), track_ne_.begin() + static_cast<std::ptrdiff_t>(n / 2),
                     track_ne_.end());
      track_ne_.swap(thinned);
    }
    track_ne_.push_back(north_m);
    track_ne_.push_back(east_m);
  }
  deliver(e);
}

void WebHub::publish_pending_stats() {
  std::lock_guard lock(mutex_);
  if (!stats_pending_) return;
  stats_pending_ = false;
  ++stats_updates_;
  deliver(std::make_shared<const std::string>(sse_event("stats", stats_json_locked())));
}

std::shared_ptr<WebClient> WebHub::subscribe(std::function<void()> wake) {
  auto client = std::make_shared<WebClient>(options_.client_queue_events, std::move(wake));
  std::lock_guard lock(mutex_);
  if (closed_ || clients_.size() >= static_cast<std::size_t>(options_.max_clients)) {
    ++counters_.clients_refused;
    return nullptr;
  }
  // the catch-up: the track so far, the contacts kept, the latest stats
  if (!track_ne_.empty()) {
    json::Writer w;
    w.begin_object().key("north_m").begin_array();
    for (std::size_t i = 0; i < track_ne_.size(); i += 2)
      w.value(track_ne_[i], 9);
    w.end_array().key("east_m").begin_array();
    for (std::size_t i = 1; i < track_ne_.size(); i += 2)
      w.value(track_ne_[i], 9);
    w.end_array().end_object();
    client->push(std::make_shared<const std::string>(sse_event("track", w.str())));
  }
  for (const Event& e : contacts_)
    client->push(e);
  if (have_stats_) {
    client->push(std::make_shared<const std::string>(sse_event("stats", stats_json_locked())));
  }
  clients_.push_back(client);
  ++counters_.clients_total;
  return client;
}

void WebHub::unsubscribe(const std::shared_ptr<WebClient>& client) {
  std::lock_guard lock(mutex_);
  const auto it = std::find(clients_.begin(), clients_.end(), client);
  if (it == clients_.end()) return;
  gone_sent_ += client->delivered();
  gone_dropped_ += client->dropped();
  clients_.erase(it);
}

WebHubCounters WebHub::counters() const {
  std::lock_guard lock(mutex_);
  return counters_locked();
}

WebHubCounters WebHub::counters_locked() const {
  WebHubCounters c = counters_;
  c.clients = clients_.size();
  c.events_sent = gone_sent_;
  c.events_dropped = gone_dropped_;
  for (const auto& client : clients_) {
    c.events_sent += client->delivered();
    c.events_dropped += client->dropped();
  }
  c.pings_not_shown = datagrams_.dropped_full() + datagrams_.dropped_oversize();
  return c;
}

std::string WebHub::stats_json() const {
  std::lock_guard lock(mutex_);
  return stats_json_locked();
}

std::string WebHub::stats_json_locked() const {
  const WebStats& s = stats_;
  json::Writer w;
  w.begin_object();
  w.field("source", s.source).field("updates", stats_updates_);
  w.field("sim_time_s", s.sim_time_s, 6);
  field_count(w, "pings", have_stats_ ? s.pings : -1);
  field_count(w, "deadline_misses", s.deadline_misses);
  w.field("lateness_p99_ms", s.lateness_p99_ms, 4);
  field_count(w, "datagrams_lost", s.datagrams_lost);
  w.field("cpu_percent", s.cpu_percent, 4);
  field_count(w, "contacts", s.contacts);
  const WebHubCounters c = counters_locked();
  w.key("web").begin_object();
  w.field("clients", c.clients).field("clients_total", c.clients_total);
  w.field("clients_refused", c.clients_refused);
  w.field("lines", c.lines).field("events", c.events);
  w.field("events_sent", c.events_sent).field("events_dropped", c.events_dropped);
  w.field("pings_not_shown", c.pings_not_shown);
  w.end_object();
  w.end_object();
  return w.str();
}

}  // namespace sonarloop::web
