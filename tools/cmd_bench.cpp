// sonarloop bench: machine-readable speed figures, one JSON object per line on stdout. Every
// speed section measures the profile renderer and the ray-traced reference side by side in the
// same run and reports their ratio (the machine may be shared: ratios taken together are what
// compare). Accuracy sections are in bench_accuracy.cpp.
#include <sys/utsname.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "bench/bench_accuracy.h"
#include "config/loader/sonar_loader.h"
#include "drivers/json/json_writer.h"
#include "emulator/emulator.h"
#include "sim/render/chip_renderer.h"
#include "sim/render/raytrace_renderer.h"
#include "sim/render/track_renderer.h"
#include "sim/scene/scene.h"
#include "tools/args.h"
#include "tools/commands.h"
#include "tools/progress.h"
#include "tools/scenario_source.h"

namespace sonarloop::tools {
namespace {

using Clock = std::chrono::steady_clock;

// One JSON object as a line on stdout, flushed (what every section prints).
void emit(const json::Writer& w) {
  std::printf("%s\n", w.str().c_str());
  std::fflush(stdout);
}

// The accuracy sections' output: JSON lines on stdout, a progress bar per section on stderr.
class SectionPrinter {
 public:
  bench::SectionOutput output() {
    return {emit, [this](const std::string& label, double done, double total) {
              if (!bar_ || label != label_) {
                bar_ = std::make_unique<Progress>(label, total);
                label_ = label;
              }
              bar_->update(done);
              if (done >= total) {
                bar_->finish();
                bar_.reset();
              }
            }};
  }

