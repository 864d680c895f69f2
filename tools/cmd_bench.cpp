// sonarloop bench: machine-readable speed figures, one JSON object per line on stdout.
#include <sys/utsname.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>
#include <thread>

#include "drivers/json/json_writer.h"
#include "sim/render/track_renderer.h"
#include "sim/scene/scene.h"
#include "tools/args.h"
#include "tools/commands.h"
#include "tools/progress.h"
#include "tools/scenario_source.h"

namespace sonarloop::tools {
namespace {

using Clock = std::chrono::steady_clock;

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown";
}

void emit(const json::Writer& w) {
  std::printf("%s\n", w.str().c_str());
  std::fflush(stdout);
}

// A straight north-going line of pings over the default scenario, one per pixel.
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
  render::SonarDesc sd = s.sonar;
  sd.along_track = render::AlongTrackModel::kStrip;
  sd.max_range_m = range_m;
  sd.bin_size_m = pixel_m;
  sd.along_track_resolution_m = pixel_m;
  sd.pulse_length_s = 0.0;
  sd.chirp_bandwidth_hz = 0.0;
  return sd;
}

// Renders poses on a prebuilt view with `threads` threads; returns the wall time.
double render_on_view(const render::PingRenderer& r, const scene::SceneView& view,
                      const std::vector<Pose>& poses, int threads) {
  std::vector<render::PingScratch> scratch(static_cast<std::size_t>(threads));
  std::vector<render::PingLines> lines(static_cast<std::size_t>(threads));
  std::atomic<std::size_t> next{0};
  const auto t0 = Clock::now();
  auto work = [&](std::size_t w) {
    for (std::size_t k = next++; k < poses.size(); k = next++) {
      r.render(view, poses[k], 1, k, {}, scratch[w], lines[w]);
    }
  };
  std::vector<std::thread> pool;
  for (int w = 1; w < threads; ++w)
    pool.emplace_back(work, static_cast<std::size_t>(w));
  work(0);
  for (auto& th : pool)
    th.join();
  return seconds_since(t0);
}

// (a) a 50 m x 50 m image at 5 cm: 1000 pings, 25 m range per side; cold = scene setup + tile
// generation + Embree build + pings; warm = the same with the tiles already made
void bench_image(const config::Scenario& s, int threads) {
  const double pixel = 0.05;
  const render::SonarDesc sd = bench_sonar(s, 25.0, pixel);
  const double depth = s.scene.water.depth_m - 6.0;
  const auto poses = line_poses(-25.0, 0.0, 50.0 - pixel, pixel, depth);
  auto t0 = Clock::now();
  const scene::Scene sc(s.scene);
  const render::SonarSetup setup = render::make_sonar_setup(sd, s.scene.water);
  const render::PingRenderer r(sc, setup);
  const double setup_s = seconds_since(t0);
  scene::Box2 all = r.swath_region(poses.front());
  all.max = all.max.cwiseMax(r.swath_region(poses.back()).max);
  t0 = Clock::now();
  sc.seabed().prepare(all.min.x(), all.min.y(), all.max.x(), all.max.y(), threads);
  const double tiles_s = seconds_since(t0);
  t0 = Clock::now();
  auto view = sc.view(all, threads);
  const double view_s = seconds_since(t0);
  const double pings_s = render_on_view(r, *view, poses, threads);
  view.reset();
  t0 = Clock::now();
  view = sc.view(all, threads);
  const double view_warm_s = seconds_since(t0);
  const double pings_warm_s = render_on_view(r, *view, poses, threads);
  const double pings_1_s = render_on_view(r, *view, poses, 1);
  json::Writer w;
  w.begin_object()
      .field("bench", "image_50m_5cm")
      .field("pings", static_cast<std::uint64_t>(poses.size()));
  w.field("bins_per_side", setup.bins).field("threads", threads);
  w.field("cold_s", setup_s + tiles_s + view_s + pings_s, 4);
  w.field("warm_s", view_warm_s + pings_warm_s, 4);
  w.key("cold_split_s")
      .begin_object()
      .field("scene_setup", setup_s, 4)
      .field("tiles", tiles_s, 4)
      .field("embree_view", view_s, 4)
      .field("pings", pings_s, 4)
      .end_object();
  w.field("pings_only_s", pings_warm_s, 4).field("pings_only_1_thread_s", pings_1_s, 4);
  w.field("paper_s", 7.0).field("paper_machine", "2 GHz Core 2 Duo (Pailhas et al. 2010)");
  w.end_object();
  emit(w);
}

