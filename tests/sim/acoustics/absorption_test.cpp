#include "sim/acoustics/absorption.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace sonarloop::acoustics;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

// Francois-Garrison at the reference water of docs/physics.md §1 (T 10 °C, S 35 ppt, pH 8, D 0 m)
double fg_ref(double freq_hz) {
  return francois_garrison_db_per_km(freq_hz, 10.0, 35.0, 0.0, 8.0);
}

}  // namespace

TEST_CASE("absorption: F&G full-precision pins (docs/physics.md §6 items 1, 2, 4, 5)") {
  // uacpy test_numeric_contracts.py, AttenMod.f90; rel 1e-9
  CHECK_THAT(fg_ref(1e5), WithinRel(33.63031641787127, 1e-9));
  CHECK_THAT(fg_ref(1e4), WithinRel(0.962637291817115, 1e-9));
  CHECK_THAT(fg_ref(1e3), WithinRel(0.060126063391378846, 1e-9));
  CHECK_THAT(francois_garrison_db_per_km(1e4, 4.0, 34.0, 2000.0, 7.9),
             WithinRel(0.8372956055122321, 1e-9));
  // T = 20 exactly takes the warm pure-water fit
  CHECK_THAT(francois_garrison_db_per_km(5e5, 20.0, 35.0, 0.0, 8.0),
             WithinRel(146.64062876899342, 1e-9));
  CHECK_THAT(francois_garrison_db_per_km(5e5, 10.0, 35.0, 0.0, 8.0),
             WithinRel(124.67276253563452, 1e-9));
  CHECK_THAT(francois_garrison_db_per_km(5e5, 25.0, 35.0, 0.0, 8.0),
             WithinRel(169.7876059853789, 1e-9));
}

TEST_CASE("absorption: F&G 1982b Table IV published values (item 3, §1a)") {
  // (T, S, f kHz, published dB/km, tolerance from the printed digits)
  struct Row {
    double t, s, f_khz, alpha, tol;
  };
  const Row rows[] = {
      {0, 30, 1, 6.10e-2, 0.0005}, {0, 35, 1, 6.40e-2, 0.0005}, {10, 35, 1, 6.00e-2, 0.0005},
      {0, 30, 10, 1.12, 0.005},    {0, 35, 10, 1.29, 0.01},     {10, 35, 10, 0.963, 0.0005},
      {0, 30, 100, 21.0, 0.05},    {0, 35, 100, 23.4, 0.05},    {10, 35, 100, 33.6, 0.05},
  };
  for (const Row& r : rows) {
    INFO("T " << r.t << " S " << r.s << " f " << r.f_khz << " kHz");
    CHECK_THAT(francois_garrison_db_per_km(r.f_khz * 1e3, r.t, r.s, 0.0, 8.0),
               WithinAbs(r.alpha, r.tol));
  }
}

TEST_CASE("absorption: F&G intermediate values and the split into three terms (§1, §1c)") {
  CHECK_THAT(sound_speed_fg_m_s(10.0, 35.0, 0.0), WithinAbs(1485.75, 1e-9));
  CHECK_THAT(sound_speed_fg_m_s(10.0, 35.0, 1000.0), WithinAbs(1485.75 + 16.7, 1e-9));
  // boric / MgSO4 / water at T10 S35 pH8 D0 (docs/physics.md §1c, 3 decimals)
  const auto t80 = francois_garrison_terms(80e3, 10.0, 35.0, 0.0, 8.0);
  CHECK_THAT(t80.boric_acid_db_per_km, WithinAbs(0.116, 0.0005));
  CHECK_THAT(t80.magnesium_sulphate_db_per_km, WithinAbs(25.219, 0.0005));
  CHECK_THAT(t80.pure_water_db_per_km, WithinAbs(1.989, 0.0005));
  const auto t100 = francois_garrison_terms(100e3, 10.0, 35.0, 0.0, 8.0);
  CHECK_THAT(t100.boric_acid_db_per_km, WithinAbs(0.116, 0.0005));
  CHECK_THAT(t100.magnesium_sulphate_db_per_km, WithinAbs(30.407, 0.0005));
  CHECK_THAT(t100.pure_water_db_per_km, WithinAbs(3.108, 0.0005));
  const auto t300 = francois_garrison_terms(300e3, 10.0, 35.0, 0.0, 8.0);
  CHECK_THAT(t300.boric_acid_db_per_km, WithinAbs(0.116, 0.0005));
  CHECK_THAT(t300.magnesium_sulphate_db_per_km, WithinAbs(45.052, 0.0005));
  CHECK_THAT(t300.pure_water_db_per_km, WithinAbs(27.972, 0.0005));
  CHECK_THAT(t300.total(), WithinRel(fg_ref(300e3), 1e-15));
}

