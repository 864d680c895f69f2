// The contact gate (atr/contact_gate.h): the fit separates what is separable, its threshold keeps
// the asked fraction of the targets, its probability is monotone in a helpful feature, and the
// features of a detection and a classification are what the names say.
#include "atr/contact_gate.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "common/rng.h"

using namespace sonarloop;
using namespace sonarloop::atr;

namespace {

// Targets have a strong highlight (feature 1) and are taller (feature 0); clutter overlaps them.
void sample(Rng& rng, int label, std::vector<std::vector<double>>& x, std::vector<int>& y) {
  std::vector<double> f(gate_feature_count(GateStage::kDetection));
  for (double& v : f)
    v = rng.normal();
  f[0] = label ? rng.normal(0.4, 0.1) : rng.normal(0.2, 0.1);    // height
  f[1] = label ? rng.normal(-1.0, 1.0) : rng.normal(-5.0, 2.0);  // highlight
  x.push_back(f);
  y.push_back(label);
}

}  // namespace

TEST_CASE("contact gate: a fit on labelled detections separates them; the threshold keeps 98 %") {
  Rng rng(3, RngStream::kTraining);
  std::vector<std::vector<double>> x;
  std::vector<int> y;
  for (int i = 0; i < 400; ++i)
    sample(rng, i % 5 == 0, x, y);  // 80 targets, 320 clutter
  GateFitOptions o;
  o.form = GateForm::kLinear;
  o.ridge = 1e-2;
  o.keep_targets = 0.98;
  const LogisticGate g = fit_gate(GateStage::kDetection, x, y, o);
  REQUIRE(g.weights.size() == gate_feature_count(GateStage::kDetection));
  CHECK(g.weights[0] > 0.5);  // taller: more likely a target
  CHECK(g.weights[1] > 0.5);  // stronger highlight: more likely a target
  int kept_targets = 0, kept_clutter = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const bool pass = g.passes(x[i]);
    (y[i] ? kept_targets : kept_clutter) += pass;
  }
  CHECK(kept_targets >= 78);  // 98 % of 80
  CHECK(kept_targets <= 80);
  CHECK(kept_clutter < 160);  // most clutter out
  // on fresh samples of the same kinds the gate still works
  std::vector<std::vector<double>> xt;
  std::vector<int> yt;
  for (int i = 0; i < 1000; ++i)
    sample(rng, i % 2, xt, yt);
  int right = 0;
  for (std::size_t i = 0; i < xt.size(); ++i)
    right += (g.probability(xt[i]) >= 0.5) == (yt[i] == 1);
  CHECK(right > 850);
  // monotone in the highlight
  std::vector<double> probe = x[0];
  probe[1] = -8.0;
  const double low = g.probability(probe);
  probe[1] = 0.0;
  CHECK(g.probability(probe) > low);
  CHECK_NOTHROW(validate_gate(g));
}

TEST_CASE("contact gate: the quadratic form learns what depends on two features at once") {
  // a target when the highlight is strong on a quiet seabed or very strong on a busy one
  // (feature 1 against feature 10): a boundary no linear gate draws
  Rng rng(5, RngStream::kTraining);
  std::vector<std::vector<double>> x;
  std::vector<int> y;
  for (int i = 0; i < 2000; ++i) {
    std::vector<double> f(gate_feature_count(GateStage::kDetection));
    for (double& v : f)
      v = rng.normal();
    y.push_back(f[1] * f[10] > 0.0 ? 1 : 0);
    x.push_back(f);
  }
  GateFitOptions linear;
  linear.form = GateForm::kLinear;
  GateFitOptions quadratic;
  const LogisticGate l = fit_gate(GateStage::kDetection, x, y, linear);
  const LogisticGate q = fit_gate(GateStage::kDetection, x, y, quadratic);
  CHECK(q.form == GateForm::kQuadratic);
  CHECK(q.weights.size() ==
        gate_term_count(gate_feature_count(GateStage::kDetection), GateForm::kQuadratic));
  int right_l = 0, right_q = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    right_l += (l.probability(x[i]) >= 0.5) == (y[i] == 1);
    right_q += (q.probability(x[i]) >= 0.5) == (y[i] == 1);
  }
  CHECK(right_l < 1200);  // about chance
  CHECK(right_q > 1800);
}

