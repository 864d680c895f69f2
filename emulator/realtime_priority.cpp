// Real-time priority for the publisher thread (realtime_priority.h).
#include "emulator/realtime_priority.h"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/resource.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

namespace sonarloop::emulator {

namespace {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitizerBuild = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
constexpr bool kSanitizerBuild = true;
#else
constexpr bool kSanitizerBuild = false;
#endif
#else
constexpr bool kSanitizerBuild = false;
#endif

std::string errno_text(int err) {
  return std::strerror(err);
}

constexpr int kCapIpcLock = 14;  // linux/capability.h: locking beyond RLIMIT_MEMLOCK

// Whether the process's effective capabilities (/proc/self/status, CapEff) hold `bit`.
bool has_effective_capability(int bit) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("CapEff:", 0) == 0) {
      return (std::stoull(line.substr(7), nullptr, 16) >> bit) & 1ULL;
    }
  }
  return false;
}

// SCHED_FIFO for the calling thread; a message either way.
bool apply_fifo(int priority, std::vector<std::string>& messages) {
  sched_param param{};
  param.sched_priority = priority;
  const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  if (err == 0) {
    messages.push_back("real-time priority: the publisher runs SCHED_FIFO at priority " +
                       std::to_string(priority));
    return true;
  }
  std::string why = errno_text(err);
  if (err == EPERM) {
    why += " (needs root, CAP_SYS_NICE, or an rtprio limit of at least " +
           std::to_string(priority) + ": `ulimit -r`, /etc/security/limits.conf)";
  }
  messages.push_back("real-time priority refused: SCHED_FIFO " + std::to_string(priority) + ": " +
                     why + "; the publisher runs at normal priority");
  return false;
}

// mlockall where it cannot make later allocations fail; a message either way.
bool apply_memory_lock(std::vector<std::string>& messages) {
  if (kSanitizerBuild) {
    messages.push_back(
        "memory not locked: a sanitizer build (its shadow memory is too large to lock)");
    return false;
  }
  rlimit limit{};
  if (getrlimit(RLIMIT_MEMLOCK, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
      !has_effective_capability(kCapIpcLock)) {
    messages.push_back(
        "memory not locked: RLIMIT_MEMLOCK is " + std::to_string(limit.rlim_cur / 1024) +
        " KiB without CAP_IPC_LOCK (`ulimit -l unlimited` to lock; a finite limit would make later "
        "allocations fail)");
    return false;
  }
  // MCL_ONFAULT: a page is locked once touched, not the whole of every mapping at once (thread
  // stacks, the allocator's reserves: about 300 MB that nothing uses)
  if (mlockall(MCL_CURRENT | MCL_FUTURE | MCL_ONFAULT) == 0) {
    messages.push_back("memory locked (mlockall: current and future pages, once touched)");
    return true;
  }
  // a kernel before 4.4 has no MCL_ONFAULT (EINVAL): every page of every mapping, then
  if (errno != EINVAL || mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    messages.push_back("memory not locked: mlockall: " + errno_text(errno));
    return false;
  }
  messages.push_back("memory locked (mlockall: current and future pages)");
  return true;
}

}  // namespace

std::string RealtimeOutcome::summary() const {
  if (!fifo && !memory_locked) return "normal";
  std::string s = fifo ? "SCHED_FIFO " + std::to_string(priority) : "normal priority";
  s += memory_locked ? ", memory locked" : ", memory not locked";
  return s;
}

void lock_process_memory(RealtimeOutcome& out) {
  out.memory_locked = apply_memory_lock(out.messages);
}

void apply_fifo_priority(int priority, RealtimeOutcome& out) {
  if (priority < kMinRealtimePriority || priority > kMaxRealtimePriority) {
    throw std::invalid_argument(
        "real-time priority must be " + std::to_string(kMinRealtimePriority) + ".." +
        std::to_string(kMaxRealtimePriority) + ", not " + std::to_string(priority));
  }
  out.priority = priority;
  out.fifo = apply_fifo(priority, out.messages);
}

}  // namespace sonarloop::emulator
