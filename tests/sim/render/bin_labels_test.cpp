// Per-bin labels of a ping (bin_labels.h) from both renderers: a box on a flat seabed is labelled
// highlight at its slant ranges and shadow behind it, at the analytic ranges, and seabed
// elsewhere; asking for labels changes no echo; not asking leaves them empty.
#include "sim/render/bin_labels.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <memory>

#include "tests/sim/render/level_pose.h"
#include "tests/sim/render/strip_sonar.h"

using namespace sonarloop;
using namespace sonarloop::render;
using sonarloop::testing::kFlatSeabedDepth_m;
using sonarloop::testing::level_pose;

namespace {

constexpr double kBin_m = 0.05;

// a flat medium-sand seabed with, optionally, a 0.7 x 0.7 x 0.4 m box whose near face is at
// ground range x_near starboard of a north-going sonar
scene::SceneDesc box_scene(bool with_box, double x_near) {
  scene::SceneDesc d;
  d.seed = 3;
  d.water.depth_m = kFlatSeabedDepth_m;
  d.seabed.origin_m = Vec2(-60, -60);
  d.seabed.extent_m = Vec2(120, 120);
  d.seabed.grid_spacing_m = 0.05;
  d.seabed.elevation.rms_m = 0.0;
  scene::RegionDesc r;
  r.sediment = *seabed::find_sediment("medium_sand");
  d.seabed.regions = {r};
  if (with_box) {
    scene::TargetDesc box;
    box.type = targets::TargetType::kBox;
    box.name = "box";
    box.position_m = Vec2(0.0, x_near + 0.35);
    d.targets = {box};
  }
  return d;
}

// the default sonar: 5 cm bins, a pulse one bin long (so a label is its own bin's)
SonarDesc test_sonar(bool speckle) {
  SonarDesc s = sonarloop::testing::pailhas_strip_sonar();
  REQUIRE(s.bin_size_m == kBin_m);
  s.speckle = speckle;
  s.noise = speckle;
  return s;
}

// A scene, a sonar and a renderer of `kind`, with the scratch and options of one ping.
struct Rig {
  Rig(const scene::SceneDesc& desc, bool speckle, RendererKind kind)
      : sc(desc),
        setup(make_sonar_setup(test_sonar(speckle), desc.water)),
        renderer(make_ping_renderer(kind, setup)) {
    options.labels = true;
  }
  void render(double altitude, std::uint64_t ping, PingLines& lines) {
    renderer->render(sc, level_pose(altitude), 7, ping, options, scratch, lines);
  }
  scene::Scene sc;
  SonarSetup setup;
  std::unique_ptr<PingRenderer> renderer;
  PingScratch scratch;
  RenderOptions options;
};

struct Runs {
  int first = -1, last = -1, count = 0;
};

Runs runs_of(const std::vector<std::uint8_t>& label, std::uint8_t value) {
  Runs r;
  for (int k = 0; k < static_cast<int>(label.size()); ++k) {
    if (label[static_cast<std::size_t>(k)] != value) continue;
    if (r.first < 0) r.first = k;
    r.last = k;
    ++r.count;
  }
  return r;
}

}  // namespace

