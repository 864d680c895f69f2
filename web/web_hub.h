#pragma once
// The live operator view's event hub (docs/web.md): what the run loop or the onboard consumer
// pushes, turned into Server-Sent Events for every browser that watches (web/web_server.h
// serves them).
//
// Producers, never blocked by a browser:
//   push_datagram(bytes)  the sonar stream as sent or received: the XTF file header and one XTF
//                         ping per datagram. Copied into a bounded queue (atr/packet_queue.h);
//                         when the hub's worker falls behind, the datagram is dropped and counted
//                         (pings_not_shown). A copy under a lock, no allocation: safe on the
//                         emulator's publisher thread.
//   push_stats(WebStats)  the run's counters, copied under a lock; the worker formats them.
//   push_contact(c)       a contact report (formatted on the caller's thread, the pipeline's).
// Worker thread: decodes the datagrams (atr/stream_receiver.h, atr/waterfall.h: levels in dB re
//   full scale, the ping's position in the stream's metres, as contact reports give theirs),
//   reduces each side to `line_pixels` pixels (web_events.h) and broadcasts a `line` event per
//   ping, at the sonar's line rate; stats go out as they come (the run pushes them every second).
// Clients (one per browser's /events connection): a bounded queue of `client_queue_events`
//   events; when full, the oldest is dropped and counted, so a slow or vanished browser loses
//   lines and nobody waits. A new client first gets the track so far, every contact kept and the
//   latest stats (the catch-up), then the live events.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "atr/contact.h"
#include "atr/packet_queue.h"
#include "common/geodesy.h"

namespace sonarloop::web {

// One Server-Sent Event, "event: NAME\ndata: JSON\n\n", shared by every client's queue.
using Event = std::shared_ptr<const std::string>;

// The live statistics a command shows (NaN or a negative count: not applicable, sent as null).
struct WebStats {
  const char* source = "run";  // "run" or "onboard"
  double sim_time_s = std::numeric_limits<double>::quiet_NaN();
  std::int64_t pings = 0;             // sent (run) or received in order (onboard)
  std::int64_t deadline_misses = -1;  // late + dropped pings (run)
  double lateness_p99_ms = std::numeric_limits<double>::quiet_NaN();  // send lateness (run)
  std::int64_t datagrams_lost = -1;  // refused by the kernel (run --udp), gaps (onboard)
  double cpu_percent = std::numeric_limits<double>::quiet_NaN();  // of one core
  std::int64_t contacts = -1;
};

// A browser's event stream: a bounded queue, oldest dropped when full.
class WebClient {
 public:
  enum class Next { kEvent, kTimeout, kClosed };
  // `wake` (optional) is called after each push and at close, outside the client's lock, from
  // the pushing thread: the server's event loop waits on it instead of on next().
  explicit WebClient(std::size_t capacity, std::function<void()> wake = {})
      : capacity_(capacity), wake_(std::move(wake)) {}

  // Queues an event; drops (and counts) the oldest when full. Never waits for the reader.
  void push(const Event& e);
  // Waits up to `timeout` (zero: not at all) for the next event; after close(), the events
  // still queued, then kClosed.
  Next next(Event& out, std::chrono::milliseconds timeout);
  // Refuses further events.
  void close();

  std::uint64_t delivered() const;
  std::uint64_t dropped() const;

 private:
  const std::size_t capacity_;
  const std::function<void()> wake_;
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<Event> queue_;
  bool closed_ = false;
  std::uint64_t delivered_ = 0;
  std::uint64_t dropped_ = 0;
};

struct WebHubOptions {
  std::size_t datagram_slots = 64;        // pings queued for the worker (4 s at 15 pings/s)
  std::size_t slot_bytes = 65536;         // largest datagram (an IPv4 UDP payload)
  std::size_t client_queue_events = 256;  // per browser: 17 s of lines at 15 pings/s
  int max_clients = 4;                    // more /events connections are refused (503)
  int line_pixels = 512;                  // per side
  // origin of north/east for latitude/longitude streams: that of the contact reports
  // (atr::OnboardOptions::frame_origin; nullopt: the stream's first ping)
  std::optional<GeoPoint> frame_origin;
};

struct WebHubCounters {
  std::uint64_t clients = 0;        // watching now
  std::uint64_t clients_total = 0;  // ever connected
  std::uint64_t clients_refused = 0;
  std::uint64_t events = 0;           // broadcast
  std::uint64_t events_sent = 0;      // handed to a browser's connection (all clients)
  std::uint64_t events_dropped = 0;   // dropped from a full client queue (all clients)
  std::uint64_t lines = 0;            // ping lines made
  std::uint64_t pings_not_shown = 0;  // datagrams dropped: the worker's queue was full
};

class WebHub {
 public:
  // Starts the worker thread. Throws std::invalid_argument for zero sizes.
  explicit WebHub(const WebHubOptions& options = {});
  ~WebHub();
  WebHub(const WebHub&) = delete;
  WebHub& operator=(const WebHub&) = delete;

  // Producers (see the header comment). push_datagram returns false when the datagram was
  // dropped (queue full, too large, or the hub closed); `wait_when_full` waits for the worker
  // instead (reading a file, where no deadline is at stake).
  bool push_datagram(std::span<const std::uint8_t> datagram, bool wait_when_full = false);
  void push_stats(const WebStats& stats);
  void push_contact(const atr::Contact& contact);

  // Sends an event to every client (and, for "track"/"contact", nothing is kept: see the
  // catch-up). `data` is one line of JSON.
  void broadcast(std::string_view name, std::string_view data);

  // A new client, with the catch-up queued; null when max_clients are watching. `wake`: see
  // WebClient.
  std::shared_ptr<WebClient> subscribe(std::function<void()> wake = {});
  void unsubscribe(const std::shared_ptr<WebClient>& client);

  // The latest statistics with the hub's counters, one JSON object (GET /stats.json).
  std::string stats_json() const;
  WebHubCounters counters() const;

  // Ends the worker (after the datagrams queued, so the browsers get every line and the last
  // statistics) and every client's stream after the events it has queued. Idempotent.
  void close();

 private:
  struct Decoder;
  void run_worker();
  void publish_line(const std::string& json, double north_m, double east_m);
  void publish_pending_stats();
  std::string stats_json_locked() const;
  WebHubCounters counters_locked() const;
  void deliver(const Event& e);  // hub mutex held

  WebHubOptions options_;
  atr::PacketQueue datagrams_;
  std::unique_ptr<Decoder> decoder_;  // worker thread only

  mutable std::mutex mutex_;
  std::vector<std::shared_ptr<WebClient>> clients_;
  std::vector<double> track_ne_;  // north, east pairs, one every kTrackStepM
  std::vector<Event> contacts_;   // the newest kMaxContactsKept
  WebStats stats_;
  bool have_stats_ = false;
  bool stats_pending_ = false;
  std::uint64_t stats_updates_ = 0;
  WebHubCounters counters_;
  std::uint64_t gone_sent_ = 0, gone_dropped_ = 0;  // of clients that left
  bool closed_ = false;

  std::thread worker_;
};

}  // namespace sonarloop::web
