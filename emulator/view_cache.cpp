#include "emulator/view_cache.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <stdexcept>

namespace sonarloop::emulator {

bool box_contains(const scene::Box2& outer, const scene::Box2& inner) {
  return outer.min.x() <= inner.min.x() && outer.min.y() <= inner.min.y() &&
         outer.max.x() >= inner.max.x() && outer.max.y() >= inner.max.y();
}

bool box_empty(const scene::Box2& b) {
  return !(b.max.x() > b.min.x() && b.max.y() > b.min.y());
}

scene::Box2 box_union(const scene::Box2& a, const scene::Box2& b) {
  return scene::Box2{a.min.cwiseMin(b.min), a.max.cwiseMax(b.max)};
}

scene::Box2 box_expand(const scene::Box2& b, double margin_m) {
  const Vec2 m(margin_m, margin_m);
  return scene::Box2{b.min - m, b.max + m};
}

ViewCache::ViewCache(const scene::Scene& scene, const Clock& clock, ViewCacheOptions options)
    : scene_(scene), clock_(clock), options_(options) {
  options_.build_threads = std::max(1, options_.build_threads);
  options_.max_views = std::max<std::size_t>(1, options_.max_views);
  builder_ = std::thread([this] { run(); });
}

ViewCache::~ViewCache() {
  stop();
}

void ViewCache::cancel() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    stopping_ = true;
  }
  cv_.notify_all();
}

void ViewCache::stop() {
  cancel();
  if (builder_.joinable()) builder_.join();
}

scene::Box2 ViewCache::clip(const scene::Box2& region) const {
  const seabed::SeabedModel& sb = scene_.seabed();
  scene::Box2 r{region.min.cwiseMax(sb.extent_min()), region.max.cwiseMin(sb.extent_max())};
  if (box_empty(r)) return scene::Box2{};  // canonical empty box: (0,0)-(0,0)
  return r;
}

ViewCache::Entry* ViewCache::find(const scene::Box2& clipped) {
  for (auto& e : entries_) {
    if (e->region.min == clipped.min && e->region.max == clipped.max) return e.get();
  }
  return nullptr;
}

ViewCache::Entry& ViewCache::enqueue(const scene::Box2& clipped) {
  auto e = std::make_unique<Entry>();
  e->region = clipped;
  e->last_use = ++use_counter_;
  entries_.push_back(std::move(e));
  evict();
  cv_.notify_all();
  return *entries_.back();
}

void ViewCache::evict() {
  while (entries_.size() > options_.max_views) {
    // the least recently used built view that nobody waits for
    auto victim = entries_.end();
    for (auto it = entries_.begin(); it != entries_.end(); ++it) {
      const Entry& e = **it;
      if (!e.view || e.waiters > 0) continue;
      if (victim == entries_.end() || e.last_use < (*victim)->last_use) victim = it;
    }
    if (victim == entries_.end()) return;  // everything is queued or awaited: keep them
    entries_.erase(victim);
    ++stats_.evictions;
  }
}

std::shared_ptr<const scene::SceneView> ViewCache::wait_for(const scene::Box2& clipped,
                                                            std::unique_lock<std::mutex>& lock) {
  Entry* e = find(clipped);
  if (!e) e = &enqueue(clipped);
  e->last_use = ++use_counter_;
  if (e->view) return e->view;
  // a renderer waits for a build: counted and timed
  ++stats_.waits;
  const std::int64_t t0 = clock_.now_ns();
  ++e->waiters;
  cv_.wait(lock, [&] {
    Entry* f = find(clipped);
    return stopping_ || !f || f->view != nullptr;
  });
  stats_.wait_total_s += static_cast<double>(clock_.now_ns() - t0) * 1e-9;
  e = find(clipped);
  if (!e) return nullptr;  // cannot happen (entries with waiters are never evicted)
  --e->waiters;
  if (stopping_ && !e->view) return nullptr;
  e->last_use = ++use_counter_;
  return e->view;
}

