// The emulator in-process: --rate max determinism, the navigation it publishes against the
// vehicle's navigation model, the UDP size rule, and following an external pose (HIL) with a
// stale period.
#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>

#include "common/geodesy.h"
#include "config/loader/scenario_loader.h"
#include "drivers/can/candump_log.h"
#include "drivers/n2k/messages.h"
#include "drivers/net/udp_receiver.h"
#include "drivers/net/udp_sender.h"
#include "drivers/pose/pose_message.h"
#include "drivers/xtf/xtf_codec.h"
#include "drivers/xtf/xtf_file.h"
#include "emulator/emulator.h"
#include "emulator/mcap_device.h"
#include "sim/vehicle/nav_sensor.h"
#include "sim/vehicle/trajectory.h"
#include "tests/emulator/test_scenario.h"
#include "tests/support/temp_dir.h"
#include "units/angles.h"

using namespace sonarloop;
using namespace sonarloop::emulator;
using namespace sonarloop::pose;

namespace {

using sonarloop::testing::slurp;

config::Scenario small_scenario() {
  return config::parse_scenario(testing::small_scenario_yaml(), "test.yaml");
}

RunStats run_max(const std::string& dir, int threads, double duration_s) {
  EmulatorOptions o;
  o.rate = parse_rate("max");
  o.threads = threads;
  o.duration_s = duration_s;
  o.record_dir = dir;
  o.stats_interval_s = 0;
  MonotonicClock clock;
  EmulatorHooks hooks;
  hooks.message = [](std::string_view) {};
  Emulator emu(small_scenario(), o, clock, hooks);
  return emu.run();
}

// A pose message of a level vehicle (pitch and roll 0) at `where`, unstamped.
PoseMessage level_pose(std::uint32_t sequence, GeoPoint where, double depth_m, double heading_rad) {
  PoseMessage m;
  m.sequence = sequence;
  m.latitude_deg = where.latitude_deg;
  m.longitude_deg = where.longitude_deg;
  m.depth_m = depth_m;
  m.heading_rad = heading_rad;
  m.pitch_rad = 0.0;
  m.roll_rad = 0.0;
  return m;
}

std::size_t count_lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

}  // namespace

TEST_CASE("emulator --rate max: byte-identical recordings on 1 and 2 threads") {
  testing::TempDir dir("emu-determinism");
  const RunStats a = run_max(dir.file("a"), 1, 4.0);
  const RunStats b = run_max(dir.file("b"), 2, 4.0);
  // 4 s at the sonar's ping period (2 x 20 m / c): the pings with k·T < 4 s
  const config::Scenario sc = small_scenario();
  const SimTime period =
      from_seconds(render::make_sonar_setup(sc.sonar, sc.scene.water).ping_period_s);
  const auto pings = static_cast<std::size_t>((from_seconds(4.0) - 1) / period + 1);
  CHECK(pings > 140);
  CHECK(a.pings_sent == pings);
  CHECK(b.pings_sent == pings);
  CHECK(a.deadline_misses() == 0);
  CHECK(a.ping_lateness.count() == 0);  // no deadlines at --rate max
  CHECK_FALSE(a.has_pose_source);       // no --pose-from: no pose counters reported
  CHECK_THAT(stats_json(a), !Catch::Contains("\"pose_source\""));
  CHECK(a.epoch_utc_ns == kMaxRateEpochUtcNs);
  for (const char* f : {"pings.xtf", "nav.log", "truth.csv"}) {
    INFO(f);
    const std::string fa = slurp(dir.file(std::string("a/") + f));
    REQUIRE(!fa.empty());
    CHECK(fa == slurp(dir.file(std::string("b/") + f)));
  }
  const auto file = xtf::read_all_pings(dir.file("a/pings.xtf"));
  REQUIRE(file.pings.size() == pings);
  for (std::size_t k = 0; k < file.pings.size(); ++k)
    REQUIRE(file.pings[k].header.ping_number == k);
  CHECK(count_lines(slurp(dir.file("a/truth.csv"))) == pings + 1);  // header + a row per ping
  // 4 s of navigation: 3 PGNs at 10 Hz, 1 at 4 Hz, 4 at 1 Hz
  CHECK(a.nav_frames == 3 * 40 + 16 + 4 * 4);
}