TEST_CASE("contact gate: the threshold keeps targets, a target when one of its detections passes") {
  // three targets, each with one strong and one weak detection; clutter in between
  std::vector<std::vector<double>> x;
  std::vector<int> y;
  std::vector<std::int64_t> id;
  const std::size_t n = gate_feature_count(GateStage::kDetection);
  for (int t = 0; t < 3; ++t) {
    for (const double h : {0.0, -8.0}) {
      std::vector<double> f(n, 0.0);
      f[1] = h + 0.1 * t;
      x.push_back(f);
      y.push_back(1);
      id.push_back(t);
    }
  }
  for (int c = 0; c < 30; ++c) {
    std::vector<double> f(n, 0.0);
    f[1] = -4.0 - 0.1 * c;
    x.push_back(f);
    y.push_back(0);
    id.push_back(-1);
  }
  GateFitOptions o;
  o.form = GateForm::kLinear;
  o.keep_targets = 1.0;
  const LogisticGate per_target = fit_gate(GateStage::kDetection, x, y, o, id);
  const LogisticGate per_detection = fit_gate(GateStage::kDetection, x, y, o);
  // every target keeps its strong detection: the weak ones may fall, and the clutter with them
  int clutter_per_target = 0, clutter_per_detection = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (y[i] == 1 && x[i][1] > -1.0) CHECK(per_target.passes(x[i]));
    if (y[i] == 0) {
      clutter_per_target += per_target.passes(x[i]);
      clutter_per_detection += per_detection.passes(x[i]);
    }
  }
  CHECK(clutter_per_target == 0);
  CHECK(clutter_per_detection == 30);  // keeping every weak look keeps all the clutter
  CHECK_THROWS_AS(fit_gate(GateStage::kDetection, x, y, o, std::vector<std::int64_t>(3, 0)),
                  std::invalid_argument);
}

TEST_CASE("contact gate: bad training data and bad gates are refused") {
  std::vector<std::vector<double>> x(
      4, std::vector<double>(gate_feature_count(GateStage::kDetection)));
  CHECK_THROWS_AS(fit_gate(GateStage::kDetection, x, {1, 1, 1, 1}), std::invalid_argument);
  CHECK_THROWS_AS(fit_gate(GateStage::kDetection, x, {1, 0}), std::invalid_argument);
  CHECK_THROWS_AS(fit_gate(GateStage::kClassification, x, {1, 0, 1, 0}), std::invalid_argument);
  x[2][0] = std::nan("");
  CHECK_THROWS_AS(fit_gate(GateStage::kDetection, x, {1, 0, 1, 0}), std::invalid_argument);
  LogisticGate g;
  CHECK_THROWS_AS(validate_gate(g), std::runtime_error);  // no weights for 11 features
  // a constant feature gets scale 1, not 0 (no division by zero)
  x[2][0] = 0.0;
  x[0][1] = 1.0;
  const LogisticGate c = fit_gate(GateStage::kDetection, x, {1, 0, 1, 0});
  CHECK(c.scale[3] == 1.0);
  CHECK(std::isfinite(c.probability(x[0])));
}

TEST_CASE("contact gate: the features of a detection and of its classification") {
  Detection d;
  d.height_m = 0.3;
  d.highlight_db = -2.0;
  d.highlight_above_db = 15.0;
  d.shadow_below_db = 40.0;
  d.pings = 4;
  d.along_extent_m = 0.5;
  d.shadow_area_m2 = 0.2;
  d.ground_m = 25.0;
  d.highlight_area_m2 = 0.05;
  d.highlight_mean_above_db = 12.0;
  d.clutter_hits_per_m = 3.0;
  const std::vector<double> f = detection_features(d);
  REQUIRE(f.size() == gate_feature_count(GateStage::kDetection));
  CHECK(f[0] == 0.3);
  CHECK(f[4] == Approx(std::log(4.0)));
  CHECK(f[6] == Approx(std::log(0.2)));
  CHECK(f[7] == 25.0);
  CHECK(f[8] == Approx(std::log(0.05)));
  CHECK(f[9] == 12.0);
  CHECK(f[10] == Approx(std::log(3.0)));
  CHECK(std::string(gate_feature_names(GateStage::kDetection)[2]) == "highlight_above_db");
  // a model of 3 classes, one of them clutter; 4 x 4 = 16 pixels: sqrt(n) = 4
  Model m;
  m.chip_width = 4;
  m.chip_height = 4;
  m.classes.resize(3);
  m.classes[0].name = "a";
  m.classes[1].name = "clutter";
  m.classes[1].clutter = true;
  m.classes[2].name = "b";
  Classification r;
  r.class_index = 1;
  r.class_distance = {2.0f, 1.0f, 3.0f};
  const std::vector<double> c = classification_features(d, r, m);
  REQUIRE(c.size() == gate_feature_count(GateStage::kClassification));
  const std::size_t n = gate_feature_count(GateStage::kDetection);
  CHECK(c[n] == Approx(2.0 / 4.0));              // the nearest target class: a
  CHECK(c[n + 1] == Approx(1.0 / 4.0));          // clutter
  CHECK(c[n + 2] == Approx((1.0 - 2.0) / 2.0));  // clutter nearer than any target: negative gap
  CHECK(c[n + 3] == Approx((3.0 - 2.0) / 2.0));  // the runner-up margin among the targets
  CHECK(std::string(gate_feature_names(GateStage::kClassification)[n]) == "target_distance");
}
