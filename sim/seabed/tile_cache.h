#pragma once
// A thread-safe cache of lazily generated tiles keyed by (ti, tj), with least-recently-used
// eviction beyond a capacity. A tile asked for by several threads at once is generated once:
// the others wait for it (prefetch() does not wait). Tiles are immutable once made
// (shared_ptr<const V>), so an evicted tile stays valid for whoever still holds it, and
// regenerating it gives the same bytes because every generator here is a pure function of (seed,
// tile). Its capacity is a count of tiles: the owner sizes it from a byte budget (its tiles are
// all one size), and counts its hits, misses and evictions (TileCacheCounters).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

namespace sonarloop::seabed {

struct TileKey {
  std::int64_t ti = 0;
  std::int64_t tj = 0;
  int level = 0;  // detail level (seabed_model.h); 0 for single-level caches
  bool operator==(const TileKey&) const = default;
};

struct TileKeyHash {
  std::size_t operator()(const TileKey& k) const {
    const auto a = static_cast<std::uint64_t>(k.ti) * 0x9E3779B97F4A7C15ULL;
    const auto b = static_cast<std::uint64_t>(k.tj) * 0xC2B2AE3D27D4EB4FULL;
    const auto c = static_cast<std::uint64_t>(k.level) * 0x165667B19E3779F9ULL;
    return static_cast<std::size_t>(a ^ (b >> 7) ^ (b << 29) ^ c);
  }
};

// What a cache did since it was made: get() calls that found their tile (made or being made by
// another thread) or had to make it, and tiles evicted; and what it holds now.
struct TileCacheCounters {
  std::uint64_t hits = 0, misses = 0, evictions = 0;
  std::size_t tiles = 0, capacity = 0;  // held now; at most (a few more while being made)
  TileCacheCounters& operator+=(const TileCacheCounters& o) {
    hits += o.hits;
    misses += o.misses;
    evictions += o.evictions;
    tiles += o.tiles;
    capacity += o.capacity;
    return *this;
  }
};

// What a seabed's caches did and hold (SeabedModel::cache_stats), the heightmap's and the noise
// layers' (summed) apart, with the bytes they hold and may hold.
struct SeabedCacheStats {
  TileCacheCounters heightmap, noise;
  std::size_t bytes = 0, budget_bytes = 0;
};

template <class V>
class TileCache {
 public:
  using Ptr = std::shared_ptr<const V>;

  explicit TileCache(std::size_t capacity) : capacity_(std::max<std::size_t>(capacity, 1)) {}

  // Returns the cached tile or makes it with `make` (called outside the lock).
  Ptr get(const TileKey& key, const std::function<Ptr()>& make) {
    std::promise<Ptr> promise;
    std::shared_future<Ptr> future;
    if (claim(key, promise, future, true)) fulfil(key, promise, make);
    return future.get();
  }

  // Makes the tile with `make` if nobody has: returns at once, without waiting, when the tile is
  // cached or another thread is making it (work ahead never waits for work ahead).
  void prefetch(const TileKey& key, const std::function<Ptr()>& make) {
    std::promise<Ptr> promise;
    std::shared_future<Ptr> future;
    if (claim(key, promise, future, false)) fulfil(key, promise, make);
  }

  std::size_t size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return map_.size();
  }
  std::size_t capacity() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return capacity_;
  }
  // A new capacity (before use; tiles beyond it go at the next insertion).
  void set_capacity(std::size_t capacity) {
    std::lock_guard<std::mutex> lock(mutex_);
    capacity_ = std::max<std::size_t>(capacity, 1);
  }

  // get()'s hits and misses (prefetch() is work ahead, not counted), evictions, size.
  TileCacheCounters counters() const {
    std::lock_guard<std::mutex> lock(mutex_);
    TileCacheCounters c = counters_;
    c.tiles = map_.size();
    c.capacity = capacity_;
    return c;
  }

  void clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    map_.clear();
  }

 private:
  struct Entry {
    std::shared_future<Ptr> value;
    std::uint64_t last_use = 0;
  };

  // The entry's future; true if it is new and this thread must fulfil it. `counted`: a get().
  bool claim(const TileKey& key, std::promise<Ptr>& promise, std::shared_future<Ptr>& future,
             bool counted) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = map_.find(key);
    if (it != map_.end()) {
      it->second.last_use = ++clock_;
      future = it->second.value;
      if (counted) ++counters_.hits;
      return false;
    }
    if (counted) ++counters_.misses;
    future = promise.get_future().share();
    map_.emplace(key, Entry{future, ++clock_});
    return true;
  }

  void fulfil(const TileKey& key, std::promise<Ptr>& promise, const std::function<Ptr()>& make) {
    try {
      promise.set_value(make());
    } catch (...) {
      // forget the failed entry so a later call retries, and pass the error on
      {
        std::lock_guard<std::mutex> lock(mutex_);
        map_.erase(key);
      }
      promise.set_exception(std::current_exception());
      throw;
    }
    evict_if_needed();
  }

  void evict_if_needed() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (map_.size() <= capacity_) return;
    // drop the least recently used ready entries until a quarter below capacity
    std::vector<std::pair<std::uint64_t, TileKey>> ready;
    ready.reserve(map_.size());
    for (const auto& [k, e] : map_) {
      if (e.value.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        ready.emplace_back(e.last_use, k);
      }
    }
    std::sort(ready.begin(), ready.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    const std::size_t target = capacity_ - capacity_ / 4;
    for (const auto& [use, k] : ready) {
      if (map_.size() <= target) break;
      map_.erase(k);
      ++counters_.evictions;
    }
  }

  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::unordered_map<TileKey, Entry, TileKeyHash> map_;
  std::uint64_t clock_ = 0;
  TileCacheCounters counters_;
};

}  // namespace sonarloop::seabed