TEST_CASE("labels: a box on a flat seabed is highlight at its ranges, shadow behind, seabed else") {
  const RendererKind kind = GENERATE(RendererKind::kProfile, RendererKind::kRaytrace);
  // the geometry of ping_renderer_test's box: altitude a, box height H, faces at x_n and x_f
  const double a = 10.0, h = 0.4, x_n = 15.0, x_f = x_n + 0.7;
  Rig rig(box_scene(true, x_n), false, kind);
  rig.options.truth = true;
  PingLines lines;
  rig.render(a, 0, lines);
  const SonarSetup& setup = rig.setup;
  REQUIRE(lines.stbd_label.size() == static_cast<std::size_t>(setup.bins));
  REQUIRE(lines.port_label.size() == static_cast<std::size_t>(setup.bins));
  const double r_h = std::hypot(a - h, x_n) / kBin_m;            // highlight starts
  const double r_t = std::hypot(a - h, x_f) / kBin_m;            // last target echo
  const double r_s = std::hypot(a, x_f * a / (a - h)) / kBin_m;  // shadow ends
  const Runs hi = runs_of(lines.stbd_label, kLabelHighlight);
  const Runs sh = runs_of(lines.stbd_label, kLabelShadow);
  INFO(renderer_name(kind) << ": highlight " << hi.first << ".." << hi.last << " (" << hi.count
                           << ") shadow " << sh.first << ".." << sh.last << " (" << sh.count
                           << ") analytic " << r_h << " " << r_t << " " << r_s);
  // highlight: from the near top edge, within the target's slant ranges
  REQUIRE(hi.count > 0);
  CHECK(std::abs(hi.first - r_h) <= 1.5);
  CHECK(hi.last <= r_t + 1.5);
  // shadow: the seabed the box hides, from its last echo to where the top edge's shadow ends
  REQUIRE(sh.count > 0);
  CHECK(sh.first >= hi.last);
  CHECK(std::abs(sh.last + 1 - r_s) <= 2.0);
  CHECK(sh.count >= 0.8 * (r_s - r_t));
  // it agrees with the truth trace of the same ping
  REQUIRE(rig.scratch.traces.size() == 1);
  const TargetTrace& tr = rig.scratch.traces[0];
  CHECK(hi.first >= tr.highlight_first - 1);
  CHECK(hi.last <= tr.highlight_last + 1);
  CHECK(sh.first >= tr.shadow_first - 1);
  CHECK(sh.last <= tr.shadow_last + 1);
  // the shadow is dark and the highlight bright against the seabed just beyond the shadow
  double shadow_sum = 0.0, seabed_sum = 0.0, highlight_sum = 0.0;
  for (int k = sh.first; k <= sh.last; ++k)
    shadow_sum += lines.stbd[static_cast<std::size_t>(k)];
  for (int k = hi.first; k <= hi.last; ++k)
    highlight_sum += lines.stbd[static_cast<std::size_t>(k)];
  for (int k = sh.last + 5; k < sh.last + 25; ++k)
    seabed_sum += lines.stbd[static_cast<std::size_t>(k)];
  CHECK(shadow_sum / sh.count < 0.05 * seabed_sum / 20.0);
  CHECK(highlight_sum / hi.count > seabed_sum / 20.0);
  // every other bin, and the whole port side, is seabed
  CHECK(hi.count + sh.count + runs_of(lines.stbd_label, kLabelSeabed).count == setup.bins);
  CHECK(runs_of(lines.port_label, kLabelSeabed).count == setup.bins);
}

TEST_CASE("labels: a seabed without targets is all seabed, its own shadows included") {
  const RendererKind kind = GENERATE(RendererKind::kProfile, RendererKind::kRaytrace);
  scene::SceneDesc desc = box_scene(false, 0.0);
  desc.seabed.elevation.rms_m = 0.3;  // relief, with shadows of its own
  desc.seabed.elevation.outer_scale_m = 5.0;
  Rig rig(desc, true, kind);
  PingLines lines;
  rig.render(4.0, 0, lines);
  CHECK(runs_of(lines.port_label, kLabelSeabed).count == rig.setup.bins);
  CHECK(runs_of(lines.stbd_label, kLabelSeabed).count == rig.setup.bins);
}

TEST_CASE("labels: asking for them changes no echo; not asking leaves them empty") {
  const RendererKind kind = GENERATE(RendererKind::kProfile, RendererKind::kRaytrace);
  Rig rig(box_scene(true, 12.0), true, kind);
  PingLines plain, labelled;
  rig.options.truth = true;
  rig.options.labels = false;
  rig.render(6.0, 3, plain);
  const std::vector<TargetTrace> plain_traces = rig.scratch.traces;
  rig.options.labels = true;
  rig.render(6.0, 3, labelled);
  CHECK(plain.port_label.empty());
  CHECK(plain.stbd_label.empty());
  CHECK(runs_of(labelled.stbd_label, kLabelHighlight).count > 0);
  REQUIRE(plain.stbd.size() == labelled.stbd.size());
  CHECK(std::memcmp(plain.stbd.data(), labelled.stbd.data(), plain.stbd.size() * 4) == 0);
  CHECK(std::memcmp(plain.port.data(), labelled.port.data(), plain.port.size() * 4) == 0);
  REQUIRE(plain_traces.size() == rig.scratch.traces.size());
  CHECK(plain_traces[0].shadow_last == rig.scratch.traces[0].shadow_last);
  // the same scratch, labels off again: the lines forget them
  rig.options.labels = false;
  rig.render(6.0, 3, labelled);
  CHECK(labelled.stbd_label.empty());
}

TEST_CASE("labels: a range window labels only its bins") {
  Rig rig(box_scene(true, 15.0), false, RendererKind::kProfile);
  PingLines full, window;
  rig.render(10.0, 0, full);
  rig.options.range_min_m = 17.0;
  rig.options.range_max_m = 19.0;
  rig.options.shadow_margin_m = 2.0;
  rig.options.side_mask = 2;
  rig.render(10.0, 0, window);
  const int k0 = static_cast<int>(17.0 / kBin_m), k1 = static_cast<int>(19.0 / kBin_m);
  for (int k = 0; k < rig.setup.bins; ++k) {
    const auto u = static_cast<std::size_t>(k);
    if (k >= k0 && k < k1) {
      CHECK(window.stbd_label[u] == full.stbd_label[u]);
    } else {
      CHECK(window.stbd_label[u] == kLabelSeabed);
    }
  }
  CHECK(runs_of(window.stbd_label, kLabelShadow).count > 0);
}
