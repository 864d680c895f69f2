#pragma once
// Clutter layer: rocks scattered as a Poisson point process with log-normal diameters
// (docs/physics.md §3, "Poisson clutter"). The plane is cut into fixed cells; each cell's rocks are
// a pure function of (seed, cell), so any tile can find the rocks that reach into it without
// knowing about other tiles. Regions with different clutter densities are handled by thinning:
// candidates are drawn at the largest density and each is kept with probability
// density(region at the rock) / largest density, which is again a Poisson process.
//
// A rock is a super-ellipsoidal cap: footprint semi-axes a >= b, exponent p in [2, 3.5] (2 =
// ellipsoid, larger = blockier), height H, sunk into the sediment by a random fraction of H. It
// sits on the large-scale elevation (slope + pink noise) at its centre; the heightmap keeps the
// higher of the rock and the textured seabed, so ripples may lap against a rock's foot.
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "sim/scene/scene_desc.h"

namespace sonarloop::seabed {

inline constexpr double kClutterCell_m = 8.0;

struct Rock {
  double x_m = 0.0;  // centre, north
  double y_m = 0.0;  // centre, east
  double semi_major_m = 0.0;
  double semi_minor_m = 0.0;
  double orientation_rad = 0.0;  // of the major axis, clockwise from north
  double exponent = 2.0;
  double height_m = 0.0;
  double sink_m = 0.0;  // depth of the rock's foot below its base level
  double base_m = 0.0;  // base level (elevation, positive up) at the centre
  int region = 0;
};

// Candidates of one cell, before thinning (for the statistics tests).
struct ClutterCandidate {
  Rock rock;
  double keep_u = 0.0;  // uniform in [0, 1): kept if keep_u < density(region) / max density
};

class Clutter {
 public:
  // region_at maps a point to its region index; base_at gives the large-scale elevation.
  Clutter(const scene::SceneDesc& desc, std::function<int(double, double)> region_at,
          std::function<double(double, double)> base_at);

  bool empty() const { return max_density_ <= 0.0; }
  double max_diameter_m() const { return max_diameter_m_; }

  // All kept rocks whose footprint may reach into [x0, x1] × [y0, y1].
  std::vector<Rock> rocks_near(double x0, double y0, double x1, double y1) const;
  // Rocks of one cell (kept ones only).
  std::vector<Rock> rocks_in_cell(std::int64_t ci, std::int64_t cj) const;

  // Raises heights (T = nx × ny grid at (x0 + r·d, y0 + c·d)) to each rock's surface.
  void rasterize(const std::vector<Rock>& rocks, double x0, double y0, double d, int nx, int ny,
                 float* height, std::size_t stride) const;

  // Height of a rock's surface above its base level at a point (>= -sink inside the footprint),
  // or -infinity outside.
  static double rock_surface(const Rock& rock, double x, double y);

 private:
  std::uint64_t seed_;
  std::vector<std::optional<scene::ClutterDesc>> per_region_;
  double max_density_ = 0.0;
  double max_diameter_m_ = 0.0;
  std::function<int(double, double)> region_at_;
  std::function<double(double, double)> base_at_;
};

}  // namespace sonarloop::seabed
