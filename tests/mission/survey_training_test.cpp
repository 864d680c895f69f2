// The gates' thresholds (mission/survey_training.h, choose_gate_threshold): a seabed whose
// targets the gate tells from its clutter sets the threshold; one where it cannot does not drag
// it down; targets the detector never reported are not the gate's to keep.
#include "mission/survey_training.h"

#include <catch2/catch.hpp>

using namespace sonarloop;

namespace {

// A linear gate on feature 0 alone: p = sigmoid(x0).
atr::LogisticGate gate_on_feature0() {
  atr::LogisticGate g;
  g.stage = atr::GateStage::kDetection;
  g.form = atr::GateForm::kLinear;
  const std::size_t n = atr::gate_feature_count(g.stage);
  g.mean.assign(n, 0.0);
  g.scale.assign(n, 1.0);
  g.weights.assign(n, 0.0);
  g.weights[0] = 1.0;
  return g;
}

void add(mission::GateRows& rows, double x0, int label, std::int64_t target, int scenario) {
  std::vector<double> x(atr::gate_feature_count(atr::GateStage::kDetection), 0.0);
  x[0] = x0;
  rows.x.push_back(x);
  rows.y.push_back(label);
  rows.target.push_back(target);
  rows.scenario.push_back(scenario);
}

}  // namespace

TEST_CASE("gate threshold: the seabeds the gate serves set it; a hopeless one does not") {
  mission::GateRows rows;
  // scenario 0 (sand): 10 targets at x0 = 2..2.9, 20 clutter at -3..-1: separable
  for (int t = 0; t < 10; ++t)
    add(rows, 2.0 + 0.1 * t, 1, t, 0);
  for (int c = 0; c < 20; ++c)
    add(rows, -3.0 + 0.1 * c, 0, -1, 0);
  // scenario 1 (rock): 10 targets at x0 = -2..-1.1, buried in 200 clutter at -2..2
  for (int t = 0; t < 10; ++t)
    add(rows, -2.0 + 0.1 * t, 1, 100 + t, 1);
  for (int c = 0; c < 200; ++c)
    add(rows, -2.0 + 0.02 * c, 0, -1, 1);
  const atr::LogisticGate g = gate_on_feature0();
  const mission::GateChoice c =
      mission::choose_gate_threshold(g, rows, {"sand", "rock"}, 10, 1.0, 1.0);
  REQUIRE(c.scenarios.size() == 2);
  CHECK(c.scenarios[0].served);
  CHECK_FALSE(c.scenarios[1].served);
  // sand's own threshold: its weakest target, sigmoid(2.0)
  CHECK(c.threshold == Approx(1.0 / (1.0 + std::exp(-2.0))));
  CHECK(c.scenarios[0].kept == Approx(1.0));
  CHECK(c.scenarios[0].false_per_target == 0.0);
  CHECK(c.scenarios[1].kept == 0.0);  // rock's targets are lost, and said to be
  CHECK(c.scenarios[1].reaching == 10);

  SECTION("a target the detector never reported is not the gate's to keep") {
    // only 8 of sand's 10 targets reached the gate: keeping all 8 still serves it
    mission::GateRows fewer;
    for (std::size_t r = 0; r < rows.x.size(); ++r) {
      if (rows.target[r] == 8 || rows.target[r] == 9) continue;
      fewer.x.push_back(rows.x[r]);
      fewer.y.push_back(rows.y[r]);
      fewer.target.push_back(rows.target[r]);
      fewer.scenario.push_back(rows.scenario[r]);
    }
    const mission::GateChoice f =
        mission::choose_gate_threshold(g, fewer, {"sand", "rock"}, 10, 1.0, 1.0);
    CHECK(f.scenarios[0].served);
    CHECK(f.scenarios[0].reaching == 8);
    CHECK(f.threshold == Approx(c.threshold));
  }
  SECTION("when no seabed is served, the threshold keeps the targets of all") {
    for (int k = 0; k < 5; ++k)
      add(rows, 2.5, 0, -1, 0);  // sand's clutter now as bright as its targets
    const mission::GateChoice all =
        mission::choose_gate_threshold(g, rows, {"sand", "rock"}, 10, 1.0, 0.1);
    CHECK_FALSE(all.scenarios[0].served);
    CHECK(all.threshold == Approx(1.0 / (1.0 + std::exp(2.0))));  // rock's weakest, sigmoid(-2)
  }
}
