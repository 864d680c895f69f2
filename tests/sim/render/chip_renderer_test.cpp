#include "sim/render/chip_renderer.h"

#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <string>

#include "tests/sim/render/strip_sonar.h"

using namespace sonarloop;
using namespace sonarloop::render;

namespace {

ChipDatasetSpec spec(std::vector<std::string> seabeds, std::vector<double> resolutions_m,
                     ChipKind kind = ChipKind::kHighlight, std::uint64_t seed = 5) {
  ChipDatasetSpec s;
  s.seed = seed;
  s.kind = kind;
  s.classes = {targets::TargetType::kManta, targets::TargetType::kRockan,
               targets::TargetType::kCuboid, targets::TargetType::kCylinder};
  for (const auto& name : seabeds)
    s.seabeds.push_back(builtin_dataset_seabed(name));
  s.resolutions_m = std::move(resolutions_m);
  s.sonar = sonarloop::testing::pailhas_strip_sonar();  // the paper's sonar
  return s;
}

std::vector<ChipImage> render_all(const ChipRenderer& r, std::size_t n, int threads,
                                  int resolution = 0) {
  std::vector<ChipJob> jobs;
  for (std::size_t i = 0; i < n; ++i)
    jobs.push_back(ChipJob{i, resolution});
  std::vector<ChipImage> out;
  const std::size_t done =
      render_chips(r, jobs, threads, [&](const ChipImage& c) { out.push_back(c); });
  REQUIRE(done == n);
  REQUIRE(out.size() == n);
  return out;
}

double wrap360(double a) {
  a = std::fmod(a, 360.0);
  return a < 0.0 ? a + 360.0 : a;
}

double quantile(std::vector<float> v, double q) {
  REQUIRE(!v.empty());
  const auto k = static_cast<long>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[static_cast<std::size_t>(k)];
}

// 10 log10 of the mean linear intensity of levels in dB.
double mean_intensity_db(const std::vector<float>& levels_db) {
  REQUIRE(!levels_db.empty());
  double sum = 0.0;
  for (float l : levels_db)
    sum += std::pow(10.0, l / 10.0);
  return 10.0 * std::log10(sum / static_cast<double>(levels_db.size()));
}

}  // namespace

