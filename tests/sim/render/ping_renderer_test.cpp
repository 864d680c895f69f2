// Both ping renderers (profile and raytrace) against the physics oracles: the flat-seabed sonar
// equation, the nadir gap, the maximum range, a box's highlight and shadow at their analytic
// slant ranges, the sediment order, speckle statistics and determinism.
#include "sim/render/ping_renderer.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "sim/acoustics/apl_sediment.h"
#include "sim/acoustics/beam_pattern.h"
#include "sim/acoustics/bottom_backscatter_apl.h"
#include "sim/render/quantise.h"
#include "sim/render/ray_fan.h"
#include "sim/render/raytrace_renderer.h"
#include "tests/sim/acoustics/oracles/spreading.h"
#include "tests/sim/render/level_pose.h"

using namespace sonarloop;
using namespace sonarloop::render;
using sonarloop::testing::kFlatSeabedDepth_m;
using sonarloop::testing::level_pose;

namespace {

scene::SceneDesc flat_scene(const char* sediment, double spacing = 0.05) {
  scene::SceneDesc d;
  d.seed = 3;
  d.water.depth_m = kFlatSeabedDepth_m;
  d.seabed.origin_m = Vec2(-60, -60);
  d.seabed.extent_m = Vec2(120, 120);
  d.seabed.grid_spacing_m = spacing;
  d.seabed.elevation.rms_m = 0.0;
  scene::RegionDesc r;
  r.sediment = *seabed::find_sediment(sediment);
  d.seabed.regions = {r};
  return d;
}

SonarDesc test_sonar() {
  SonarDesc s;
  s.frequency_hz = 100e3;
  s.source_level_db = 210.0;
  s.array_length_m = 1.0;
  s.array_height_m = 0.03;
  s.depression_deg = 20.0;
  s.max_range_m = 40.0;
  s.bin_size_m = 0.05;
  s.speckle = false;
  s.noise = false;
  return s;
}

double db(double x) {
  return 10.0 * std::log10(x);
}

RendererKind any_renderer() {
  return GENERATE(RendererKind::kProfile, RendererKind::kRaytrace);
}

// A ping over a flat very coarse sand seabed `altitude` m below the sonar against the sonar
// equation, bin by bin; returns the worst error (dB).
double check_flat_seabed_oracle(const PingLines& lines, const SonarDesc& sd,
                                const SonarSetup& setup, AlongTrackModel model, double altitude,
                                RendererKind kind) {
  CHECK(lines.altitude_m == Approx(altitude).margin(1e-3));
  const auto sed = acoustics::apl_sediment(*seabed::find_sediment("very_coarse_sand"));
  int checked = 0;
  double worst = 0.0;
  // the sonar equation at slant range r (dB re 1 µPa²), for a bin's worth of cell
  const auto echo_level = [&](double r) {
    const double grazing = std::asin(altitude / r);
    const double tl = acoustics::transmission_loss_db(r, setup.alpha_db_per_m);
    const double sb = acoustics::apl_backscatter_db(grazing, sd.frequency_hz, sed);
    // the cell: a slant bin covers bin/cos(grazing) of ground; along track a line array's
    // beam spans r·φ at slant range r whatever the depression (the cone sin ψ = const), and a
    // strip spans its width. (docs/physics.md's cosine cancellation in A = (cτ/2)·φ·r holds for a
    // beam whose width φ is an azimuth in the horizontal plane, not for a line array.)
    const double along = model == AlongTrackModel::kStrip ? setup.along_track_resolution_m
                                                          : setup.horizontal_beam_integral_rad * r;
    const double area = sd.bin_size_m / std::cos(grazing) * along;
    const double gv = acoustics::two_way_pattern_db(grazing - setup.array.depression_rad,
                                                    sd.array_height_m, setup.wavelength_m);
    return sd.source_level_db - 2.0 * tl + sb + db(area) + gv;
  };
  for (int k = 0; k < setup.bins; ++k) {
    const double r = (k + 0.5) * sd.bin_size_m;
    if (r < 1.5 * altitude || r > 0.95 * sd.max_range_m) continue;
    // what a bin receives is the equation averaged over its ranges (at 1.5x the altitude the
    // vertical pattern curves enough over 5 cm for the average to differ from the centre's
    // value by 0.002 dB)
    double mean = 0.0;
    constexpr int kSub = 64;
    for (int q = 0; q < kSub; ++q)
      mean +=
          std::pow(10.0, echo_level(k * sd.bin_size_m + (q + 0.5) * sd.bin_size_m / kSub) / 10.0) /
          kSub;
    const double expected = db(mean);
    const double got = db(lines.stbd[static_cast<std::size_t>(k)]);
    const double got_port = db(lines.port[static_cast<std::size_t>(k)]);
    INFO(renderer_name(kind) << " model " << int(model) << " bin " << k << " r " << r
                             << " expected " << expected << " got " << got);
    CHECK(std::abs(got - expected) < 0.002);
    CHECK(std::abs(got_port - got) < 1e-6);
    worst = std::max(worst, std::abs(got - expected));
    ++checked;
  }
  CHECK(checked > 500);
  return worst;
}

// Renders one ping of `desc` with the test sonar at `model`, the sonar at `pose_altitude` above
// the water depth's seabed, and checks it against the flat-seabed oracle for a seabed
// `altitude` m below; returns the worst error (dB).
double flat_seabed_ping_error(const scene::SceneDesc& desc, RendererKind kind,
                              AlongTrackModel model, double pose_altitude, double altitude) {
  const scene::Scene sc(desc);
  SonarDesc sd = test_sonar();
  sd.along_track = model;
  const SonarSetup setup = make_sonar_setup(sd, desc.water);
  const auto renderer = make_ping_renderer(kind, setup);
  PingScratch scratch;
  PingLines lines;
  renderer->render(sc, level_pose(pose_altitude), 1, 0, RenderOptions{}, scratch, lines);
  return check_flat_seabed_oracle(lines, sd, setup, model, altitude, kind);
}

}  // namespace

