// --realtime-priority (emulator/realtime_priority.h): SCHED_FIFO for the calling thread and
// locked memory where the system permits it, a message saying why where it does not; in a run,
// only the publisher thread is raised. Each outcome is checked against an oracle read from the
// system independently of the code under test (the effective capabilities and rlimits), so the
// tests assert on whichever outcome this machine must give.
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>

#include "config/loader/scenario_loader.h"
#include "emulator/emulator.h"
#include "emulator/realtime_priority.h"
#include "emulator/run_stats.h"
#include "tests/emulator/test_scenario.h"

using namespace sonarloop;
using namespace sonarloop::emulator;

namespace {

// Calls `fn` on the publisher thread with every ping it sends, as a device on the wire does
// (emulator/device.h).
class PingProbe final : public Device {
 public:
  explicit PingProbe(std::function<void()> fn) : fn_(std::move(fn)) {}
  void ping(const PingSlot&, std::span<const std::uint8_t>) override { fn_(); }
  bool on_wire() const override { return true; }
  std::vector<std::string> describe() const override { return {}; }

 private:
  std::function<void()> fn_;
};

constexpr int kCapIpcLock = 14;  // linux/capability.h
constexpr int kCapSysNice = 23;

// Whether the effective capability set (/proc/self/status CapEff) holds capability `bit`.
bool has_capability(int bit) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("CapEff:", 0) == 0) {
      const unsigned long long caps = std::stoull(line.substr(7), nullptr, 16);
      return (caps >> bit) & 1ULL;
    }
  }
  return false;
}

// The oracle for SCHED_FIFO at `priority`: CAP_SYS_NICE, or an RLIMIT_RTPRIO that allows it.
bool fifo_permitted(int priority) {
  if (has_capability(kCapSysNice)) return true;
  rlimit r{};
  return getrlimit(RLIMIT_RTPRIO, &r) == 0 &&
         (r.rlim_cur == RLIM_INFINITY || r.rlim_cur >= static_cast<rlim_t>(priority));
}

bool sanitizer_build() {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  return true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
  return true;
#else
  return false;
#endif
#else
  return false;
#endif
}

int thread_policy(int* priority = nullptr) {
  int policy = -1;
  sched_param p{};
  pthread_getschedparam(pthread_self(), &policy, &p);
  if (priority) *priority = p.sched_priority;
  return policy;
}

// Threads of this process whose scheduling policy (/proc/self/task/*/stat, field 41) is
// SCHED_FIFO.
int fifo_threads() {
  int n = 0;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
    std::ifstream in(task.path() / "stat");
    std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto close = stat.rfind(')');  // the command name may hold spaces
    if (close == std::string::npos) continue;
    std::istringstream fields(stat.substr(close + 2));
    std::string f;
    for (int i = 3; i <= 41 && fields >> f; ++i) {
      if (i == 41 && std::stoi(f) == SCHED_FIFO) ++n;
    }
  }
  return n;
}

// A paced run of the small scenario on 2 render threads, quiet, with a 5 ms lateness tolerance
// (a slow first render on a loaded machine, under the sanitizers, must not count as late).
EmulatorOptions paced_options(const char* rate, double duration_s) {
  EmulatorOptions o;
  o.rate = parse_rate(rate);
  o.threads = 2;
  o.duration_s = duration_s;
  o.stats_interval_s = 0;
  o.deadline_tolerance_s = 0.005;
  return o;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines)
    s += l + "\n";
  return s;
}

}  // namespace

TEST_CASE("realtime priority: SCHED_FIFO for the calling thread where permitted, else a reason") {
  const bool permitted = fifo_permitted(10);
  RealtimeOutcome out;
  int policy_after = -1, priority_after = -1, policy_of_child = -1;
  std::thread t([&] {
    apply_fifo_priority(10, out);
    policy_after = thread_policy(&priority_after);
    std::thread child([&] { policy_of_child = thread_policy(); });  // inherits its creator's
    child.join();
  });
  t.join();
  INFO(joined(out.messages));
  REQUIRE(out.messages.size() == 1);
  CHECK(out.priority == 10);
  CHECK(out.fifo == permitted);
  CHECK(thread_policy() == SCHED_OTHER);  // only the calling thread
  if (permitted) {
    CHECK(policy_after == SCHED_FIFO);
    CHECK(priority_after == 10);
    CHECK(policy_of_child == SCHED_FIFO);  // why the emulator raises the publisher last
    CHECK_THAT(out.messages[0], Catch::Contains("SCHED_FIFO at priority 10"));
    CHECK(out.summary() == "SCHED_FIFO 10, memory not locked");
  } else {
    CHECK(policy_after == SCHED_OTHER);
    CHECK_THAT(out.messages[0], Catch::Contains("refused") && Catch::Contains("normal priority"));
    CHECK(out.summary() == "normal");
  }
  CHECK_THROWS_AS(apply_fifo_priority(0, out), std::invalid_argument);
  CHECK_THROWS_AS(apply_fifo_priority(100, out), std::invalid_argument);
}

