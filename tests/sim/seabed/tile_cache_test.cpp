// The tile cache on its own: one generation per tile whatever the threads, waits in get() and
// none in prefetch(), retries after a failure, eviction of the least recently used tiles, and
// its counters.
#include "sim/seabed/tile_cache.h"

#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <condition_variable>
#include <future>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

using namespace sonarloop::seabed;

namespace {

using Cache = TileCache<int>;

Cache::Ptr value(int v) {
  return std::make_shared<const int>(v);
}

// A generator that blocks until released, so that a test can hold a tile "being made".
class HeldMaker {
 public:
  Cache::Ptr make(int v) {
    std::unique_lock<std::mutex> lock(mu_);
    entered_ = true;
    cv_.notify_all();
    cv_.wait(lock, [&] { return go_; });
    return value(v);
  }
  bool wait_entered() {
    std::unique_lock<std::mutex> lock(mu_);
    return cv_.wait_for(lock, std::chrono::seconds(20), [&] { return entered_; });
  }
  void let_go() {
    std::lock_guard<std::mutex> lock(mu_);
    go_ = true;
    cv_.notify_all();
  }

 private:
  std::mutex mu_;
  std::condition_variable cv_;
  bool entered_ = false;
  bool go_ = false;
};

}  // namespace

TEST_CASE("tile cache: a tile is made once, whatever the number of threads asking") {
  Cache cache(64);
  std::atomic<int> made{0};
  std::vector<std::thread> pool;
  std::vector<int> seen(8, 0);
  for (int t = 0; t < 8; ++t) {
    pool.emplace_back([&, t] {
      seen[static_cast<std::size_t>(t)] = *cache.get({3, -2, 1}, [&] {
        ++made;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        return value(42);
      });
    });
  }
  for (auto& th : pool)
    th.join();
  CHECK(made.load() == 1);
  for (int v : seen)
    CHECK(v == 42);
  // the level is part of the key
  CHECK(*cache.get({3, -2, 0}, [] { return value(7); }) == 7);
  CHECK(cache.size() == 2);
}

TEST_CASE("tile cache: prefetch makes a missing tile and never waits for one being made") {
  Cache cache(64);
  // a missing tile: prefetch makes it, get() then finds it
  int calls = 0;
  cache.prefetch({0, 0, 0}, [&] {
    ++calls;
    return value(1);
  });
  CHECK(calls == 1);
  CHECK(*cache.get({0, 0, 0}, [&] {
    ++calls;
    return value(-1);
  }) == 1);
  CHECK(calls == 1);

  // a tile another thread is making: prefetch returns at once without making it
  HeldMaker held;
  std::thread maker([&] { cache.get({5, 5, 0}, [&] { return held.make(5); }); });
  REQUIRE(held.wait_entered());
  auto prefetched = std::async(std::launch::async, [&] {
    cache.prefetch({5, 5, 0}, [&] {
      ++calls;
      return value(-5);
    });
  });
  const bool returned = prefetched.wait_for(std::chrono::seconds(20)) == std::future_status::ready;
  held.let_go();
  maker.join();
  prefetched.wait();
  CHECK(returned);  // while the tile was still being made
  CHECK(calls == 1);
  CHECK(*cache.get({5, 5, 0}, [] { return value(-5); }) == 5);
}

TEST_CASE("tile cache: a failed tile is forgotten and made again on the next call") {
  Cache cache(64);
  CHECK_THROWS_AS(cache.get({1, 1, 0}, []() -> Cache::Ptr { throw std::runtime_error("disk"); }),
                  std::runtime_error);
  CHECK(cache.size() == 0);
  CHECK(*cache.get({1, 1, 0}, [] { return value(11); }) == 11);
}

TEST_CASE("tile cache: beyond capacity the least recently used tiles go, and come back equal") {
  Cache cache(8);
  int made = 0;
  auto make = [&](int v) {
    return [&made, v] {
      ++made;
      return value(v);
    };
  };
  for (int k = 0; k < 8; ++k)
    cache.get({k, 0, 0}, make(k));
  CHECK(made == 8);
  // touch 0 and 1, then go over capacity: the oldest untouched ones are evicted
  cache.get({0, 0, 0}, make(-1));
  cache.get({1, 0, 0}, make(-1));
  cache.get({8, 0, 0}, make(8));
  CHECK(made == 9);
  CHECK(cache.size() <= 8);
  CHECK(cache.size() >= 6);
  const int before = made;
  CHECK(*cache.get({0, 0, 0}, make(-1)) == 0);  // kept: recently used
  CHECK(*cache.get({1, 0, 0}, make(-1)) == 1);
  CHECK(made == before);
  CHECK(*cache.get({2, 0, 0}, make(2)) == 2);  // evicted: made again, same value
  CHECK(made == before + 1);
  // the counters: get()s that found their tile, that made it, and the tiles evicted
  const TileCacheCounters c = cache.counters();
  CHECK(c.hits == 4);
  CHECK(c.misses == static_cast<std::uint64_t>(made));
  CHECK(c.evictions == static_cast<std::uint64_t>(made) - c.tiles);
  CHECK(c.tiles == cache.size());
  CHECK(c.capacity == 8);
  // prefetch is not counted (work ahead); a smaller capacity takes effect at the next insertion
  cache.prefetch({100, 0, 0}, make(100));
  CHECK(cache.counters().misses == c.misses);
  cache.set_capacity(2);
  cache.get({101, 0, 0}, make(101));
  CHECK(cache.size() <= 2);
  CHECK(cache.counters().capacity == 2);
}
