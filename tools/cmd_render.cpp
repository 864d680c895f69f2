// sonarloop render: fly a straight line over a scenario and write the pings as XTF and images.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <thread>

#include <unistd.h>

#include "drivers/json/json_writer.h"
#include "drivers/xtf/xtf_codec.h"
#include "drivers/xtf/xtf_file.h"
#include "emulator/xtf_ping.h"
#include "sim/core/geodesy.h"
#include "sim/render/quantise.h"
#include "sim/render/track_renderer.h"
#include "sim/scene/scene.h"
#include "sim/targets/target_type.h"
#include "tools/args.h"
#include "tools/cli_helpers.h"
#include "tools/commands.h"
#include "tools/progress.h"
#include "tools/scenario_source.h"
#include "tools/waterfall.h"
#include "tools/waterfall_annotations.h"

namespace sonarloop::tools {
namespace {

// Ping times are counted from this UTC instant (2026-01-01T00:00:00Z), so that renders are
// byte-identical from run to run.
constexpr std::int64_t kEpochUtcNs = 1767225600LL * 1'000'000'000LL;

struct Track {
  Vec2 start = Vec2::Zero();
  Vec2 end = Vec2::Zero();
};

// Memory per ping while rendering: its pose, both sides' float amplitudes and labels, the 8-bit
// slant- and ground-range waterfall images, and the altitude.
std::size_t bytes_per_ping(int bins) {
  return sizeof(Pose) + sizeof(double) + 2 * static_cast<std::size_t>(bins) * (sizeof(float) + 3);
}

std::string gib_text(double bytes) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1f GiB", bytes / (1024.0 * 1024.0 * 1024.0));
  return buf;
}

// The whole line is held in memory (the waterfall images): refuse, before any allocation, a
// line whose pings would need more than this machine's memory (issue 11: "std::bad_alloc").
void check_track_memory(const std::string& track_text, double length_m, double spacing_m,
                        int bins) {
  const double pings = std::floor(length_m / spacing_m) + 1.0;
  const double need = pings * static_cast<double>(bytes_per_ping(bins));
  const double have = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) *
                      static_cast<double>(::sysconf(_SC_PAGE_SIZE));
  if (std::isfinite(need) && need <= have && pings < 2e9) return;
  char msg[512];
  std::snprintf(msg, sizeof msg,
                "--track %s: a line of %.6g m at %.3g m per ping is %.4g pings of %d samples "
                "per side, about %s of memory for the waterfall, more than the %s of this "
                "machine; shorten the track or choose a coarser --resolution-cm",
                track_text.c_str(), length_m, spacing_m, pings, bins, gib_text(need).c_str(),
                gib_text(have).c_str());
  throw UsageError(msg);
}

Track parse_track(const std::string& text) {
  double n0 = 0, e0 = 0, n1 = 0, e1 = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf:%lf,%lf%c", &n0, &e0, &n1, &e1, &tail) != 4 ||
      (n0 == n1 && e0 == e1) || !std::isfinite(n0) || !std::isfinite(e0) || !std::isfinite(n1) ||
      !std::isfinite(e1)) {
    throw UsageError("--track: '" + text +
                     "' is not NORTH0,EAST0:NORTH1,EAST1 (two distinct points)");
  }
  return Track{Vec2(n0, e0), Vec2(n1, e1)};
}

// Default line: north-going over the targets' mean east position, from 20 m before the
// southernmost target to 20 m past the northernmost (the seabed's centre line if no targets),
// clipped to the extent.
Track default_track(const scene::Scene& s) {
  const Vec2 lo = s.seabed().extent_min();
  const Vec2 hi = s.seabed().extent_max();
  if (s.targets().empty()) {
    const double e = 0.5 * (lo.y() + hi.y());
    return Track{Vec2(lo.x(), e), Vec2(hi.x(), e)};
  }
  double n_min = 1e300, n_max = -1e300, e_sum = 0.0;
  for (const auto& t : s.targets()) {
    n_min = std::min(n_min, t.desc.position_m.x());
    n_max = std::max(n_max, t.desc.position_m.x());
    e_sum += t.desc.position_m.y();
  }
  const double e = e_sum / static_cast<double>(s.targets().size());
  return Track{Vec2(std::max(lo.x(), n_min - 20.0), e), Vec2(std::min(hi.x(), n_max + 20.0), e)};
}

