// The heightfield profile renderer against the ray-traced reference on terrain: the four seabed
// kinds, a sonar pitched and rolled, the range window with its shadow margin, and the coarser
// detail levels for coarse pixels.
#include "sim/render/profile_renderer.h"

#include <atomic>
#include <catch2/catch.hpp>
#include <cmath>

#include "sim/render/chip_renderer.h"
#include "sim/render/raytrace_renderer.h"
#include "units/angles.h"

using namespace sonarloop;
using namespace sonarloop::render;
using sonarloop::kRadPerDeg;

namespace {

scene::SceneDesc seabed_scene(const std::string& kind) {
  scene::SceneDesc d = builtin_dataset_seabed(kind).desc;
  d.seabed.origin_m = Vec2(-60, -60);
  d.seabed.extent_m = Vec2(120, 120);
  scene::TargetDesc manta;
  manta.type = targets::TargetType::kManta;
  manta.name = "manta";
  manta.position_m = Vec2(0.0, 14.0);
  d.targets = {manta};
  return d;
}

SonarDesc noiseless_strip_sonar(double bin_m = 0.05) {
  SonarDesc s;
  s.frequency_hz = 300e3;
  s.array_length_m = 0.5;
  s.array_height_m = 0.006;
  s.depression_deg = 15.0;
  s.max_range_m = 30.0;
  s.bin_size_m = bin_m;
  s.along_track = AlongTrackModel::kStrip;
  s.speckle = false;
  s.noise = false;
  return s;
}

struct Diff {
  double rms_db = 0.0;
  long lit = 0;
  long dark_mismatch = 0;  // bins dark in one render and lit in the other, beyond the nadir gap
  long bins = 0;
};

Diff compare(const PingLines& a, const PingLines& b) {
  Diff d;
  double se = 0.0;
  for (const auto* pair : {&a.port, &a.stbd}) {
    const auto& x = *pair;
    const auto& y = pair == &a.port ? b.port : b.stbd;
    // from the reference's first lit bin (the nadir gap) to its last (its fan is laid out for a
    // flat seabed at the nadir altitude and can fall short of the far end over deeper seabed)
    std::size_t k = 0, end = y.size();
    while (k < y.size() && y[k] <= 0.0f)
      ++k;
    while (end > k && y[end - 1] <= 0.0f)
      --end;
    for (k += 4; k < end; ++k) {
      ++d.bins;
      if (x[k] > 0.0f && y[k] > 0.0f) {
        const double e = 10.0 * std::log10(static_cast<double>(x[k]) / y[k]);
        se += e * e;
        ++d.lit;
      } else if ((x[k] > 0.0f) != (y[k] > 0.0f)) {
        ++d.dark_mismatch;
      }
    }
  }
  d.rms_db = d.lit ? std::sqrt(se / static_cast<double>(d.lit)) : 0.0;
  return d;
}

// Errors of the profile renderer and of the ray tracer at its default (2 rays per bin, 2 along
// track) against a dense ray-traced reference (8 x 4) on the same pings. On rough rock the
// reference's triangulated grid and the profile's bilinear surface differ at the lattice scale,
// so the profile is held to the ray tracer's own default error there, not to zero.
struct Errors {
  double profile_rms = 0.0, raytrace_rms = 0.0;
  double profile_dark = 0.0, raytrace_dark = 0.0;  // fraction of lit/dark disagreements
};

Errors errors_against_reference(const scene::Scene& sc, const std::vector<Pose>& poses,
                                bool check_targets) {
  const SonarSetup setup = make_sonar_setup(noiseless_strip_sonar(), sc.desc().water);
  Fidelity ref_f = default_fidelity(setup);
  ref_f.rays_per_bin = 8;
  ref_f.along_track_rays = 4;
  const RaytraceRenderer ref(setup, ref_f);
  const RaytraceRenderer ray(setup, default_fidelity(setup));
  const ProfileRenderer prof(setup, default_fidelity(setup));
  RenderOptions opt;
  opt.truth = true;
  PingScratch s0, s1, s2;
  PingLines l0, l1, l2;
  Errors e;
  long bins = 0, dark1 = 0, dark2 = 0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    ref.render(sc, poses[k], 1, k, opt, s0, l0);
    prof.render(sc, poses[k], 1, k, opt, s1, l1);
    ray.render(sc, poses[k], 1, k, opt, s2, l2);
    const Diff d1 = compare(l1, l0), d2 = compare(l2, l0);
    e.profile_rms += d1.rms_db / static_cast<double>(poses.size());
    e.raytrace_rms += d2.rms_db / static_cast<double>(poses.size());
    bins += d1.bins;
    dark1 += d1.dark_mismatch;
    dark2 += d2.dark_mismatch;
    if (!check_targets) continue;
    // the Manta: seen by both, its highlight starting in the same bin
    REQUIRE(s1.traces.size() == 1);
    REQUIRE(s0.traces.size() == 1);
    CHECK(std::abs(s1.traces[0].highlight_first - s0.traces[0].highlight_first) <= 1);
    CHECK(std::abs(s1.traces[0].shadow_last - s0.traces[0].shadow_last) <= 2);
    CHECK(s1.traces[0].energy / s0.traces[0].energy == Approx(1.0).margin(0.25));
  }
  e.profile_dark = static_cast<double>(dark1) / static_cast<double>(bins);
  e.raytrace_dark = static_cast<double>(dark2) / static_cast<double>(bins);
  return e;
}

