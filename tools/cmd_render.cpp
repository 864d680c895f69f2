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

#include "common/geodesy.h"
#include "drivers/json/json_writer.h"
#include "drivers/xtf/xtf_codec.h"
#include "drivers/xtf/xtf_file.h"
#include "emulator/xtf_ping.h"
#include "products/render_truth.h"
#include "products/waterfall.h"
#include "products/waterfall_annotations.h"
#include "sim/render/quantise.h"
#include "sim/render/track_renderer.h"
#include "sim/scene/scene.h"
#include "sim/targets/target_type.h"
#include "tools/args.h"
#include "tools/cli_helpers.h"
#include "tools/commands.h"
#include "tools/progress.h"
#include "tools/scenario_source.h"

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

// --resolution-cm R: isotropic pixels; range bin, along-track resolution and ping spacing all
// equal R (no pulse or chirp to widen the range bin).
void apply_resolution(const Args& args, render::SonarDesc& sd) {
  if (const auto r = args.get_double("--resolution-cm", 1.0, 100.0)) {
    sd.bin_size_m = *r / 100.0;
    sd.along_track_resolution_m = *r / 100.0;
    sd.pulse_length_s = 0.0;
    sd.chirp_bandwidth_hz = 0.0;
  }
}

// One ping every `spacing` m along the line, at constant depth, heading along it.
std::vector<Pose> line_poses(const Track& track, std::size_t n_pings, double spacing,
                             double depth_m) {
  const Vec2 dir = (track.end - track.start).normalized();
  std::vector<Pose> poses(n_pings);
  for (std::size_t k = 0; k < n_pings; ++k) {
    const Vec2 p = track.start + dir * (static_cast<double>(k) * spacing);
    poses[k].position_W = Vec3(p.x(), p.y(), depth_m);
    poses[k].yaw = std::atan2(dir.y(), dir.x());
  }
  return poses;
}

// Ping k's navigation for its XTF packet: times from kEpochUtcNs at the ping period.
emulator::PingNav ping_nav(std::size_t k, const Pose& pose, const render::PingLines& lines,
                           const render::SonarSetup& setup, const LocalTangentPlane& ltp,
                           double speed_m_s) {
  emulator::PingNav nav;
  nav.time_utc_ns =
      kEpochUtcNs +
      static_cast<std::int64_t>(std::llround(static_cast<double>(k) * setup.ping_period_s * 1e9));
  nav.sensor = ltp.to_geodetic(pose.position_W.x(), pose.position_W.y());
  nav.heading_deg = heading_deg_from_yaw(pose.yaw);
  nav.depth_m = pose.position_W.z();
  nav.altitude_m = lines.altitude_m;
  nav.speed_m_s = speed_m_s;
  nav.ping_number = static_cast<std::uint32_t>(k);
  return nav;
}

// What the line's images and truth are made of, filled ping by ping.
struct LineImages {
  products::WaterfallData wf;
  std::vector<std::vector<render::TargetTrace>> traces_by_ping;  // to tell the targets' boxes apart
  std::vector<products::TargetTruth> truth;                      // per target
};

LineImages make_line_images(std::size_t n_pings, int bins, double bin_size_m, std::size_t targets) {
  LineImages li;
  li.wf.bins = bins;
  li.wf.bin_size_m = bin_size_m;
  li.wf.amplitude.resize(n_pings * 2 * static_cast<std::size_t>(bins));
  li.wf.altitude_m.resize(n_pings);
  li.wf.label.resize(li.wf.amplitude.size());
  li.traces_by_ping.resize(n_pings);
  li.truth.resize(targets);
  return li;
}