TEST_CASE("render: a flat homogeneous seabed follows SL - 2TL + Sb + 10 log A + beam pattern") {
  const RendererKind kind = any_renderer();
  for (auto model : {AlongTrackModel::kBeam, AlongTrackModel::kStrip}) {
    const double worst =
        flat_seabed_ping_error(flat_scene("very_coarse_sand"), kind, model, 8.0, 8.0);
    WARN("flat seabed oracle, " << renderer_name(kind) << ", along-track model " << int(model)
                                << ": worst error " << worst << " dB");
  }
}

TEST_CASE("render: a flat bathymetry grid gives the flat-seabed oracle") {
  // a grid 3 m deeper than the water depth everywhere, turned 20 degrees against north (as a
  // projected grid is, by its meridian convergence, though less): the seabed is 3 m lower and
  // the ping is the flat seabed's at the altitude that gives
  const RendererKind kind = any_renderer();
  scene::SceneDesc desc = flat_scene("very_coarse_sand");
  auto grid = std::make_shared<seabed::ReliefGrid>();
  grid->rows = 70;
  grid->cols = 70;
  const double turn = 20.0 * std::numbers::pi / 180.0;
  grid->row_step_m = 2.0 * Vec2(-std::cos(turn), -std::sin(turn));
  grid->col_step_m = 2.0 * Vec2(-std::sin(turn), std::cos(turn));
  grid->origin_m = -34.5 * (grid->row_step_m + grid->col_step_m);  // centred on the origin
  grid->elevation_m.assign(70 * 70, -3.0f);
  desc.seabed.bathymetry = scene::BathymetryDesc{};
  desc.seabed.bathymetry->grid = grid;
  const double worst = flat_seabed_ping_error(desc, kind, AlongTrackModel::kStrip, 5.0, 8.0);
  WARN("flat bathymetry grid, " << renderer_name(kind) << ": worst error " << worst << " dB");
}

TEST_CASE("render: first seabed return at the altitude (nadir gap), nothing beyond max range") {
  const RendererKind kind = any_renderer();
  const scene::SceneDesc desc = flat_scene("medium_sand");
  const scene::Scene sc(desc);
  const SonarSetup setup = make_sonar_setup(test_sonar(), desc.water);
  const auto renderer = make_ping_renderer(kind, setup);
  for (double altitude : {4.0, 9.3}) {
    const Pose pose = level_pose(altitude);
    PingScratch scratch;
    PingLines lines;
    renderer->render(sc, pose, 1, 0, RenderOptions{}, scratch, lines);
    int first = -1;
    for (int k = 0; k < setup.bins; ++k) {
      if (lines.stbd[static_cast<std::size_t>(k)] > 0.0f) {
        first = k;
        break;
      }
    }
    INFO(renderer_name(kind) << " altitude " << altitude);
    CHECK(std::abs(first - altitude / 0.05) <= 1.0);
    CHECK(lines.stbd.size() == static_cast<std::size_t>(setup.bins));
  }
}