std::shared_ptr<const scene::SceneView> ViewCache::build_now(const scene::Box2& region,
                                                             int threads) {
  const scene::Box2 clipped = clip(region);
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (Entry* e = find(clipped); e && e->view) return e->view;
  }
  const std::int64_t t0 = clock_.now_ns();
  auto view = scene_.view(clipped, std::max(1, threads));
  const double s = static_cast<double>(clock_.now_ns() - t0) * 1e-9;
  std::lock_guard<std::mutex> lock(mu_);
  ++stats_.builds;
  stats_.build_total_s += s;
  stats_.build_max_s = std::max(stats_.build_max_s, s);
  Entry* e = find(clipped);
  if (!e) {
    auto fresh = std::make_unique<Entry>();
    fresh->region = clipped;
    entries_.push_back(std::move(fresh));
    e = entries_.back().get();
  }
  e->view = view;
  e->building = false;
  e->last_use = ++use_counter_;
  evict();
  cv_.notify_all();
  return view;
}

std::shared_ptr<const scene::SceneView> ViewCache::get(const scene::Box2& region) {
  const scene::Box2 clipped = clip(region);
  std::unique_lock<std::mutex> lock(mu_);
  return wait_for(clipped, lock);
}

std::shared_ptr<const scene::SceneView> ViewCache::get_covering(const scene::Box2& needed,
                                                                const scene::Box2& build_region) {
  const scene::Box2 need = clip(needed);
  std::unique_lock<std::mutex> lock(mu_);
  for (auto& e : entries_) {
    if (e->view && box_contains(e->region, need)) {
      e->last_use = ++use_counter_;
      return e->view;
    }
  }
  // a queued build that will cover it, else a new one
  for (auto& e : entries_) {
    if (!e->view && box_contains(e->region, need)) {
      const scene::Box2 r = e->region;
      return wait_for(r, lock);
    }
  }
  scene::Box2 build = clip(box_union(build_region, needed));
  return wait_for(build, lock);
}

void ViewCache::prefetch(const scene::Box2& region) {
  const scene::Box2 clipped = clip(region);
  std::lock_guard<std::mutex> lock(mu_);
  if (find(clipped)) return;
  enqueue(clipped);
}

void ViewCache::prefetch_covering(const scene::Box2& needed, const scene::Box2& build_region) {
  const scene::Box2 need = clip(needed);
  std::lock_guard<std::mutex> lock(mu_);
  for (auto& e : entries_)
    if (box_contains(e->region, need)) return;
  const scene::Box2 build = clip(box_union(build_region, needed));
  if (find(build)) return;
  enqueue(build);
}

void ViewCache::run() {
  if (options_.builder_nice > 0) {
    // per-thread on Linux; raising one's own niceness needs no privilege (best effort)
    errno = 0;
    [[maybe_unused]] const int rc =
        setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()),
                    getpriority(PRIO_PROCESS, 0) + options_.builder_nice);
  }
  std::unique_lock<std::mutex> lock(mu_);
  for (;;) {
    Entry* next = nullptr;
    cv_.wait(lock, [&] {
      if (stopping_) return true;
      for (auto& e : entries_) {
        if (!e->view && !e->building) {
          next = e.get();
          return true;
        }
      }
      return false;
    });
    if (stopping_) return;
    next->building = true;
    const scene::Box2 region = next->region;
    lock.unlock();
    const std::int64_t t0 = clock_.now_ns();
    std::shared_ptr<const scene::SceneView> view;
    std::string error;
    try {
      view = scene_.view(region, options_.build_threads);
    } catch (const std::exception& e) {
      error = e.what();
    }
    const double s = static_cast<double>(clock_.now_ns() - t0) * 1e-9;
    lock.lock();
    if (!error.empty()) {
      // an Embree failure (out of memory): fatal for the run; waiters give up
      stopping_ = true;
      cv_.notify_all();
      error_ = "building the scene view: " + error;
      return;
    }
    ++stats_.builds;
    stats_.build_total_s += s;
    stats_.build_max_s = std::max(stats_.build_max_s, s);
    if (Entry* e = find(region)) {
      e->view = std::move(view);
      e->building = false;
    }
    evict();
    cv_.notify_all();
  }
}

ViewCacheStats ViewCache::stats() const {
  std::lock_guard<std::mutex> lock(mu_);
  return stats_;
}

std::string ViewCache::error() const {
  std::lock_guard<std::mutex> lock(mu_);
  return error_;
}

std::size_t ViewCache::cached_views() const {
  std::lock_guard<std::mutex> lock(mu_);
  std::size_t n = 0;
  for (const auto& e : entries_)
    n += e->view ? 1 : 0;
  return n;
}

}  // namespace sonarloop::emulator