TEST_CASE("emulator: nav.log carries the vehicle's navigation within the PGN resolution") {
  testing::TempDir dir("emu-nav");
  run_max(dir.file("r"), 2, 3.0);
  const config::Scenario sc = small_scenario();
  const vehicle::Trajectory traj(sc.vehicle.trajectory);  // constant depth: no seabed needed
  const vehicle::NavSensorModel nav(sc.vehicle.nav, sc.scene.seed);
  const LocalTangentPlane ltp(
      GeoPoint{sc.scene.origin.latitude_deg, sc.scene.origin.longitude_deg});
  can::CandumpReader reader(dir.file("r/nav.log"));
  int positions = 0, headings = 0, frames = 0;
  while (const auto rec = reader.next()) {
    ++frames;
    REQUIRE(rec->channel == "vcan0");
    const SimTime t = rec->t_ns - kMaxRateEpochUtcNs;  // stamped with epoch + sample time
    const vehicle::NavSolution want = nav.measure(traj.state_at(t));
    if (const auto p = n2k::decode<n2k::PositionRapidUpdate>(rec->frame)) {
      const GeoPoint g = ltp.to_geodetic(want.north_m, want.east_m);
      CHECK(*p->latitude_deg == Approx(g.latitude_deg).margin(0.51e-7));
      CHECK(*p->longitude_deg == Approx(g.longitude_deg).margin(0.51e-7));
      ++positions;
    } else if (const auto h = n2k::decode<n2k::VesselHeading>(rec->frame)) {
      CHECK(*h->heading_rad == Approx(want.heading).margin(0.51e-4));
      ++headings;
    }
  }
  CHECK(positions == 30);
  CHECK(headings == 30);
  CHECK(frames == 3 * 30 + 12 + 4 * 3);
}

TEST_CASE("emulator: a ping too large for one UDP datagram is refused, naming the limit") {
  CHECK(max_udp_samples_per_side(1) == 32544);
  CHECK(max_udp_samples_per_side(2) == 16272);
  CHECK(max_udp_samples_per_side(4) == 8136);
  // the limit is exact: at the limit the encoded ping fits, one more sample does not
  for (int bps : {1, 2, 4}) {
    const int n = max_udp_samples_per_side(bps);
    const auto size = [&](int samples) {
      return ((256 + 2 * (64 + samples * bps)) + 63) / 64 * 64;
    };
    CHECK(size(n) <= 65507);
    CHECK(size(n + 1) > 65507);
  }
  config::Scenario sc = small_scenario();
  sc.sonar.max_range_m = 200.0;
  sc.sonar.bin_size_m = 0.01;  // 20000 uint16 samples per side
  EmulatorOptions o;
  o.udp = net::parse_host_port("127.0.0.1:9");
  MonotonicClock clock;
  try {
    Emulator emu(sc, o, clock);
    FAIL("accepted");
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    CHECK(m.find("20000 samples per side") != std::string::npos);
    CHECK(m.find("at most 16272 samples per side") != std::string::npos);
    CHECK(m.find("uint16") != std::string::npos);
  }
  // without --udp it is fine (recording only)
  o.udp.reset();
  o.rate = parse_rate("max");
  CHECK_NOTHROW(Emulator(sc, o, clock));
}