TEST_CASE("render: nothing beyond the maximum range reaches the line") {
  const RendererKind kind = any_renderer();
  // a box whose nearest point is 1 m beyond the 40 m maximum slant range changes nothing
  const double a = 8.0;
  scene::SceneDesc with = flat_scene("medium_sand");
  scene::TargetDesc box;
  box.type = targets::TargetType::kBox;
  box.name = "far-box";
  const double x_near = std::sqrt(41.0 * 41.0 - (a - 0.4) * (a - 0.4));
  box.position_m = Vec2(0.0, x_near + 0.35);
  with.targets = {box};
  const scene::SceneDesc without = flat_scene("medium_sand");
  const scene::Scene s_with(with), s_without(without);
  const SonarSetup setup = make_sonar_setup(test_sonar(), with.water);
  const auto r = make_ping_renderer(kind, setup);
  const Pose pose = level_pose(a);
  PingScratch scratch;
  PingLines l_with, l_without;
  RenderOptions opt;
  opt.truth = true;
  // raytrace: views wider than the swath, so that the box is in the scene the rays are traced in
  opt.view_region = scene::Box2{Vec2(-50, -50), Vec2(50, 50)};
  r->render(s_with, pose, 1, 0, opt, scratch, l_with);
  CHECK(scratch.traces.empty());  // no ray reached it
  r->render(s_without, pose, 1, 0, opt, scratch, l_without);
  CHECK(l_with.stbd == l_without.stbd);
  CHECK(l_with.stbd.size() == static_cast<std::size_t>(setup.bins));
}

TEST_CASE("render: a box on a flat seabed: highlight and shadow at the analytic slant ranges") {
  const RendererKind kind = any_renderer();
  // geometry (flat seabed, sensor altitude a, box of height H whose near face is at ground range
  // x_n and far face at x_f = x_n + w, faces square to the beam):
  //   highlight starts at the near top edge:      r_h = sqrt((a - H)^2 + x_n^2)
  //   the last target echo is the far top edge:   r_t = sqrt((a - H)^2 + x_f^2)
  //   the top edge's shadow reaches the seabed at x_s = x_f · a / (a - H), slant r_s = sqrt(a^2 +
  //   x_s^2) so the shadow occupies slant ranges (r_t, r_s) (when the seabed in front, up to
  //   sqrt(a^2 + x_n^2), ends before r_t, as here)
  scene::SceneDesc desc = flat_scene("medium_sand");
  scene::TargetDesc box;
  box.type = targets::TargetType::kBox;  // 0.7 x 0.7 x 0.4
  box.name = "box";
  const double a = 10.0, h = 0.4, w = 0.7, x_n = 15.0;
  box.position_m = Vec2(0.0, x_n + w / 2);  // starboard of a north-going sonar
  box.heading_deg = 0.0;
  desc.targets = {box};
  const scene::Scene sc(desc);
  const SonarSetup setup = make_sonar_setup(test_sonar(), desc.water);
  const auto renderer = make_ping_renderer(kind, setup);
  const Pose pose = level_pose(a);
  PingScratch scratch;
  PingLines lines;
  RenderOptions opt;
  opt.truth = true;
  renderer->render(sc, pose, 1, 0, opt, scratch, lines);
  const double x_f = x_n + w;
  const double r_h = std::hypot(a - h, x_n);
  const double r_t = std::hypot(a - h, x_f);
  const double r_s = std::hypot(a, x_f * a / (a - h));
  const double dr = 0.05;
  // the rendered line: the shadow is the run of empty bins after the highlight
  const auto& s = lines.stbd;
  REQUIRE(scratch.traces.size() == 1);
  const TargetTrace& tr = scratch.traces[0];
  CHECK(tr.side == 1);
  CHECK(std::abs(tr.highlight_first - r_h / dr) <= 1.0);
  int empty_first = -1, empty_last = -1;
  for (int k = tr.highlight_first; k < setup.bins; ++k) {
    if (s[static_cast<std::size_t>(k)] == 0.0f) {
      if (empty_first < 0) empty_first = k;
      empty_last = k;
    } else if (empty_first >= 0) {
      break;
    }
  }
  INFO(renderer_name(kind) << ": highlight " << tr.highlight_first << ".." << tr.highlight_last
                           << " shadow " << empty_first << ".." << empty_last << " analytic r_h "
                           << r_h / dr << " r_t " << r_t / dr << " r_s " << r_s / dr);
  CHECK(std::abs(empty_first - r_t / dr) <= 2.0);
  CHECK(std::abs(empty_last + 1 - r_s / dr) <= 2.0);
  // the truth trace agrees with the analytic shadow on the seabed
  CHECK(std::abs(tr.shadow_last + 1 - r_s / dr) <= 2.0);
  // the port side sees no target and is lit throughout beyond the nadir gap
  for (float v : lines.port)
    REQUIRE(std::isfinite(v));
}

