// The shared acoustic terms: tables against direct evaluation, the splat's energy, the ray
// tubes' sonar equation.
#include "sim/render/echo_model.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numeric>

#include "sim/acoustics/beam_pattern.h"
#include "sim/acoustics/target_specular.h"

using namespace sonarloop;
using namespace sonarloop::render;

namespace {

SonarSetup setup_for(double freq_hz, double height_m) {
  SonarDesc s;
  s.frequency_hz = freq_hz;
  s.array_height_m = height_m;
  s.max_range_m = 50.0;
  s.bin_size_m = 0.05;
  return make_sonar_setup(s, scene::WaterDesc{});
}

}  // namespace

TEST_CASE("echo model: the tabulated vertical pattern matches sinc^4 in the main lobe") {
  for (double h : {0.006, 0.02, 0.05}) {
    const SonarSetup s = setup_for(300e3, h);
    const EchoModel em(s, default_fidelity(s));
    double worst = 0.0;
    for (int k = -1000; k <= 1000; ++k) {
      const double x = k / 1000.0;
      const double exact = em.vertical_pattern(x);
      if (exact < 1e-3) continue;  // the main lobe and the first sidelobes (> -30 dB)
      worst = std::max(worst, std::abs(em.vertical_pattern_fast(x) / exact - 1.0));
    }
    INFO("array height " << h);
    CHECK(worst < 2e-4);  // 0.001 dB
  }
}

TEST_CASE("echo model: sigma / sin(grazing) by sin(grazing) matches the angle table") {
  const SonarSetup s = setup_for(300e3, 0.006);
  const EchoModel em(s, default_fidelity(s));
  for (int sed : {0, 3, 7, 12}) {
    double worst = 0.0;
    for (int k = 1; k <= 900; ++k) {
      const double grazing = k * 0.1 * std::numbers::pi / 180.0;  // 0.1 .. 90 deg
      const double x = std::sin(grazing);
      const double exact = em.seabed_sigma(sed, std::asin(std::max(x, 1e-3))) / std::max(x, 1e-3);
      worst = std::max(worst, std::abs(em.seabed_sigma_over_sin(sed, x) / exact - 1.0));
    }
    INFO("sediment " << sed);
    CHECK(worst < 0.01);  // 0.04 dB, at the steepest slope of the table (low grazing)
  }
}

TEST_CASE("echo model: a splat keeps its energy and puts it where it spans") {
  std::vector<double> acc(20, 0.0);
  splat(acc, 5.5, 0.0, 2.0);  // a point
  CHECK(acc[5] == 2.0);
  splat(acc, 10.0, 2.0, 4.0);  // over [9, 11): two bins, 2 each
  CHECK(acc[9] == Approx(2.0));
  CHECK(acc[10] == Approx(2.0));
  splat(acc, 19.5, 3.0, 3.0);  // partly beyond the end: only what lies inside
  CHECK(acc[18] == Approx(1.0));
  CHECK(acc[19] == Approx(1.0));
  splat(acc, 0.2, 1.0, 1.0);  // partly before the start
  CHECK(acc[0] == Approx(0.7));
  CHECK(std::accumulate(acc.begin(), acc.end(), 0.0) == Approx(2.0 + 4.0 + 2.0 + 0.7));
}

TEST_CASE("echo model: range factor is SL e^(-2 alpha r) / r^3, also at bin centres") {
  const SonarSetup s = setup_for(100e3, 0.03);
  const EchoModel em(s, default_fidelity(s));
  const double sl = std::pow(10.0, s.desc.source_level_db / 10.0);
  for (double r : {2.0, 10.0, 49.0}) {
    const double expected = sl * std::pow(10.0, -2.0 * s.alpha_db_per_m * r / 10.0) / (r * r * r);
    CHECK(em.range_factor(r) == Approx(expected).epsilon(1e-12));
  }
  REQUIRE(em.range_factor_at_bin().size() == static_cast<std::size_t>(s.bins));
  CHECK(em.range_factor_at_bin()[100] == Approx(em.range_factor(100.5 * 0.05)));
}

TEST_CASE(
    "echo model: a target tube is (mu cos^2 + f R^2 sigma_spec) / cos of the sonar equation") {
  SonarDesc d;
  d.max_range_m = 50.0;
  d.bin_size_m = 0.05;
  d.target_rms_slope = 0.2;
  const SonarSetup s = make_sonar_setup(d, scene::WaterDesc{});
  const EchoModel em(s, default_fidelity(s));
  RayMeta m;
  m.solid_angle = 1e-4f;
  m.depression_width = 1e-3f;
  m.pattern = 0.5f;
  const double r = 20.0;
  const double spread = em.tube_spread(m, r);
  const double mu = 0.2;
  for (double cos_i : {1.0, 0.95, 0.6, 0.1}) {
    INFO("cos_i " << cos_i);
    // Lambert only: SL·G_v·dΩ·e^(−2αr)/r² · μ cos θ (echo_model.h)
    const auto lambert = em.target_tube(m, r, cos_i, {mu, 0.0});
    CHECK(lambert.intensity == Approx(spread * mu * cos_i).epsilon(1e-12));
    // with the specular term: + w·σ_spec(θ)/cos θ (acoustics/target_specular.h)
    const double w = 0.4;
    const auto both = em.target_tube(m, r, cos_i, {mu, w});
    const double spec = w * acoustics::kirchhoff_facet_backscatter(cos_i, 0.2) / cos_i;
    CHECK(both.intensity == Approx(spread * (mu * cos_i + spec)).epsilon(1e-12));
    CHECK(both.width_bins == lambert.width_bins);
    CHECK(both.intensity >= lambert.intensity);
  }
  // the glint: at normal incidence w/(8π s²) = 0.4/(0.32π) ≈ 2 μ, 60° off normal it is gone
  CHECK(em.target_tube(m, r, 1.0, {0.0, 0.4}).intensity >
        1.9 * em.target_tube(m, r, 1.0, {mu, 0.0}).intensity);
  CHECK(em.target_tube(m, r, 0.5, {0.0, 0.4}).intensity <
        1e-6 * em.target_tube(m, r, 0.5, {mu, 0.0}).intensity);
}