TEST_CASE("absorption: F&G in the sidescan band (item 7, §1c table)") {
  CHECK_THAT(fg_ref(300e3), WithinAbs(73.139, 0.01));
  CHECK_THAT(fg_ref(80e3), WithinAbs(27.324, 0.01));
  // the rest of the §1c columns, to their printed 3 decimals
  struct Row {
    double f_khz, fg, warm_deep;
  };
  const Row rows[] = {{80, 27.324, 28.494},   {100, 33.630, 36.980},  {120, 38.823, 44.339},
                      {150, 45.268, 53.500},  {200, 54.446, 65.500},  {250, 63.430, 75.645},
                      {300, 73.139, 85.413},  {400, 96.114, 106.432}, {500, 124.673, 131.191},
                      {900, 299.463, 278.257}};
  for (const Row& r : rows) {
    INFO("f " << r.f_khz << " kHz");
    CHECK_THAT(fg_ref(r.f_khz * 1e3), WithinAbs(r.fg, 0.0006));
    CHECK_THAT(francois_garrison_db_per_km(r.f_khz * 1e3, 15.0, 35.0, 20.0, 8.0),
               WithinAbs(r.warm_deep, 0.0006));
  }
}

TEST_CASE("absorption: arlpy doctest values (item 6)") {
  const double alpha = francois_garrison_db_per_km(50e3, 27.0, 35.0, 10.0, 8.1);
  CHECK_THAT(alpha, WithinAbs(10.710, 0.005));
  // arlpy's "linear" 1 km factor is an amplitude factor, 10^(−α/20); and 3 km in dB
  CHECK_THAT(std::pow(10.0, -alpha / 20.0), WithinAbs(0.2914, 0.0001));
  CHECK_THAT(-alpha * 3.0, WithinAbs(-32.13, 0.005));
}

TEST_CASE("absorption: depth ratio exercises P2 and P3 (item 9)") {
  const double deep = francois_garrison_db_per_km(63e3, 10.0, 35.0, 4000.0, 8.0);
  const double surface = francois_garrison_db_per_km(63e3, 10.0, 35.0, 0.0, 8.0);
  CHECK_THAT(deep / surface, WithinRel(0.54917617566523, 1e-9));
}

TEST_CASE("absorption: Ainslie-McColm (item 8, §1a and §1c columns)") {
  const double am = ainslie_mccolm_db_per_km(100e3, 10.0, 35.0, 0.0, 8.0);
  CHECK_THAT(am, WithinAbs(34.34, 0.01));
  CHECK(std::fabs(am - fg_ref(100e3)) / fg_ref(100e3) < 0.10);
  struct Row {
    double f_khz, am;
  };
  const Row band[] = {{80, 27.884},  {100, 34.341}, {120, 39.687},  {150, 46.384},  {200, 56.066},
                      {250, 65.679}, {300, 76.151}, {400, 101.058}, {500, 132.097}, {900, 322.309}};
  for (const Row& r : band) {
    INFO("f " << r.f_khz << " kHz");
    CHECK_THAT(ainslie_mccolm_db_per_km(r.f_khz * 1e3, 10.0, 35.0, 0.0, 8.0),
               WithinAbs(r.am, 0.0006));
    // the paper's claim: within 10 % of F&G
    CHECK(std::fabs(ainslie_mccolm_db_per_km(r.f_khz * 1e3, 10.0, 35.0, 0.0, 8.0) /
                        fg_ref(r.f_khz * 1e3) -
                    1.0) < 0.10);
  }
  // Table IV conditions (§1a last column)
  CHECK_THAT(ainslie_mccolm_db_per_km(1e3, 0.0, 30.0, 0.0, 8.0), WithinAbs(0.06141, 0.000006));
  CHECK_THAT(ainslie_mccolm_db_per_km(10e3, 10.0, 35.0, 0.0, 8.0), WithinAbs(0.9866, 0.00006));
  CHECK_THAT(ainslie_mccolm_db_per_km(100e3, 0.0, 30.0, 0.0, 8.0), WithinAbs(20.89, 0.006));
  // depth enters in km inside: 1 km deep lowers the MgSO4 and water terms
  CHECK(ainslie_mccolm_db_per_km(100e3, 10.0, 35.0, 1000.0, 8.0) <
        ainslie_mccolm_db_per_km(100e3, 10.0, 35.0, 0.0, 8.0));
}