TEST_CASE("render: rougher sediments return more, in the order of the APL table") {
  const RendererKind kind = any_renderer();
  const char* order[] = {"rough_rock", "sandy_gravel", "very_coarse_sand", "very_fine_sand"};
  double prev = 1e300;
  for (const char* name : order) {
    const scene::SceneDesc desc = flat_scene(name);
    const scene::Scene sc(desc);
    const SonarSetup setup = make_sonar_setup(test_sonar(), desc.water);
    const auto renderer = make_ping_renderer(kind, setup);
    const Pose pose = level_pose(8.0);
    PingScratch scratch;
    PingLines lines;
    renderer->render(sc, pose, 1, 0, RenderOptions{}, scratch, lines);
    double sum = 0.0;
    for (int k = 200; k < 700; ++k)
      sum += lines.stbd[static_cast<std::size_t>(k)];
    INFO(renderer_name(kind) << " " << name << " mean " << db(sum / 500));
    CHECK(sum < prev);
    prev = sum;
  }
}

TEST_CASE("render: speckle on a flat homogeneous patch is exponential") {
  const RendererKind kind = any_renderer();
  const scene::SceneDesc desc = flat_scene("very_coarse_sand");
  const scene::Scene sc(desc);
  SonarDesc sd = test_sonar();
  sd.speckle = true;
  const SonarSetup setup = make_sonar_setup(sd, desc.water);
  const auto renderer = make_ping_renderer(kind, setup);
  const Pose pose = level_pose(8.0);
  PingScratch scratch;
  PingLines mean_line, line;
  RenderOptions no_speckle;
  no_speckle.speckle = false;
  renderer->render(sc, pose, 1, 0, no_speckle, scratch, mean_line);
  // intensity / local mean over many pings and bins: exponential with mean 1
  double s1 = 0, s2 = 0;
  long n = 0, above = 0;
  for (std::uint64_t ping = 0; ping < 200; ++ping) {
    renderer->render(sc, pose, 1, ping, RenderOptions{}, scratch, line);
    for (int k = 250; k < 750; ++k) {
      const double x =
          line.stbd[static_cast<std::size_t>(k)] / mean_line.stbd[static_cast<std::size_t>(k)];
      s1 += x;
      s2 += x * x;
      above += x > 2.0;
      ++n;
    }
  }
  const double mean = s1 / n;
  const double contrast = std::sqrt(s2 / n - mean * mean) / mean;
  // 10^5 samples: the sample mean, contrast and exceedance have standard errors well below these
  CHECK(mean == Approx(1.0).margin(0.01));
  CHECK(contrast == Approx(1.0).margin(0.02));
  CHECK(double(above) / n == Approx(0.1353).margin(0.005));
}

