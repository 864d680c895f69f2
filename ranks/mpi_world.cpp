#include "ranks/mpi_world.h"

#include <sched.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <thread>

#ifdef SONARLOOP_HAVE_MPI
// the C API only: the deprecated C++ bindings do not compile cleanly under our warnings
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace sonarloop::ranks::mpi {
namespace {

// The state of this process's world: a world of one until start() brings MPI up.
struct World {
  bool running = false;  // MPI_Init done, MPI_Finalize not yet
  int rank = 0;
  int size = 1;
  ~World();
};

World& world() {
  static World w;
  return w;
}

#ifdef SONARLOOP_HAVE_MPI

// Waits until `done()` holds, sleeping between polls (10 µs doubling up to kMaxPollSleep_us).
void poll_until(const std::function<bool()>& done, const std::function<void()>& while_waiting) {
  int sleep_us = 10;
  while (!done()) {
    if (while_waiting) while_waiting();
    std::this_thread::sleep_for(std::chrono::microseconds(sleep_us));
    sleep_us = std::min(2 * sleep_us, kMaxPollSleep_us);
  }
}

void check(int rc, const char* what) {
  if (rc != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

#endif

}  // namespace

#ifdef SONARLOOP_HAVE_MPI

World::~World() {
  if (running) MPI_Finalize();
}

bool built_with_mpi() {
  return true;
}

void start() {
  World& w = world();
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (initialised || !launched_by_mpi()) return;
  int provided = 0;
  check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  w.running = true;
  if (provided < MPI_THREAD_FUNNELED) {
    throw std::runtime_error("MPI: the library does not support MPI_THREAD_FUNNELED");
  }
  check(MPI_Comm_rank(MPI_COMM_WORLD, &w.rank), "MPI_Comm_rank");
  check(MPI_Comm_size(MPI_COMM_WORLD, &w.size), "MPI_Comm_size");
}

void send(int dest, int tag, std::span<const std::byte> bytes,
          const std::function<void()>& while_waiting) {
  if (!world().running) throw std::logic_error("mpi::send in a world of one");
  if (bytes.size() > static_cast<std::size_t>(INT_MAX)) {
    throw std::length_error("mpi::send: message over 2 GiB");
  }
  MPI_Request request = MPI_REQUEST_NULL;
  check(MPI_Issend(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, dest, tag,
                   MPI_COMM_WORLD, &request),
        "MPI_Issend");
  poll_until(
      [&] {
        int done = 0;
        check(MPI_Test(&request, &done, MPI_STATUS_IGNORE), "MPI_Test");
        return done != 0;
      },
      while_waiting);
}

bool message_waiting(int source, int tag) {
  if (!world().running) return false;
  int flag = 0;
  check(MPI_Iprobe(source, tag < 0 ? MPI_ANY_TAG : tag, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE),
        "MPI_Iprobe");
  return flag != 0;
}

Message receive(int source, int tag, const std::function<void()>& while_waiting) {
  if (!world().running) throw std::logic_error("mpi::receive in a world of one");
  MPI_Status status{};
  poll_until(
      [&] {
        int flag = 0;
        check(MPI_Iprobe(source, tag < 0 ? MPI_ANY_TAG : tag, MPI_COMM_WORLD, &flag, &status),
              "MPI_Iprobe");
        return flag != 0;
      },
      while_waiting);
  int count = 0;
  check(MPI_Get_count(&status, MPI_BYTE, &count), "MPI_Get_count");
  Message m;
  m.source = status.MPI_SOURCE;
  m.tag = status.MPI_TAG;
  m.bytes.resize(static_cast<std::size_t>(count));
  check(
      MPI_Recv(m.bytes.data(), count, MPI_BYTE, m.source, m.tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
      "MPI_Recv");
  return m;
}

int end_after_error(int exit_code) {
  const World& w = world();
  if (w.running && w.size > 1) {
    std::fflush(stdout);
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, exit_code);
  }
  return exit_code;
}

#else  // a world of one

World::~World() = default;

bool built_with_mpi() {
  return false;
}

void start() {}

void send(int, int, std::span<const std::byte>, const std::function<void()>&) {
  throw std::logic_error("mpi::send: this sonarloop was built without MPI");
}

bool message_waiting(int, int) {
  return false;
}

Message receive(int, int, const std::function<void()>&) {
  throw std::logic_error("mpi::receive: this sonarloop was built without MPI");
}

int end_after_error(int exit_code) {
  return exit_code;
}

#endif

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"}) {
    if (std::getenv(name)) return true;
  }
  return false;
}

int rank() {
  return world().rank;
}

int size() {
  return world().size;
}

int default_threads() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

}  // namespace sonarloop::ranks::mpi
