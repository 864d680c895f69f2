#pragma once
// Scene views built ahead of the pings, on a background thread (design.md: "scene views are built
// ahead along the trajectory ... so publishing never waits for a BVH build").
//
// A scene::SceneView is the Embree scene of one rectangle of the seabed (Scene::view). Building
// one takes seconds for a 100 m x 100 m patch at 2.5 cm (the heightmap tiles are generated and
// the BVH is compiled), so it must never happen on the publishing path. The cache holds a few
// views keyed by their region (clipped to the seabed extent, as Scene::view clips) and builds
// missing ones on its own thread, one at a time, with `build_threads` threads:
// - prefetch(region) queues a build if the region is neither built nor queued;
// - get(region) returns the view of exactly that region, queuing it and waiting if needed (the
//   wait is counted: a render worker waited for a build);
// - get_covering(needed, build_region) returns any built view whose region contains `needed`
//   (for poses that are not known ahead, --pose-from), or queues `build_region` and waits.
// Views are immutable and shared (std::shared_ptr): a view evicted from the cache lives on
// while a renderer holds it. At most max_views are kept; the least recently used built view
// without waiters is evicted first.
//
// Rendering is a pure function of the view's region (its local origin is the region's rounded
// centre), so for byte-identical pings every ping must be rendered with a view of a region that
// depends only on the ping (the emulator's view plan, ping_producer.h), never on which views
// happen to be cached: that is why get() matches regions exactly.
//
// Thread safety: every method may be called from any thread. stop() wakes all waiters (get()
// then returns nullptr) and joins the builder.
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "emulator/pacer.h"
#include "sim/scene/scene.h"

namespace sonarloop::emulator {

struct ViewCacheOptions {
  int build_threads = 1;      // threads of each background build (Scene::view)
  std::size_t max_views = 3;  // views kept (each ~200 MB for 100 m x 100 m at 2.5 cm)
  // Niceness added to the builder thread (0 = unchanged): in a paced run the builds, seconds of
  // CPU each, then yield to the publisher and the renderers, which have deadlines.
  int builder_nice = 0;
};

struct ViewCacheStats {
  std::uint64_t builds = 0;  // views built (background and build_now)
  double build_total_s = 0.0;
  double build_max_s = 0.0;
  std::uint64_t waits = 0;  // get()/get_covering() calls that had to wait for a build
  double wait_total_s = 0.0;
  std::uint64_t evictions = 0;
};

// True if `outer` contains `inner` (edges included).
bool box_contains(const scene::Box2& outer, const scene::Box2& inner);
// True if the box has no area (max <= min on an axis).
bool box_empty(const scene::Box2& b);
// The smallest box holding both.
scene::Box2 box_union(const scene::Box2& a, const scene::Box2& b);
// `b` grown by margin_m on every side.
scene::Box2 box_expand(const scene::Box2& b, double margin_m);

class ViewCache {
 public:
  // `clock` times the builds and waits (statistics only).
  ViewCache(const scene::Scene& scene, const Clock& clock, ViewCacheOptions options = {});
  ~ViewCache();
  ViewCache(const ViewCache&) = delete;
  ViewCache& operator=(const ViewCache&) = delete;

  // `region` clipped to the seabed extent, the key under which its view is cached. Regions that
  // clip to nothing (entirely off the seabed) all map to one canonical empty box.
  scene::Box2 clip(const scene::Box2& region) const;

  // Builds the view of `region` on the calling thread with `threads` threads and caches it
  // (start-up: the first view before the clock starts). Returns it.
  std::shared_ptr<const scene::SceneView> build_now(const scene::Box2& region, int threads);
  std::shared_ptr<const scene::SceneView> get(const scene::Box2& region);
  std::shared_ptr<const scene::SceneView> get_covering(const scene::Box2& needed,
                                                       const scene::Box2& build_region);
  void prefetch(const scene::Box2& region);
  // Queues `build_region` unless a built or queued view already contains `needed` (prefetching
  // around poses that are not known ahead).
  void prefetch_covering(const scene::Box2& needed, const scene::Box2& build_region);

  // Wakes every waiter (get() and get_covering() then return nullptr) and stops queuing builds;
  // does not wait for a build under way. stop() also joins the builder thread.
  void cancel();
  void stop();
  ViewCacheStats stats() const;
  // Why a build failed (an Embree error such as out of memory), empty otherwise. After a failure
  // the cache is stopped: get() and get_covering() return nullptr.
  std::string error() const;
  std::size_t cached_views() const;  // built views held now

 private:
  struct Entry {
    scene::Box2 region;                            // clipped
    std::shared_ptr<const scene::SceneView> view;  // null while queued / building
    bool building = false;
    int waiters = 0;
    std::uint64_t last_use = 0;
  };
  // all with mu_ held
  Entry* find(const scene::Box2& clipped);
  Entry& enqueue(const scene::Box2& clipped);
  std::shared_ptr<const scene::SceneView> wait_for(const scene::Box2& clipped,
                                                   std::unique_lock<std::mutex>& lock);
  void evict();
  void run();

  const scene::Scene& scene_;
  const Clock& clock_;
  ViewCacheOptions options_;
  mutable std::mutex mu_;
  std::condition_variable cv_;  // builder: work queued / stop; waiters: a build finished
  std::vector<std::unique_ptr<Entry>> entries_;
  std::uint64_t use_counter_ = 0;
  bool stopping_ = false;
  std::string error_;
  ViewCacheStats stats_;
  std::thread builder_;
};

}  // namespace sonarloop::emulator