TEST_CASE("render: speckle through the pulse keeps the mean and is correlated over it") {
  // a 0.2 ms pulse is 15 cm: 3 bins of 5 cm. Per bin (the old model) adjacent bins are
  // independent; through the pulse their intensities correlate as (1 - k/3)^2
  // (acoustics/pulse_speckle.h); the recorder's max of 3 raw samples of a pulse one raw sample long
  // raises the mean by H_3 = 11/6 (acoustics/recorder_downsample.h)
  struct Setting {
    SpeckleModel model;
    int raw;
    acoustics::Downsample how;
    double pulse_s;
    double mean;
    std::array<double, 4> correlation;  // at 0 .. 3 bins
  };
  const Setting settings[] = {
      {SpeckleModel::kPerBin, 1, acoustics::Downsample::kRms, 2e-4, 1.0, {1.0, 0.0, 0.0, 0.0}},
      {SpeckleModel::kPulse, 1, acoustics::Downsample::kRms, 2e-4, 1.0, {1.0, 4.0 / 9, 1.0 / 9, 0}},
      {SpeckleModel::kPulse, 3, acoustics::Downsample::kMax, 2e-4 / 9, 11.0 / 6, {}}};
  const scene::SceneDesc desc = flat_scene("very_coarse_sand");
  const scene::Scene sc(desc);
  for (const Setting& st : settings) {
    SonarDesc sd = test_sonar();
    sd.speckle = true;
    sd.pulse_length_s = st.pulse_s;
    sd.speckle_model = st.model;
    sd.raw_samples_per_bin = st.raw;
    sd.downsample = st.how;
    const SonarSetup setup = make_sonar_setup(sd, desc.water);
    const auto renderer = make_ping_renderer(RendererKind::kProfile, setup);
    PingScratch scratch;
    PingLines mean_line, line;
    RenderOptions no_speckle;
    no_speckle.speckle = false;
    renderer->render(sc, level_pose(8.0), 1, 0, no_speckle, scratch, mean_line);
    std::vector<double> x;  // intensity over the local mean, bins 250 .. 749 of 300 pings
    for (std::uint64_t ping = 0; ping < 300; ++ping) {
      renderer->render(sc, level_pose(8.0), 1, ping, RenderOptions{}, scratch, line);
      for (std::size_t k = 250; k < 750; ++k)
        x.push_back(line.stbd[k] / mean_line.stbd[k]);
    }
    double s1 = 0.0;
    for (double v : x)
      s1 += v;
    const double mean = s1 / static_cast<double>(x.size());
    INFO("model " << int(st.model) << ", " << st.raw << " raw samples per bin");
    CHECK(mean == Approx(st.mean).epsilon(0.015));
    if (st.raw > 1) continue;
    for (std::size_t lag = 1; lag <= 3; ++lag) {
      double sab = 0.0, saa = 0.0;
      long n = 0;
      for (std::size_t j = 0; j + lag < x.size(); ++j) {
        if ((j % 500) + lag >= 500) continue;  // within one ping
        sab += (x[j] - mean) * (x[j + lag] - mean);
        saa += (x[j] - mean) * (x[j] - mean);
        ++n;
      }
      INFO("lag " << lag);
      CHECK(sab / saa == Approx(st.correlation[lag]).margin(0.02));
    }
  }
}

TEST_CASE("render: the recorder's floor fills the water column, the ring-down saturates") {
  // a floor of -40 dB re full scale: the water column's mean A² is 1e-4 per bin, and H_2 = 1.5
  // times that after the max of 2 independent raw samples (a pulse one raw sample long); the
  // transmit ring-down saturates the bins whose centre it reaches (acoustics/transmit_ringdown.h)
  struct Setting {
    SpeckleModel model;
    int raw;
    acoustics::Downsample how;
    double mean_a2;
  };
  const Setting settings[] = {{SpeckleModel::kPerBin, 1, acoustics::Downsample::kRms, 1e-4},
                              {SpeckleModel::kPulse, 2, acoustics::Downsample::kMax, 1.5e-4}};
  const scene::SceneDesc desc = flat_scene("very_coarse_sand");
  const scene::Scene sc(desc);
  for (const Setting& st : settings) {
    SonarDesc sd = test_sonar();
    sd.speckle = true;
    sd.sample_type = SampleType::kInt16;
    sd.speckle_model = st.model;
    sd.raw_samples_per_bin = st.raw;
    sd.downsample = st.how;
    sd.noise_floor_db_fs = -40.0;
    SonarSetup setup = make_sonar_setup(sd, desc.water);
    sd.pulse_length_s = 2.0 * 0.025 / setup.sound_speed_m_s;          // 2.5 cm: one raw sample
    sd.ringdown_s = 2.0 * 5 * sd.bin_size_m / setup.sound_speed_m_s;  // 5 bins' centres
    setup = make_sonar_setup(sd, desc.water);
    const auto renderer = make_ping_renderer(RendererKind::kProfile, setup);
    PingScratch scratch;
    PingLines line;
    std::vector<std::uint16_t> samples(static_cast<std::size_t>(setup.bins));
    double sum = 0.0;
    long n = 0;
    for (std::uint64_t ping = 0; ping < 300; ++ping) {
      renderer->render(sc, level_pose(8.0), 1, ping, RenderOptions{}, scratch, line);
      for (const auto* side : {&line.port, &line.stbd}) {
        quantise_line(setup, *side, samples);
        for (std::size_t k = 0; k < 5; ++k)
          CHECK(samples[k] == 32767);
        CHECK(samples[5] < 32767);
        // the water column, before the first return at 8 m (bin 160)
        for (std::size_t k = 10; k < 150; ++k) {
          const double a = relative_amplitude(setup, (*side)[k], (k + 0.5) * sd.bin_size_m);
          sum += a * a;
          ++n;
        }
      }
    }
    INFO("model " << int(st.model) << ", " << st.raw << " raw samples per bin");
    CHECK(sum / n == Approx(st.mean_a2).epsilon(0.02));
    // without noise the water column is silent; the ring-down stays
    RenderOptions quiet;
    quiet.noise = false;
    renderer->render(sc, level_pose(8.0), 1, 0, quiet, scratch, line);
    quantise_line(setup, line.stbd, samples);
    CHECK(samples[4] == 32767);
    for (std::size_t k = 5; k < 150; ++k)
      CHECK(line.stbd[k] == 0.0f);
  }
}