TEST_CASE("chips: parameters are balanced, within bounds and consistent") {
  ChipDatasetSpec s = spec({"flat", "ripples", "clutter"}, {0.05});
  std::map<int, int> per_class, per_seabed, per_side;
  std::map<std::pair<int, int>, int> class_seabed;
  constexpr int kN = 1200;
  for (std::uint64_t i = 0; i < kN; ++i) {
    const ChipParams p = chip_params(s, i);
    CHECK(p.index == i);
    ++per_class[static_cast<int>(p.type)];
    ++per_seabed[p.seabed];
    ++per_side[p.side];
    ++class_seabed[{static_cast<int>(p.type), p.seabed}];
    CHECK(p.type == s.classes[i % 4]);
    CHECK(p.altitude_m >= 2.0);
    CHECK(p.altitude_m <= 10.0);
    CHECK(p.ground_range_m >= 5.0);
    CHECK(p.ground_range_m <= 50.0);
    CHECK(p.target_heading_deg >= 0.0);
    CHECK(p.target_heading_deg < 360.0);
    CHECK(p.aspect_deg >= 0.0);
    CHECK(p.aspect_deg < 360.0);
    CHECK(std::abs(p.along_offset) <= 0.5);
    const double look = p.track_heading_deg + (p.side == 1 ? 90.0 : -90.0);
    const double d = wrap360(p.target_heading_deg - look - p.aspect_deg);
    CHECK(std::min(d, 360.0 - d) < 1e-9);
    // on the shared seabed, inside its margins
    CHECK(std::abs(p.target_ne_m.x()) <= 0.5 * kDatasetSeabedSize_m - kDatasetSeabedMargin_m);
    CHECK(std::abs(p.target_ne_m.y()) <= 0.5 * kDatasetSeabedSize_m - kDatasetSeabedMargin_m);
  }
  // exactly balanced classes, and every class on every seabed equally
  REQUIRE(per_class.size() == 4);
  for (const auto& [c, n] : per_class)
    CHECK(n == kN / 4);
  REQUIRE(per_seabed.size() == 3);
  for (const auto& [b, n] : per_seabed)
    CHECK(n == kN / 3);
  for (const auto& [cb, n] : class_seabed)
    CHECK(n == kN / 12);
  // both sides, about half each
  CHECK(per_side[0] > kN / 2 - 100);
  CHECK(per_side[1] > kN / 2 - 100);
  // the same index gives the same parameters; another seed others
  const ChipParams a = chip_params(s, 17);
  const ChipParams b = chip_params(s, 17);
  CHECK(a.altitude_m == b.altitude_m);
  CHECK(a.target_ne_m == b.target_ne_m);
  s.seed = 6;
  CHECK(chip_params(s, 17).altitude_m != a.altitude_m);
  // shadow chips: the same scenes at the fixed 25 m ground range
  ChipDatasetSpec sh = spec({"flat", "ripples", "clutter"}, {0.05}, ChipKind::kShadow);
  const ChipParams hp = chip_params(spec({"flat", "ripples", "clutter"}, {0.05}), 3);
  const ChipParams sp = chip_params(sh, 3);
  CHECK(sp.ground_range_m == kShadowGroundRange_m);
  CHECK(sp.altitude_m == hp.altitude_m);
  CHECK(sp.target_heading_deg == hp.target_heading_deg);
}

TEST_CASE("chips: the same index gives the same bytes on any number of threads") {
  const ChipRenderer r(spec({"flat", "ripples", "clutter"}, {0.2}));
  const auto one = render_all(r, 9, 1);
  const auto two = render_all(r, 9, 2);
  const auto three = render_all(r, 9, 3);
  for (std::size_t i = 0; i < one.size(); ++i) {
    INFO("chip " << i);
    CHECK(one[i].params.index == i);
    CHECK(two[i].params.index == i);
    CHECK(one[i].pixels == two[i].pixels);
    CHECK(one[i].pixels == three[i].pixels);
    CHECK(one[i].level_db == two[i].level_db);
  }
  // alone and out of order, too
  const ChipImage again = r.render(4, 0);
  CHECK(again.pixels == one[4].pixels);
  CHECK(again.level_db == one[4].level_db);
  // chips differ from one another, and with another seed
  CHECK(one[0].pixels != one[1].pixels);
  const ChipRenderer other(spec({"flat", "ripples", "clutter"}, {0.2}, ChipKind::kHighlight, 6));
  CHECK(other.render(4, 0).pixels != one[4].pixels);
}