 private:
  std::unique_ptr<Progress> bar_;
  std::string label_;
};
using render::RendererKind;
constexpr RendererKind kKinds[] = {RendererKind::kProfile, RendererKind::kRaytrace};

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown";
}

void emit_ratio(const char* bench, const char* what, double profile, double raytrace) {
  json::Writer w;
  w.begin_object().field("bench", bench).field("ratio", what);
  w.field("profile", profile, 5).field("raytrace", raytrace, 5);
  w.field("raytrace_over_profile", profile > 0 ? raytrace / profile : 0.0, 4);
  w.end_object();
  emit(w);
}

// A straight north-going line of pings.
std::vector<Pose> line_poses(double north0, double east, double length, double spacing,
                             double depth) {
  std::vector<Pose> p(static_cast<std::size_t>(std::floor(length / spacing)) + 1);
  for (std::size_t k = 0; k < p.size(); ++k) {
    p[k].position_W = Vec3(north0 + static_cast<double>(k) * spacing, east, depth);
    p[k].yaw = 0.0;
  }
  return p;
}

render::SonarDesc bench_sonar(const config::Scenario& s, double range_m, double pixel_m) {
  return bench::isotropic_strip_sonar(s.sonar, range_m, pixel_m);
}

// Renders `poses` with `threads` threads (render_track: prepares ahead, renders, in order);
// returns the wall time.
double render_poses(const scene::Scene& sc, const render::PingRenderer& r,
                    const std::vector<Pose>& poses, int threads) {
  render::TrackRenderOptions opt;
  opt.threads = threads;
  const auto t0 = Clock::now();
  render::render_track(
      sc, r, poses, 1, opt,
      [](std::size_t, const render::PingLines&, std::span<const render::TargetTrace>) {});
  return seconds_since(t0);
}

// (a) a 50 m x 50 m image at 5 cm: 1000 pings, 25 m range per side. cold = scenario text ->
// last ping (parse, scene, renderer, tiles or views, pings); warm = the same pings again
void bench_image(const std::optional<std::string>& path, int threads) {
  const double pixel = 0.05;
  double cold[2] = {0, 0}, warm[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    const RendererKind kind = kKinds[i];
    auto t0 = Clock::now();
    const config::Scenario s = load_scenario_or_default(path);
    const double parse_s = seconds_since(t0);
    t0 = Clock::now();
    const render::SonarDesc sd = bench_sonar(s, 25.0, pixel);
    const scene::Scene sc(s.scene);
    const render::SonarSetup setup = render::make_sonar_setup(sd, s.scene.water);
    const auto r = render::make_ping_renderer(kind, setup);
    const double setup_s = seconds_since(t0);
    const auto poses = line_poses(-25.0, 0.0, 50.0 - pixel, pixel, s.scene.water.depth_m - 6.0);
    const double pings_s = render_poses(sc, *r, poses, threads);
    const std::uint64_t tiles = sc.seabed().tiles_made();
    warm[i] = render_poses(sc, *r, poses, threads);
    const double one_thread_s = render_poses(sc, *r, poses, 1);
    cold[i] = parse_s + setup_s + pings_s;
    json::Writer w;
    w.begin_object().field("bench", "image_50m_5cm").field("renderer", render::renderer_name(kind));
    w.field("pings", static_cast<std::uint64_t>(poses.size()));
    w.field("bins_per_side", setup.bins).field("threads", threads);
    w.field("cold_s", cold[i], 4).field("warm_s", warm[i], 4);
    w.key("cold_split_s")
        .begin_object()
        .field("parse", parse_s, 4)
        .field("scene_and_renderer", setup_s, 4)
        .field("pings_with_tiles_or_views", pings_s, 4)
        .end_object();
    w.field("tiles_made", tiles).field("warm_1_thread_s", one_thread_s, 4);
    w.field("paper_s", 7.0).field("paper_machine", "2 GHz Core 2 Duo (Pailhas et al. 2010)");
    w.end_object();
    emit(w);
  }
  emit_ratio("image_50m_5cm", "cold_s", cold[0], cold[1]);
  emit_ratio("image_50m_5cm", "warm_s", warm[0], warm[1]);
}

// (b) pings per second and real-time factor at 5 cm, 50 m range, on 1 thread and all threads,
// with the scene made (tiles / views) before timing
void bench_realtime(const config::Scenario& s, int threads) {
  const render::SonarDesc sd = bench_sonar(s, 50.0, 0.05);
  const scene::Scene sc(s.scene);
  const render::SonarSetup setup = render::make_sonar_setup(sd, s.scene.water);
  const auto poses = line_poses(-20.0, 0.0, 20.0, 0.05, s.scene.water.depth_m - 7.5);
  const double realtime_pps = setup.sound_speed_m_s / (2.0 * sd.max_range_m);
  double per_thread[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    const auto r = render::make_ping_renderer(kKinds[i], setup);
    render_poses(sc, *r, poses, threads);  // make the scene
    for (int t : {1, threads}) {
      const double seconds = render_poses(sc, *r, poses, t);
      const double pps = static_cast<double>(poses.size()) / seconds;
      if (t == 1) per_thread[i] = pps;
      json::Writer w;
      w.begin_object().field("bench", "realtime_5cm_50m");
      w.field("renderer", render::renderer_name(kKinds[i])).field("threads", t);
      w.field("pings", static_cast<std::uint64_t>(poses.size()));
      w.field("rays_per_bin", r->fidelity().rays_per_bin)
          .field("along_track_rays", r->fidelity().along_track_rays);
      w.field("pings_per_s", pps, 5).field("realtime_pings_per_s", realtime_pps, 5);
      w.field("realtime_factor", pps / realtime_pps, 4);
      w.field("realtime_factor_per_thread", pps / realtime_pps / t, 4);
      w.end_object();
      emit(w);
      if (threads == 1) break;
    }
  }
  emit_ratio("realtime_5cm_50m", "pings_per_s_1_thread", per_thread[0], per_thread[1]);
}

// (c) where the time goes. Ray tracer: generate / intersect / shade and bare Embree on the same
// rays. Profile: the march and shading (on the scene without targets), the target rays (the
// difference with targets), and the heightmap tiles a ping needs when nothing is made yet.
void bench_split(const config::Scenario& s) {
  const render::SonarDesc sd = bench_sonar(s, 50.0, 0.05);
  const scene::Scene sc(s.scene);
  const render::SonarSetup setup = render::make_sonar_setup(sd, s.scene.water);
  const auto poses = line_poses(-10.0, 0.0, 10.0, 0.05, s.scene.water.depth_m - 7.5);
  {
    const render::RaytraceRenderer r(setup, render::default_fidelity(setup));
    render::PingScratch scratch;
    render::PingLines lines;
    double t_gen = 0, t_isect = 0, t_shade = 0, t_bare = 0;
    std::uint64_t rays = 0;
    render::PingScratch saved;  // its ray buffer only
    for (std::size_t k = 0; k < poses.size(); ++k) {
      const auto view = r.view_for(sc, poses[k], {});
      auto t0 = Clock::now();
      const double alt = r.generate_rays(sc, *view, poses[k], {}, scratch);
      t_gen += seconds_since(t0);
      render::RaytraceRenderer::copy_rays(scratch, saved);
      t0 = Clock::now();
      render::RaytraceRenderer::intersect(*view, {}, scratch);
      t_isect += seconds_since(t0);
      t0 = Clock::now();
      r.shade(sc, *view, 1, k, {}, alt, scratch, lines);
      t_shade += seconds_since(t0);
      rays += render::RaytraceRenderer::ray_count(saved);
      // bare Embree: the same rays, one rtcIntersect1 each, nothing else
      t0 = Clock::now();
      render::RaytraceRenderer::intersect_one_by_one(*view, saved);
      t_bare += seconds_since(t0);
    }
    const double total = t_gen + t_isect + t_shade;
    json::Writer w;
    w.begin_object().field("bench", "split").field("renderer", "raytrace").field("threads", 1);
    w.field("rays", rays)
        .field("rays_per_ping", static_cast<double>(rays) / static_cast<double>(poses.size()), 5);
    w.field("ms_per_ping", 1e3 * total / static_cast<double>(poses.size()), 4);
    w.field("renderer_rays_per_s", static_cast<double>(rays) / total, 5);
    w.field("bare_embree_rays_per_s", static_cast<double>(rays) / t_bare, 5);
    w.field("ratio_renderer_to_bare", t_bare / total, 4);
    w.key("time_split")
        .begin_object()
        .field("generate", t_gen / total, 3)
        .field("intersect", t_isect / total, 3)
        .field("shade", t_shade / total, 3)
        .end_object();
    w.end_object();
    emit(w);
  }
  {
    scene::SceneDesc bare = s.scene;
    bare.targets.clear();
    const auto r = render::make_ping_renderer(RendererKind::kProfile, setup);
    // tiles: a fresh scene, each ping prepared (tiles made) then rendered, on one thread
    const scene::Scene cold(s.scene);
    render::PingScratch scratch;
    render::PingLines lines;
    double t_tiles = 0.0;
    for (const Pose& p : poses) {
      const auto t0 = Clock::now();
      r->prepare(cold, p, {}, scratch);
      t_tiles += seconds_since(t0);
    }
    const scene::Scene no_targets(bare);
    render_poses(no_targets, *r, poses, 1);
    render_poses(sc, *r, poses, 1);
    const double t_march = render_poses(no_targets, *r, poses, 1);
    const double t_all = render_poses(sc, *r, poses, 1);
    std::uint64_t samples = 0, rays = 0;
    for (std::size_t k = 0; k < poses.size(); ++k) {
      r->render(sc, poses[k], 1, k, {}, scratch, lines);
      samples += scratch.samples;
      rays += scratch.rays_cast;
    }
    const double n = static_cast<double>(poses.size());
    json::Writer w;
    w.begin_object().field("bench", "split").field("renderer", "profile").field("threads", 1);
    w.field("samples_per_ping", static_cast<double>(samples) / n, 5);
    w.field("target_rays_per_ping", static_cast<double>(rays) / n, 5);
    w.field("ms_per_ping", 1e3 * t_all / n, 4);
    w.field("ns_per_sample", 1e9 * t_march / static_cast<double>(samples), 4);
    w.key("ms_per_ping_split")
        .begin_object()
        .field("march_and_shade", 1e3 * t_march / n, 4)
        .field("target_rays", 1e3 * std::max(0.0, t_all - t_march) / n, 4)
        .field("tiles_when_cold", 1e3 * t_tiles / n, 4)
        .end_object();
    w.end_object();
    emit(w);
  }
}

// (d) chips of the paper's study at 5 cm (single thread), highlight and shadow, on the default
// seabed mix: the first N chips (tiles made as they go) and the same chips again
void bench_chips(const config::Scenario& s, int count) {
  double ms[2][2] = {{0, 0}, {0, 0}};
  for (int kind_i = 0; kind_i < 2; ++kind_i) {
    const chips::ChipKind ck = kind_i == 0 ? chips::ChipKind::kHighlight : chips::ChipKind::kShadow;
    for (int i = 0; i < 2; ++i) {
      render::ChipDatasetSpec spec;
      spec.kind = ck;
      spec.classes = {targets::TargetType::kManta, targets::TargetType::kRockan,
                      targets::TargetType::kCuboid, targets::TargetType::kCylinder};
      for (const char* name : {"flat", "ripples", "clutter"})
        spec.seabeds.push_back(render::builtin_dataset_seabed(name));
      spec.resolutions_m = {0.05};
      spec.sonar = s.sonar;
      spec.renderer = kKinds[i];
      const auto t_setup = Clock::now();
      const render::ChipRenderer cr(spec);
      const double setup_s = seconds_since(t_setup);
      auto t0 = Clock::now();
      for (int k = 0; k < count; ++k)
        cr.render(static_cast<std::uint64_t>(k), 0);
      const double first_s = seconds_since(t0);
      t0 = Clock::now();
      for (int k = 0; k < count; ++k)
        cr.render(static_cast<std::uint64_t>(k), 0);
      const double again_s = seconds_since(t0);
      ms[kind_i][i] = 1e3 * again_s / count;
      json::Writer w;
      w.begin_object().field("bench", "chips_5cm").field("kind", chips::chip_kind_name(ck));
      w.field("renderer", render::renderer_name(kKinds[i])).field("threads", 1);
      w.field("chips", count).field("setup_s", setup_s, 4);
      w.field("ms_per_chip_first", 1e3 * first_s / count, 4);
      w.field("ms_per_chip", 1e3 * again_s / count, 4);
      w.field("rows", cr.rows(0)).field("cols", cr.cols(0));
      w.end_object();
      emit(w);
    }
    emit_ratio("chips_5cm", chips::chip_kind_name(ck), ms[kind_i][0], ms[kind_i][1]);
  }
}

// (e) the receive chain's cost (docs/physics.md §3, "Receive chain"): ms per ping of the
// iver2_600khz preset over the scenario's seabed (profile renderer, one thread, the scene made
// before timing), from every effect off to the preset, adding one effect at a time. The rounds
// interleave the settings and each keeps its fastest, so a busy moment does not land on one.
void bench_chain(const config::Scenario& s, int rounds) {
  render::SonarDesc sd = config::builtin_sonar("iver2_600khz");
  struct Step {
    const char* name;
    render::SonarDesc desc;
  };
  std::vector<Step> steps;
  render::SonarDesc d = sd;
  d.speckle_model = render::SpeckleModel::kPerBin;
  d.raw_samples_per_bin = 1;
  d.downsample = acoustics::Downsample::kRms;
  d.noise_floor_db_fs = 0.0;
  d.ringdown_s = 0.0;
  steps.push_back({"per_bin", d});
  d.speckle_model = render::SpeckleModel::kPulse;
  steps.push_back({"pulse_speckle", d});
  d.raw_samples_per_bin = sd.raw_samples_per_bin;
  d.downsample = sd.downsample;
  steps.push_back({"raw_samples_downsampled", d});
  d.noise_floor_db_fs = sd.noise_floor_db_fs;
  steps.push_back({"noise_floor", d});
  d.ringdown_s = sd.ringdown_s;
  steps.push_back({"ringdown", d});
  const scene::Scene sc(s.scene);
  const auto poses = line_poses(-20.0, 0.0, 40.0, 0.1, s.scene.water.depth_m - 6.0);
  std::vector<std::unique_ptr<render::PingRenderer>> renderers;
  for (const Step& st : steps) {
    renderers.push_back(render::make_ping_renderer(
        RendererKind::kProfile, render::make_sonar_setup(st.desc, s.scene.water)));
  }
  render_poses(sc, *renderers[0], poses, 1);  // make the scene
  std::vector<double> best(steps.size(), 1e300);
  for (int round = 0; round < rounds; ++round) {
    for (std::size_t i = 0; i < steps.size(); ++i)
      best[i] = std::min(best[i], render_poses(sc, *renderers[i], poses, 1));
  }
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const double ms = 1e3 * best[i] / static_cast<double>(poses.size());
    json::Writer w;
    w.begin_object().field("bench", "receive_chain").field("sonar", sd.name);
    w.field("with", steps[i].name).field("renderer", "profile").field("threads", 1);
    w.field("pings", static_cast<std::uint64_t>(poses.size()));
    w.field("ms_per_ping", ms, 4);
    w.field("over_per_bin", best[i] / best[0], 4);
    w.end_object();
    emit(w);
  }
}

