// Scene views built ahead on the cache's thread.
#include <catch2/catch.hpp>
#include <thread>

#include "config/loader/scenario_loader.h"
#include "emulator/view_cache.h"
#include "tests/emulator/test_scenario.h"

using namespace sonarloop;
using namespace sonarloop::emulator;

namespace {

scene::Box2 box(double n0, double e0, double n1, double e1) {
  return scene::Box2{Vec2(n0, e0), Vec2(n1, e1)};
}

// Waits until the cache has built `n` views (the builder runs on its own thread).
bool wait_builds(const ViewCache& c, std::uint64_t n) {
  for (int i = 0; i < 6000 && c.stats().builds < n; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return c.stats().builds >= n;
}

}  // namespace

TEST_CASE("ViewCache: box helpers and clipping to the seabed") {
  const auto sc = config::parse_scenario(testing::small_scenario_yaml(), "test.yaml");
  const scene::Scene scene(sc.scene);
  MonotonicClock clock;
  ViewCache c(scene, clock);
  const auto r = c.clip(box(-100, -5, 10, 100));
  CHECK(r.min == Vec2(-30, -5));
  CHECK(r.max == Vec2(10, 30));
  // entirely off the seabed: the canonical empty box
  const auto off = c.clip(box(100, 100, 200, 200));
  CHECK(box_empty(off));
  CHECK(off.min == off.max);
  CHECK(box_contains(box(0, 0, 10, 10), box(1, 1, 10, 9)));
  CHECK_FALSE(box_contains(box(0, 0, 10, 10), box(-1, 1, 5, 5)));
  CHECK(box_expand(box(0, 0, 1, 1), 2).min == Vec2(-2, -2));
  CHECK(box_union(box(0, 0, 1, 1), box(5, -1, 6, 0)).max == Vec2(6, 1));
}

TEST_CASE("ViewCache: one build per region; get() waits for it and shares it") {
  const auto sc = config::parse_scenario(testing::small_scenario_yaml(), "test.yaml");
  const scene::Scene scene(sc.scene);
  MonotonicClock clock;
  ViewCache c(scene, clock);
  const auto a = c.get(box(-10, -10, 10, 10));
  REQUIRE(a);
  CHECK(c.stats().builds == 1);
  CHECK(c.stats().waits == 1);  // nothing was prefetched: the caller waited
  CHECK(a->region().min == Vec2(-10, -10));
  // the same region (after clipping) is the same view, no new build or wait
  const auto b = c.get(box(-10, -10, 10, 10));
  CHECK(b == a);
  CHECK(c.stats().builds == 1);
  CHECK(c.stats().waits == 1);
  // a covering view serves a smaller need
  const auto inner = c.get_covering(box(-5, -5, 5, 5), box(-20, -20, 20, 20));
  CHECK(inner == a);
  CHECK(c.stats().builds == 1);
}

TEST_CASE("ViewCache: prefetch builds in the background, so a later get() does not wait") {
  const auto sc = config::parse_scenario(testing::small_scenario_yaml(), "test.yaml");
  const scene::Scene scene(sc.scene);
  MonotonicClock clock;
  ViewCache c(scene, clock);
  c.prefetch(box(0, -20, 20, 20));
  c.prefetch(box(0, -20, 20, 20));  // queued once
  REQUIRE(wait_builds(c, 1));
  const auto v = c.get(box(0, -20, 20, 20));
  REQUIRE(v);
  CHECK(c.stats().waits == 0);
  CHECK(c.stats().builds == 1);
  // prefetch_covering does nothing when a view already covers the need
  c.prefetch_covering(box(5, -5, 15, 5), box(-40, -40, 40, 40));
  CHECK(c.stats().builds == 1);
  CHECK(c.cached_views() == 1);
}

TEST_CASE("ViewCache: at most max_views are kept; evicted views live on with their users") {
  const auto sc = config::parse_scenario(testing::small_scenario_yaml(), "test.yaml");
  const scene::Scene scene(sc.scene);
  MonotonicClock clock;
  ViewCacheOptions o;
  o.max_views = 2;
  ViewCache c(scene, clock, o);
  const auto v1 = c.get(box(-30, -5, -20, 5));
  const auto v2 = c.get(box(-20, -5, -10, 5));
  const auto v3 = c.get(box(-10, -5, 0, 5));
  CHECK(c.cached_views() == 2);
  CHECK(c.stats().evictions == 1);
  // v1 was evicted but is still usable
  const scene::Hit h = v1->intersect(Vec3(-25, 0, 0), Vec3(0, 0, 1), 100.0);
  CHECK(h.kind == scene::HitKind::kSeabed);
  // asking for it again builds it again
  c.get(box(-30, -5, -20, 5));
  CHECK(c.stats().builds == 4);
}

TEST_CASE("ViewCache: stop() wakes a waiting get(), which returns nullptr") {
  const auto sc = config::parse_scenario(testing::small_scenario_yaml(), "test.yaml");
  const scene::Scene scene(sc.scene);
  MonotonicClock clock;
  ViewCache c(scene, clock);
  c.stop();
  CHECK(c.get(box(-10, -10, 10, 10)) == nullptr);
}