TEST_CASE("chips: another look is the same object from another pass") {
  for (const ChipKind kind : {ChipKind::kHighlight, ChipKind::kShadow}) {
    INFO(chip_kind_name(kind));
    const ChipDatasetSpec base = spec({"flat", "ripples"}, {0.2}, kind);
    ChipDatasetSpec look1 = base, look2 = base;
    look1.look = 1;
    look2.look = 2;
    const ChipRenderer r0(base), r1(look1), r2(look2);
    int altitude_changed = 0, track_changed = 0;
    for (std::uint64_t i = 0; i < 24; ++i) {
      INFO("chip " << i);
      const ChipParams p0 = chip_params(base, i), p1 = chip_params(look1, i);
      const ChipParams p2 = chip_params(look2, i);
      // the object: type, seabed, position and heading
      CHECK(p1.type == p0.type);
      CHECK(p1.seabed == p0.seabed);
      CHECK(p1.target_ne_m == p0.target_ne_m);
      CHECK(p1.target_heading_deg == p0.target_heading_deg);
      // the pass: drawn afresh within the dataset's bounds, differently for each look
      CHECK(p1.altitude_m >= base.altitude_min_m);
      CHECK(p1.altitude_m <= base.altitude_max_m);
      CHECK(p1.ground_range_m >= (kind == ChipKind::kShadow ? kShadowGroundRange_m : 5.0));
      CHECK(p1.ground_range_m <= (kind == ChipKind::kShadow ? kShadowGroundRange_m : 50.0));
      const double look_deg = p1.track_heading_deg + (p1.side == 1 ? 90.0 : -90.0);
      const double d = wrap360(p1.target_heading_deg - look_deg - p1.aspect_deg);
      CHECK(std::min(d, 360.0 - d) < 1e-9);
      altitude_changed += p1.altitude_m != p0.altitude_m && p2.altitude_m != p1.altitude_m;
      track_changed += p1.track_heading_deg != p0.track_heading_deg &&
                       p2.track_heading_deg != p1.track_heading_deg;
    }
    CHECK(altitude_changed == 24);
    CHECK(track_changed == 24);
    // look 0 is the dataset as before the field existed; other looks draw other chips, each
    // the same on every call
    const ChipImage a0 = r0.render(3, 0), a1 = r1.render(3, 0);
    CHECK(a0.params.index == 3);
    CHECK(a0.pixels == render_all(ChipRenderer(base), 4, 1)[3].pixels);
    CHECK(a1.pixels != a0.pixels);
    CHECK(a1.pixels == r1.render(3, 0).pixels);
    CHECK(r2.render(3, 0).pixels != a1.pixels);
  }
  ChipDatasetSpec bad = spec({"flat"}, {0.2});
  bad.look = -1;
  CHECK_THROWS_WITH(ChipRenderer(bad), Catch::Contains("look"));
}

TEST_CASE("chips: reciprocal looks fly a lawnmower's neighbouring lines") {
  for (const ChipKind kind : {ChipKind::kHighlight, ChipKind::kShadow}) {
    INFO(chip_kind_name(kind));
    ChipDatasetSpec base = spec({"flat", "ripples"}, {0.2}, kind);
    base.look_geometry = LookGeometry::kReciprocal;  // look 0 is the same in either geometry
    for (std::uint64_t i = 0; i < 24; ++i) {
      INFO("chip " << i);
      const ChipParams p0 = chip_params(base, i);
      ChipDatasetSpec independent = base;
      independent.look_geometry = LookGeometry::kIndependent;
      CHECK(chip_params(independent, i).altitude_m == p0.altitude_m);
      for (int look = 1; look <= 2; ++look) {
        ChipDatasetSpec s = base;
        s.look = look;
        const ChipParams p = chip_params(s, i);
        // one altitude and range for the survey, the object as it was
        CHECK(p.altitude_m == p0.altitude_m);
        CHECK(p.ground_range_m == p0.ground_range_m);
        CHECK(p.type == p0.type);
        CHECK(p.target_ne_m == p0.target_ne_m);
        CHECK(p.side == p0.side);
        // odd looks: the reciprocal track, so the object seen from the opposite direction;
        // even looks: look 0's line again
        const double turn = look % 2 == 1 ? 180.0 : 0.0;
        const double dt = wrap360(p.track_heading_deg - p0.track_heading_deg - turn);
        const double da = wrap360(p.aspect_deg - p0.aspect_deg - turn);
        CHECK(std::min(dt, 360.0 - dt) < 1e-9);
        CHECK(std::min(da, 360.0 - da) < 1e-9);
        // the same draws as an independent look of that number (only the flight differs)
        ChipDatasetSpec ind = independent;
        ind.look = look;
        CHECK(p.along_offset == chip_params(ind, i).along_offset);
      }
    }
  }
  CHECK(parse_look_geometry("reciprocal") == LookGeometry::kReciprocal);
  CHECK(parse_look_geometry("independent") == LookGeometry::kIndependent);
  CHECK_FALSE(parse_look_geometry("lawnmower").has_value());
  CHECK(std::string(look_geometry_name(LookGeometry::kReciprocal)) == "reciprocal");
}

