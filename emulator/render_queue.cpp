#include "emulator/render_queue.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace sonarloop::emulator {

RenderQueue::RenderQueue(PingProducer& producer, int slots, int threads, std::size_t packet_bytes)
    : producer_(producer), threads_(std::max(1, threads)) {
  if (slots < 1) throw std::invalid_argument("RenderQueue: at least one slot is needed");
  slots_.resize(static_cast<std::size_t>(slots));
  for (auto& s : slots_)
    s.packet.assign(packet_bytes, 0);
  state_.assign(slots_.size(), State::kFree);
  released_.assign(slots_.size(), false);
  claimed_.assign(slots_.size(), -1);
  abandon_ = std::make_unique<std::atomic<bool>[]>(slots_.size());
  for (std::size_t s = 0; s < slots_.size(); ++s) {
    abandon_[s].store(false);
    slots_[s].abandon = &abandon_[s];
  }
}

RenderQueue::~RenderQueue() {
  stop();
}

void RenderQueue::set_deadlines(std::function<std::int64_t(std::int64_t)> give_up_ns,
                                const Clock& clock) {
  std::lock_guard<std::mutex> lock(mu_);
  if (!workers_.empty()) throw std::logic_error("RenderQueue::set_deadlines after start");
  give_up_ns_ = std::move(give_up_ns);
  clock_ = &clock;
}

std::int64_t RenderQueue::first_deliverable() const {
  std::int64_t k = next_claim_;
  if (!give_up_ns_ || render_mean_ns_ <= 0) return k;
  const std::int64_t done = clock_->now_ns() + render_mean_ns_;
  while (k < end_ && give_up_ns_(k) < done)
    ++k;
  return k;
}

void RenderQueue::start(std::int64_t first, std::int64_t end) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (!workers_.empty()) throw std::logic_error("RenderQueue::start called twice");
    next_claim_ = first;
    consumer_next_ = first;
    end_ = end;
  }
  for (int w = 0; w < threads_; ++w)
    workers_.emplace_back([this, w] { work(w); });
}

void RenderQueue::stop() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    stopping_ = true;
    for (std::size_t s = 0; s < slots_.size(); ++s)
      if (state_[s] == State::kProducing) abandon_[s].store(true);
  }
  producer_.cancel();
  cv_.notify_all();
  for (auto& t : workers_)
    if (t.joinable()) t.join();
  wakeup_.notify();
}

std::string RenderQueue::error() const {
  std::lock_guard<std::mutex> lock(mu_);
  return error_;
}

const PingSlot* RenderQueue::ready(std::int64_t k) const {
  const auto s = static_cast<std::size_t>(k % static_cast<std::int64_t>(slots_.size()));
  std::lock_guard<std::mutex> lock(mu_);
  if (state_[s] == State::kReady && claimed_[s] == k) return &slots_[s];
  return nullptr;
}

void RenderQueue::release(std::int64_t k) {
  const auto s = static_cast<std::size_t>(k % static_cast<std::int64_t>(slots_.size()));
  {
    std::lock_guard<std::mutex> lock(mu_);
    consumer_next_ = std::max(consumer_next_, k + 1);
    if (claimed_[s] == k) {
      if (state_[s] == State::kReady) {
        state_[s] = State::kFree;
      } else if (state_[s] == State::kProducing) {
        released_[s] = true;  // the worker frees it when done
        abandon_[s].store(true);
      }
    }
  }
  cv_.notify_all();
}

void RenderQueue::fail(std::unique_lock<std::mutex>& lock, const std::string& what) {
  if (error_.empty()) error_ = what;
  failed_ = true;
  stopping_ = true;
  lock.unlock();
  cv_.notify_all();
  producer_.cancel();
  wakeup_.notify();
}

void RenderQueue::work(int worker) {
  const auto n = static_cast<std::int64_t>(slots_.size());
  std::unique_lock<std::mutex> lock(mu_);
  for (;;) {
    // claim the next ping whose slot is free, skipping pings the publisher gave up on
    std::size_t s = 0;
    std::int64_t k = 0;
    cv_.wait(lock, [&] {
      if (stopping_) return true;
      next_claim_ = std::max(next_claim_, consumer_next_);
      next_claim_ = first_deliverable();
      if (next_claim_ >= end_) return false;
      s = static_cast<std::size_t>(next_claim_ % n);
      return state_[s] == State::kFree;
    });
    if (stopping_) return;
    k = next_claim_++;
    state_[s] = State::kProducing;
    released_[s] = false;
    abandon_[s].store(false);
    claimed_[s] = k;
    PingSlot& slot = slots_[s];
    lock.unlock();

    std::string what;
    try {
      producer_.produce(k, worker, slot);
    } catch (const std::exception& e) {
      what = "ping " + std::to_string(k) + ": " + e.what();
    }

    lock.lock();
    if (!what.empty()) {
      state_[s] = State::kFree;
      return fail(lock, what);
    }
    // Only a ping that was rendered counts: a period without one (a stale external pose) takes
    // no render time and must not pull the mean down or show in the render statistics. A render
    // cut short counts in the mean (the time is a lower bound of what it needed) and is counted
    // apart.
    if (slot.abandoned) abandoned_.fetch_add(1);
    if (slot.emitted) {
      // running mean over about the last 8 pings (the first ping sets it); one slow ping (a
      // tile made on the spot) counts at most 4 times the mean, so it does not make the
      // workers skip pings they could deliver
      if (render_mean_ns_ == 0) {
        render_mean_ns_ = std::max<std::int64_t>(slot.produce_ns, 1);
      } else {
        const std::int64_t sample = std::min(slot.produce_ns, 4 * render_mean_ns_);
        render_mean_ns_ =
            std::max<std::int64_t>(1, render_mean_ns_ + (sample - render_mean_ns_) / 8);
      }
    }
    if (slot.emitted && !slot.abandoned) {
      produced_.fetch_add(1);
      produce_total_ns_.fetch_add(slot.produce_ns);
      std::int64_t prev = produce_max_ns_.load();
      while (slot.produce_ns > prev &&
             !produce_max_ns_.compare_exchange_weak(prev, slot.produce_ns)) {
      }
    }
    slot.index = k;  // the producer is done with the slot: it is the queue's again
    if (released_[s]) {
      state_[s] = State::kFree;
      released_[s] = false;
      cv_.notify_all();
    } else {
      state_[s] = State::kReady;
    }
    lock.unlock();
    wakeup_.notify();

    // the ping is out of this worker's hands: now the work for later pings
    try {
      producer_.work_ahead(k, worker);
    } catch (const std::exception& e) {
      what = "work ahead of ping " + std::to_string(k) + ": " + e.what();
    }
    lock.lock();
    if (!what.empty()) return fail(lock, what);
  }
}

}  // namespace sonarloop::emulator
