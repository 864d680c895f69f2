// The render-ahead ring with a controllable producer: order, run-ahead depth, a slow ping that
// does not hold up the others, dropped pings, errors.
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include "emulator/render_queue.h"
#include "tests/emulator/simulated_clock.h"

using namespace sonarloop::emulator;
using sonarloop::testing::SimulatedClock;

namespace {

// A gate a producer blocks at until the test lets it go or the queue cancels.
class Gate {
 public:
  // blocks; `entered` is set (and waiters woken) on the way in
  void wait() {
    std::unique_lock<std::mutex> lock(mu_);
    entered_ = true;
    cv_.notify_all();
    cv_.wait(lock, [&] { return go_ || cancelled_; });
  }
  void cancel() { set(cancelled_); }
  bool cancelled() {
    std::lock_guard<std::mutex> lock(mu_);
    return cancelled_;
  }
  void let_go() { set(go_); }
  // true once a producer is waiting at the gate (gives up after 20 s)
  bool entered() {
    std::unique_lock<std::mutex> lock(mu_);
    return cv_.wait_for(lock, std::chrono::seconds(20), [&] { return entered_; });
  }

 private:
  void set(bool& flag) {
    std::lock_guard<std::mutex> lock(mu_);
    flag = true;
    cv_.notify_all();
  }
  std::mutex mu_;
  std::condition_variable cv_;
  bool entered_ = false;
  bool go_ = false;
  bool cancelled_ = false;
};

// Writes k into the first packet byte; ping `slow` blocks until released.
class FakeProducer final : public PingProducer {
 public:
  explicit FakeProducer(std::int64_t slow = -1, std::int64_t fail = -1)
      : slow_(slow), fail_(fail) {}
  void produce(std::int64_t k, int, PingSlot& slot) override {
    if (k == fail_) throw std::runtime_error("boom");
    if (k == slow_) gate_.wait();
    slot.packet[0] = static_cast<std::uint8_t>(k & 0xFF);
    slot.packet_size = 1;
    ++produced_;
    highest_ = std::max<std::int64_t>(highest_, k);
  }
  void cancel() override { gate_.cancel(); }
  void let_go() { gate_.let_go(); }
  bool wait_in_slow() { return gate_.entered(); }
  bool cancelled() { return gate_.cancelled(); }
  std::atomic<int> produced_{0};
  std::atomic<std::int64_t> highest_{-1};

 private:
  std::int64_t slow_;
  std::int64_t fail_;
  Gate gate_;
};

// work_ahead(k) of ping `blocked` waits until released; work_ahead of ping `fail` throws.
class AheadProducer final : public PingProducer {
 public:
  AheadProducer(std::int64_t blocked, std::int64_t fail) : blocked_(blocked), fail_(fail) {}
  void produce(std::int64_t k, int, PingSlot& slot) override {
    slot.packet[0] = static_cast<std::uint8_t>(k & 0xFF);
    slot.packet_size = 1;
  }
  void work_ahead(std::int64_t k, int) override {
    if (k == fail_) throw std::runtime_error("no tile");
    if (k == blocked_) gate_.wait();
  }
  void cancel() override { gate_.cancel(); }
  void let_go() { gate_.let_go(); }
  bool in_blocked() { return gate_.entered(); }

 private:
  std::int64_t blocked_;
  std::int64_t fail_;
  Gate gate_;
};

// Each ping takes `render_ns` of the simulated clock; records when each one was finished.
class SlowProducer final : public PingProducer {
 public:
  SlowProducer(SimulatedClock& clock, std::int64_t render_ns)
      : clock_(clock), render_ns_(render_ns) {}
  void produce(std::int64_t k, int, PingSlot& slot) override {
    clock_.advance(render_ns_);
    slot.produce_ns = render_ns_;
    slot.packet_size = 1;
    std::lock_guard<std::mutex> lock(mu_);
    finished_.emplace_back(k, clock_.now_ns());
  }
  std::vector<std::pair<std::int64_t, std::int64_t>> finished() {
    std::lock_guard<std::mutex> lock(mu_);
    return finished_;
  }