TEST_CASE("chips: the profile and the ray-traced renderers draw the same chip") {
  // the same chips by both renderers (no speckle differences: each is a pure function of the
  // chip, the renderers share the randomness): the target echo in the same place, the seabed at
  // the same level
  for (const ChipKind kind : {ChipKind::kHighlight, ChipKind::kShadow}) {
    ChipDatasetSpec s = spec({"flat", "ripples", "clutter"}, {0.05}, kind);
    const ChipRenderer prof(s);
    s.renderer = RendererKind::kRaytrace;
    const ChipRenderer ray(s);
    for (std::uint64_t i : {0, 1, 2, 3, 4, 5}) {
      const ChipImage a = prof.render(i, 0);
      const ChipImage b = ray.render(i, 0);
      INFO("kind " << chip_kind_name(kind) << " chip " << i << " seabed " << a.params.seabed);
      REQUIRE(a.rows == b.rows);
      REQUIRE(a.cols == b.cols);
      // echo centroids (truth energy) and the first and last shadowed columns agree
      double ea = 0, eb = 0, ca = 0, cb = 0;
      long shadow_a = 0, shadow_b = 0;
      for (int row = 0; row < a.rows; ++row) {
        const ChipRowTruth& ta = a.truth[static_cast<std::size_t>(row)];
        const ChipRowTruth& tb = b.truth[static_cast<std::size_t>(row)];
        if (ta.highlight_first >= 0) {
          ea += ta.energy;
          ca += ta.energy * 0.5 * (ta.highlight_first + ta.highlight_last);
        }
        if (tb.highlight_first >= 0) {
          eb += tb.energy;
          cb += tb.energy * 0.5 * (tb.highlight_first + tb.highlight_last);
        }
        // shadowed cells inside the chip (the truth may run beyond it)
        const auto inside = [&](const ChipRowTruth& t) {
          if (t.shadow_last < 0) return 0;
          return std::max(0, std::min(t.shadow_last, a.cols - 1) - std::max(t.shadow_first, 0) + 1);
        };
        shadow_a += inside(ta);
        shadow_b += inside(tb);
      }
      REQUIRE(ea > 0.0);
      REQUIRE(eb > 0.0);
      CHECK(std::abs(ca / ea - cb / eb) < 1.5);
      CHECK(10.0 * std::log10(ea / eb) == Approx(0.0).margin(1.0));
      CHECK(std::abs(shadow_a - shadow_b) <= 0.1 * static_cast<double>(shadow_b) + 4.0);
      // the seabed's median level (speckle-free comparison is not possible here: speckle is
      // the same draw, so levels compare pixel by pixel up to the mean's difference)
      CHECK(std::abs(quantile(a.level_db, 0.5) - quantile(b.level_db, 0.5)) < 1.5);
    }
  }
}