void check_at_least_as_close(const Errors& e) {
  CHECK(e.profile_rms <= std::max(1.2 * e.raytrace_rms, e.raytrace_rms + 0.2));
  CHECK(e.profile_dark <= std::max(1.2 * e.raytrace_dark, e.raytrace_dark + 0.01));
}

}  // namespace

TEST_CASE("profile renderer: as close to a dense ray-traced reference as the ray tracer is") {
  for (const std::string kind : {"flat", "ripples", "clutter", "rocky"}) {
    const scene::Scene sc(seabed_scene(kind));
    std::vector<Pose> poses;
    for (int k = 0; k < 6; ++k) {
      Pose pose;
      pose.position_W = Vec3(-0.4 + 0.15 * k, 0.0, sc.desc().water.depth_m - 5.0);
      poses.push_back(pose);
    }
    const Errors e = errors_against_reference(sc, poses, true);
    INFO(kind << ": RMS profile " << e.profile_rms << " dB, raytrace " << e.raytrace_rms
              << " dB; lit/dark disagreements profile " << e.profile_dark << ", raytrace "
              << e.raytrace_dark);
    check_at_least_as_close(e);
    if (kind != "rocky") CHECK(e.profile_rms < 1.0);
    WARN("against raytrace 8x4 on " << kind << ": profile " << e.profile_rms
                                    << " dB RMS, raytrace 2x2 " << e.raytrace_rms << " dB RMS");
  }
}

TEST_CASE("profile renderer: pitched, rolled and yawed, as close to the reference") {
  const scene::Scene sc(seabed_scene("rocky"));
  for (const auto& [pitch, roll, yaw] :
       {std::tuple{5.0, 0.0, 0.0}, {0.0, 8.0, 0.0}, {-4.0, -6.0, 30.0}, {3.0, 10.0, 200.0}}) {
    Pose pose;
    pose.position_W = Vec3(0.0, 0.0, sc.desc().water.depth_m - 6.0);
    pose.pitch = pitch * kRadPerDeg;
    pose.roll = roll * kRadPerDeg;
    pose.yaw = yaw * kRadPerDeg;
    const Errors e = errors_against_reference(sc, {pose}, false);
    INFO("pitch " << pitch << " roll " << roll << " yaw " << yaw << ": RMS profile "
                  << e.profile_rms << " dB, raytrace " << e.raytrace_rms << " dB; lit/dark profile "
                  << e.profile_dark << ", raytrace " << e.raytrace_dark);
    check_at_least_as_close(e);
  }
}

TEST_CASE("profile renderer: a range window renders the same bins as the whole line") {
  const scene::Scene sc(seabed_scene("clutter"));
  const SonarSetup setup = make_sonar_setup(noiseless_strip_sonar(), sc.desc().water);
  const ProfileRenderer prof(setup, default_fidelity(setup));
  Pose pose;
  pose.position_W = Vec3(0.2, 0.0, sc.desc().water.depth_m - 5.0);
  PingScratch s;
  PingLines whole, part;
  prof.render(sc, pose, 1, 0, {}, s, whole);
  RenderOptions w;
  w.range_min_m = 10.0;
  w.range_max_m = 14.0;
  w.shadow_margin_m = 3.0;
  prof.render(sc, pose, 1, 0, w, s, part);
  // inside the window, the lines agree except where a shadow caster lies more than the margin
  // before it (none here at 5 m altitude and 0.25 m rocks); outside it, nothing
  int same = 0, inside = 0;
  for (int k = 0; k < setup.bins; ++k) {
    const double r = (k + 0.5) * 0.05;
    const auto i = static_cast<std::size_t>(k);
    if (r > 10.0 && r < 14.0) {
      ++inside;
      same += std::abs(part.stbd[i] - whole.stbd[i]) <= 1e-3f * whole.stbd[i];
    } else if (r < 9.9 || r > 14.1) {
      CHECK(part.stbd[i] == 0.0f);
    }
  }
  CHECK(same >= inside - 2);
}

