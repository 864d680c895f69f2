#include "common/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace sonarloop {

void parallel_for(std::size_t n, int workers,
                  const std::function<void(std::size_t item, int worker)>& fn) {
  if (n == 0) return;
  const int w = static_cast<int>(
      std::clamp<std::size_t>(static_cast<std::size_t>(std::max(1, workers)), 1, n));
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mu;
  const auto work = [&](int worker) {
    try {
      for (std::size_t i = next++; i < n; i = next++)
        fn(i, worker);
    } catch (...) {
      const std::lock_guard lock(error_mu);
      if (!error) error = std::current_exception();
      next = n;  // the others stop at their next item
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(static_cast<std::size_t>(w - 1));
  for (int k = 1; k < w; ++k)
    pool.emplace_back(work, k);
  work(0);
  for (auto& t : pool)
    t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace sonarloop
