// Fusing distances from several looks (atr/fusion.h): the three normalisations against hand
// computations, and why per-class scales can overturn a look's own ranking.
#include "atr/fusion.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "tests/atr/classification_looks.h"

namespace sonarloop::atr {
namespace {

// A model of named classes with given typical distances on 4-pixel features.
Model model_of(const std::vector<std::string>& names, const std::vector<float>& typical) {
  Model m;
  m.chip_width = 2;
  m.chip_height = 2;
  for (std::size_t i = 0; i < names.size(); ++i) {
    ClassModel c;
    c.name = names[i];
    c.typical_distance = typical[i];
    m.classes.push_back(c);
  }
  return m;
}

using testing::look;

TEST_CASE("fusion: the three normalisations, by hand") {
  const Model m = model_of({"a", "b"}, {10.0f, 20.0f});
  std::vector<float> f(2, 0.0f);
  add_look(m, look({12.0f, 16.0f}), FusionNorm::kClassTypical, f);
  CHECK(f[0] == Approx(1.2));
  CHECK(f[1] == Approx(0.8));
  std::fill(f.begin(), f.end(), 0.0f);
  add_look(m, look({12.0f, 16.0f}), FusionNorm::kModelTypical, f);  // T = 15
  CHECK(f[0] == Approx(0.8));
  CHECK(f[1] == Approx(16.0 / 15.0));
  std::fill(f.begin(), f.end(), 0.0f);
  add_look(m, look({12.0f, 16.0f}), FusionNorm::kLookZScore, f);  // mean 14, sd 2
  CHECK(f[0] == Approx(-1.0));
  CHECK(f[1] == Approx(1.0));
  // an uncalibrated class falls back on sqrt(pixels) = 2
  const Model raw = model_of({"a", "b"}, {0.0f, 0.0f});
  std::fill(f.begin(), f.end(), 0.0f);
  add_look(raw, look({12.0f, 16.0f}), FusionNorm::kClassTypical, f);
  CHECK(f[0] == Approx(6.0));
  CHECK(f[1] == Approx(8.0));
}

TEST_CASE("fusion: per-class scales can overturn a look's ranking; one scale per model keeps it") {
  // one look: class a is nearer (12 < 16), but b's typical distance is twice a's
  const Model m = model_of({"a", "b"}, {10.0f, 20.0f});
  std::vector<float> f(2, 0.0f);
  add_look(m, look({12.0f, 16.0f}), FusionNorm::kClassTypical, f);
  CHECK(fused_decision(f) == 1);
  std::fill(f.begin(), f.end(), 0.0f);
  add_look(m, look({12.0f, 16.0f}), FusionNorm::kModelTypical, f);
  CHECK(fused_decision(f) == 0);
}

TEST_CASE("fusion: two looks add; a confident look outvotes a hesitant one") {
  const Model h = model_of({"a", "b", "c"}, {10.0f, 10.0f, 10.0f});
  const Model s = model_of({"a", "b", "c"}, {40.0f, 40.0f, 40.0f});
  std::vector<float> f(3, 0.0f);
  add_look(h, look({8.0f, 12.0f, 12.0f}), FusionNorm::kModelTypical, f);   // a, by 0.4
  add_look(s, look({41.0f, 40.0f, 48.0f}), FusionNorm::kModelTypical, f);  // b, by 0.025
  CHECK(fused_decision(f) == 0);
  CHECK(f[0] == Approx(0.8 + 41.0 / 40.0));
  CHECK(fused_decision(std::vector<float>{}) == -1);
}

TEST_CASE("fusion: mismatched models and sizes are errors") {
  const Model a = model_of({"a", "b"}, {1.0f, 1.0f});
  const Model b = model_of({"a", "c"}, {1.0f, 1.0f});
  CHECK_THROWS_AS(check_same_classes(a, b), std::invalid_argument);
  CHECK_NOTHROW(check_same_classes(a, a));
  std::vector<float> f(3, 0.0f);
  CHECK_THROWS_AS(add_look(a, look({1.0f, 2.0f}), FusionNorm::kLookZScore, f),
                  std::invalid_argument);
  CHECK(std::string(fusion_norm_name(FusionNorm::kLookZScore)) == "look_zscore");
}

}  // namespace
}  // namespace sonarloop::atr