 private:
  SimulatedClock& clock_;
  std::int64_t render_ns_;
  std::mutex mu_;
  std::vector<std::pair<std::int64_t, std::int64_t>> finished_;
};

// Ping `endless` renders until its slot's abandon flag is raised (at most 20 s), as a renderer
// does between beam planes; the others at once. Ignores cancel(): only the flag ends it.
class EndlessProducer final : public PingProducer {
 public:
  explicit EndlessProducer(std::int64_t endless) : endless_(endless) {}
  void produce(std::int64_t k, int, PingSlot& slot) override {
    slot.abandoned = false;
    slot.packet_size = 1;
    if (k != endless_) return;
    entered_ = true;
    for (int i = 0; i < 20000 && !slot.abandon->load(); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    slot.abandoned = slot.abandon->load();
  }
  std::atomic<bool> entered_{false};

 private:
  std::int64_t endless_;
};

// Waits (on the queue's wake-up) until ping k is ready.
const PingSlot* wait_ready(RenderQueue& q, std::int64_t k) {
  for (int i = 0; i < 2000; ++i) {
    const auto gen = q.wakeup().generation();
    if (const PingSlot* s = q.ready(k)) return s;
    if (q.failed()) return nullptr;
    MonotonicClock clock;
    q.wakeup().wait_until(clock.now_ns() + 10'000'000, gen);
  }
  return nullptr;
}

}  // namespace

TEST_CASE("RenderQueue: pings come out in order, never more than the ring ahead") {
  FakeProducer p;
  RenderQueue q(p, 4, 3, 16);
  q.start(0, 100);
  for (std::int64_t k = 0; k < 100; ++k) {
    const PingSlot* s = wait_ready(q, k);
    REQUIRE(s);
    CHECK(s->index == k);
    CHECK(s->packet[0] == (k & 0xFF));
    // the workers never run more than 4 pings ahead of the publisher
    CHECK(p.highest_.load() < k + 4);
    q.release(k);
  }
  q.stop();
  CHECK(p.produced_.load() == 100);
  CHECK(q.produced() == 100);
}

TEST_CASE("RenderQueue: a slow ping does not stop the other workers filling the ring") {
  FakeProducer p(/*slow=*/2);
  RenderQueue q(p, 8, 2, 16);
  q.start(0, 50);
  for (std::int64_t k = 0; k < 2; ++k) {
    REQUIRE(wait_ready(q, k));
    q.release(k);
  }
  // ping 2 is stuck; the other worker renders 3..9 (the rest of the ring) meanwhile
  REQUIRE(wait_ready(q, 9));
  CHECK_FALSE(q.ready(2));
  // the publisher gives up on ping 2 (its window passed) and goes on with 3..9
  q.release(2);
  for (std::int64_t k = 3; k < 10; ++k) {
    REQUIRE(wait_ready(q, k));
    q.release(k);
  }
  // slot of ping 2 (= slot of 10) is free once the slow render finishes
  p.let_go();
  for (std::int64_t k = 10; k < 50; ++k) {
    const PingSlot* s = wait_ready(q, k);
    REQUIRE(s);
    CHECK(s->index == k);
    q.release(k);
  }
}

TEST_CASE("RenderQueue: pings the publisher gave up on before a worker took them are skipped") {
  FakeProducer p(/*slow=*/0);
  RenderQueue q(p, 4, 1, 16);  // one worker, stuck on ping 0
  q.start(0, 20);
  REQUIRE(p.wait_in_slow());  // the worker is inside ping 0
  // the publisher drops 0..5 without waiting (their windows passed)
  for (std::int64_t k = 0; k < 6; ++k)
    q.release(k);
  p.let_go();
  for (std::int64_t k = 6; k < 20; ++k) {
    REQUIRE(wait_ready(q, k));
    q.release(k);
  }
  q.stop();
  // ping 0 was rendered (it was under way), 1..5 never were
  CHECK(p.produced_.load() == 1 + 14);
}

TEST_CASE("RenderQueue: a ping given up while it renders is abandoned, not waited for") {
  // issue 29: a pose the renderer could not render in time held a worker for 2-46 s a ping
  EndlessProducer p(/*endless=*/2);
  RenderQueue q(p, 4, 1, 16);  // one worker: everything after ping 2 waits for it
  q.start(0, 10);
  for (std::int64_t k = 0; k < 2; ++k) {
    REQUIRE(wait_ready(q, k));
    q.release(k);
  }
  for (int i = 0; i < 2000 && !p.entered_.load(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  REQUIRE(p.entered_.load());
  q.release(2);  // its window closed: the flag is raised, the render stops, the worker goes on
  for (std::int64_t k = 3; k < 10; ++k) {
    REQUIRE(wait_ready(q, k));
    q.release(k);
  }
  q.stop();
  CHECK(q.abandoned() == 1);
  CHECK(q.produced() == 9);  // the abandoned ping is not counted as rendered
}

TEST_CASE("RenderQueue: stop() abandons the ping being rendered") {
  EndlessProducer p(/*endless=*/0);
  RenderQueue q(p, 2, 1, 16);
  q.start(0);
  for (int i = 0; i < 2000 && !p.entered_.load(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  REQUIRE(p.entered_.load());
  q.stop();  // returns only once the worker has: the flag ended the render
  CHECK(q.abandoned() == 1);
  CHECK_FALSE(q.failed());
}

TEST_CASE("RenderQueue: a producer error stops the queue and is reported") {
  FakeProducer p(-1, /*fail=*/3);
  RenderQueue q(p, 4, 2, 16);
  q.start(0, 100);
  for (std::int64_t k = 0; k < 3; ++k) {
    REQUIRE(wait_ready(q, k));
    q.release(k);
  }
  CHECK(wait_ready(q, 3) == nullptr);
  CHECK(q.failed());
  CHECK(q.error().find("ping 3: boom") != std::string::npos);
}

TEST_CASE("RenderQueue: stop() returns while a producer is blocked") {
  FakeProducer p(/*slow=*/0);
  RenderQueue q(p, 2, 2, 16);
  q.start(0);
  REQUIRE(p.wait_in_slow());  // a worker is blocked inside ping 0
  q.stop();                   // cancel() releases it; the workers are joined
  CHECK(p.cancelled());
  CHECK_FALSE(q.failed());
}

TEST_CASE("RenderQueue: work for later pings runs after the ping is handed over") {
  AheadProducer p(/*blocked=*/0, /*fail=*/-1);
  RenderQueue q(p, 4, 1, 16);  // one worker
  q.start(0, 10);
  // the only worker is held inside work_ahead(0): ping 0 is ready all the same
  REQUIRE(p.in_blocked());
  const PingSlot* s = wait_ready(q, 0);
  REQUIRE(s);
  CHECK(s->index == 0);
  q.release(0);
  CHECK_FALSE(q.ready(1));  // the worker is still busy ahead
  p.let_go();
  for (std::int64_t k = 1; k < 10; ++k) {
    REQUIRE(wait_ready(q, k));
    q.release(k);
  }
  q.stop();
  CHECK(q.produced() == 10);
}

TEST_CASE("RenderQueue: an error in the work ahead stops the queue and is reported") {
  AheadProducer p(-1, /*fail=*/2);
  RenderQueue q(p, 8, 1, 16);
  q.start(0, 100);
  for (std::int64_t k = 0; k < 3; ++k) {  // 0..2 are handed over before the failure
    REQUIRE(wait_ready(q, k));
    q.release(k);
  }
  CHECK(wait_ready(q, 3) == nullptr);
  CHECK(q.failed());
  CHECK(q.error().find("work ahead of ping 2: no tile") != std::string::npos);
}

TEST_CASE(
    "RenderQueue: when rendering is slower than the pings, workers render pings they can deliver") {
  // pings given up every 10 ms, each render takes 25 ms: one worker can deliver one in three
  SimulatedClock clock;
  SlowProducer p(clock, 25'000'000);
  RenderQueue q(p, 64, 1, 16);
  auto give_up = [](std::int64_t k) { return (k + 1) * 10'000'000; };
  q.set_deadlines(give_up, clock);
  q.start(0, 40);
  // the publisher is not needed here: the ring (64) holds every ping; wait for the worker to end
  for (int i = 0; i < 2000 && clock.now_ns() < 400'000'000; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  q.stop();
  const auto done = p.finished();
  REQUIRE(done.size() >= 10);
  // ping 0 (no render time known yet) is late; every later one is finished before it is given up,
  // and none is skipped that could have been delivered
  CHECK(done[0].first == 0);
  for (std::size_t i = 1; i < done.size(); ++i) {
    INFO("ping " << done[i].first << " finished at " << done[i].second);
    CHECK(done[i].second <= give_up(done[i].first));
    CHECK(done[i].second > give_up(done[i].first - 1));
  }
}

TEST_CASE("RenderQueue: periods without a ping (stale pose) are not counted as rendered") {
  // every third period has no ping (as a stale external pose gives), produced in no time
  class GapProducer final : public PingProducer {
   public:
    void produce(std::int64_t k, int, PingSlot& slot) override {
      slot.emitted = k % 3 != 0;
      slot.produce_ns = slot.emitted ? 1'000'000 : 0;
      slot.packet_size = slot.emitted ? 1 : 0;
    }
  } p;
  RenderQueue q(p, 4, 2, 16);
  q.start(0, 30);
  int emitted = 0;
  for (std::int64_t k = 0; k < 30; ++k) {
    const PingSlot* s = wait_ready(q, k);
    REQUIRE(s);
    CHECK(s->emitted == (k % 3 != 0));
    emitted += s->emitted ? 1 : 0;
    q.release(k);
  }
  q.stop();
  CHECK(emitted == 20);
  CHECK(q.produced() == 20);
  CHECK(q.produce_total_ns() == 20 * 1'000'000);  // the mean stays 1 ms
  CHECK(q.produce_max_ns() == 1'000'000);
}