TEST_CASE("profile renderer: coarse pixels read a coarser level of the same surface") {
  // 30 cm pixels: the 10 cm level (a 16th of the points of the 2.5 cm grid). The mean level is
  // kept; bin by bin the rippled seabed differs by about a dB (a 0.8 m ripple sampled 8 times a
  // wavelength has gentler slopes between lattice points: docs/rendering.md, "Level of detail")
  for (const std::string kind : {"flat", "ripples", "rocky"}) {
    const scene::Scene sc(seabed_scene(kind));
    const SonarSetup setup = make_sonar_setup(noiseless_strip_sonar(0.3), sc.desc().water);
    const Fidelity coarse = default_fidelity(setup);
    REQUIRE(march_plan(coarse, 0.025, 0.3).level == 2);
    Fidelity fine = coarse;
    fine.heightfield_spacing_m = 0.0;  // level 0
    REQUIRE(march_plan(fine, 0.025, 0.3).level == 0);
    const ProfileRenderer a(setup, coarse), b(setup, fine);
    PingScratch s1, s2;
    PingLines la, lb;
    double rms = 0.0, sum_a = 0.0, sum_b = 0.0;
    for (int k = 0; k < 5; ++k) {
      Pose pose;
      pose.position_W = Vec3(-20.0 + 0.3 * k, 0.0, sc.desc().water.depth_m - 5.0);
      a.render(sc, pose, 1, 0, {}, s1, la);
      b.render(sc, pose, 1, 0, {}, s2, lb);
      rms += compare(la, lb).rms_db / 5;
      for (std::size_t i = 20; i < la.stbd.size(); ++i) {
        sum_a += la.stbd[i] + la.port[i];
        sum_b += lb.stbd[i] + lb.port[i];
      }
      CHECK(s1.samples < s2.samples / 3);
    }
    const double bias_db = 10.0 * std::log10(sum_a / sum_b);
    INFO(kind << ": RMS " << rms << " dB, mean level " << bias_db << " dB");
    CHECK(std::abs(bias_db) < 0.5);
    CHECK(rms < 2.0);
    WARN("level 2 against level 0 at 30 cm, " << kind << ": " << rms << " dB RMS per bin, "
                                              << bias_db << " dB mean");
  }
}

TEST_CASE("profile renderer: a steep pitch reads no heights out of range, and sees nothing") {
  // issue 29: a pose pitched 80-90° (its beam planes nearly level) had each sample's depth
  // below the plane land dz·tan(pitch) along track, hundreds of metres away: each ping made
  // tiles there for 2-46 s, for samples out of range anyway
  const scene::SceneDesc desc = seabed_scene("rocky");
  const SonarSetup setup = make_sonar_setup(noiseless_strip_sonar(), desc.water);
  const ProfileRenderer prof(setup, default_fidelity(setup));
  const auto tiles_for = [&](double pitch_deg, PingLines& lines) {
    const scene::Scene sc(desc);  // a fresh scene: no tiles yet
    Pose pose;
    pose.position_W = Vec3(0.0, 0.0, sc.desc().water.depth_m - 6.0);
    pose.pitch = pitch_deg * kRadPerDeg;
    PingScratch s;
    prof.render(sc, pose, 1, 0, {}, s, lines);
    return sc.seabed().tiles_made();
  };
  PingLines level, steep;
  const auto level_tiles = tiles_for(0.0, level);
  const auto steep_tiles = tiles_for(89.5, steep);
  INFO("tiles made: level " << level_tiles << ", pitched 89.5° " << steep_tiles);
  CHECK(steep_tiles <= 4 * level_tiles);
  // the planes meet the seabed 690 m away, far beyond the 30 m range: every bin is dark
  for (const auto* line : {&steep.port, &steep.stbd})
    for (float v : *line)
      CHECK(v == 0.0f);
}

TEST_CASE("renderers: an abandoned ping returns early; an unset flag changes nothing") {
  const scene::Scene sc(seabed_scene("clutter"));
  const SonarSetup setup = make_sonar_setup(noiseless_strip_sonar(), sc.desc().water);
  const ProfileRenderer prof(setup, default_fidelity(setup));
  const RaytraceRenderer ray(setup, default_fidelity(setup));
  Pose pose;
  pose.position_W = Vec3(0.2, 0.0, sc.desc().water.depth_m - 5.0);
  for (const PingRenderer* r :
       {static_cast<const PingRenderer*>(&prof), static_cast<const PingRenderer*>(&ray)}) {
    const bool profile = r->kind() == RendererKind::kProfile;
    INFO((profile ? "profile" : "raytrace"));
    PingScratch s;
    PingLines plain, flagged, cut;
    r->render(sc, pose, 1, 0, {}, s, plain);
    std::atomic<bool> abandon{false};
    RenderOptions o;
    o.abandon = &abandon;
    r->render(sc, pose, 1, 0, o, s, flagged);
    CHECK(flagged.port == plain.port);
    CHECK(flagged.stbd == plain.stbd);
    abandon = true;
    r->render(sc, pose, 1, 0, o, s, cut);
    CHECK(s.samples == 0);  // no beam plane marched
    if (!profile) CHECK(s.rays_cast == 0);
  }
}