// (b) pings per second and real-time factor at 5 cm, 50 m range, 1 thread and all threads, on
// a prebuilt view (the emulator builds views ahead of the pings, off the rendering path)
void bench_realtime(const config::Scenario& s, int threads) {
  const render::SonarDesc sd = bench_sonar(s, 50.0, 0.05);
  const scene::Scene sc(s.scene);
  const render::SonarSetup setup = render::make_sonar_setup(sd, s.scene.water);
  const render::PingRenderer r(sc, setup);
  const auto poses = line_poses(-20.0, 0.0, 20.0, 0.05, s.scene.water.depth_m - 7.5);
  scene::Box2 all = r.swath_region(poses.front());
  all.max = all.max.cwiseMax(r.swath_region(poses.back()).max);
  const auto view = sc.view(all, threads);
  for (int t : {1, threads}) {
    const double seconds = render_on_view(r, *view, poses, t);
    const double pps = static_cast<double>(poses.size()) / seconds;
    const double realtime_pps = setup.sound_speed_m_s / (2.0 * sd.max_range_m);
    json::Writer w;
    w.begin_object().field("bench", "realtime_5cm_50m").field("threads", t);
    w.field("pings", static_cast<std::uint64_t>(poses.size()));
    w.field("rays_per_bin", r.fidelity().rays_per_bin)
        .field("along_track_rays", r.fidelity().along_track_rays);
    w.field("pings_per_s", pps, 5).field("realtime_pings_per_s", realtime_pps, 5);
    w.field("realtime_factor", pps / realtime_pps, 4);
    w.field("realtime_factor_per_thread", pps / realtime_pps / t, 4);
    w.end_object();
    emit(w);
    if (threads == 1) break;
  }
}

// (c) renderer ray throughput against bare Embree on the same rays
void bench_rays(const config::Scenario& s) {
  const render::SonarDesc sd = bench_sonar(s, 50.0, 0.05);
  const scene::Scene sc(s.scene);
  const render::SonarSetup setup = render::make_sonar_setup(sd, s.scene.water);
  const render::PingRenderer r(sc, setup);
  const auto poses = line_poses(-10.0, 0.0, 10.0, 0.05, s.scene.water.depth_m - 7.5);
  scene::Box2 all = r.swath_region(poses.front());
  all.max = all.max.cwiseMax(r.swath_region(poses.back()).max);
  const auto view = sc.view(all, 2);
  render::PingScratch scratch;
  render::PingLines lines;
  double t_gen = 0, t_isect = 0, t_shade = 0, t_bare = 0;
  std::uint64_t rays = 0;
  std::vector<RTCRayHit> saved;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    auto t0 = Clock::now();
    const double alt = r.generate_rays(*view, poses[k], {}, scratch);
    t_gen += seconds_since(t0);
    saved = scratch.rays;
    t0 = Clock::now();
    render::PingRenderer::intersect(*view, scratch);
    t_isect += seconds_since(t0);
    t0 = Clock::now();
    r.shade(*view, 1, k, {}, alt, scratch, lines);
    t_shade += seconds_since(t0);
    rays += saved.size();
    // bare Embree: the same rays, one rtcIntersect1 each, nothing else
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    t0 = Clock::now();
    for (auto& rh : saved)
      rtcIntersect1(view->rtc_scene(), &ctx, &rh);
    t_bare += seconds_since(t0);
  }
  const double total = t_gen + t_isect + t_shade;
  json::Writer w;
  w.begin_object().field("bench", "ray_throughput").field("threads", 1);
  w.field("rays", rays)
      .field("rays_per_ping", static_cast<double>(rays) / static_cast<double>(poses.size()), 5);
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