// (f) the emulator at --rate max (no outputs) along a straight line over a seabed stretched to
// hold it: pings per second and start-up
void bench_run(const config::Scenario& base, int threads, double profile_length_m,
               double raytrace_length_m) {
  double pps[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    const double length = i == 0 ? profile_length_m : raytrace_length_m;
    config::Scenario s = base;
    s.scene.seabed.origin_m = Vec2(-50.0, -50.0);
    s.scene.seabed.extent_m = Vec2(length + 100.0, 100.0);
    s.vehicle.trajectory = vehicle::TrajectoryDesc{};
    s.vehicle.trajectory.kind = vehicle::TrajectoryKind::kStraight;
    s.vehicle.trajectory.start = {-45.0, 0.0};
    s.vehicle.trajectory.start_heading = 0.0;
    s.vehicle.trajectory.straight_length_m = length;
    s.vehicle.trajectory.speed_m_s = 2.0;
    s.vehicle.trajectory.depth.mode = vehicle::DepthMode::kAltitude;
    s.vehicle.trajectory.depth.altitude_m = 7.5;
    emulator::EmulatorOptions o;
    o.rate.max = true;
    o.threads = threads;
    o.renderer = kKinds[i];
    o.stats_interval_s = 0.0;
    emulator::MonotonicClock clock;
    emulator::EmulatorHooks hooks;
    hooks.message = [](std::string_view) {};
    const auto t0 = Clock::now();
    emulator::Emulator emu(s, o, clock, hooks);
    const emulator::RunStats st = emu.run();
    const double total_s = seconds_since(t0);
    pps[i] = st.wall_time_s > 0 ? static_cast<double>(st.pings_sent) / st.wall_time_s : 0.0;
    json::Writer w;
    w.begin_object().field("bench", "run_rate_max");
    w.field("renderer", render::renderer_name(kKinds[i])).field("threads", threads);
    w.field("line_m", length, 1).field("pings", st.pings_sent);
    w.field("pings_per_s", pps[i], 5).field("realtime_factor", st.sim_time_s / st.wall_time_s, 4);
    w.field("startup_s", st.startup_s, 4).field("total_s", total_s, 4);
    w.field("render_mean_ms", st.render_mean_ms, 4).field("tiles_made", st.tiles_made);
    w.end_object();
    emit(w);
  }
  emit_ratio("run_rate_max", "pings_per_s", pps[0], pps[1]);
}

