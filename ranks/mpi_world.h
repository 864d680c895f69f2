#pragma once
// The processes of one `sonarloop` run: rank 0 .. size-1 of an MPI job started by `mpirun`, or
// a world of one. This is the only place that talks to MPI (ranks/mpi_world.cpp); with MPI not
// found at build time (SONARLOOP_HAVE_MPI unset) every function here is the one-process
// version, so callers never need an #ifdef.
//
// When MPI starts: only at start(), which only `sweep` and `dataset` call, and only when the
// process was launched by an MPI launcher (OMPI_COMM_WORLD_SIZE set by Open MPI's mpirun, or
// PMI_SIZE / PMIX_RANK by other launchers). Any other command, and these two when run
// directly, never initialise MPI: a plain `sonarloop run` only pays for loading the shared
// library. MPI_Finalize runs at exit.
//
// Messages are blocking for the caller but waited for by polling with short sleeps (up to
// kMaxPollSleep_us), so a rank waiting for another does not spin a core that its render threads
// need (Open MPI's own blocking calls busy-wait). Only the thread that called start() may call
// the messaging functions (MPI_THREAD_FUNNELED).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace sonarloop::ranks::mpi {

// Longest sleep between two polls of a pending message, in microseconds: a rank waiting for its
// turn wakes at most 1000 times a second (each poll runs Open MPI's progress engine, a few
// system calls); rank 0 finds the other ranks' chips already waiting when they render ahead.
inline constexpr int kMaxPollSleep_us = 1000;

// Whether this binary was built with MPI.
bool built_with_mpi();
// Whether an MPI launcher started this process (see the header comment).
bool launched_by_mpi();

// Initialises MPI when built with it and launched by mpirun; otherwise (or when called again)
// does nothing. Throws std::runtime_error when MPI fails to start.
void start();

int rank();  // 0 in a world of one
int size();  // 1 in a world of one
inline bool is_root() {
  return rank() == 0;
}

// A received message: who sent it, its tag, its bytes.
struct Message {
  int source = 0;
  int tag = 0;
  std::vector<std::byte> bytes;
};

// Sends `bytes` to `dest` and returns once `dest` has started receiving them (a synchronous
// send: the sender never runs ahead of the receiver by more than one message). `while_waiting`
// (optional) is called between polls. Throws std::logic_error in a world of one.
void send(int dest, int tag, std::span<const std::byte> bytes,
          const std::function<void()>& while_waiting = {});
// Whether a message from `source` (with tag `tag`, or any tag when tag < 0) is waiting.
bool message_waiting(int source, int tag = -1);
// Receives the next message from `source` (with tag `tag`, or any tag when tag < 0), waiting
// for it. `while_waiting` (optional) is called between polls.
Message receive(int source, int tag = -1, const std::function<void()>& while_waiting = {});

// Called by main() after a command failed with `exit_code`: in a job of several ranks, ends
// them all (MPI_Abort), since the others would wait for this one forever; otherwise returns
// exit_code.
int end_after_error(int exit_code);

// Default worker threads per process: the CPUs this process may run on (its affinity mask, which
// mpirun narrows when it binds ranks to cores), at least 1.
int default_threads();

}  // namespace sonarloop::ranks::mpi