struct LineSet {
  std::vector<render::PingLines> lines;
  std::vector<std::vector<render::TargetTrace>> traces;
  double seconds = 0.0;
};

LineSet render_set(const scene::SceneDesc& scene_desc, const render::SonarDesc& sd,
                   const std::vector<Pose>& poses) {
  const scene::Scene sc(scene_desc);
  const render::SonarSetup setup = render::make_sonar_setup(sd, scene_desc.water);
  const render::PingRenderer r(sc, setup);
  LineSet out;
  out.lines.resize(poses.size());
  out.traces.resize(poses.size());
  render::RenderOptions opt;
  opt.speckle = false;
  opt.noise = false;
  opt.truth = true;
  std::vector<std::shared_ptr<const scene::SceneView>> views;
  for (const auto& p : poses)
    views.push_back(sc.view(r.swath_region(p), 2));
  render::PingScratch scratch;
  const auto t0 = Clock::now();
  for (std::size_t k = 0; k < poses.size(); ++k) {
    r.render(*views[k], poses[k], 1, k, opt, scratch, out.lines[k]);
    out.traces[k] = scratch.traces;
  }
  out.seconds = seconds_since(t0);
  return out;
}

// (d) speed against accuracy across the fidelity knobs, against a high-fidelity reference
void bench_fidelity(const config::Scenario& s, bool quick) {
  // pings across each target of the default scenario (5 cm pixels, 30 m range)
  render::SonarDesc base = bench_sonar(s, 30.0, 0.05);
  std::vector<Pose> poses;
  const scene::Scene probe(s.scene);
  for (const auto& t : probe.targets()) {
    for (int k = -3; k <= 3; ++k) {
      Pose p;
      p.position_W = Vec3(t.desc.position_m.x() + 0.05 * k, 0.0, s.scene.water.depth_m - 7.0);
      poses.push_back(p);
    }
  }
  struct Setting {
    int rays_per_bin, along_rays;
    double grid_m;
  };
  scene::SceneDesc ref_scene = s.scene;
  ref_scene.seabed.grid_spacing_m = 0.0125;
  render::SonarDesc ref_sonar = base;
  ref_sonar.rays_per_bin = quick ? 4 : 8;
  ref_sonar.along_track_rays = quick ? 4 : 8;
  const LineSet ref = render_set(ref_scene, ref_sonar, poses);
  std::vector<Setting> settings;
  for (double g : {0.0125, 0.025, 0.05, 0.1}) {
    for (int v : {1, 2, 4}) {
      for (int a : {1, 2, 4}) {
        if (quick && (v == 4 || a == 4 || g == 0.0125)) continue;
        settings.push_back({v, a, g});
      }
    }
  }
  for (const Setting& st : settings) {
    scene::SceneDesc sdsc = s.scene;
    sdsc.seabed.grid_spacing_m = st.grid_m;
    render::SonarDesc son = base;
    son.rays_per_bin = st.rays_per_bin;
    son.along_track_rays = st.along_rays;
    const LineSet got = render_set(sdsc, son, poses);
    // RMS dB error over seabed bins lit in both renders (no speckle, no noise)
    double se = 0.0;
    long n = 0;
    double edge_err = 0.0;
    long edges = 0;
    for (std::size_t k = 0; k < poses.size(); ++k) {
      for (int side = 0; side < 2; ++side) {
        const auto& a = side == 0 ? got.lines[k].port : got.lines[k].stbd;
        const auto& b = side == 0 ? ref.lines[k].port : ref.lines[k].stbd;
        for (std::size_t i = 0; i < a.size(); ++i) {
          if (a[i] > 0.0f && b[i] > 0.0f) {
            const double e = 10.0 * std::log10(static_cast<double>(a[i]) / b[i]);
            se += e * e;
            ++n;
          }
        }
      }
      for (const auto& tr : ref.traces[k]) {
        for (const auto& tg : got.traces[k]) {
          if (tg.target == tr.target && tg.side == tr.side && tr.shadow_last >= 0 &&
              tg.shadow_last >= 0) {
            edge_err += std::abs(tg.shadow_last - tr.shadow_last);
            ++edges;
          }
        }
      }
    }
    json::Writer w;
    w.begin_object().field("bench", "fidelity");
    w.field("rays_per_bin", st.rays_per_bin).field("along_track_rays", st.along_rays);
    w.field("grid_spacing_m", st.grid_m, 4);
    w.field("ms_per_ping", 1e3 * got.seconds / static_cast<double>(poses.size()), 4);
    w.field("rms_db_error", n ? std::sqrt(se / static_cast<double>(n)) : 0.0, 4);
    w.field("shadow_edge_error_bins", edges ? edge_err / static_cast<double>(edges) : 0.0, 4);
    w.field("reference", std::string("rays ") + std::to_string(ref_sonar.rays_per_bin) + "x" +
                             std::to_string(ref_sonar.along_track_rays) + ", grid 0.0125 m");
    w.end_object();
    emit(w);
  }
}