TEST_CASE("render: the same seed renders byte-identical pings, another seed differs") {
  const RendererKind kind = any_renderer();
  scene::SceneDesc desc = flat_scene("very_coarse_sand");
  desc.seabed.elevation.rms_m = 0.2;
  const scene::Scene sc(desc);
  SonarDesc sd = test_sonar();
  sd.speckle = true;
  sd.noise = true;
  const SonarSetup setup = make_sonar_setup(sd, desc.water);
  const auto renderer = make_ping_renderer(kind, setup);
  const Pose pose = level_pose(8.0, 30.0);
  PingScratch s1, s2;
  PingLines a, b, c;
  renderer->render(sc, pose, 7, 42, RenderOptions{}, s1, a);
  renderer->render(sc, pose, 7, 42, RenderOptions{}, s2, b);
  renderer->render(sc, pose, 8, 42, RenderOptions{}, s2, c);
  CHECK(a.port == b.port);
  CHECK(a.stbd == b.stbd);
  CHECK(a.stbd != c.stbd);
}

TEST_CASE("render: one scratch serves both renderers in turn, each making its own buffers") {
  scene::SceneDesc desc = flat_scene("very_coarse_sand");
  desc.seabed.elevation.rms_m = 0.2;
  const scene::Scene sc(desc);
  SonarDesc sd = test_sonar();
  sd.speckle = true;
  const SonarSetup setup = make_sonar_setup(sd, desc.water);
  const auto profile = make_ping_renderer(RendererKind::kProfile, setup);
  const auto raytrace = make_ping_renderer(RendererKind::kRaytrace, setup);
  const Pose pose = level_pose(8.0, 30.0);
  PingScratch fresh_profile, fresh_raytrace, shared;
  PingLines p0, r0, p1, r1, p2;
  profile->render(sc, pose, 7, 42, RenderOptions{}, fresh_profile, p0);
  raytrace->render(sc, pose, 7, 42, RenderOptions{}, fresh_raytrace, r0);
  CHECK(fresh_profile.own != nullptr);  // the profile renderer's own (the march's) buffers
  profile->render(sc, pose, 7, 42, RenderOptions{}, shared, p1);
  raytrace->render(sc, pose, 7, 42, RenderOptions{}, shared, r1);
  profile->render(sc, pose, 7, 42, RenderOptions{}, shared, p2);
  CHECK(p1.port == p0.port);
  CHECK(p1.stbd == p0.stbd);
  CHECK(r1.port == r0.port);
  CHECK(r1.stbd == r0.stbd);
  CHECK(p2.port == p0.port);
  CHECK(p2.stbd == p0.stbd);
}

TEST_CASE("render: a sonar out of the water (or below the seabed) renders silent lines") {
  const RendererKind kind = any_renderer();
  const scene::SceneDesc desc = flat_scene("medium_sand");
  const scene::Scene sc(desc);
  SonarDesc sd = test_sonar();
  sd.noise = true;
  const SonarSetup setup = make_sonar_setup(sd, desc.water);
  const auto renderer = make_ping_renderer(kind, setup);
  Pose pose = level_pose(-1.0);  // 1 m below the seabed
  PingScratch scratch;
  PingLines lines;
  renderer->render(sc, pose, 1, 0, RenderOptions{}, scratch, lines);
  CHECK(std::isnan(lines.altitude_m));
  CHECK(lines.stbd == std::vector<float>(static_cast<std::size_t>(setup.bins), 0.0f));
}