namespace {

// One hardware-in-the-loop run: 2.5 s of the small scenario at real time, recorded into
// DIR/hil, its pose from UDP on 127.0.0.1 (stale after `stale_after_s`), sent by `send` on a
// thread of its own once the run has started, at `where` (12 m west of the planned line).
struct HilRun {
  RunStats stats;
  std::vector<std::string> messages;  // everything the emulator said
  GeoPoint where;
};

HilRun run_hil(const testing::TempDir& dir, double stale_after_s,
               const std::function<void(net::UdpSender&, const GeoPoint&)>& send) {
  std::uint16_t port = 0;  // a free UDP port for the pose source
  {
    net::UdpReceiver probe(net::parse_host_port("127.0.0.1:0"));
    port = probe.bound_port();
  }
  const config::Scenario sc = small_scenario();
  const LocalTangentPlane ltp(
      GeoPoint{sc.scene.origin.latitude_deg, sc.scene.origin.longitude_deg});
  HilRun run;
  run.where = ltp.to_geodetic(10.0, -12.0);

  EmulatorOptions o;
  o.rate = parse_rate("realtime");
  o.threads = 1;
  o.duration_s = 2.5;
  o.record_dir = dir.file("hil");
  o.pose_from = "udp:127.0.0.1:" + std::to_string(port);
  o.stale_after_s = stale_after_s;
  o.stats_interval_s = 0;
  MonotonicClock clock;
  std::mutex mu;
  std::atomic<bool> started{false};
  EmulatorHooks hooks;
  hooks.message = [&](std::string_view m) {
    std::lock_guard<std::mutex> lock(mu);
    run.messages.emplace_back(m);
    if (m.find("scene for the first ping") != std::string_view::npos)
      started = true;  // t = 0 follows
  };
  Emulator emu(sc, o, clock, hooks);
  std::thread sender([&] {
    net::UdpSender tx(net::parse_host_port("127.0.0.1:" + std::to_string(port)));
    // (bounded, so that a changed start-up message fails the test instead of hanging it)
    for (int w = 0; !started && w < 10000; ++w)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    send(tx, run.where);
  });
  run.stats = emu.run();
  sender.join();
  return run;
}

}  // namespace

