#include "bench/bench_accuracy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numbers>
#include <thread>

#include "config/loader/sonar_loader.h"
#include "drivers/json/json_writer.h"
#include "sim/render/chip_renderer.h"
#include "sim/render/raytrace_renderer.h"
#include "units/angles.h"

namespace sonarloop::bench {
namespace {

using Clock = std::chrono::steady_clock;

// The transitions between lit and dark bins of a line beyond its nadir gap and before bin
// `end` (the reference's last lit bin: its fan, laid out for a flat seabed at the nadir
// altitude, can fall short of the far end over deeper seabed).
void edges_of(const std::vector<float>& line, std::size_t end, std::vector<int>& out) {
  out.clear();
  std::size_t k = 0;
  while (k < line.size() && line[k] <= 0.0f)
    ++k;  // the water column
  for (++k; k < std::min(end, line.size()); ++k) {
    if ((line[k] > 0.0f) != (line[k - 1] > 0.0f)) out.push_back(static_cast<int>(k));
  }
}

// One past the last lit bin of a line.
std::size_t lit_end(const std::vector<float>& line) {
  std::size_t end = line.size();
  while (end > 0 && line[end - 1] <= 0.0f)
    --end;
  return end;
}

// Σ over `a` of the distance to the nearest edge of `b` (capped), and the count.
void edge_distances(const std::vector<int>& a, const std::vector<int>& b, double& sum, long& n) {
  for (int e : a) {
    int best = kMaxEdgeMatchBins;
    for (int f : b)
      best = std::min(best, std::abs(e - f));
    sum += best;
    ++n;
  }
}

render::Fidelity reference_fidelity(const render::SonarSetup& setup, bool full) {
  render::Fidelity f = render::default_fidelity(setup);
  const int dense = full ? 8 : 4;
  f.rays_per_bin = dense;
  f.along_track_rays = std::min(64, std::max(dense, 2 * f.along_track_rays));
  return f;
}

struct Case {
  std::string name;
  scene::SceneDesc scene;
  render::SonarDesc sonar;
  std::vector<Pose> poses;
  // the scene, made once for every case over the same description (its tiles are made once)
  std::shared_ptr<const scene::Scene> built;
};

// Pings along a north-going line at east 0 across each of the first `targets` targets (the
// default scenario's Manta to starboard and Rockan to port), `per_target` pings 10 cm apart.
std::vector<Pose> poses_across_targets(const scene::SceneDesc& desc, int targets, int per_target,
                                       double altitude_m) {
  std::vector<Pose> poses;
  const int n = std::min<int>(targets, static_cast<int>(desc.targets.size()));
  for (int t = 0; t < n; ++t) {
    for (int k = 0; k < per_target; ++k) {
      Pose p;
      const double north = desc.targets[static_cast<std::size_t>(t)].position_m.x() +
                           0.1 * (k - 0.5 * (per_target - 1));
      p.position_W = Vec3(north, 0.0, desc.water.depth_m - altitude_m);
      poses.push_back(p);
    }
  }
  return poses;
}

scene::SceneDesc with_seabed_kind(const scene::SceneDesc& base, const std::string& kind) {
  const render::DatasetSeabed k = render::builtin_dataset_seabed(kind);
  scene::SceneDesc d = base;
  const Vec2 origin = d.seabed.origin_m;
  const Vec2 extent = d.seabed.extent_m;
  d.seabed = k.desc.seabed;
  d.seabed.origin_m = origin;
  d.seabed.extent_m = extent;
  d.seed = k.desc.seed;
  d.name = base.name + "/" + kind;
  return d;
}

}  // namespace

render::SonarDesc isotropic_strip_sonar(const render::SonarDesc& base, double range_m,
                                        double pixel_m) {
  render::SonarDesc sd = base;
  sd.along_track = render::AlongTrackModel::kStrip;
  sd.max_range_m = range_m;
  sd.bin_size_m = pixel_m;
  sd.along_track_resolution_m = pixel_m;
  sd.pulse_length_s = 0.0;
  sd.chirp_bandwidth_hz = 0.0;
  return echoes_only(sd);
}

render::SonarDesc echoes_only(render::SonarDesc sd) {
  sd.ringdown_s = 0.0;
  return sd;
}

namespace {

// render_set on `threads` threads: ping k on thread k mod threads (this one among them), after
// one untimed pass that makes the tiles and views in order. Each ping is a function of (scene,
// pose, seed, k): the thread that renders it changes nothing.
LineSet render_lines(const scene::Scene& scene, const render::PingRenderer& renderer,
                     const std::vector<Pose>& poses, int threads) {
  LineSet out;
  out.lines.resize(poses.size());
  out.traces.resize(poses.size());
  render::RenderOptions opt;
  opt.speckle = false;
  opt.noise = false;
  opt.truth = true;
  render::PingScratch scratch;
  for (std::size_t k = 0; k < poses.size(); ++k)  // tiles and views, untimed
    renderer.prepare(scene, poses[k], opt, scratch);
  const auto n = static_cast<std::size_t>(std::max(1, threads));
  const auto render_from = [&](std::size_t first, render::PingScratch& own) {
    for (std::size_t k = first; k < poses.size(); k += n) {
      renderer.render(scene, poses[k], 1, k, opt, own, out.lines[k]);
      out.traces[k] = own.traces;
    }
  };
  const auto t0 = Clock::now();
  std::vector<std::thread> others;
  for (std::size_t t = 1; t < n; ++t) {
    others.emplace_back([&, t] {
      render::PingScratch own;
      render_from(t, own);
    });
  }
  render_from(0, scratch);
  for (auto& th : others)
    th.join();
  out.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return out;
}

}  // namespace

LineSet render_set(const scene::Scene& scene, const render::PingRenderer& renderer,
                   const std::vector<Pose>& poses) {
  return render_lines(scene, renderer, poses, 1);
}

LineSet render_reference(const scene::Scene& scene, const render::PingRenderer& renderer,
                         const std::vector<Pose>& poses, int threads) {
  return render_lines(scene, renderer, poses, threads);
}

namespace {

// kRmsFloorDb below the median of the line's lit bins (0 for a dark line)
float rms_floor(const std::vector<float>& line) {
  std::vector<float> lit;
  for (float v : line)
    if (v > 0.0f) lit.push_back(v);
  if (lit.empty()) return 0.0f;
  auto mid = lit.begin() + static_cast<std::ptrdiff_t>(lit.size() / 2);
  std::nth_element(lit.begin(), mid, lit.end());
  return static_cast<float>(*mid * std::pow(10.0, -kRmsFloorDb / 10.0));
}

}  // namespace

LineErrors compare_lines(const LineSet& got, const LineSet& ref) {
  LineErrors e;
  double se = 0.0;
  double edge_sum = 0.0;
  double terrain_sum = 0.0;
  std::vector<int> ea, eb;
  for (std::size_t k = 0; k < got.lines.size(); ++k) {
    for (int side = 0; side < 2; ++side) {
      const auto& a = side == 0 ? got.lines[k].port : got.lines[k].stbd;
      const auto& b = side == 0 ? ref.lines[k].port : ref.lines[k].stbd;
      const float floor = rms_floor(b);
      for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
        if (a[i] > floor && b[i] > floor) {
          const double d = 10.0 * std::log10(static_cast<double>(a[i]) / b[i]);
          se += d * d;
          ++e.lit_bins;
        }
      }
      const std::size_t end = lit_end(b);
      edges_of(a, end, ea);
      edges_of(b, end, eb);
      edge_distances(ea, eb, terrain_sum, e.terrain_edges);
      edge_distances(eb, ea, terrain_sum, e.terrain_edges);
    }
    for (const auto& tr : ref.traces[k]) {
      for (const auto& tg : got.traces[k]) {
        if (tg.target == tr.target && tg.side == tr.side && tr.shadow_last >= 0 &&
            tg.shadow_last >= 0) {
          edge_sum += std::abs(tg.shadow_last - tr.shadow_last);
          ++e.target_edges;
        }
      }
    }
  }
  e.rms_db = e.lit_bins ? std::sqrt(se / static_cast<double>(e.lit_bins)) : 0.0;
  e.target_edge_bins = e.target_edges ? edge_sum / static_cast<double>(e.target_edges) : 0.0;
  e.terrain_edge_bins = e.terrain_edges ? terrain_sum / static_cast<double>(e.terrain_edges) : 0.0;
  return e;
}