TEST_CASE("render: the default fidelity follows the pixel; the march plan picks coarser levels") {
  SonarDesc sd = test_sonar();
  const scene::WaterDesc water;
  sd.bin_size_m = 0.05;
  Fidelity f = default_fidelity(make_sonar_setup(sd, water));
  CHECK(f.rays_per_bin == 2);
  MarchPlan p = march_plan(f, 0.025, 0.05);
  CHECK(p.level == 0);
  CHECK(p.step_m == Approx(0.0125));
  // 30 cm pixels on a 2.5 cm grid: the 10 cm level, marched at 5 cm
  sd.bin_size_m = 0.3;
  f = default_fidelity(make_sonar_setup(sd, water));
  p = march_plan(f, 0.025, 0.3);
  CHECK(p.level == 2);
  CHECK(p.spacing_m == Approx(0.1));
  CHECK(p.step_m == Approx(0.05));
  // never coarser than half a bin, whatever the fidelity asks
  f.march_step_per_spacing = 4.0;
  CHECK(march_plan(f, 0.025, 0.3).step_m == Approx(0.15));
  // a grid already coarser than the pixel: level 0
  CHECK(march_plan(f, 0.5, 0.3).level == 0);
}

TEST_CASE("render: a target on seabed deeper than at nadir is seen through a narrow window") {
  // a seabed sloping down 5 % to starboard: at the box, 20 m out, it lies 1 m deeper than below
  // the sonar, so the box is seen at steeper depressions than a flat seabed at the nadir
  // altitude would put the window's ranges: the renderer must still cast rays at it
  scene::SceneDesc desc = flat_scene("medium_sand");
  desc.seabed.elevation.slope = Vec2(0.0, -0.05);
  scene::TargetDesc box;
  box.type = targets::TargetType::kBox;
  box.name = "box";
  box.position_m = Vec2(0.0, 20.0);
  desc.targets = {box};
  const scene::Scene sc(desc);
  const SonarSetup setup = make_sonar_setup(test_sonar(), desc.water);
  const auto renderer = make_ping_renderer(RendererKind::kProfile, setup);
  const Pose pose = level_pose(3.0);
  const double slant = std::hypot(20.0, 3.0 + 1.0 - 0.2);  // to the box's middle
  RenderOptions opt;
  opt.truth = true;
  opt.side_mask = 2;
  opt.range_min_m = slant - 1.5;
  opt.range_max_m = slant + 1.5;
  opt.shadow_margin_m = 1.5;
  PingScratch scratch;
  PingLines lines;
  renderer->render(sc, pose, 1, 0, opt, scratch, lines);
  REQUIRE(scratch.traces.size() == 1);
  CHECK(scratch.traces[0].highlight_first >= 0);
  CHECK(std::abs(scratch.traces[0].highlight_first * 0.05 - std::hypot(19.65, 3.6)) < 0.2);
  CHECK(scratch.traces[0].shadow_last > scratch.traces[0].highlight_last);
}

TEST_CASE("render: a ray tracer's view at a steep pitch covers no more than the range") {
  // a plane tilted by pitch reaches at most r·sin(pitch) along track within range r; the view
  // was r·tan(pitch) long (11 x the range at 85°), hundreds of metres of BVH out of range
  const scene::SceneDesc desc = flat_scene("medium_sand");
  const SonarSetup setup = make_sonar_setup(test_sonar(), desc.water);
  const RaytraceRenderer rt(setup, default_fidelity(setup));
  for (double pitch_deg : {0.0, 30.0, 85.0, 89.5}) {
    Pose pose = level_pose(8.0);
    pose.pitch = pitch_deg * std::numbers::pi / 180.0;
    const scene::Box2 b = rt.view_region_for(pose, RenderOptions{});
    // heading north: along track is x; the range (with margins) and one snapping cell each side
    const double bound = 2.0 * (kRangeMargin * setup.desc.max_range_m + 2.0) + 2.0 * kViewGrid_m;
    INFO("pitch " << pitch_deg << ": view " << b.max.x() - b.min.x() << " m along track");
    CHECK(b.max.x() - b.min.x() <= bound);
  }
}
