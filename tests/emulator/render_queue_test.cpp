// The render-ahead ring with a controllable producer: order, run-ahead depth, a slow ping that
// does not hold up the others, dropped pings, errors.
#include <atomic>
#include <catch2/catch.hpp>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "emulator/render_queue.h"

using namespace sonarloop::emulator;

namespace {

// Writes k into the first packet byte; ping `slow` blocks until released.
class FakeProducer final : public PingProducer {
 public:
  explicit FakeProducer(std::int64_t slow = -1, std::int64_t fail = -1)
      : slow_(slow), fail_(fail) {}
  void produce(std::int64_t k, int, PingSlot& slot) override {
    if (k == fail_) throw std::runtime_error("boom");
    if (k == slow_) {
      in_slow_ = true;
      std::unique_lock<std::mutex> lock(mu_);
      cv_.wait(lock, [&] { return go_ || cancelled_; });
    }
    slot.packet[0] = static_cast<std::uint8_t>(k & 0xFF);
    slot.packet_size = 1;
    ++produced_;
    highest_ = std::max<std::int64_t>(highest_, k);
  }
  void cancel() override {
    std::lock_guard<std::mutex> lock(mu_);
    cancelled_ = true;
    cv_.notify_all();
  }
  void let_go() {
    std::lock_guard<std::mutex> lock(mu_);
    go_ = true;
    cv_.notify_all();
  }
  void wait_in_slow() const {
    while (!in_slow_)
      std::this_thread::yield();
  }
  std::atomic<int> produced_{0};
  std::atomic<bool> in_slow_{false};
  std::atomic<std::int64_t> highest_{-1};

 private:
  std::int64_t slow_;
  std::int64_t fail_;
  std::mutex mu_;
  std::condition_variable cv_;
  bool go_ = false;
  bool cancelled_ = false;
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
  p.wait_in_slow();  // the worker is inside ping 0
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
  q.stop();  // cancel() releases the blocked producer
  SUCCEED();
}