void bench_fidelity(const config::Scenario& s, bool full, int threads, const SectionOutput& out) {
  // pings across each target of the scenario (5 cm pixels, 30 m range)
  const render::SonarDesc base = isotropic_strip_sonar(s.sonar, 30.0, 0.05);
  std::vector<Pose> poses;
  for (const auto& t : s.scene.targets) {
    for (int k = -3; k <= 3; ++k) {
      Pose p;
      p.position_W = Vec3(t.position_m.x() + 0.05 * k, 0.0, s.scene.water.depth_m - 7.0);
      poses.push_back(p);
    }
  }
  scene::SceneDesc ref_desc = s.scene;
  ref_desc.seabed.grid_spacing_m = 0.0125;
  const auto ref_scene = std::make_shared<const scene::Scene>(ref_desc);
  const render::SonarSetup base_setup = render::make_sonar_setup(base, s.scene.water);
  const render::Fidelity ref_fid = reference_fidelity(base_setup, full);
  const auto ref_renderer =
      render::make_ping_renderer(render::RendererKind::kRaytrace, base_setup, ref_fid);
  const LineSet ref = render_reference(*ref_scene, *ref_renderer, poses, threads);
  const std::string ref_name = "raytrace " + std::to_string(ref_fid.rays_per_bin) + "x" +
                               std::to_string(ref_fid.along_track_rays) + ", grid 0.0125 m";

  struct Setting {
    render::RendererKind kind;
    int rays_per_bin, along;
    double grid_m;
    double heightfield_m;  // profile: level spacing asked for (0: the grid)
    double step_fraction;  // profile: march step per level spacing
  };
  std::vector<Setting> settings;
  const std::vector<double> grids =
      full ? std::vector<double>{0.0125, 0.025, 0.05, 0.1} : std::vector<double>{0.025};
  const std::vector<int> counts = full ? std::vector<int>{1, 2, 4} : std::vector<int>{1, 2};
  for (double g : grids) {
    for (int v : counts)
      for (int a : counts)
        settings.push_back({render::RendererKind::kRaytrace, v, a, g, 0.0, 0.5});
    for (int a : counts) {
      for (double f : full ? std::vector<double>{1.0, 0.5, 0.25} : std::vector<double>{1.0, 0.5})
        settings.push_back({render::RendererKind::kProfile, 2, a, g, 0.0, f});
    }
  }
  // coarser heightfield levels of the 2.5 cm grid (level of detail)
  for (double h : full ? std::vector<double>{0.05, 0.1} : std::vector<double>{0.05})
    settings.push_back({render::RendererKind::kProfile, 2, 2, 0.025, h, 0.5});
  if (!full) settings.push_back({render::RendererKind::kRaytrace, 4, 2, 0.025, 0.0, 0.5});

  const std::string label = "fidelity: " + std::to_string(settings.size()) + " settings";
  const auto total = static_cast<double>(settings.size());
  if (out.progress) out.progress(label, 0.0, total);
  int done = 0;
  // one scene per grid (its tiles made once), and the ray tracers of a grid render from the
  // views of its first (each view built once)
  std::map<double, std::shared_ptr<const scene::Scene>> scenes;
  std::map<double, const render::RaytraceRenderer*> first_raytracer;
  std::vector<std::unique_ptr<render::PingRenderer>> raytracers;  // those, kept
  scenes[ref_desc.seabed.grid_spacing_m] = ref_scene;  // --full's finest grid is the reference's
  first_raytracer[ref_desc.seabed.grid_spacing_m] =
      dynamic_cast<const render::RaytraceRenderer*>(ref_renderer.get());
  for (const Setting& st : settings) {
    auto& built = scenes[st.grid_m];
    if (!built) {
      scene::SceneDesc sdsc = s.scene;
      sdsc.seabed.grid_spacing_m = st.grid_m;
      built = std::make_shared<const scene::Scene>(sdsc);
    }
    const scene::Scene& sc = *built;
    render::Fidelity f = render::default_fidelity(base_setup);
    f.rays_per_bin = st.rays_per_bin;
    f.along_track_rays = st.along;
    f.heightfield_spacing_m = st.heightfield_m;
    f.march_step_per_spacing = st.step_fraction;
    std::unique_ptr<render::PingRenderer> r = render::make_ping_renderer(st.kind, base_setup, f);
    if (auto* rt = dynamic_cast<render::RaytraceRenderer*>(r.get())) {
      const render::RaytraceRenderer*& first = first_raytracer[st.grid_m];
      if (first) rt->share_views_with(*first);
      if (!first) first = rt;
    }
    const LineSet got = render_set(sc, *r, poses);
    const LineErrors e = compare_lines(got, ref);
    const render::MarchPlan plan = render::march_plan(f, st.grid_m, base.bin_size_m);
    json::Writer w;
    w.begin_object().field("bench", "fidelity").field("renderer", render::renderer_name(st.kind));
    w.field("rays_per_bin", st.rays_per_bin).field("along_track_rays", st.along);
    w.field("grid_spacing_m", st.grid_m, 4);
    if (st.kind == render::RendererKind::kProfile) {
      w.field("heightfield_spacing_m", plan.spacing_m, 4).field("march_step_m", plan.step_m, 5);
    }
    w.field("ms_per_ping", 1e3 * got.seconds / static_cast<double>(poses.size()), 4);
    w.field("rms_db_error", e.rms_db, 4);
    w.field("shadow_edge_error_bins", e.target_edge_bins, 4);
    w.field("terrain_edge_error_bins", e.terrain_edge_bins, 4);
    w.field("reference", ref_name);
    w.end_object();
    if (out.emit) out.emit(w);
    if (r->kind() == render::RendererKind::kRaytrace) raytracers.push_back(std::move(r));
    ++done;
    if (out.progress) out.progress(label, done, total);
  }
}

