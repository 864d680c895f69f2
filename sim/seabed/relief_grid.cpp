#include "sim/seabed/relief_grid.h"

#include <algorithm>
#include <cmath>

#include "sim/seabed/noise_layer.h"

namespace sonarloop::seabed {
namespace {

// W -> cell coordinates: the inverse of the 2 x 2 matrix [row_step col_step]
struct CellMap {
  Vec2 origin;
  double a, b, c, d;  // row = a·dx + b·dy, col = c·dx + d·dy

  explicit CellMap(const ReliefGrid& g) : origin(g.origin_m) {
    const Vec2 r = g.row_step_m;
    const Vec2 s = g.col_step_m;
    const double det = r.x() * s.y() - s.x() * r.y();
    a = s.y() / det;
    b = -s.x() / det;
    c = -r.y() / det;
    d = r.x() / det;
  }
  Vec2 operator()(double x, double y) const {
    const double dx = x - origin.x();
    const double dy = y - origin.y();
    return {a * dx + b * dy, c * dx + d * dy};
  }
};

double interpolate(const ReliefGrid& g, Vec2 cell) {
  const double u = std::clamp(cell.x(), 0.0, static_cast<double>(g.rows - 1));
  const double v = std::clamp(cell.y(), 0.0, static_cast<double>(g.cols - 1));
  const auto i = static_cast<int>(std::floor(u));
  const auto j = static_cast<int>(std::floor(v));
  // in double: a constant grid stays constant to the last bit of its floats
  double wu[4];
  double wv[4];
  catmull_rom_weights(u - i, wu);
  catmull_rom_weights(v - j, wv);
  double sum = 0.0;
  if (i >= 1 && j >= 1 && i + 2 < g.rows && j + 2 < g.cols) {  // inside: no clamping
    const float* p = g.elevation_m.data() + static_cast<std::size_t>(i - 1) * g.cols + (j - 1);
    for (int a = 0; a < 4; ++a, p += g.cols)
      sum += wu[a] * (wv[0] * p[0] + wv[1] * p[1] + wv[2] * p[2] + wv[3] * p[3]);
    return sum;
  }
  for (int a = 0; a < 4; ++a) {
    const int row = std::clamp(i - 1 + a, 0, g.rows - 1);
    const float* line = g.elevation_m.data() + static_cast<std::size_t>(row) * g.cols;
    double across = 0.0;
    for (int b = 0; b < 4; ++b)
      across += wv[b] * line[std::clamp(j - 1 + b, 0, g.cols - 1)];
    sum += wu[a] * across;
  }
  return sum;
}

}  // namespace

Vec2 relief_cell_of(const ReliefGrid& g, double x, double y) {
  return CellMap(g)(x, y);
}

double relief_at(const ReliefGrid& g, double x, double y) {
  return interpolate(g, CellMap(g)(x, y));
}

void add_relief(const ReliefGrid& g, double x0, double y0, double d, int nx, int ny, float* out,
                std::size_t stride) {
  const CellMap map(g);
  for (int r = 0; r < nx; ++r) {
    float* row = out + static_cast<std::size_t>(r) * stride;
    for (int c = 0; c < ny; ++c)
      row[c] += static_cast<float>(interpolate(g, map(x0 + r * d, y0 + c * d)));
  }
}

}  // namespace sonarloop::seabed