struct TargetTruth {
  int side = -1;
  int ping_first = -1, ping_last = -1;
  int sample_first = -1, sample_last = -1;
  int shadow_ping_first = -1, shadow_ping_last = -1;
  int shadow_first = -1, shadow_last = -1;
  double energy = 0.0, energy_ping = 0.0, energy_sample = 0.0;  // for the energy centroid
};

void extend(int& lo, int& hi, int v) {
  if (v < 0) return;
  if (lo < 0 || v < lo) lo = v;
  if (hi < 0 || v > hi) hi = v;
}

int run_render(const std::vector<std::string>& argv) {
  const Args args(
      argv,
      {{"--out"}, {"--resolution-cm"}, {"--altitude"}, {"--track"}, {"--threads"}, {"--renderer"}});
  if (args.positionals().size() > 1) throw UsageError("expected at most one SCENARIO.yaml");
  const auto out_dir = args.get("--out");
  if (!out_dir) throw UsageError("--out DIR is required");
  const int threads =
      static_cast<int>(args.get_int("--threads", 1, 256)
                           .value_or(std::max(1u, std::thread::hardware_concurrency())));

  config::Scenario scenario = load_scenario_or_default(
      args.positionals().empty() ? std::nullopt : std::optional(args.positionals()[0]));
  render::SonarDesc& sd = scenario.sonar;
  if (const auto r = args.get_double("--resolution-cm", 1.0, 100.0)) {
    // isotropic pixels: range bin, along-track resolution and ping spacing all equal R
    sd.bin_size_m = *r / 100.0;
    sd.along_track_resolution_m = *r / 100.0;
    sd.pulse_length_s = 0.0;
    sd.chirp_bandwidth_hz = 0.0;
  }
  const scene::Scene sc(scenario.scene);
  const render::SonarSetup setup = render::make_sonar_setup(sd, scenario.scene.water);
  const auto renderer_ptr = render::make_ping_renderer(renderer_option(args), setup);
  const render::PingRenderer& renderer = *renderer_ptr;
  const Track track = args.get("--track") ? parse_track(*args.get("--track")) : default_track(sc);
  const double altitude = args.get_double("--altitude", 0.5, 500.0)
                              .value_or(std::clamp(0.15 * sd.max_range_m, 2.0, 20.0));

  // pings every pixel along the line, at constant depth (altitude above the mean seabed)
  const double spacing = sd.along_track == render::AlongTrackModel::kStrip
                             ? setup.along_track_resolution_m
                             : sd.bin_size_m;
  const Vec2 dir = (track.end - track.start).normalized();
  const double length = (track.end - track.start).norm();
  check_track_memory(args.get("--track").value_or("(default)"), length, spacing, setup.bins);
  const auto n_pings = static_cast<std::size_t>(std::floor(length / spacing)) + 1;
  std::vector<Pose> poses(n_pings);
  for (std::size_t k = 0; k < n_pings; ++k) {
    const Vec2 p = track.start + dir * (static_cast<double>(k) * spacing);
    poses[k].position_W = Vec3(p.x(), p.y(), scenario.scene.water.depth_m - altitude);
    poses[k].yaw = std::atan2(dir.y(), dir.x());
  }
  const double speed_m_s = spacing / setup.ping_period_s;

  namespace fs = std::filesystem;
  const fs::path dir_out(*out_dir);
  fs::create_directories(dir_out);
  const xtf::XtfFileHeader header =
      emulator::make_xtf_file_header(setup, sd.name, "sonarloop render " + scenario.scene.name);
  xtf::XtfWriter writer((dir_out / "pings.xtf").string(), header);
  const LocalTangentPlane ltp(
      GeoPoint{scenario.scene.origin.latitude_deg, scenario.scene.origin.longitude_deg});

  WaterfallData wf;
  wf.bins = setup.bins;
  wf.bin_size_m = sd.bin_size_m;
  wf.amplitude.resize(n_pings * 2 * static_cast<std::size_t>(setup.bins));
  wf.altitude_m.resize(n_pings);
  wf.label.resize(wf.amplitude.size());
  std::vector<std::vector<render::TargetTrace>> traces_by_ping(n_pings);
  std::vector<TargetTruth> truth(sc.targets().size());
  xtf::XtfPing packet;

  render::TrackRenderOptions opt;
  opt.ping.truth = true;
  opt.ping.labels = true;
  opt.threads = threads;
  const auto t0 = std::chrono::steady_clock::now();
  Progress bar("rendering " + std::to_string(n_pings) + " pings", 1.0);
  render::render_track(
      sc, renderer, poses, scenario.scene.seed, opt,
      [&](std::size_t k, const render::PingLines& lines,
          std::span<const render::TargetTrace> traces) {
        // XTF packet
        emulator::PingNav nav;
        nav.time_utc_ns = kEpochUtcNs + static_cast<std::int64_t>(std::llround(
                                            static_cast<double>(k) * setup.ping_period_s * 1e9));
        nav.sensor = ltp.to_geodetic(poses[k].position_W.x(), poses[k].position_W.y());
        nav.heading_deg = heading_deg_from_yaw(poses[k].yaw);
        nav.depth_m = poses[k].position_W.z();
        nav.altitude_m = lines.altitude_m;
        nav.speed_m_s = speed_m_s;
        nav.ping_number = static_cast<std::uint32_t>(k);
        emulator::make_xtf_ping(setup, header, lines, nav, packet);
        writer.write_ping(packet);
        // waterfall (relative amplitude) and truth
        float* row = wf.amplitude.data() + k * 2 * static_cast<std::size_t>(setup.bins);
        for (int b = 0; b < setup.bins; ++b) {
          const double r = (b + 0.5) * sd.bin_size_m;
          row[b] = static_cast<float>(
              render::relative_amplitude(setup, lines.port[static_cast<std::size_t>(b)], r));
          row[setup.bins + b] = static_cast<float>(
              render::relative_amplitude(setup, lines.stbd[static_cast<std::size_t>(b)], r));
        }
        wf.altitude_m[k] = lines.altitude_m;
        // labels, laid out as the amplitudes; the traces, to tell the targets' boxes apart
        std::uint8_t* label_row = wf.label.data() + k * 2 * static_cast<std::size_t>(setup.bins);
        std::copy(lines.port_label.begin(), lines.port_label.end(), label_row);
        std::copy(lines.stbd_label.begin(), lines.stbd_label.end(), label_row + setup.bins);
        traces_by_ping[k].assign(traces.begin(), traces.end());
        for (const auto& tr : traces) {
          TargetTruth& t = truth[static_cast<std::size_t>(tr.target)];
          t.side = tr.side;
          const int p = static_cast<int>(k);
          if (tr.highlight_first >= 0) {
            extend(t.ping_first, t.ping_last, p);
            extend(t.sample_first, t.sample_last, tr.highlight_first);
            extend(t.sample_first, t.sample_last, tr.highlight_last);
            t.energy += tr.energy;
            t.energy_ping += tr.energy * p;
            t.energy_sample += tr.energy * 0.5 * (tr.highlight_first + tr.highlight_last);
          }
          if (tr.shadow_first >= 0) {
            extend(t.shadow_ping_first, t.shadow_ping_last, p);
            extend(t.shadow_first, t.shadow_last, tr.shadow_first);
            extend(t.shadow_first, t.shadow_last, tr.shadow_last);
          }
        }
      },
      [&](double f) { bar.update(f); });
  bar.finish();
  writer.close();
  const double render_s = seconds_since(t0);

  write_waterfall_png((dir_out / "waterfall.png").string(), wf);
  write_ground_waterfall_png((dir_out / "waterfall_ground.png").string(), wf);
  write_label_png((dir_out / "labels.png").string(), wf);
  std::vector<AnnotatedTarget> annotated;
  for (const auto& pt : sc.targets())
    annotated.push_back(AnnotatedTarget{pt.desc.name, pt.desc.type});
  write_coco_annotations((dir_out / "annotations.json").string(), wf,
                         label_boxes(wf, traces_by_ping), annotated, "waterfall.png", "labels.png");

  json::Writer w(true);
  w.begin_object().field("scenario", scenario.scene.name).field("seed", scenario.scene.seed);
  w.field("sonar", sd.name);
  w.field("pings", static_cast<std::uint64_t>(n_pings)).field("bins_per_side", setup.bins);
  w.field("bin_size_m", sd.bin_size_m)
      .field("ping_spacing_m", spacing)
      .field("altitude_m", altitude);
  w.field("frame",
          "track_m and position_m are [north, east] in metres from the scenario origin (the frame "
          "of scene.json and of the onboard consumer's contacts, north_m / east_m)");
  w.key("origin")
      .begin_object()
      .field("latitude_deg", scenario.scene.origin.latitude_deg, 9)
      .field("longitude_deg", scenario.scene.origin.longitude_deg, 9)
      .end_object();
  w.key("track_m").begin_array();
  w.begin_array().value(track.start.x()).value(track.start.y()).end_array();
  w.begin_array().value(track.end.x()).value(track.end.y()).end_array();
  w.end_array();
  w.field(
      "indexing",
      "ping = XTF PingNumber (0 = first, at track start); sample = slant-range bin of that side "
      "counted from nadir (bin k covers [k, k+1) * bin_size_m); in waterfall.png a port sample "
      "is at column bins-1-sample, a starboard one at bins+sample, and ping p at row pings-1-p");
  w.key("targets").begin_array();
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const auto& t = truth[i];
    const auto& pt = sc.targets()[i];
    w.begin_object()
        .field("name", pt.desc.name)
        .field("type", std::string(targets::target_type_info(pt.desc.type).key));
    w.key("position_m")
        .begin_array()
        .value(pt.desc.position_m.x())
        .value(pt.desc.position_m.y())
        .end_array();
    w.field("seen", t.ping_first >= 0);
    if (t.ping_first >= 0) {
      w.field("side", t.side == 0 ? "port" : "starboard");
      w.key("highlight")
          .begin_object()
          .field("ping_first", t.ping_first)
          .field("ping_last", t.ping_last)
          .field("sample_first", t.sample_first)
          .field("sample_last", t.sample_last)
          .field("centroid_ping", t.energy_ping / t.energy, 6)
          .field("centroid_sample", t.energy_sample / t.energy, 6)
          .end_object();
      w.key("shadow").begin_object();
      if (t.shadow_first >= 0) {
        w.field("ping_first", t.shadow_ping_first)
            .field("ping_last", t.shadow_ping_last)
            .field("sample_first", t.shadow_first)
            .field("sample_last", t.shadow_last);
      }
      w.end_object();
    }
    w.end_object();
  }
  w.end_array();
  w.field("renderer", render::renderer_name(renderer.kind()));
  w.field("render_s", render_s, 4).field("threads", threads);
  w.end_object();
  std::ofstream(dir_out / "truth.json") << w.str() << '\n';
  std::printf(
      "rendered %zu pings x 2 x %d bins at %.3g m in %.2f s (%s renderer, %d threads): "
      "%s\n",
      n_pings, setup.bins, sd.bin_size_m, render_s, render::renderer_name(renderer.kind()), threads,
      dir_out.string().c_str());
  return 0;
}

}  // namespace

