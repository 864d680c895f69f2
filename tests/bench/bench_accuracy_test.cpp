// The line comparison of the bench's accuracy sections (bench/bench_accuracy.h) on lines with a
// known answer: identical lines have no error; a line 10 times brighter is 10 dB off in every
// bin lit in both, but for bins 60 dB under the line's level; a shadow edge or a lit/dark
// transition moved by k bins is k bins off; the isotropic strip sonar has the pixel as its bin and
// along-track resolution; the reference rendered on two threads is the one-thread render, ping for
// ping.
#include "bench/bench_accuracy.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "sim/render/chip_renderer.h"

using namespace sonarloop;

namespace {

// One ping: port dark, starboard lit from bin 10 to `lit_end` (exclusive) at `level` but for a
// dark run from `dark_first` (10 bins), a target's shadow ending at `shadow_last`.
bench::LineSet one_ping(float level, int lit_end, int shadow_last, int dark_first = 50) {
  bench::LineSet s;
  render::PingLines l;
  l.port.assign(100, 0.0f);
  l.stbd.assign(100, 0.0f);
  for (int i = 10; i < lit_end; ++i) {
    if (i < dark_first || i >= dark_first + 10) l.stbd[static_cast<std::size_t>(i)] = level;
  }
  s.lines.push_back(l);
  render::TargetTrace t;
  t.target = 0;
  t.side = 1;
  t.shadow_first = 40;
  t.shadow_last = shadow_last;
  s.traces.push_back({t});
  return s;
}

}  // namespace

TEST_CASE("bench accuracy: the line comparison measures what it says") {
  const bench::LineSet ref = one_ping(1.0f, 80, 50);
  const bench::LineErrors same = bench::compare_lines(ref, ref);
  CHECK(same.rms_db == 0.0);
  CHECK(same.lit_bins == 60);
  CHECK(same.terrain_edges == 4);  // the dark run's two transitions, both ways
  CHECK(same.target_edge_bins == 0.0);
  CHECK(same.target_edges == 1);
  CHECK(same.terrain_edge_bins == 0.0);

  const bench::LineErrors brighter = bench::compare_lines(one_ping(10.0f, 80, 50), ref);
  CHECK(brighter.rms_db == Approx(10.0));
  CHECK(brighter.lit_bins == 60);

  // the target's shadow ends 3 bins later
  CHECK(bench::compare_lines(one_ping(1.0f, 80, 53), ref).target_edge_bins == Approx(3.0));

  // the dark run 2 bins further: each of its transitions 2 bins from the reference's
  CHECK(bench::compare_lines(one_ping(1.0f, 80, 50, 52), ref).terrain_edge_bins == Approx(2.0));
  // the lit run ending 2 bins early makes a transition the reference does not have (before its
  // last lit bin): counted as kMaxEdgeMatchBins, one of five
  const bench::LineErrors shorter = bench::compare_lines(one_ping(1.0f, 78, 50), ref);
  CHECK(shorter.terrain_edges == 5);
  CHECK(shorter.terrain_edge_bins == Approx(bench::kMaxEdgeMatchBins / 5.0));
}

TEST_CASE("bench accuracy: bins far below the line's level are not in the dB error") {
  // one bin 150 dB under the others (a sliver lit at a shadow's edge) and 10 dB off: outside
  // the error; one 40 dB under and 10 dB off: inside it
  bench::LineSet ref = one_ping(1.0f, 80, 50);
  bench::LineSet got = ref;
  ref.lines[0].stbd[20] = 1e-15f;
  got.lines[0].stbd[20] = 1e-14f;
  const bench::LineErrors sliver = bench::compare_lines(got, ref);
  CHECK(sliver.rms_db == 0.0);
  CHECK(sliver.lit_bins == 59);
  ref.lines[0].stbd[20] = 1e-4f;
  got.lines[0].stbd[20] = 1e-3f;
  const bench::LineErrors faint = bench::compare_lines(got, ref);
  CHECK(faint.lit_bins == 60);
  CHECK(faint.rms_db == Approx(10.0 / std::sqrt(60.0)).epsilon(1e-4));
}

TEST_CASE("bench accuracy: the isotropic strip sonar") {
  render::SonarDesc base;
  base.bin_size_m = 0.02;
  base.pulse_length_s = 1e-4;
  const render::SonarDesc s = bench::isotropic_strip_sonar(base, 30.0, 0.05);
  CHECK(s.along_track == render::AlongTrackModel::kStrip);
  CHECK(s.max_range_m == 30.0);
  CHECK(s.bin_size_m == 0.05);
  CHECK(s.along_track_resolution_m == 0.05);
  CHECK(s.pulse_length_s == 0.0);
  CHECK(s.chirp_bandwidth_hz == 0.0);
}

TEST_CASE("bench accuracy: compared lines hold echoes only, not the recorder's ring-down") {
  render::SonarDesc base;
  base.ringdown_s = 320e-6;
  base.noise_floor_db_fs = -45.0;
  CHECK(bench::echoes_only(base).ringdown_s == 0.0);
  CHECK(bench::isotropic_strip_sonar(base, 30.0, 0.05).ringdown_s == 0.0);
  // a ring-down that read full scale in both lines would be edges at distance 0
  bench::LineSet a = one_ping(1.0f, 90, 55);
  bench::LineSet b = one_ping(1.0f, 90, 55);
  const auto clean = bench::compare_lines(a, b);
  for (auto* s : {&a, &b}) {
    for (std::size_t k = 0; k < 5; ++k)
      s->lines[0].stbd[k] = 1e3f;
  }
  CHECK(bench::compare_lines(a, b).terrain_edges > clean.terrain_edges);
}

TEST_CASE("bench accuracy: the reference on two threads is the one-thread render, ping for ping") {
  scene::SceneDesc d = render::builtin_dataset_seabed("clutter").desc;
  d.seabed.origin_m = Vec2(-30, -30);
  d.seabed.extent_m = Vec2(60, 60);
  const scene::Scene sc(d);
  render::SonarDesc sonar;
  sonar = bench::isotropic_strip_sonar(sonar, 15.0, 0.05);
  const render::SonarSetup setup = render::make_sonar_setup(sonar, d.water);
  std::vector<Pose> poses;
  for (int k = 0; k < 7; ++k) {
    Pose p;
    p.position_W = Vec3(-2.0 + 0.3 * k, 0.0, d.water.depth_m - 5.0);
    p.roll = 0.05 * k;
    poses.push_back(p);
  }
  for (const auto kind : {render::RendererKind::kProfile, render::RendererKind::kRaytrace}) {
    const auto r = render::make_ping_renderer(kind, setup);
    const bench::LineSet one = bench::render_set(sc, *r, poses);
    const bench::LineSet two = bench::render_reference(sc, *r, poses, 2);
    REQUIRE(two.lines.size() == poses.size());
    for (std::size_t k = 0; k < poses.size(); ++k) {
      CHECK(two.lines[k].port == one.lines[k].port);
      CHECK(two.lines[k].stbd == one.lines[k].stbd);
      CHECK(two.traces[k].size() == one.traces[k].size());
    }
    const bench::LineErrors e = bench::compare_lines(two, one);
    CHECK(e.rms_db == 0.0);
    CHECK(e.lit_bins > 0);
  }
}