int run_bench(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--only"}, {"--threads"}, {"--quick", false}});
  if (args.positionals().size() > 1) throw UsageError("expected at most one SCENARIO.yaml");
  const int threads =
      static_cast<int>(args.get_int("--threads", 1, 256)
                           .value_or(std::max(1u, std::thread::hardware_concurrency())));
  const std::string only = args.get_or("--only", "all");
  if (only != "all" && only != "image" && only != "realtime" && only != "rays" &&
      only != "fidelity") {
    throw UsageError("--only: '" + only + "' is not one of image, realtime, rays, fidelity");
  }
  const config::Scenario s = load_scenario_or_default(
      args.positionals().empty() ? std::nullopt : std::optional(args.positionals()[0]));
  utsname un{};
  uname(&un);
  json::Writer m;
  m.begin_object().field("bench", "machine").field("cpu", cpu_model());
  m.field("hardware_threads", static_cast<int>(std::thread::hardware_concurrency()));
  m.field("kernel", std::string(un.release)).field("scenario", s.scene.name).end_object();
  emit(m);
  if (only == "all" || only == "image") bench_image(s, threads);
  if (only == "all" || only == "realtime") bench_realtime(s, threads);
  if (only == "all" || only == "rays") bench_rays(s);
  if (only == "all" || only == "fidelity") bench_fidelity(s, args.has("--quick"));
  return 0;
}

}  // namespace

const Command kBenchCommand{
    "bench", "speed figures as JSON lines: image time, real-time factor, ray throughput, fidelity",
    R"(usage: sonarloop bench [SCENARIO.yaml] [--only image|realtime|rays|fidelity] [--threads N] [--quick]

Prints one JSON object per line on stdout (the first describes the machine):
  image_50m_5cm      a 50 m x 50 m image at 5 cm (1000 pings, 25 m a side): cold (scene
                     setup, tile generation, Embree build and rendering) and warm
  realtime_5cm_50m   pings per second at 5 cm and 50 m range on 1 thread and on all, and the
                     real-time factor (real time = c / (2 x 50 m) pings per second)
  ray_throughput     the renderer's rays per second against bare Embree rtcIntersect1 on the
                     same rays, and where the renderer's time goes
  fidelity           for each fidelity setting (rays per bin, along-track rays, seabed grid
                     spacing): ms per ping, RMS dB error on the seabed and shadow-edge error in
                     bins against a high-fidelity reference render of the same pings
Without SCENARIO.yaml the embedded default scenario is used. --quick trims the fidelity sweep.
tools/plot_bench.py turns the fidelity lines into a chart.

examples:
  sonarloop bench > bench.jsonl
  sonarloop bench --only fidelity | /usr/bin/python3 tools/plot_bench.py - fidelity.png
)",
    run_bench, 90};
SONARLOOP_REGISTER_COMMAND(kBenchCommand);

}  // namespace sonarloop::tools