TEST_CASE("emulator --pose-from: pings follow the external pose and pause while it is stale") {
  testing::TempDir dir("emu-hil");
  // the external vehicle: 1 s of poses at 50 Hz once the run starts, then silence
  const HilRun run = run_hil(dir, 0.4, [](net::UdpSender& tx, const GeoPoint& where) {
    for (std::uint32_t i = 0; i < 50; ++i) {
      tx.send(encode_pose_message(level_pose(i, where, 12.0, 0.3)));
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  const RunStats& s = run.stats;
  const GeoPoint& where = run.where;
  const std::vector<std::string>& messages = run.messages;

  CHECK(s.pings_sent > 0);
  CHECK(s.pings_stale > 0);
  CHECK(s.stale_episodes >= 1);
  CHECK(s.nav_frames_withheld > 0);
  // one warning per episode without a fresh pose: possibly "no pose received yet" (if ping 0
  // came before the first message), then "stale" once the sender stopped
  std::size_t warnings = 0, stale_warnings = 0;
  for (const auto& m : messages) {
    if (m.rfind("warning", 0) != 0) continue;
    ++warnings;
    if (m.find("stale") != std::string::npos) ++stale_warnings;
  }
  CHECK(warnings == s.stale_episodes);
  CHECK(stale_warnings == 1);
  // every recorded ping was rendered at the external pose, and says so in its navigation
  const auto file = xtf::read_all_pings(dir.file("hil/pings.xtf"));
  REQUIRE(file.pings.size() == s.pings_sent);
  for (const auto& p : file.pings) {
    CHECK(p.header.sensor_y == Approx(where.latitude_deg).margin(1e-9));
    CHECK(p.header.sensor_x == Approx(where.longitude_deg).margin(1e-9));
    CHECK(p.header.sensor_depth_m == Approx(12.0f));
    CHECK(p.header.sensor_heading_deg == Approx(0.3 * 180.0 / M_PI).margin(1e-4));
  }
  const std::string truth = slurp(dir.file("hil/truth.csv"));
  CHECK(truth.find(",external\n") != std::string::npos);
  CHECK(truth.find(",trajectory\n") == std::string::npos);
}

namespace {

// A clock whose every reading is 10 s after the previous one: start-up looks very slow.
class SlowStartClock final : public Clock {
 public:
  std::int64_t now_ns() const override { return t_ns_ += 10'000'000'000; }
  std::int64_t utc_now_ns() const override { return now_ns(); }
  std::int64_t process_cpu_ns() const override { return 0; }
  void sleep_until(std::int64_t) override {}

 private:
  mutable std::int64_t t_ns_ = 0;
};

// The small scenario with a 1 km line sampled every 5 cm: 20,001 seabed points to plan on.
config::Scenario long_line_scenario() {
  config::Scenario sc = small_scenario();
  sc.vehicle.trajectory.straight_length_m = 1000.0;
  sc.vehicle.trajectory.depth.profile_step_m = 0.05;
  return sc;
}

}  // namespace

TEST_CASE("emulator: a long trajectory's start-up reports progress and honours a stop request") {
  EmulatorOptions o;
  o.rate = parse_rate("max");
  o.threads = 1;
  o.duration_s = 1.0;
  o.stats_interval_s = 0;
  std::vector<std::string> messages;
  EmulatorHooks hooks;
  hooks.message = [&](std::string_view m) { messages.emplace_back(m); };
  SECTION("progress while the seabed is sampled along the path") {
    SlowStartClock clock;
    Emulator emu(long_line_scenario(), o, clock, hooks);
    const auto progress = std::count_if(messages.begin(), messages.end(), [](const auto& m) {
      return m.find("preparing: sampling the seabed along the vehicle's path") == 0 &&
             m.find("of 20001 points; Ctrl-C stops)") != std::string::npos;
    });
    CHECK(progress >= 2);
  }
  SECTION("a stop request during the planning abandons the start-up") {
    MonotonicClock clock;
    int polls = 0;
    hooks.stop_requested = [&] { return ++polls >= 3; };  // within the seabed sampling
    CHECK_THROWS_AS(Emulator(long_line_scenario(), o, clock, hooks), StartupStopped);
    CHECK(polls == 3);
  }
}

namespace {

// Flies the small scenario for 3 s in real time following a 10 Hz UDP pose source that moves
// north at 2 m/s (each message stamped with its own time, as tools/send_pose.py does), with
// --pose-delay `delay_s`; returns the recorded pings (number, north, east) and the stats.
struct PingAt {
  std::uint32_t number = 0;
  Vec2 ne = Vec2::Zero();
};
std::pair<std::vector<PingAt>, RunStats> fly_10hz_pose_source(const std::string& dir,
                                                              double delay_s) {
  std::uint16_t port = 0;
  {
    net::UdpReceiver probe(net::parse_host_port("127.0.0.1:0"));
    port = probe.bound_port();
  }
  const config::Scenario sc = small_scenario();
  const LocalTangentPlane ltp(
      GeoPoint{sc.scene.origin.latitude_deg, sc.scene.origin.longitude_deg});
  EmulatorOptions o;
  o.rate = parse_rate("realtime");
  o.threads = 2;
  o.duration_s = 3.0;
  o.record_dir = dir;
  o.pose_from = "udp:127.0.0.1:" + std::to_string(port);
  o.pose_delay_s = delay_s;
  o.stats_interval_s = 0;
  MonotonicClock clock;
  EmulatorHooks hooks;
  hooks.message = [](std::string_view) {};
  Emulator emu(sc, o, clock, hooks);
  std::atomic<bool> done{false};
  std::thread sender([&] {
    net::UdpSender tx(net::parse_host_port("127.0.0.1:" + std::to_string(port)));
    const auto t0 = std::chrono::system_clock::now();
    const auto start = std::chrono::steady_clock::now();
    for (std::uint32_t i = 0; !done && i < 600; ++i) {
      const auto now = std::chrono::system_clock::now();
      const double s = std::chrono::duration<double>(now - t0).count();
      const GeoPoint g = ltp.to_geodetic(-20.0 + 2.0 * s, -3.0);
      PoseMessage m = level_pose(i, g, 14.0, 0.0);
      m.time_unix_ns =
          std::chrono::duration_cast<std::chrono::nanoseconds>(now.time_since_epoch()).count();
      tx.send(encode_pose_message(m));
      std::this_thread::sleep_until(start + std::chrono::milliseconds(100) * (i + 1));
    }
  });
  const RunStats s = emu.run();
  done = true;
  sender.join();
  std::vector<PingAt> pings;
  for (const auto& p : xtf::read_all_pings(dir + "/pings.xtf").pings) {
    pings.push_back(
        {p.header.ping_number, ltp.to_local(GeoPoint{p.header.sensor_y, p.header.sensor_x})});
  }
  return {pings, s};
}

// Checks that consecutive pings are evenly spaced along track (the speed times the ping period,
// per ping number: a ping dropped by a loaded machine leaves a gap of two steps), after the
// first 0.3 s (before the second pose sample a ping can only hold the first).
void check_even_spacing(const std::vector<PingAt>& pings, const RunStats& s) {
  const double step_m = 2.0 * 0.02667;
  REQUIRE(pings.size() > 40);
  REQUIRE(s.pings_sent == pings.size());
  int uneven = 0;
  for (std::size_t k = 12; k < pings.size(); ++k) {
    const double step = (pings[k].ne - pings[k - 1].ne).norm();
    const double expected_m = step_m * (pings[k].number - pings[k - 1].number);
    const bool even = std::abs(step - expected_m) < 0.2 * step_m;
    if (!even) {
      ++uneven;
      UNSCOPED_INFO("ping " << k << ": " << step << " m from the previous one");
    }
  }
  // stale pings (none expected) would break the sequence: say so
  INFO(s.pings_stale << " stale pings, " << s.pings_extrapolated << " extrapolated");
  CHECK(uneven == 0);
}

}  // namespace

TEST_CASE("emulator --pose-from: pings from a 10 Hz pose source are evenly spaced along track") {
  testing::TempDir dir("emu-pose-spacing");
  // interpolated (default delay): the waterfall does not stutter at the pose rate
  const auto [ne, s] = fly_10hz_pose_source(dir.file("interp"), 0.1);
  check_even_spacing(ne, s);
  CHECK(s.pings_extrapolated < s.pings_sent);
  // no delay: every ping extrapolated from the last two samples, still even for even motion
  const auto [ne0, s0] = fly_10hz_pose_source(dir.file("extrap"), 0.0);
  check_even_spacing(ne0, s0);
  CHECK(s0.pings_extrapolated > s0.pings_sent / 2);
}

TEST_CASE("emulator --pose-from: a source of absurd poses stalls the pings; they resume after") {
  testing::TempDir dir("emu-hil-absurd");
  // 50 Hz: 0.5 s plausible, 1 s at a depth of 5 km (below the scene's deepest seabed), plausible
  // again
  const HilRun run = run_hil(dir, 0.3, [](net::UdpSender& tx, const GeoPoint& where) {
    for (std::uint32_t i = 0; i < 110; ++i) {
      const bool absurd = i >= 25 && i < 75;
      tx.send(encode_pose_message(level_pose(i, where, absurd ? 5000.0 : 12.0, 0.3)));
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  const RunStats& s = run.stats;
  const std::vector<std::string>& messages = run.messages;

  CHECK(s.pings_sent > 0);
  CHECK(s.pings_stale > 0);
  CHECK(s.stale_episodes >= 1);
  const auto said = [&](std::string_view text) {
    return std::any_of(messages.begin(), messages.end(),
                       [&](const std::string& m) { return m.find(text) != std::string::npos; });
  };
  // the rejection warned about (rate-limited: far fewer lines than the 50 rejected messages),
  // the pause and the resumption said
  const auto rejections = std::count_if(messages.begin(), messages.end(), [](const auto& m) {
    return m.rfind("warning: udp pose on", 0) == 0 &&
           m.find("implausible pose rejected") != std::string::npos;
  });
  CHECK(rejections >= 1);
  CHECK(rejections <= 3);
  CHECK(said("depth 5000 m is below the scene's deepest seabed"));
  CHECK(said("pings paused"));
  CHECK(said("pings resumed"));
  // the run's statistics count them: all 50 absurd messages (sent 0.5 s to 1.5 s into the 2.5 s
  // run) rejected, the plausible ones that arrived before the end as updates
  CHECK(s.has_pose_source);
  CHECK(s.pose_rejected == 50);
  CHECK(s.pose_updates >= 25);
  CHECK(s.pose_updates <= 60);
  CHECK(s.pose_malformed == 0);
  CHECK_THAT(stats_json(s), Catch::Contains("\"pose_source\"") && Catch::Contains("\"rejected\""));
  // no ping at the absurd depth
  const auto file = xtf::read_all_pings(dir.file("hil/pings.xtf"));
  REQUIRE(file.pings.size() == s.pings_sent);
  for (const auto& p : file.pings)
    CHECK(p.header.sensor_depth_m == Approx(12.0f));
}

TEST_CASE("emulator --pose-from: a vehicle pitched 89.5° still gets its pings, and the run ends") {
  // issue 29: a pitch between about 80° and 90° passed the plausibility check, then each ping
  // took 2-46 s to render, every ping was dropped and the run outlived its duration
  testing::TempDir dir("emu-hil-steep");
  const HilRun run = run_hil(dir, 0.5, [](net::UdpSender& tx, const GeoPoint& where) {
    for (std::uint32_t i = 0; i < 120; ++i) {
      PoseMessage m = level_pose(i, where, 12.0, 0.3);
      m.pitch_rad = 89.5 * sonarloop::kRadPerDeg;
      tx.send(encode_pose_message(m));
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  const RunStats& s = run.stats;
  CHECK(s.pose_rejected == 0);  // a plausible attitude: accepted, and rendered
  CHECK(s.pings_sent > 0);
  CHECK(s.pings_rendered >= s.pings_sent);
  // the beam planes run nearly level: nothing in range, the pings are dark
  const auto file = xtf::read_all_pings(dir.file("hil/pings.xtf"));
  REQUIRE(file.pings.size() == s.pings_sent);
  for (const auto& p : file.pings)
    CHECK(p.header.sensor_pitch_deg == Approx(89.5f));
}

namespace {

// A device of the caller's that notes when it is closed.
class ClosingDevice final : public Device {
 public:
  ClosingDevice(std::vector<std::string>& closed, std::string name)
      : closed_(closed), name_(std::move(name)) {}
  bool on_wire() const override { return false; }
  std::vector<std::string> describe() const override { return {}; }
  void close() override { closed_.push_back(name_); }

 private:
  std::vector<std::string>& closed_;
  std::string name_;
};

}  // namespace

TEST_CASE("emulator: devices close in the reverse order of their adding; find_device") {
  testing::TempDir dir("emu-close-order");
  EmulatorOptions o;
  o.rate = parse_rate("max");
  o.duration_s = 0.5;
  o.mcap_path = dir.file("plain.mcap");
  o.stats_interval_s = 0;
  MonotonicClock clock;
  EmulatorHooks hooks;
  hooks.message = [](std::string_view) {};
  // the same run without contacts: its message count
  const std::uint64_t plain = Emulator(small_scenario(), o, clock, hooks).run().mcap_messages;
  REQUIRE(plain > 0);
  o.mcap_path = dir.file("r.mcap");
  std::vector<std::string> closed;
  Emulator emu(small_scenario(), o, clock, hooks);
  CHECK(emu.find_device<ClosingDevice>() == nullptr);
  REQUIRE(emu.find_device<McapDevice>() != nullptr);
  emu.add_device(std::make_unique<ClosingDevice>(closed, "first"));
  emu.add_device(std::make_unique<ClosingDevice>(closed, "second"));
  CHECK(emu.find_device<ClosingDevice>() == emu.devices()[emu.devices().size() - 2]);
  // the MCAP recording (the emulator's own) is still open when the added devices close: a
  // contact given then is in the file (a string and a fix)
  McapDevice* mcap = emu.find_device<McapDevice>();
  mcap->record_contacts();
  struct Feeder final : Device {
    McapDevice* mcap;
    explicit Feeder(McapDevice* m) : mcap(m) {}
    bool on_wire() const override { return false; }
    std::vector<std::string> describe() const override { return {}; }
    void close() override { mcap->add_contact({std::nullopt, 1, 0.0, 0.0, "{\"late\":1}"}); }
  };
  emu.add_device(std::make_unique<Feeder>(mcap));
  const RunStats stats = emu.run();
  CHECK(closed == std::vector<std::string>{"second", "first"});
  CHECK(stats.mcap_error.empty());
  CHECK(stats.mcap_messages == plain + 2);
}