TEST_CASE("chips: round(size / R) pixels a side at every resolution") {
  const std::vector<double> res = {0.03, 0.05, 0.07, 0.2, 0.3};
  const ChipRenderer hl(spec({"flat"}, res));
  const ChipRenderer sh(spec({"flat"}, res, ChipKind::kShadow));
  const int hl_side[] = {100, 60, 43, 15, 10};
  const int sh_cols[] = {333, 200, 143, 50, 33};
  for (int k = 0; k < static_cast<int>(res.size()); ++k) {
    INFO("resolution " << res[static_cast<std::size_t>(k)]);
    CHECK(hl.rows(k) == hl_side[k]);
    CHECK(hl.cols(k) == hl_side[k]);
    CHECK(sh.rows(k) == hl_side[k]);
    CHECK(sh.cols(k) == sh_cols[k]);
    CHECK(hl.sonar(k).desc.bin_size_m == res[static_cast<std::size_t>(k)]);
    CHECK(hl.sonar(k).along_track_resolution_m == res[static_cast<std::size_t>(k)]);
    CHECK(hl.sonar(k).desc.along_track == AlongTrackModel::kStrip);
    CHECK(hl.sonar(k).range_resolution_m == Approx(res[static_cast<std::size_t>(k)]));
    const ChipImage c = hl.render(1, k);
    CHECK(c.rows == hl_side[k]);
    CHECK(c.cols == hl_side[k]);
    CHECK(c.pixels.size() == static_cast<std::size_t>(c.rows * c.cols));
    CHECK(c.level_db.size() == c.pixels.size());
    CHECK(c.truth.size() == static_cast<std::size_t>(c.rows));
    CHECK(c.resolution_m == res[static_cast<std::size_t>(k)]);
  }
  // the same scene at every resolution: the target's centre lies at the same place in metres
  const ChipImage fine = hl.render(2, 1);
  const ChipImage coarse = hl.render(2, 4);
  CHECK(fine.slant_range_m == coarse.slant_range_m);
  CHECK((fine.target_col + 0.5) * 0.05 + fine.range_start_m ==
        Approx((coarse.target_col + 0.5) * 0.3 + coarse.range_start_m));
}

TEST_CASE("chips: pixels map a fixed dB span (-60..0 dB re full scale by default)") {
  const ChipLevels levels;
  CHECK(chip_pixel(-60.0, levels) == 0);
  CHECK(chip_pixel(-100.0, levels) == 0);
  CHECK(chip_pixel(-300.0, levels) == 0);
  CHECK(chip_pixel(0.0, levels) == 255);
  CHECK(chip_pixel(12.0, levels) == 255);
  CHECK(chip_pixel(-30.0, levels) == 128);  // 127.5 rounds up
  CHECK(chip_pixel(-59.9, levels) == 0);    // 0.425
  CHECK(chip_pixel(-59.8, levels) == 1);    // 0.85
  const ChipLevels wide{-80.0, 10.0};
  CHECK(chip_pixel(-35.0, wide) == 128);
  // every chip pixel is its level through that mapping, never auto-levelled
  const ChipRenderer r(spec({"ripples"}, {0.1}));
  const ChipImage c = r.render(3, 0);
  for (std::size_t k = 0; k < c.pixels.size(); ++k)
    REQUIRE(c.pixels[k] == chip_pixel(c.level_db[k], levels));
  // speckled: seabed pixels vary
  const auto [lo, hi] = std::minmax_element(c.pixels.begin(), c.pixels.end());
  CHECK(*hi - *lo > 50);
}

