// A bathymetry grid's relief (sim/seabed/relief_grid.h): cell values at cell centres, planes
// exactly, continuous slopes across cells, the grid's placement (turned, running south), and the
// tile filler against the point sampler.
#include "sim/seabed/relief_grid.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

using namespace sonarloop;
using namespace sonarloop::seabed;

namespace {

// rows x cols cells of spacing `cell`, turned by `turn_deg` (rows run along -x turned, like a
// north-up file whose rows run south), cell (0, 0) at `origin`; values from f(row, col)
template <class F>
ReliefGrid make_grid(int rows, int cols, double cell, double turn_deg, Vec2 origin, F f) {
  ReliefGrid g;
  g.rows = rows;
  g.cols = cols;
  const double a = turn_deg * std::numbers::pi / 180.0;
  g.row_step_m = cell * Vec2(-std::cos(a), -std::sin(a));
  g.col_step_m = cell * Vec2(-std::sin(a), std::cos(a));
  g.origin_m = origin;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      g.elevation_m.push_back(static_cast<float>(f(r, c)));
  return g;
}

Vec2 centre_of(const ReliefGrid& g, double r, double c) {
  return g.origin_m + r * g.row_step_m + c * g.col_step_m;
}

}  // namespace

TEST_CASE("relief grid: cell values at cell centres, whatever the grid's turn") {
  for (double turn : {0.0, 1.7, 30.0}) {
    const ReliefGrid g = make_grid(12, 9, 2.0, turn, Vec2(30.0, -10.0),
                                   [](int r, int c) { return std::sin(r * 1.3) + 0.7 * c; });
    for (int r = 0; r < g.rows; ++r) {
      for (int c = 0; c < g.cols; ++c) {
        const Vec2 p = centre_of(g, r, c);
        INFO("turn " << turn << " cell " << r << ", " << c);
        const Vec2 cell = relief_cell_of(g, p.x(), p.y());
        CHECK(cell.x() == Approx(r).margin(1e-9));
        CHECK(cell.y() == Approx(c).margin(1e-9));
        CHECK(relief_at(g, p.x(), p.y()) == Approx(g.elevation_m[r * g.cols + c]).margin(1e-5));
      }
    }
  }
}

TEST_CASE("relief grid: a plane is reproduced exactly between cells") {
  // elevation = 0.01 x - 0.03 y + 2 in W: the cells hold it, and every point between them too
  const auto plane = [](Vec2 p) { return 0.01 * p.x() - 0.03 * p.y() + 2.0; };
  ReliefGrid g = make_grid(20, 20, 4.0, 12.0, Vec2(40.0, -40.0), [](int, int) { return 0.0; });
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c)
      g.elevation_m[r * g.cols + c] = static_cast<float>(plane(centre_of(g, r, c)));
  for (double x = -20.0; x <= 20.0; x += 1.37) {
    for (double y = -10.0; y <= 20.0; y += 0.93) {
      INFO("x " << x << " y " << y);
      CHECK(relief_at(g, x, y) == Approx(plane(Vec2(x, y))).margin(2e-6));
    }
  }
}

TEST_CASE("relief grid: slopes are continuous across cell edges (C1)") {
  const ReliefGrid g = make_grid(10, 10, 2.0, 0.0, Vec2(18.0, 0.0), [](int r, int c) {
    return std::sin(0.9 * r) * std::cos(0.6 * c) + ((r * 7 + c * 3) % 5) * 0.1;
  });
  // along a column, across the edge between rows 4 and 5 (x = 18 - 9 = 9): one-sided slopes
  // meet; a bilinear surface would have a kink
  const double h = 1e-4;
  for (double y : {3.1, 6.7, 9.9}) {
    const double x = 9.0;
    const double below = (relief_at(g, x, y) - relief_at(g, x - h, y)) / h;
    const double above = (relief_at(g, x + h, y) - relief_at(g, x, y)) / h;
    INFO("y " << y << " slopes " << below << " / " << above);
    CHECK(below == Approx(above).margin(1e-3));
  }
}

TEST_CASE("relief grid: add_relief adds what relief_at gives at every grid point") {
  const ReliefGrid g = make_grid(16, 16, 1.5, 5.0, Vec2(12.0, -12.0),
                                 [](int r, int c) { return 0.1 * r * c - 0.05 * r; });
  const int nx = 40;
  const int ny = 30;
  std::vector<float> out(static_cast<std::size_t>(nx) * ny, 1.0f);
  add_relief(g, -8.0, -6.0, 0.4, nx, ny, out.data(), ny);
  for (int r = 0; r < nx; ++r) {
    for (int c = 0; c < ny; ++c) {
      CHECK(out[static_cast<std::size_t>(r * ny + c)] ==
            Approx(1.0 + relief_at(g, -8.0 + r * 0.4, -6.0 + c * 0.4)).margin(1e-5));
    }
  }
}
