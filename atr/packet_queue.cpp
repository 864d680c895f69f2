#include "atr/packet_queue.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace sonarloop::atr {

PacketQueue::PacketQueue(std::size_t slots, std::size_t slot_bytes)
    : slots_(slots), slot_bytes_(slot_bytes) {
  if (slots == 0 || slot_bytes == 0) {
    throw std::invalid_argument("packet queue: need at least one slot of at least one byte");
  }
  // default-initialised (new T[n], not make_unique<T[]>(n)): pages are touched only as used
  storage_ = std::unique_ptr<std::uint8_t[]>(new std::uint8_t[slots * slot_bytes]);
  sizes_ = std::unique_ptr<std::size_t[]>(new std::size_t[slots]);
}

bool PacketQueue::push(std::span<const std::uint8_t> packet, bool wait_when_full) {
  std::unique_lock lock(mutex_);
  if (closed_) return false;
  if (packet.size() > slot_bytes_) {
    ++dropped_oversize_;
    return false;
  }
  if (count_ == slots_) {
    if (!wait_when_full) {
      ++dropped_full_;
      return false;
    }
    not_full_.wait(lock, [&] { return closed_ || count_ < slots_; });
    if (closed_) return false;
  }
  const std::size_t tail = (head_ + count_) % slots_;
  // the tail slot is free: pop() only reads the head slot, which is never the tail here
  std::memcpy(storage_.get() + tail * slot_bytes_, packet.data(), packet.size());
  sizes_[tail] = packet.size();
  ++count_;
  ++pushed_;
  high_water_ = std::max(high_water_, count_);
  lock.unlock();
  not_empty_.notify_one();
  return true;
}

bool PacketQueue::wait_for_packet(std::unique_lock<std::mutex>& lock, int timeout_ms) {
  auto ready = [&] { return count_ > 0 || closed_; };
  if (timeout_ms < 0) {
    not_empty_.wait(lock, ready);
  } else if (!not_empty_.wait_for(lock, std::chrono::milliseconds(timeout_ms), ready)) {
    return false;
  }
  return count_ > 0;
}

void PacketQueue::release_front() {
  {
    const std::lock_guard lock(mutex_);
    head_ = (head_ + 1) % slots_;
    --count_;
  }
  not_full_.notify_one();
}

void PacketQueue::close() {
  {
    const std::lock_guard lock(mutex_);
    closed_ = true;
  }
  not_empty_.notify_all();
  not_full_.notify_all();
}

bool PacketQueue::closed() const {
  const std::lock_guard lock(mutex_);
  return closed_;
}

std::uint64_t PacketQueue::pushed() const {
  const std::lock_guard lock(mutex_);
  return pushed_;
}

std::uint64_t PacketQueue::dropped_full() const {
  const std::lock_guard lock(mutex_);
  return dropped_full_;
}

std::uint64_t PacketQueue::dropped_oversize() const {
  const std::lock_guard lock(mutex_);
  return dropped_oversize_;
}

std::size_t PacketQueue::size() const {
  const std::lock_guard lock(mutex_);
  return count_;
}

std::size_t PacketQueue::high_water() const {
  const std::lock_guard lock(mutex_);
  return high_water_;
}

}  // namespace sonarloop::atr
