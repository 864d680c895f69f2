// The packet queue between a receiving thread and the pipeline: first in, first out across
// threads; a full queue either drops (counted) or makes the producer wait; close() drains.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "atr/packet_queue.h"

using namespace sonarloop;

namespace {

std::vector<std::uint8_t> packet(std::uint32_t i, std::size_t size) {
  std::vector<std::uint8_t> p(size);
  for (std::size_t k = 0; k < size; ++k)
    p[k] = static_cast<std::uint8_t>(i + k);
  p[0] = static_cast<std::uint8_t>(i);
  p[1] = static_cast<std::uint8_t>(i >> 8);
  return p;
}

std::uint32_t number_of(std::span<const std::uint8_t> p) {
  return static_cast<std::uint32_t>(p[0] | (p[1] << 8));
}

}  // namespace

TEST_CASE("packet queue: lossless across threads when the producer waits") {
  atr::PacketQueue q(8, 256);
  constexpr std::uint32_t kN = 5000;
  std::thread producer([&] {
    for (std::uint32_t i = 0; i < kN; ++i)
      REQUIRE(q.push(packet(i, 10 + i % 200), true));
    q.close();
  });
  std::uint32_t next = 0;
  bool ok = true;
  while (q.pop(
      [&](std::span<const std::uint8_t> p) {
        ok = ok && number_of(p) == (next & 0xFFFF) && p.size() == 10 + next % 200 &&
             std::vector<std::uint8_t>(p.begin(), p.end()) == packet(next, p.size());
        ++next;
      },
      -1)) {
  }
  producer.join();
  CHECK(ok);
  CHECK(next == kN);
  CHECK(q.dropped_full() == 0);
  CHECK(q.pushed() == kN);
  CHECK(q.high_water() <= 8);
}

TEST_CASE("packet queue: drops when full and told not to wait; oversize packets") {
  atr::PacketQueue q(4, 100);
  for (std::uint32_t i = 0; i < 6; ++i)
    q.push(packet(i, 50), false);
  CHECK(q.size() == 4);
  CHECK(q.dropped_full() == 2);
  CHECK_FALSE(q.push(packet(9, 101), false));
  CHECK(q.dropped_oversize() == 1);
  std::vector<std::uint32_t> got;
  while (q.pop([&](std::span<const std::uint8_t> p) { got.push_back(number_of(p)); }, 0)) {
  }
  CHECK(got == std::vector<std::uint32_t>{0, 1, 2, 3});
  // a pop on an empty queue times out
  CHECK_FALSE(q.pop([](std::span<const std::uint8_t>) {}, 10));
  // a producer waiting on a full queue is released by close()
  for (std::uint32_t i = 0; i < 4; ++i)
    q.push(packet(i, 10), false);
  std::atomic<bool> returned{false};
  std::thread waiter([&] {
    CHECK_FALSE(q.push(packet(5, 10), true));
    returned = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  CHECK_FALSE(returned);
  q.close();
  waiter.join();
  CHECK(returned);
  CHECK(q.closed());
}