TEST_CASE("highlight chips: the target's echo is at the chip's centre") {
  ChipDatasetSpec s = spec({"flat", "ripples", "clutter"}, {0.05});
  s.renderer = GENERATE(RendererKind::kProfile, RendererKind::kRaytrace);
  INFO("renderer " << renderer_name(s.renderer));
  const ChipRenderer r(s);
  const auto chips = render_all(r, 24, 2);
  int seen = 0;
  for (const ChipImage& c : chips) {
    INFO("chip " << c.params.index << " altitude " << c.params.altitude_m << " range "
                 << c.params.ground_range_m);
    // the target's centre, by geometry
    CHECK(std::abs(c.target_row - 0.5 * (c.rows - 1)) <= 0.5 + 1e-9);
    CHECK(std::abs(c.target_col - 0.5 * (c.cols - 1)) <= 1.0);
    // the energy centroid of its echo, from the renderer's truth rays: within the target's
    // half-length (0.5 m = 10 pixels) of the chip's centre
    double e = 0.0, er = 0.0, ec = 0.0;
    std::vector<float> echo, rest;
    for (int row = 0; row < c.rows; ++row) {
      const ChipRowTruth& t = c.truth[static_cast<std::size_t>(row)];
      for (int col = 0; col < c.cols; ++col) {
        const bool on =
            t.highlight_first >= 0 && col >= t.highlight_first && col <= t.highlight_last;
        const bool hidden = t.shadow_first >= 0 && col >= t.shadow_first && col <= t.shadow_last;
        const float v = c.level_db[static_cast<std::size_t>(row * c.cols + col)];
        if (on) {
          echo.push_back(v);
        } else if (!hidden) {
          rest.push_back(v);
        }
      }
      if (t.highlight_first < 0) continue;
      e += t.energy;
      er += t.energy * row;
      ec += t.energy * 0.5 * (t.highlight_first + t.highlight_last);
      CHECK(t.highlight_first >= 0);
      CHECK(t.highlight_last < c.cols);
    }
    REQUIRE(e > 0.0);
    ++seen;
    CHECK(std::abs(er / e - 0.5 * (c.rows - 1)) < 10.0);
    CHECK(std::abs(ec / e - 0.5 * (c.cols - 1)) < 10.0);
    // and the image shows it there: the echo's pixels stand well above the seabed's
    CHECK(mean_intensity_db(echo) > mean_intensity_db(rest) + 6.0);
  }
  CHECK(seen == 24);
}

TEST_CASE("shadow chips: the target near the chip's start, its whole shadow behind it") {
  ChipDatasetSpec s = spec({"flat", "ripples", "clutter"}, {0.1}, ChipKind::kShadow);
  s.renderer = GENERATE(RendererKind::kProfile, RendererKind::kRaytrace);
  INFO("renderer " << renderer_name(s.renderer));
  const ChipRenderer r(s);
  const auto chips = render_all(r, 24, 2);
  int whole = 0;
  for (const ChipImage& c : chips) {
    INFO("chip " << c.params.index << " altitude " << c.params.altitude_m);
    CHECK(c.params.ground_range_m == kShadowGroundRange_m);
    CHECK(c.cols == 100);
    // the target's centre 1 m (10 pixels) into the chip
    CHECK(std::abs(c.target_col - (kShadowChipNear_m / 0.1 - 0.5)) <= 1.0);
    int rows_with_shadow = 0;
    double shadow_col = 0.0;
    bool inside = true;
    std::vector<float> shadow, rest;
    for (int row = 0; row < c.rows; ++row) {
      const ChipRowTruth& t = c.truth[static_cast<std::size_t>(row)];
      if (t.shadow_first >= 0) {
        ++rows_with_shadow;
        shadow_col += 0.5 * (t.shadow_first + t.shadow_last);
        CHECK(t.shadow_first >= t.highlight_first);
        if (t.shadow_last >= c.cols) inside = false;
      }
      for (int col = 0; col < c.cols; ++col) {
        const float v = c.level_db[static_cast<std::size_t>(row * c.cols + col)];
        if (t.shadow_first >= 0 && col >= t.shadow_first && col <= t.shadow_last) {
          shadow.push_back(v);
        } else if (t.highlight_first < 0 || col < t.highlight_first || col > t.highlight_last) {
          rest.push_back(v);
        }
      }
    }
    REQUIRE(rows_with_shadow >= 3);
    // behind the target (further in range)
    CHECK(shadow_col / rows_with_shadow > c.target_col + 2.0);
    whole += inside ? 1 : 0;
    // dark in the image: a good part of it at the noise floor, black in the 8-bit chip, and
    // far below the seabed's bright pixels (edge rows and edge bins are partly lit; on ripples
    // seen from low altitude most of the seabed itself lies in the crests' shadows)
    CHECK(quantile(shadow, 0.25) < -60.0);
    CHECK(quantile(shadow, 0.25) < quantile(rest, 0.9) - 30.0);
  }
  // the chip is sized so that shadows fit (relief behind a target could stretch one beyond)
  CHECK(whole >= 22);
}

