#pragma once
// The render-ahead queue: worker threads produce pings k, k+1, ... ahead of the publisher into a
// fixed ring of preallocated slots, so that one slow ping never stalls publishing.
//
// Slots. Ping k lives in slot k mod S. A worker claims the next ping index when its slot is free
// (the publisher has released ping k - S), produces it into the slot (PingProducer: pose, view,
// render, XTF encoding) and marks it ready; the publisher takes ready pings strictly in order
// and releases each one, sent or dropped. Nothing is allocated per ping: every buffer of a slot
// (lines, XTF ping, encoded packet) keeps its capacity from ping to ping.
//
// Work ahead. After a worker has handed ping k to the publisher it calls the producer's
// work_ahead(k): what later pings will read (the scene's tiles) is made there, off the path of
// ping k, so a ping due now never waits for scene work meant for a ping further on.
//
// Falling behind. In a paced run the publisher gives ping k up at a wall time (the close of its
// send window, set_deadlines). A worker that claims a ping then skips every ping it could not
// finish before that time at the recent render time (a running mean of produce_ns), and renders
// the first one it can still deliver: when rendering is slower than the ping rate the run sends
// every n-th ping instead of rendering each one just too late and sending none.
//
// Dropped pings. The publisher may give up on ping k (its send window passed, pacer.h
// ping_window) while a worker is still producing it: release(k) then marks the slot and raises
// its abandon flag (PingSlot::abandon), the renderer stops at its next look at the flag, and the
// worker frees the slot: a ping that cannot make its window costs at most the window plus one
// beam plane's (or ray batch's) work, never a worker for as long as it would take, and stop()
// raises every flag. A ping the publisher gave up on before any worker claimed it is skipped by
// the workers (never produced).
//
// Errors: an exception thrown by the producer stops the queue; the publisher sees it through
// failed() / error() and stops the run.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "common/geodesy.h"
#include "drivers/xtf/xtf_types.h"
#include "emulator/pacer.h"
#include "sim/frames.h"
#include "sim/render/ping_renderer.h"

namespace sonarloop::emulator {

// What a ping was rendered from (for truth.csv and the statistics).
struct PingTruth {
  SimTime t = 0;                 // ping time (transmission), ns since the mission start
  std::int64_t time_utc_ns = 0;  // epoch + t
  Pose pose;                     // the pose the ping was rendered from (true pose, W frame)
  GeoPoint geo;                  // pose position as latitude/longitude
  double altitude_m = 0.0;       // renderer's nadir altitude (NaN: no seabed below)
  double speed_m_s = 0.0;        // true speed over ground
  bool external = false;         // pose from --pose-from (else the scenario's trajectory)
  // --pose-from: ns since the external pose was received, at the ping time (-1: never received)
  std::int64_t pose_age_ns = 0;
  // --pose-from: the pose was extrapolated past the last sample (emulator/pose_history.h)
  bool pose_extrapolated = false;
};

struct PingSlot {
  std::int64_t index = -1;  // ping number k
  bool emitted = true;      // false: no ping this period (stale external pose)
  render::PingLines lines;
  xtf::XtfPing xtf;
  std::vector<std::uint8_t> packet;  // sized once to the encoded size of the sonar's pings
  std::size_t packet_size = 0;       // bytes of `packet` holding this ping
  PingTruth truth;
  std::int64_t produce_ns = 0;  // worker time spent on this ping (render + encode)
  // Set by the queue while the ping is produced, when the publisher gives it up or the queue
  // stops: the producer passes it to the renderer (RenderOptions::abandon), which then returns
  // early. `abandoned`: the producer's report that the render was cut short.
  const std::atomic<bool>* abandon = nullptr;
  bool abandoned = false;
};

// Fills a slot for ping k. Called concurrently from the worker threads (worker = 0..threads-1,
// for per-thread scratch). Must not allocate once warmed up.
class PingProducer {
 public:
  virtual ~PingProducer() = default;
  virtual void produce(std::int64_t k, int worker, PingSlot& slot) = 0;
  // Called by the same worker after ping k is ready (or given up on): work for later pings.
  virtual void work_ahead(std::int64_t /*k*/, int /*worker*/) {}
  // Asks producers blocked in produce() (waiting for a view or for a ping time) to return soon.
  virtual void cancel() {}
};

class RenderQueue {
 public:
  // `packet_bytes`: capacity of each slot's packet buffer.
  RenderQueue(PingProducer& producer, int slots, int threads, std::size_t packet_bytes);
  ~RenderQueue();
  RenderQueue(const RenderQueue&) = delete;
  RenderQueue& operator=(const RenderQueue&) = delete;

