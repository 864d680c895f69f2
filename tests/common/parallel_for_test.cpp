// The one parallel loop (common/parallel_for.h): every item once, on at most the workers asked
// (and never more than there are items), worker 0 the calling thread; the first exception stops
// the others and reaches the caller after every worker has ended.
#include "common/parallel_for.h"

#include <atomic>
#include <catch2/catch.hpp>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

using sonarloop::parallel_for;

TEST_CASE("parallel_for: every item once, whatever the number of workers") {
  for (const int workers : {1, 2, 3, 8}) {
    for (const std::size_t n :
         {std::size_t{0}, std::size_t{1}, std::size_t{5}, std::size_t{1000}}) {
      INFO("workers " << workers << ", items " << n);
      std::vector<std::atomic<int>> seen(n);
      std::mutex mu;
      std::set<int> ids;
      parallel_for(n, workers, [&](std::size_t i, int w) {
        ++seen[i];
        const std::lock_guard lock(mu);
        ids.insert(w);
      });
      for (std::size_t i = 0; i < n; ++i)
        CHECK(seen[i] == 1);
      // worker ids in [0, min(workers, n))
      for (const int w : ids) {
        CHECK(w >= 0);
        CHECK(static_cast<std::size_t>(w) < std::min<std::size_t>(workers, n));
      }
    }
  }
}

TEST_CASE("parallel_for: worker 0 is the calling thread; fewer than one worker means one") {
  const std::thread::id caller = std::this_thread::get_id();
  bool zero_on_caller = true;
  std::mutex mu;
  parallel_for(50, 4, [&](std::size_t, int w) {
    const std::lock_guard lock(mu);
    if (w == 0 && std::this_thread::get_id() != caller) zero_on_caller = false;
  });
  CHECK(zero_on_caller);
  int items = 0;
  parallel_for(7, 0, [&](std::size_t, int w) {
    CHECK(w == 0);
    CHECK(std::this_thread::get_id() == caller);
    ++items;
  });
  CHECK(items == 7);
}

TEST_CASE("parallel_for: the first exception stops the others and reaches the caller") {
  for (const int workers : {1, 2, 4}) {
    INFO("workers " << workers);
    std::atomic<int> ran{0};
    CHECK_THROWS_WITH(parallel_for(10000, workers,
                                   [&](std::size_t i, int) {
                                     ++ran;
                                     if (i == 10) throw std::runtime_error("item 10 failed");
                                   }),
                      "item 10 failed");
    // the workers stopped at their next item: far fewer than all ran (at most the items each
    // worker had already started, and the ones before item 10)
    CHECK(ran < 10000);
    CHECK(ran >= 11);
  }
}
