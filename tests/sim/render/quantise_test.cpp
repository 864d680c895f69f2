#include "sim/render/quantise.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "sim/acoustics/tvg.h"

using namespace sonarloop;
using namespace sonarloop::render;

namespace {

SonarSetup setup_for(AlongTrackModel model, SampleType type, double gain_db = 0.0) {
  SonarDesc d;
  d.along_track = model;
  d.sample_type = type;
  d.gain_db = gain_db;
  d.max_range_m = 20.0;
  d.bin_size_m = 0.1;
  return make_sonar_setup(d, scene::WaterDesc{});
}

// the intensity whose TVG-corrected level is `db_re_full_scale` dB re the full-scale level
float intensity_at(const SonarSetup& s, double range_m, double db_re_full_scale) {
  const double level = full_scale_level_db(s) + db_re_full_scale -
                       acoustics::tvg_db(range_m, s.alpha_db_per_m, s.tvg);
  return static_cast<float>(std::pow(10.0, level / 10.0));
}

}  // namespace

TEST_CASE("quantise: TVG law follows the along-track model unless set") {
  CHECK(setup_for(AlongTrackModel::kBeam, SampleType::kUint16).tvg == acoustics::TvgLaw::kArea);
  CHECK(setup_for(AlongTrackModel::kStrip, SampleType::kUint16).tvg == acoustics::TvgLaw::kPoint);
  SonarDesc d;
  d.tvg = acoustics::TvgLaw::kSpherical;
  CHECK(make_sonar_setup(d, scene::WaterDesc{}).tvg == acoustics::TvgLaw::kSpherical);
}

TEST_CASE("quantise: full scale, -20 dB and clipping for every sample type") {
  for (auto model : {AlongTrackModel::kBeam, AlongTrackModel::kStrip}) {
    const SonarSetup s = setup_for(model, SampleType::kUint16);
    std::vector<float> in(s.bins);
    for (int k = 0; k < s.bins; ++k) {
      const double r = (k + 0.5) * s.desc.bin_size_m;
      // bins cycle through 0 dB (full scale), -20 dB (a tenth in amplitude) and +10 dB (clips)
      in[k] = intensity_at(s, r, k % 3 == 0 ? 0.0 : (k % 3 == 1 ? -20.0 : 10.0));
    }
    std::vector<std::uint16_t> q16(s.bins);
    std::vector<std::uint8_t> q8(s.bins);
    std::vector<float> qf(s.bins);
    quantise_line(s, in, q16);
    quantise_line(s, in, q8);
    quantise_line(s, in, qf);
    for (int k = 0; k < s.bins; ++k) {
      INFO("bin " << k);
      if (k % 3 == 0) {
        CHECK(q16[k] == 65535);
        CHECK(q8[k] == 255);
        CHECK(qf[k] == Approx(1.0).epsilon(1e-5));
      } else if (k % 3 == 1) {
        CHECK(std::abs(q16[k] - 6553.5) <= 1.0);
        CHECK(std::abs(q8[k] - 25.5) <= 1.0);
        CHECK(qf[k] == Approx(0.1).epsilon(1e-4));
      } else {
        CHECK(q16[k] == 65535);  // clipped
        CHECK(q8[k] == 255);
        CHECK(qf[k] == Approx(std::pow(10.0, 0.5)).epsilon(1e-4));  // float keeps headroom
      }
    }
  }
}

TEST_CASE("quantise: int16 samples reach 32767 at full scale and clip there") {
  const SonarSetup s = setup_for(AlongTrackModel::kBeam, SampleType::kInt16);
  std::vector<float> in(s.bins);
  for (int k = 0; k < s.bins; ++k) {
    const double r = (k + 0.5) * s.desc.bin_size_m;
    in[k] = intensity_at(s, r, k % 3 == 0 ? 0.0 : (k % 3 == 1 ? -20.0 : 10.0));
  }
  std::vector<std::uint16_t> q(s.bins);
  quantise_line(s, in, q);
  for (int k = 0; k < s.bins; ++k) {
    INFO("bin " << k);
    if (k % 3 == 1) {
      CHECK(std::abs(q[k] - 3276.7) <= 1.0);
    } else {
      CHECK(q[k] == 32767);  // full scale, or clipped: never beyond the signed range
    }
  }
}

TEST_CASE("quantise: gain shifts the level, zero intensity stays zero") {
  const SonarSetup s0 = setup_for(AlongTrackModel::kStrip, SampleType::kFloat32, 0.0);
  const SonarSetup s6 = setup_for(AlongTrackModel::kStrip, SampleType::kFloat32, 6.0);
  const float i = intensity_at(s0, 10.0, -30.0);
  CHECK(relative_amplitude(s6, i, 10.0) / relative_amplitude(s0, i, 10.0) ==
        Approx(std::pow(10.0, 6.0 / 20.0)).epsilon(1e-9));
  CHECK(relative_amplitude(s0, 0.0, 10.0) == 0.0);
}

TEST_CASE("quantise: intensity_at_level_db_fs is relative_amplitude's inverse") {
  for (const double gain : {0.0, 14.0, -6.0}) {
    const SonarSetup s = setup_for(AlongTrackModel::kBeam, SampleType::kInt16, gain);
    for (const double r : {0.3, 5.0, 19.9}) {
      for (const double level : {-48.0, -10.0, 0.0}) {
        INFO("gain " << gain << " range " << r << " level " << level);
        const double i = intensity_at_level_db_fs(s, level, r);
        CHECK(relative_amplitude(s, i, r) == Approx(std::pow(10.0, level / 20.0)).epsilon(1e-12));
        // the same level as the test's own construction from the TVG law, shifted by the gain
        CHECK(i == Approx(intensity_at(s, r, level - gain)).epsilon(1e-6));
      }
    }
    // full scale quantises to full scale
    const float fs = static_cast<float>(intensity_at_level_db_fs(s, 0.0, 0.05));
    std::vector<std::uint16_t> out(1);
    quantise_line(s, std::span<const float>(&fs, 1), out);
    CHECK(out[0] == 32767);
  }
}
