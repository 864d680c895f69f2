// Confusion matrix counts and the Wilson score interval against values computed by hand.
#include <catch2/catch.hpp>
#include <cmath>

#include "atr/confusion.h"

using namespace sonarloop::atr;

TEST_CASE("confusion: Wilson interval matches the formula and its known properties") {
  // x = 0 of n = 10: [0, z^2 / (n + z^2)] = [0, 0.27753]
  Interval i = wilson_interval(0, 10);
  CHECK(i.lo == Approx(0.0).margin(1e-12));
  CHECK(i.hi == Approx(kZ95 * kZ95 / (10 + kZ95 * kZ95)).epsilon(1e-12));
  CHECK(i.hi == Approx(0.27753).epsilon(1e-4));
  // x = n: the mirror image
  i = wilson_interval(10, 10);
  CHECK(i.lo == Approx(10.0 / (10 + kZ95 * kZ95)).epsilon(1e-12));
  CHECK(i.hi == Approx(1.0));
  // 81 of 263 (a textbook example): 0.2553 .. 0.3662
  i = wilson_interval(81, 263);
  CHECK(i.lo == Approx(0.255289).epsilon(1e-5));
  CHECK(i.hi == Approx(0.366210).epsilon(1e-5));
  // 50 of 100: symmetric about 0.5, 0.4038 .. 0.5962
  i = wilson_interval(50, 100);
  CHECK(i.lo == Approx(0.403832).epsilon(1e-5));
  CHECK(0.5 - i.lo == Approx(i.hi - 0.5).epsilon(1e-12));
  // no trials: no information
  i = wilson_interval(0, 0);
  CHECK(i.lo == 0.0);
  CHECK(i.hi == 1.0);
}

TEST_CASE("confusion: counts, accuracy, names that differ between truth and prediction") {
  ConfusionMatrix m({"manta", "rockan", "rock"}, {"manta", "rockan"});
  m.add(0, 0);
  m.add(0, 0);
  m.add(0, 1);
  m.add(1, 1);
  m.add(2, 0);  // a class the model does not know is always wrong
  CHECK(m.total() == 5);
  CHECK(m.correct() == 3);
  CHECK(m.accuracy() == Approx(0.6));
  CHECK(m.count(0, 1) == 1);
  CHECK(m.row_total(0) == 3);
  const Interval i = m.accuracy_interval();
  CHECK(i.lo < 0.6);
  CHECK(i.hi > 0.6);
  const std::string text = m.to_text();
  CHECK_THAT(text,
             Catch::Contains("manta") && Catch::Contains("66.7%") && Catch::Contains("100.0%"));
  CHECK_THROWS(m.add(3, 0));
}
