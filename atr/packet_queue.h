#pragma once
// A bounded first-in first-out queue of datagrams between two threads: the thread that receives
// them (a UDP socket reader, or the emulator's publisher for `run --classify`) and the onboard
// pipeline that processes them, so that a slow step (classifying a contact) never stalls the
// socket or the emulator.
//
// Memory is fixed at construction: `slots` buffers of `slot_bytes` each (one allocation, pages
// touched only as used). push() copies a datagram in: when the queue is full it either waits for
// a free slot (lossless, for --rate max where the producer may be slowed down) or drops the
// datagram and counts it (paced runs, where the producer must never wait). A datagram larger than
// a slot is dropped and counted as oversize. pop() hands the oldest datagram to a callback
// without holding the lock, then frees its slot. No allocation per datagram.
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <mutex>
#include <span>

namespace sonarloop::atr {

class PacketQueue {
 public:
  // Throws std::invalid_argument if slots or slot_bytes is 0.
  PacketQueue(std::size_t slots, std::size_t slot_bytes);

  // Copies `packet` into a free slot. When full: waits (wait_when_full) until a slot frees or
  // close() is called, or drops it. Returns false if the packet was not queued.
  bool push(std::span<const std::uint8_t> packet, bool wait_when_full);

  // Waits up to timeout_ms (< 0: forever) for a datagram and calls f(span) with it. Returns
  // false on timeout, or when closed and empty.
  template <class F>
  bool pop(F&& f, int timeout_ms);

  // Wakes every waiter; push() then refuses, pop() drains what is left and then returns false.
  void close();
  bool closed() const;

  std::uint64_t pushed() const;
  std::uint64_t dropped_full() const;
  std::uint64_t dropped_oversize() const;
  std::size_t size() const;
  std::size_t capacity() const { return slots_; }
  std::size_t high_water() const;  // most datagrams queued at once

 private:
  bool wait_for_packet(std::unique_lock<std::mutex>& lock, int timeout_ms);
  void release_front();

  std::size_t slots_;
  std::size_t slot_bytes_;
  std::unique_ptr<std::uint8_t[]> storage_;  // slots x slot_bytes, default-initialised
  std::unique_ptr<std::size_t[]> sizes_;     // (slots)
  mutable std::mutex mutex_;
  std::condition_variable not_empty_;
  std::condition_variable not_full_;
  std::size_t head_ = 0;  // oldest
  std::size_t count_ = 0;
  bool closed_ = false;
  std::uint64_t pushed_ = 0;
  std::uint64_t dropped_full_ = 0;
  std::uint64_t dropped_oversize_ = 0;
  std::size_t high_water_ = 0;
};

template <class F>
bool PacketQueue::pop(F&& f, int timeout_ms) {
  std::span<const std::uint8_t> packet;
  {
    std::unique_lock lock(mutex_);
    if (!wait_for_packet(lock, timeout_ms)) return false;
    packet = {storage_.get() + head_ * slot_bytes_, sizes_[head_]};
  }
  // the slot stays ours until release_front(): push() never writes the head slot
  try {
    f(packet);
  } catch (...) {
    release_front();
    throw;
  }
  release_front();
  return true;
}

}  // namespace sonarloop::atr