int run_bench(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--only", true, true}, {"--threads"}, {"--full", false}});
  if (args.positionals().size() > 1) throw UsageError("expected at most one SCENARIO.yaml");
  const int threads =
      static_cast<int>(args.get_int("--threads", 1, 256)
                           .value_or(std::max(1u, std::thread::hardware_concurrency())));
  const std::vector<std::string> all = {"image", "realtime", "split",    "chips",
                                        "chain", "run",      "fidelity", "accuracy"};
  std::vector<std::string> only = args.get_all("--only");
  if (only.empty()) only = all;
  for (const auto& o : only) {
    if (std::find(all.begin(), all.end(), o) == all.end()) {
      throw UsageError("--only: '" + o +
                       "' is not one of image, realtime, split, chips, chain, run, fidelity, "
                       "accuracy");
    }
  }
  const auto want = [&](const char* name) {
    return std::find(only.begin(), only.end(), name) != only.end();
  };
  const bool full = args.has("--full");
  const std::optional<std::string> path =
      args.positionals().empty() ? std::nullopt : std::optional(args.positionals()[0]);
  const config::Scenario s = load_scenario_or_default(path);
  utsname un{};
  uname(&un);
  json::Writer m;
  m.begin_object().field("bench", "machine").field("cpu", cpu_model());
  m.field("hardware_threads", static_cast<int>(std::thread::hardware_concurrency()));
  m.field("kernel", std::string(un.release)).field("scenario", s.scene.name);
  m.field("full", full).end_object();
  emit(m);
  if (want("image")) bench_image(path, threads);
  if (want("realtime")) bench_realtime(s, threads);
  if (want("split")) bench_split(s);
  if (want("chips")) bench_chips(s, full ? 200 : 40);
  if (want("chain")) bench_chain(s, full ? 5 : 3);
  if (want("run")) bench_run(s, threads, 1000.0, full ? 300.0 : 100.0);
  SectionPrinter printer;
  if (want("fidelity")) bench::bench_fidelity(s, full, threads, printer.output());
  if (want("accuracy")) bench::bench_accuracy(s, full, threads, printer.output());
  return 0;
}

}  // namespace

