#pragma once
// Real-time priority for the publisher (issue 11 §2): on a shared machine a busy neighbour can
// delay the thread that sends each ping at its deadline. `run --realtime-priority N` asks for
//  - SCHED_FIFO at priority N (1..99) for the calling thread only (the publisher; the render
//    workers, which compute for milliseconds at a time, stay at normal priority so that they
//    cannot starve the machine), and
//  - mlockall(MCL_CURRENT | MCL_FUTURE | MCL_ONFAULT): no page fault of the publisher waits for
//    the disk. Pages are locked as they are touched (ONFAULT), so that the reserved but unused
//    parts of mappings (thread stacks, the allocator's arenas) stay out of memory.
// Each part is applied where the system permits it (root, CAP_SYS_NICE / CAP_IPC_LOCK, or
// rtprio / memlock limits) and otherwise refused with a message saying why and what to change;
// the run goes on at normal priority either way.
#include <string>
#include <vector>

namespace sonarloop::emulator {

inline constexpr int kMinRealtimePriority = 1;
inline constexpr int kMaxRealtimePriority = 99;

struct RealtimeOutcome {
  int priority = 0;            // requested
  bool fifo = false;           // the calling thread runs SCHED_FIFO at the requested priority
  bool memory_locked = false;  // mlockall(MCL_CURRENT | MCL_FUTURE | MCL_ONFAULT) succeeded
  std::vector<std::string> messages;  // one line each: what was applied or refused, and why
  // "SCHED_FIFO 50, memory locked", "SCHED_FIFO 50, memory not locked", "normal" ...
  std::string summary() const;
};

// Locks the process's memory (mlockall, current and future pages) and records the outcome in
// `out`. Never in a sanitizer build (the sanitizers' shadow memory is terabytes of reserved
// address space) nor when RLIMIT_MEMLOCK is finite without CAP_IPC_LOCK (MCL_FUTURE would then
// make later allocations fail once the limit is reached): both are said in a message. Pages
// already touched are locked at once, the others when first touched: call it before the clock
// starts, once the first ping's scene is made.
void lock_process_memory(RealtimeOutcome& out);

// Puts the calling thread on SCHED_FIFO at `priority` (kMinRealtimePriority..kMaxRealtimePriority,
// else std::invalid_argument) and records the outcome in `out`. Threads created afterwards by this
// thread inherit the policy: call it once the worker threads run.
void apply_fifo_priority(int priority, RealtimeOutcome& out);

}  // namespace sonarloop::emulator
