#pragma once
// Pictures of a generated scene for `sonarloop scene`: heightmap, sediment map and a shaded
// relief with the targets drawn in, all north-up.
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "sim/frames.h"
#include "sim/scene/scene.h"

namespace sonarloop::products {

struct SceneImages {
  int rows = 0;  // along north; row 0 = southern edge
  int cols = 0;  // along east
  double spacing_m = 0.0;
  Vec2 origin_m = Vec2::Zero();        // (north, east) of sample [0][0]
  std::vector<float> elevation_m;      // seabed only (rows x cols)
  std::vector<std::uint8_t> sediment;  // (rows x cols)
  std::vector<float> display_m;        // elevation with target tops, for the relief
  std::vector<std::uint8_t> target;    // 1 where a target is seen from above
};

// Casts vertical rays over each target's footprint to find its top (using `view` if it covers
// the target, otherwise a small view around it) and fills display_m and target.
void draw_targets(const scene::Scene& s, const scene::SceneView* view, SceneImages& img);

// Writes the 16-bit heightmap; returns the (min, max) elevation the grey levels span.
std::pair<double, double> write_heightmap_png(const std::string& path, const SceneImages& img);
void write_sediments_png(const std::string& path, const SceneImages& img);
// Hillshade (sun from the north-west, 45° up, heights exaggerated 3×) tinted by sediment.
void write_relief_png(const std::string& path, const SceneImages& img);

std::vector<int> sediments_present(const SceneImages& img);
std::array<int, 3> sediment_colour(int sediment_id);

}  // namespace sonarloop::products