// Ping k into the waterfall (relative amplitude, labels laid out as the amplitudes) and the truth.
void add_ping(LineImages& li, std::size_t k, const render::SonarSetup& setup, double bin_size_m,
              const render::PingLines& lines, std::span<const render::TargetTrace> traces) {
  products::WaterfallData& wf = li.wf;
  float* row = wf.amplitude.data() + k * 2 * static_cast<std::size_t>(setup.bins);
  for (int b = 0; b < setup.bins; ++b) {
    const double r = (b + 0.5) * bin_size_m;
    row[b] = static_cast<float>(
        render::relative_amplitude(setup, lines.port[static_cast<std::size_t>(b)], r));
    row[setup.bins + b] = static_cast<float>(
        render::relative_amplitude(setup, lines.stbd[static_cast<std::size_t>(b)], r));
  }
  wf.altitude_m[k] = lines.altitude_m;
  std::uint8_t* label_row = wf.label.data() + k * 2 * static_cast<std::size_t>(setup.bins);
  std::copy(lines.port_label.begin(), lines.port_label.end(), label_row);
  std::copy(lines.stbd_label.begin(), lines.stbd_label.end(), label_row + setup.bins);
  li.traces_by_ping[k].assign(traces.begin(), traces.end());
  products::add_ping_traces(li.truth, k, traces);
}

// The slant- and ground-range waterfalls, the label image and their COCO annotations.
void write_images(const std::filesystem::path& dir_out, const LineImages& li,
                  const scene::Scene& sc) {
  products::write_waterfall_png((dir_out / "waterfall.png").string(), li.wf);
  products::write_ground_waterfall_png((dir_out / "waterfall_ground.png").string(), li.wf);
  products::write_label_png((dir_out / "labels.png").string(), li.wf);
  std::vector<products::AnnotatedTarget> annotated;
  for (const auto& pt : sc.targets())
    annotated.push_back(products::AnnotatedTarget{pt.desc.name, pt.desc.type});
  products::write_coco_annotations((dir_out / "annotations.json").string(), li.wf,
                                   products::label_boxes(li.wf, li.traces_by_ping), annotated,
                                   "waterfall.png", "labels.png");
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
  apply_resolution(args, sd);
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
  const double length = (track.end - track.start).norm();
  check_track_memory(args.get("--track").value_or("(default)"), length, spacing, setup.bins);
  const auto n_pings = static_cast<std::size_t>(std::floor(length / spacing)) + 1;
  const std::vector<Pose> poses =
      line_poses(track, n_pings, spacing, scenario.scene.water.depth_m - altitude);
  const double speed_m_s = spacing / setup.ping_period_s;

  namespace fs = std::filesystem;
  const fs::path dir_out(*out_dir);
  fs::create_directories(dir_out);
  const xtf::XtfFileHeader header =
      emulator::make_xtf_file_header(setup, sd.name, "sonarloop render " + scenario.scene.name);
  xtf::XtfWriter writer((dir_out / "pings.xtf").string(), header);
  const LocalTangentPlane ltp(
      GeoPoint{scenario.scene.origin.latitude_deg, scenario.scene.origin.longitude_deg});
  LineImages images = make_line_images(n_pings, setup.bins, sd.bin_size_m, sc.targets().size());
  xtf::XtfPing packet;

  // render: each ping to pings.xtf, the waterfall and the truth
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
        emulator::make_xtf_ping(setup, header, lines,
                                ping_nav(k, poses[k], lines, setup, ltp, speed_m_s), packet);
        writer.write_ping(packet);
        add_ping(images, k, setup, sd.bin_size_m, lines, traces);
      },
      [&](double f) { bar.update(f); });
  bar.finish();
  writer.close();
  const double render_s = seconds_since(t0);

  // report: the images, truth.json and a line on stdout
  write_images(dir_out, images, sc);
  products::RenderedLine line;
  line.scenario = scenario.scene.name;
  line.seed = scenario.scene.seed;
  line.latitude_deg = scenario.scene.origin.latitude_deg;
  line.longitude_deg = scenario.scene.origin.longitude_deg;
  line.sonar = sd.name;
  line.pings = n_pings;
  line.bins_per_side = setup.bins;
  line.bin_size_m = sd.bin_size_m;
  line.ping_spacing_m = spacing;
  line.altitude_m = altitude;
  line.track_start = track.start;
  line.track_end = track.end;
  line.renderer = render::renderer_name(renderer.kind());
  line.render_s = render_s;
  line.threads = threads;
  products::write_render_truth_json((dir_out / "truth.json").string(), line, sc, images.truth);
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