TEST_CASE("realtime priority: memory locked only where it cannot make allocations fail") {
  rlimit limit{};
  REQUIRE(getrlimit(RLIMIT_MEMLOCK, &limit) == 0);
  RealtimeOutcome out;
  lock_process_memory(out);
  INFO(joined(out.messages));
  REQUIRE(out.messages.size() == 1);
  if (sanitizer_build()) {
    CHECK_FALSE(out.memory_locked);
    CHECK_THAT(out.messages[0], Catch::Contains("sanitizer"));
  } else if (limit.rlim_cur != RLIM_INFINITY && !has_capability(kCapIpcLock)) {
    CHECK_FALSE(out.memory_locked);
    CHECK_THAT(out.messages[0], Catch::Contains("RLIMIT_MEMLOCK"));
  } else {
    CHECK(out.memory_locked);  // no limit, or CAP_IPC_LOCK: nothing stops mlockall
    CHECK_THAT(out.messages[0], Catch::Contains("memory locked"));
  }
  if (out.memory_locked) {
    std::ifstream in("/proc/self/status");
    std::string line, locked;
    while (std::getline(in, line))
      if (line.rfind("VmLck:", 0) == 0) locked = line;
    INFO(locked);
    CHECK(std::stoll(locked.substr(6)) > 0);  // kB locked
    munlockall();
  }
}

TEST_CASE("emulator --realtime-priority: the publisher alone runs SCHED_FIFO; the tolerance") {
  const bool permitted = fifo_permitted(10);
  EmulatorOptions o = paced_options("4", 1.0);
  o.realtime_priority = 10;
  MonotonicClock clock;
  std::vector<std::string> messages;
  int pings = 0, publisher_fifo = 0, fifo_tasks_max = 0;
  EmulatorHooks hooks;
  hooks.message = [&](std::string_view m) { messages.emplace_back(m); };
  Emulator emu(config::parse_scenario(testing::small_scenario_yaml(), "test.yaml"), o, clock,
               hooks);
  emu.add_device(std::make_unique<PingProbe>([&] {  // on the publisher thread
    ++pings;
    if (thread_policy() == SCHED_FIFO) ++publisher_fifo;
    fifo_tasks_max = std::max(fifo_tasks_max, fifo_threads());
  }));
  const RunStats s = emu.run();
  INFO(joined(messages));
  REQUIRE(pings > 0);
  CHECK(s.deadline_tolerance_ns == 5'000'000);
  CHECK_THAT(stats_json(s), Catch::Contains("\"deadline_tolerance_ms\": 5") &&
                                Catch::Contains("\"realtime\": \"" + s.realtime + "\""));
  if (permitted) {
    CHECK(publisher_fifo == pings);
    CHECK(fifo_tasks_max == 1);  // the render workers and the rest stay at normal priority
    CHECK_THAT(s.realtime, Catch::StartsWith("SCHED_FIFO 10"));
  } else {
    CHECK(publisher_fifo == 0);
    CHECK(s.realtime == "normal");
  }
  munlockall();  // a Release build as root locked this process's memory
}

TEST_CASE("emulator: a publisher held up is late by its own fault, not the renderer's") {
  // a device runs on the publisher: holding it 40 ms at ping 5 (a 26.7 ms ping period)
  // makes ping 6 about 13 ms late with its render long ready (16 pings are rendered ahead)
  const EmulatorOptions o = paced_options("realtime", 0.5);
  MonotonicClock clock;
  int pings = 0;
  EmulatorHooks hooks;
  hooks.message = [](std::string_view) {};
  Emulator emu(config::parse_scenario(testing::small_scenario_yaml(), "test.yaml"), o, clock,
               hooks);
  emu.add_device(std::make_unique<PingProbe>([&] {
    if (pings++ == 5) std::this_thread::sleep_for(std::chrono::milliseconds(40));
  }));
  const RunStats s = emu.run();
  INFO(stats_json(s));
  CHECK(s.pings_late >= 1);
  CHECK(s.pings_late_render == 0);
  CHECK(s.ping_lateness.max_ns() > 10'000'000);  // 40 ms held, one 26.7 ms period later
  CHECK_THAT(stats_json(s), Catch::Contains("\"late_render\": 0"));
}
