#pragma once
// Large-scale relief from a bathymetry grid (a multibeam survey or a public grid of the user's
// site): the seabed elevation the scenario's fractal detail, sediments, ripples and rocks are
// added to (docs/physics.md §5, "Relief from a grid"). Plain data: the scenario loader reads the
// file and places it in the world frame (config/loader/bathymetry_loader.h); the seabed only
// samples it.
#include <cstddef>
#include <string>
#include <vector>

#include "sim/frames.h"

namespace sonarloop::seabed {

// A regular grid of seabed elevations (m, positive up, relative to the scenario's mean depth)
// and where it lies in the world frame W (x north, y east): the centre of cell (row, col) is at
// origin_m + row * row_step_m + col * col_step_m. The steps are vectors, so the grid may be
// turned against true north (a projected grid's north differs from true north by the
// projection's meridian convergence) and may run in any direction.
struct ReliefGrid {
  int rows = 0;
  int cols = 0;
  std::vector<float> elevation_m;  // rows x cols, row-major, every value finite
  Vec2 origin_m = Vec2::Zero();
  Vec2 row_step_m = Vec2(1.0, 0.0);
  Vec2 col_step_m = Vec2(0.0, 1.0);
  std::string source;  // where it came from, for messages (the file and its CRS)
};

// The grid's cell coordinates (row, col) of the W point (x, y).
Vec2 relief_cell_of(const ReliefGrid& g, double x, double y);

// The elevation at the W point (x, y): Catmull–Rom interpolation of the 4 x 4 cells around it
// (C1, so that slopes and the sonar's incidence are continuous across cells; it reproduces a
// plane exactly). Beyond the outermost cell centres the edge cells are repeated.
double relief_at(const ReliefGrid& g, double x, double y);

// out[r * stride + c] += the elevation at (x0 + r·d, y0 + c·d), r < nx, c < ny.
void add_relief(const ReliefGrid& g, double x0, double y0, double d, int nx, int ny, float* out,
                std::size_t stride);

}  // namespace sonarloop::seabed