  // Paced runs, before start(): ping k is given up at wall time give_up_ns(k) on `clock`.
  void set_deadlines(std::function<std::int64_t(std::int64_t)> give_up_ns, const Clock& clock);
  // Starts the workers on pings [first, end).
  void start(std::int64_t first, std::int64_t end = std::numeric_limits<std::int64_t>::max());
  // Stops and joins the workers (idempotent).
  void stop();

  // Publisher side (one thread): the slot of ping k if it is ready, else nullptr. The slot stays
  // valid and unchanged until release(k).
  const PingSlot* ready(std::int64_t k) const;
  // The publisher is done with ping k (sent or dropped); pings below k + 1 are never produced
  // again. Must be called in increasing k.
  void release(std::int64_t k);
  // Notified whenever a ping becomes ready (and when the queue fails).
  Wakeup& wakeup() { return wakeup_; }

  bool failed() const { return failed_.load(); }
  std::string error() const;

  int slots() const { return static_cast<int>(slots_.size()); }
  int threads() const { return threads_; }
  // Pings rendered (slots produced with emitted set; a period without a ping is not counted) and
  // their total and largest production times.
  std::uint64_t produced() const { return produced_.load(); }
  // Pings whose render was cut short (given up, or the queue stopped while it rendered).
  std::uint64_t abandoned() const { return abandoned_.load(); }
  std::int64_t produce_total_ns() const { return produce_total_ns_.load(); }
  std::int64_t produce_max_ns() const { return produce_max_ns_.load(); }

 private:
  enum class State : std::uint8_t { kFree, kProducing, kReady };
  void work(int worker);
  // the first ping from next_claim_ on that can be finished before it is given up (mu_ held)
  std::int64_t first_deliverable() const;
  // records the first error and stops the queue; unlocks `lock`
  void fail(std::unique_lock<std::mutex>& lock, const std::string& what);

  PingProducer& producer_;
  int threads_;
  std::vector<PingSlot> slots_;
  std::vector<State> state_;
  std::vector<bool> released_;  // the publisher gave up on the ping being produced
  // the ping each slot was last claimed for (mu_): the slot's own index is the producer's to
  // write while it produces, so the publisher side never reads it then
  std::vector<std::int64_t> claimed_;
  std::unique_ptr<std::atomic<bool>[]> abandon_;  // per slot (PingSlot::abandon)

  mutable std::mutex mu_;
  std::condition_variable cv_;  // workers: a slot was freed, the publisher moved, stop
  std::int64_t next_claim_ = 0;
  std::int64_t end_ = 0;
  std::int64_t consumer_next_ = 0;  // the publisher has released every ping below this
  std::function<std::int64_t(std::int64_t)> give_up_ns_;  // paced runs (set_deadlines)
  const Clock* clock_ = nullptr;
  std::int64_t render_mean_ns_ = 0;  // running mean of produce_ns (0: none yet)
  bool stopping_ = false;
  std::string error_;
  std::atomic<bool> failed_{false};
  Wakeup wakeup_;

  std::atomic<std::uint64_t> produced_{0};
  std::atomic<std::uint64_t> abandoned_{0};
  std::atomic<std::int64_t> produce_total_ns_{0};
  std::atomic<std::int64_t> produce_max_ns_{0};
  std::vector<std::thread> workers_;
};

}  // namespace sonarloop::emulator