const Command kRenderCommand{
    "render", "fly a straight line over a scenario; write pings.xtf, waterfalls and target truth",
    R"(usage: sonarloop render [SCENARIO.yaml] --out DIR [options]

Flies the scenario's sonar along a straight line at constant depth, one ping per pixel along
track, renders every ping (the sonar equation over what the ping sees: the heightfield profile
renderer by default, --renderer raytrace for the Embree reference) and writes:
  pings.xtf              the pings as XTF (2 channels, the sonar's sample type)
  waterfall.png          8-bit slant-range waterfall: port on the left, starboard on the right,
                         the last ping at the top (a north-going line reads north-up)
  waterfall_ground.png   the same, ground-range corrected with each ping's nadir altitude
  truth.json             per target: the pings and samples of its highlight and of its shadow
  labels.png             per pixel of waterfall.png (aligned pixel for pixel): 0 seabed,
                         1 target highlight, 2 target shadow, from the render's physics
                         (docs/rendering.md); the values themselves, so it looks black
  annotations.json       COCO-style boxes around each target's labelled highlight and shadow
                         pixels (separate annotations, attribute "part"), category = target type
Without SCENARIO.yaml the embedded default scenario is used.

options:
  --out DIR              output folder (created if needed)
  --resolution-cm R      pixel size: range bin, along-track resolution and ping spacing (cm)
                         (default: the sonar's bin size)
  --altitude A           altitude above the mean seabed in metres (default 15 % of max range,
                         within 2..20 m)
  --track N0,E0:N1,E1    the line, metres north/east (default: north-going over the targets);
                         it is held in memory: a line needing more than the machine has
                         is refused up front
  --threads N            rendering threads (default: all cores)
  --renderer R           profile (default) or raytrace (the Embree reference)

examples:
  sonarloop render --out out/render
  sonarloop render --out out/render_rt --renderer raytrace
  sonarloop render config/seabed_rocky.yaml --out out/rocky --resolution-cm 3 --altitude 8
  sonarloop render config/default.yaml --out out/line --track -40,5:40,5
)",
    run_render, 30};
SONARLOOP_REGISTER_COMMAND(kRenderCommand);

}  // namespace sonarloop::tools