TEST_CASE("chips: a half-buried target casts about half the shadow of the same target on top") {
  // shadow length ~ height x range / altitude (flat seabed): sinking the base by half the height
  // halves the part that casts it; the altitude stays above the seabed
  ChipDatasetSpec s = spec({"flat"}, {0.1}, ChipKind::kShadow);
  const auto mean_shadow_bins = [&](double burial) {
    s.burial_fraction = burial;
    const ChipRenderer r(s);
    double sum = 0.0;
    int n = 0;
    for (const ChipImage& c : render_all(r, 8, 2)) {
      for (const ChipRowTruth& t : c.truth) {
        if (t.shadow_first < 0) continue;
        sum += t.shadow_last - t.shadow_first + 1;
        ++n;
      }
    }
    return n ? sum / n : 0.0;
  };
  const double on_top = mean_shadow_bins(0.0);
  const double half = mean_shadow_bins(0.5);
  INFO("mean shadow " << on_top << " bins on top, " << half << " half buried");
  REQUIRE(on_top > 10.0);
  CHECK(half < 0.7 * on_top);
  CHECK(half > 0.3 * on_top);
  s.burial_fraction = 0.95;
  CHECK_THROWS_AS(ChipRenderer(s), std::invalid_argument);
}

TEST_CASE("render_chips: a stop leaves exactly the first chips, in order; errors propagate") {
  const ChipRenderer r(spec({"flat"}, {0.3}));
  std::vector<ChipJob> jobs;
  for (std::uint64_t i = 0; i < 40; ++i)
    jobs.push_back(ChipJob{i, 0});
  std::vector<std::uint64_t> got;
  std::atomic<int> polls{0};
  const std::size_t n = render_chips(
      r, jobs, 2, [&](const ChipImage& c) { got.push_back(c.params.index); },
      [&] { return polls.fetch_add(1) >= 6; });
  CHECK(n == got.size());
  CHECK(n < jobs.size());
  for (std::size_t k = 0; k < got.size(); ++k)
    CHECK(got[k] == k);
  // a bad job (no such resolution) and a throwing sink both surface in the caller
  jobs[5].resolution = 3;
  CHECK_THROWS_AS(render_chips(r, jobs, 2, [](const ChipImage&) {}), std::out_of_range);
  jobs[5].resolution = 0;
  int calls = 0;
  CHECK_THROWS_WITH(render_chips(r, jobs, 2,
                                 [&](const ChipImage&) {
                                   if (++calls == 3) throw std::runtime_error("disk full");
                                 }),
                    "disk full");
  CHECK(calls == 3);
  CHECK(render_chips(r, {}, 2, [](const ChipImage&) {}) == 0);
}

TEST_CASE("chips: bad specs are refused") {
  CHECK_THROWS_AS(ChipRenderer(spec({"flat"}, {})), std::invalid_argument);
  CHECK_THROWS_AS(ChipRenderer(spec({"flat"}, {0.001})), std::invalid_argument);
  CHECK_THROWS_AS(ChipRenderer(spec({}, {0.05})), std::invalid_argument);
  ChipDatasetSpec s = spec({"flat"}, {0.05});
  s.classes.clear();
  CHECK_THROWS_AS(ChipRenderer(s), std::invalid_argument);
  s = spec({"flat"}, {0.05});
  s.altitude_min_m = 5.0;
  s.altitude_max_m = 4.0;
  CHECK_THROWS_AS(ChipRenderer(s), std::invalid_argument);
  CHECK_THROWS_WITH(builtin_dataset_seabed("sandy"), Catch::Contains("flat, ripples, clutter"));
  s = spec({"flat", "ripples"}, {0.05});
  s.seabeds[1].desc.water.depth_m = 40.0;
  CHECK_THROWS_WITH(ChipRenderer(s), Catch::Contains("water"));
}