const Command kBenchCommand{
    "bench",
    "speed and accuracy figures as JSON lines: both renderers side by side, and their ratio",
    R"(usage: sonarloop bench [SCENARIO.yaml] [--only SECTION]... [--threads N] [--full]

Prints one JSON object per line on stdout (the first describes the machine). Each speed section
measures the profile renderer and the ray-traced reference in the same run and prints their
ratio ("raytrace_over_profile"): on a shared machine, compare ratios, not seconds.
  image      a 50 m x 50 m image at 5 cm (1000 pings, 25 m a side): cold (scenario text to
             the last ping: parse, scene, renderer, tiles or views, pings) and warm
  realtime   pings per second at 5 cm and 50 m range on 1 thread and on all, and the
             real-time factor (real time = c / (2 x 50 m) pings per second)
  split      where a ping's time goes: ray tracer (generate, intersect, shade, against bare
             Embree on the same rays); profile (march and shade, target rays, cold tiles)
  chips      ms per 5 cm highlight and shadow chip of the resolution study (one thread)
  chain      the receive chain's cost: ms per ping of the iver2_600khz preset with its
             effects added one at a time (speckle through the pulse, raw samples and the
             recorder's max, noise floor, ring-down), against per-bin speckle
  run        the emulator at --rate max on a straight line (1 km for the profile renderer):
             pings per second and start-up
  fidelity   every fidelity setting of both renderers: ms per ping, RMS dB error on the
             seabed, shadow-edge errors, against a ray-traced reference on a 1.25 cm grid
  accuracy   each renderer at its default against the reference: the scenario and the four
             seabed kinds with every sonar preset, and a line with pitch and roll
Without SCENARIO.yaml the embedded default scenario is used. The default run takes about a
minute on two cores; --full takes the exhaustive fidelity grid, an 8x8-ray reference (4x4
otherwise), more chips and pings (about 4 minutes). tools/plot_bench.py charts the fidelity
lines.

examples:
  sonarloop bench > bench.jsonl
  sonarloop bench --only image --only realtime
  sonarloop bench --only fidelity --full | /usr/bin/python3 tools/plot_bench.py - fidelity.png
)",
    run_bench, 90};
SONARLOOP_REGISTER_COMMAND(kBenchCommand);

}  // namespace sonarloop::tools