void bench_accuracy(const config::Scenario& s, bool full, int threads, const SectionOutput& out) {
  const int per_target = full ? 11 : 5;
  std::vector<Case> cases;
  std::vector<std::pair<std::string, scene::SceneDesc>> scenes = {{s.scene.name, s.scene}};
  for (const std::string& kind : render::builtin_dataset_seabed_names())
    scenes.emplace_back(s.scene.name + "/" + kind, with_seabed_kind(s.scene, kind));
  for (const auto& [name, desc] : scenes) {
    const auto built = std::make_shared<const scene::Scene>(desc);
    for (const std::string& preset : config::builtin_sonar_names()) {
      Case c;
      c.name = name + " " + preset;
      c.scene = desc;
      c.built = built;
      c.sonar = echoes_only(config::builtin_sonar(preset));
      c.poses = poses_across_targets(desc, 2, per_target, 7.5);
      cases.push_back(std::move(c));
    }
  }
  {
    // terrain following over the rocky seabed with pitch and roll
    Case c;
    c.scene = with_seabed_kind(s.scene, "rocky");
    c.name = c.scene.name + " pailhas_strip pitch+roll";
    c.sonar = config::builtin_sonar("pailhas_strip");
    const scene::Scene probe(c.scene);
    const int n = 4 * per_target;
    for (int k = 0; k < n; ++k) {
      Pose p;
      const double north = -32.0 + 0.25 * k;
      p.position_W = Vec3(north, 0.0, probe.seabed_z(north, 0.0) - 6.0);
      p.pitch = 4.0 * kRadPerDeg * std::sin(0.3 * k);
      p.roll = 6.0 * kRadPerDeg * std::cos(0.2 * k);
      p.yaw = 3.0 * kRadPerDeg * std::sin(0.1 * k);
      c.poses.push_back(p);
    }
    c.built = std::make_shared<const scene::Scene>(c.scene);
    cases.push_back(std::move(c));
  }

  struct Sum {
    double rms = 0.0, target_edge = 0.0, terrain_edge = 0.0, ms = 0.0;
    int n = 0;
  };
  Sum sums[2];
  const std::string label = "accuracy: " + std::to_string(cases.size()) + " cases";
  const auto total = static_cast<double>(cases.size());
  if (out.progress) out.progress(label, 0.0, total);
  int done = 0;
  for (const Case& c : cases) {
    const scene::Scene& sc = *c.built;
    const render::SonarSetup setup = render::make_sonar_setup(c.sonar, c.scene.water);
    const render::Fidelity ref_fid = reference_fidelity(setup, full);
    const auto ref_r = render::make_ping_renderer(render::RendererKind::kRaytrace, setup, ref_fid);
    const LineSet ref = render_reference(sc, *ref_r, c.poses, threads);
    for (const render::RendererKind kind :
         {render::RendererKind::kProfile, render::RendererKind::kRaytrace}) {
      const auto r = render::make_ping_renderer(kind, setup);
      // the ray tracer renders from the reference's views (the same scene and regions)
      if (auto* rt = dynamic_cast<render::RaytraceRenderer*>(r.get()))
        rt->share_views_with(dynamic_cast<const render::RaytraceRenderer&>(*ref_r));
      const LineSet got = render_set(sc, *r, c.poses);
      const LineErrors e = compare_lines(got, ref);
      const double ms = 1e3 * got.seconds / static_cast<double>(c.poses.size());
      Sum& sum = sums[kind == render::RendererKind::kProfile ? 0 : 1];
      sum.rms += e.rms_db;
      sum.target_edge += e.target_edge_bins;
      sum.terrain_edge += e.terrain_edge_bins;
      sum.ms += ms;
      ++sum.n;
      json::Writer w;
      w.begin_object().field("bench", "accuracy").field("case", c.name);
      w.field("renderer", render::renderer_name(kind));
      w.field("rays_per_bin", r->fidelity().rays_per_bin)
          .field("along_track_rays", r->fidelity().along_track_rays);
      w.field("pings", static_cast<std::uint64_t>(c.poses.size()));
      w.field("ms_per_ping", ms, 4).field("rms_db_error", e.rms_db, 4);
      w.field("shadow_edge_error_bins", e.target_edge_bins, 4);
      w.field("terrain_edge_error_bins", e.terrain_edge_bins, 4);
      w.field("reference", "raytrace " + std::to_string(ref_fid.rays_per_bin) + "x" +
                               std::to_string(ref_fid.along_track_rays));
      w.end_object();
      if (out.emit) out.emit(w);
    }
    ++done;
    if (out.progress) out.progress(label, done, total);
  }
  for (int k = 0; k < 2; ++k) {
    const Sum& sum = sums[k];
    if (sum.n == 0) continue;
    json::Writer w;
    w.begin_object().field("bench", "accuracy_mean");
    w.field("renderer", k == 0 ? "profile" : "raytrace").field("cases", sum.n);
    w.field("ms_per_ping", sum.ms / sum.n, 4).field("rms_db_error", sum.rms / sum.n, 4);
    w.field("shadow_edge_error_bins", sum.target_edge / sum.n, 4);
    w.field("terrain_edge_error_bins", sum.terrain_edge / sum.n, 4);
    w.end_object();
    if (out.emit) out.emit(w);
  }
}

}  // namespace sonarloop::bench
