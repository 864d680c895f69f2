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

// Scenario 0 (sand): 10 targets at x0 = 2.0..2.9, 20 clutter at -3.0..-1.1: separable.
void add_sand(mission::GateRows& rows) {
  for (int t = 0; t < 10; ++t)
    add(rows, 2.0 + 0.1 * t, 1, t, 0);
  for (int c = 0; c < 20; ++c)
    add(rows, -3.0 + 0.1 * c, 0, -1, 0);
}

}  // namespace

TEST_CASE("gate threshold: the seabeds the gate serves set it; a hopeless one does not") {
  mission::GateRows rows;
  add_sand(rows);
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

TEST_CASE(
    "gate threshold, false budget: the lowest within every seabed's budget, within its "
    "allowance of missed targets") {
  const atr::LogisticGate g = gate_on_feature0();
  const auto sig = [](double x) { return 1.0 / (1.0 + std::exp(-x)); };
  mission::GateRows rows;
  add_sand(rows);
  // gravel: 10 targets at 0.0..0.9, clutter among them at 0.05..0.95
  for (int t = 0; t < 10; ++t)
    add(rows, 0.1 * t, 1, 100 + t, 1);
  for (int c = 0; c < 10; ++c)
    add(rows, 0.05 + 0.1 * c, 0, -1, 1);
  // budget 0.1 per target: one false detection of 10 targets; keep 0.9: 9 of 10 targets
  const mission::GateChoice keep =
      mission::choose_gate_threshold(g, rows, {"sand", "gravel"}, 10, 0.9, 0.1);
  const mission::GateChoice budget = mission::choose_gate_threshold(
      g, rows, {"sand", "gravel"}, 10, 0.9, 0.1, mission::GateAim::kFalseBudget);
  REQUIRE(budget.scenarios.size() == 2);
  // sand: its own threshold keeps 9 of its 10 targets (2.1); its budget passes one clutter (-1.1)
  CHECK(budget.scenarios[0].own_threshold == Approx(sig(2.1)));
  CHECK(budget.scenarios[0].budget_threshold > sig(-1.2));
  CHECK(budget.scenarios[0].budget_threshold == Approx(sig(-1.2)));
  CHECK(budget.scenarios[0].served);
  // gravel cannot have both (9 clutter above its own threshold 0.1): not served
  CHECK(budget.scenarios[1].own_threshold == Approx(sig(0.1)));
  CHECK(budget.scenarios[1].budget_threshold == Approx(sig(0.85)));
  CHECK_FALSE(budget.scenarios[1].served);
  // keep-targets: sand's own threshold; false budget: gravel spends its allowance (1 target) on
  // fewer false detections, asking for its own threshold, the highest ask
  CHECK(keep.threshold == Approx(sig(2.1)));
  CHECK(budget.threshold == Approx(sig(0.1)));
  CHECK(budget.scenarios[1].kept == Approx(0.9));
  CHECK(budget.scenarios[0].kept == Approx(1.0));
  CHECK(budget.scenarios[0].false_per_target == 0.0);

  SECTION("a seabed that can have both asks for its budget, no more") {
    // gravel's clutter: one among its targets (0.55), one below them (-0.5)
    mission::GateRows two;
    for (std::size_t r = 0; r < rows.x.size(); ++r) {
      if (rows.scenario[r] == 1 && rows.y[r] == 0) continue;
      two.x.push_back(rows.x[r]);
      two.y.push_back(rows.y[r]);
      two.target.push_back(rows.target[r]);
      two.scenario.push_back(rows.scenario[r]);
    }
    add(two, 0.55, 0, -1, 1);
    add(two, -0.5, 0, -1, 1);
    const mission::GateChoice b = mission::choose_gate_threshold(
        g, two, {"sand", "gravel"}, 10, 0.9, 0.1, mission::GateAim::kFalseBudget);
    CHECK(b.scenarios[1].served);
    // the lowest threshold within both budgets: gravel's, which passes 0.55 and not -0.5; all
    // of gravel's targets kept, where keep-targets would have lost one
    CHECK(b.threshold == Approx(sig(-0.5)));
    CHECK(b.threshold > sig(-0.5));
    CHECK(b.scenarios[1].kept == Approx(1.0));
    CHECK(b.scenarios[1].false_per_target == Approx(0.1));
    const mission::GateChoice k =
        mission::choose_gate_threshold(g, two, {"sand", "gravel"}, 10, 0.9, 0.1);
    CHECK(k.threshold == Approx(sig(0.1)));
    CHECK(k.scenarios[1].kept == Approx(0.9));
  }
}
