// seabed.bathymetry (config/loader/bathymetry_loader.h) on the real grid files of
// tests/data/bathymetry: placement by the file's CRS against positions GDAL's own command-line
// tool gives, placement of a grid without a CRS, GeoTIFF and ASCII alike, and every refusal.
#include "config/loader/bathymetry_loader.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "config/loader/scene_loader.h"
#include "sim/seabed/noise_layer.h"
#include "sim/seabed/relief_grid.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop;
using namespace sonarloop::config;

namespace {

const std::string kData = SONARLOOP_SOURCE_DIR "/tests/data/bathymetry/";

// A scene at 25 m depth over `extent` m square from `origin` with `bathymetry` (YAML lines under
// seabed.bathymetry, indented by 4).
std::string scene_text(const std::string& bathymetry, double origin = -50.0,
                       double extent = 100.0) {
  std::ostringstream s;
  s << "seed: 1\nwater:\n  depth_m: 25.0\nseabed:\n  origin_m: [" << origin << ", " << origin
    << "]\n  extent_m: [" << extent << ", " << extent
    << "]\n  grid_spacing_m: 0.05\n  bathymetry:\n"
    << bathymetry;
  return s.str();
}

std::string error_of(const std::string& text) {
  try {
    parse_scene(text, "bathymetry-test.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

// The .asc file's cells (row 0 north) and header, read here on their own.
struct AscGrid {
  int rows = 0, cols = 0;
  double xll = 0, yll = 0, cell = 0;
  std::vector<double> depth;
  double at(int r, int c) const {
    r = std::clamp(r, 0, rows - 1);
    c = std::clamp(c, 0, cols - 1);
    return depth[static_cast<std::size_t>(r * cols + c)];
  }
  // Catmull–Rom at the UTM point (E, N): the interpolation relief_grid.h states
  double depth_at(double e, double n) const {
    const double col = (e - xll) / cell - 0.5;
    const double row = (yll + rows * cell - n) / cell - 0.5;
    const int r0 = static_cast<int>(std::floor(row));
    const int c0 = static_cast<int>(std::floor(col));
    double wr[4], wc[4];
    seabed::catmull_rom_weights(row - r0, wr);
    seabed::catmull_rom_weights(col - c0, wc);
    double sum = 0.0;
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        sum += wr[a] * wc[b] * at(r0 - 1 + a, c0 - 1 + b);
    return sum;
  }
};

AscGrid read_asc(const std::string& path) {
  std::ifstream in(path);
  AscGrid g;
  std::string key;
  double nodata = 0;
  in >> key >> g.cols >> key >> g.rows >> key >> g.xll >> key >> g.yll >> key >> g.cell >> key >>
      nodata;
  double v;
  while (in >> v)
    g.depth.push_back(v);
  REQUIRE(g.depth.size() == static_cast<std::size_t>(g.rows * g.cols));
  return g;
}

}  // namespace

TEST_CASE("bathymetry: a grid with a CRS is placed by the scenario's origin") {
  // UTM zone 30N positions of points of the scenario's frame (north, east from 55.9 N, 3.2 W),
  // from GDAL's command-line tool through an azimuthal equidistant projection about the origin
  // (the tangent plane to 0.2 mm at 50 m):
  //   echo "E N" | gdaltransform -s_srs '+proj=aeqd +lat_0=55.9 +lon_0=-3.2 +datum=WGS84'
  //                              -t_srs EPSG:32630
  struct Known {
    double north, east, utm_e, utm_n;
  };
  const Known known[] = {{0.0, 0.0, 487494.257596034, 6194968.02276949},
                         {40.0, 0.0, 487494.373169275, 6195008.00667918},
                         {0.0, 40.0, 487534.241505487, 6194967.90719649},
                         {-45.0, 30.0, 487524.115508862, 6194922.95419174}};
  const AscGrid asc = read_asc(kData + "forth_2m.asc");
  for (const std::string file : {"forth_2m.asc", "forth_2m.tif"}) {
    const auto s = parse_scene(scene_text("    file: " + kData + file + "\n"), "b.yaml");
    REQUIRE(s.seabed.bathymetry);
    const auto& grid = *s.seabed.bathymetry->grid;
    INFO(file << ": " << grid.source);
    CHECK(grid.source.find("UTM zone 30N") != std::string::npos);
    for (const Known& k : known) {
      const double expected = 25.0 - asc.depth_at(k.utm_e, k.utm_n);
      INFO("north " << k.north << " east " << k.east);
      CHECK(seabed::relief_at(grid, k.north, k.east) == Approx(expected).margin(0.005));
    }
    // the grid's columns run east turned by the meridian convergence here, about -0.17 degrees
    // ((lon - lon0) sin lat), and its cells are 2 m / 0.9996 (the UTM scale factor) long
    const double turn_deg =
        std::atan2(grid.col_step_m.x(), grid.col_step_m.y()) * 180.0 / std::numbers::pi;
    CHECK(turn_deg == Approx(0.166).margin(0.01));
    CHECK(grid.col_step_m.norm() == Approx(2.0 / 0.9996).margin(2e-4));
  }
}

TEST_CASE("bathymetry: a grid in latitude and longitude (as EMODnet's and GEBCO's) is placed too") {
  // the UTM grid resampled to 0.000026 degree cells (1.6 m east, 2.9 m north): the same seabed
  // within what the bilinear resampling and the coarser rows change (centimetres, 10 at most)
  const auto utm = parse_scene(scene_text("    file: " + kData + "forth_2m.tif\n"), "b.yaml");
  const auto geo = parse_scene(scene_text("    file: " + kData + "forth_wgs84.tif\n"), "b.yaml");
  const auto& g = *geo.seabed.bathymetry->grid;
  CHECK(g.source.find("WGS 84") != std::string::npos);
  CHECK(g.col_step_m.norm() == Approx(0.0000259810 * std::numbers::pi / 180.0 * 6.39e6 *
                                      std::cos(55.9 * std::numbers::pi / 180.0))
                                   .epsilon(0.01));
  double sum2 = 0.0;
  int n = 0;
  for (double north = -45.0; north <= 45.0; north += 5.0) {
    for (double east = -45.0; east <= 45.0; east += 5.0) {
      const double d = seabed::relief_at(g, north, east) -
                       seabed::relief_at(*utm.seabed.bathymetry->grid, north, east);
      CHECK(std::abs(d) < 0.15);
      sum2 += d * d;
      ++n;
    }
  }
  CHECK(std::sqrt(sum2 / n) < 0.03);
}

TEST_CASE("bathymetry: a grid without a CRS is placed by origin_xy_m, and a plane stays one") {
  // plane_4m.xyz holds depth = 25 + 0.01 X + 0.02 Y; with the scenario's origin at X = 10,
  // Y = -20, the point (north n, east e) is at X = 10 + e, Y = -20 + n
  const auto s = parse_scene(
      scene_text("    file: " + kData + "plane_4m.xyz\n    origin_xy_m: [10.0, -20.0]\n"),
      "b.yaml");
  const auto& grid = *s.seabed.bathymetry->grid;
  for (double n = -50.0; n <= 50.0; n += 7.3) {
    for (double e = -50.0; e <= 50.0; e += 9.1) {
      const double depth = 25.0 + 0.01 * (10.0 + e) + 0.02 * (-20.0 + n);
      CHECK(seabed::relief_at(grid, n, e) == Approx(25.0 - depth).margin(1e-4));
    }
  }
  // the window read is the extent and the interpolation's margin, not the whole file
  CHECK(grid.rows * grid.cols < 100 * 100);
  CHECK(grid.rows >= 100 / 4);
}

TEST_CASE("bathymetry: elevations instead of depths") {
  // the same file read as elevations would put the seabed 23-29 m above the surface: refused,
  // naming the key; a file of elevations is the negative of the depths
  CHECK_THAT(error_of(scene_text("    file: " + kData + "forth_2m.asc\n    values: elevation\n")),
             Catch::Contains("seabed.bathymetry.values") && Catch::Contains("not under water"));
}

TEST_CASE("bathymetry: cells without data are refused, or filled when asked") {
  // a 300 m extent reaches the north-east corner the survey did not cover
  const std::string asc = "    file: " + kData + "forth_2m.asc\n";
  const std::string err = error_of(scene_text(asc, -150.0, 300.0));
  CHECK_THAT(err, Catch::Contains("seabed.bathymetry.nodata") &&
                      Catch::Contains("cells without data") && Catch::Contains("fill"));
  const auto s = parse_scene(scene_text(asc + "    nodata: fill\n", -150.0, 300.0), "b.yaml");
  const auto& grid = *s.seabed.bathymetry->grid;
  double lo = 1e9, hi = -1e9;
  for (float v : grid.elevation_m) {
    REQUIRE(std::isfinite(v));
    lo = std::min(lo, static_cast<double>(v));
    hi = std::max(hi, static_cast<double>(v));
  }
  // filled from the surveyed depths (23-29 m): within their range
  CHECK(lo > 25.0 - 30.0);
  CHECK(hi < 25.0 - 22.0);
  // the filled corner continues the neighbouring seabed
  CHECK(seabed::relief_at(grid, 140.0, 140.0) ==
        Approx(seabed::relief_at(grid, 110.0, 110.0)).margin(2.0));
}

TEST_CASE("bathymetry: what is refused, and the message says why") {
  const std::string asc = "    file: " + kData + "forth_2m.asc\n";
  const std::string xyz = "    file: " + kData + "plane_4m.xyz\n";
  SECTION("a grid that does not cover the seabed's extent") {
    CHECK_THAT(error_of(scene_text(asc, -500.0, 1000.0)),
               Catch::Contains("seabed.bathymetry.file") &&
                   Catch::Contains("does not cover the seabed's extent") &&
                   Catch::Contains("the grid spans"));
  }
  SECTION("a grid without a CRS and no origin_xy_m") {
    CHECK_THAT(error_of(scene_text(xyz)),
               Catch::Contains("seabed.bathymetry.origin_xy_m") && Catch::Contains("no CRS"));
  }
  SECTION("origin_xy_m for a grid with a CRS") {
    CHECK_THAT(error_of(scene_text(asc + "    origin_xy_m: [487494, 6194968]\n")),
               Catch::Contains("seabed.bathymetry.origin_xy_m") && Catch::Contains("has a CRS"));
  }
  SECTION("no file, a folder, a file that is not a grid") {
    CHECK_THAT(error_of(scene_text("    values: depth\n")),
               Catch::Contains("seabed.bathymetry.file") && Catch::Contains("is not set"));
    CHECK_THAT(error_of(scene_text("    file: " + kData + "missing.tif\n")),
               Catch::Contains("no such file"));
    CHECK_THAT(error_of(scene_text("    file: " + kData + "\n")),
               Catch::Contains("not a regular file"));
    CHECK_THAT(error_of(scene_text("    file: " + kData + "make_grids.py\n")),
               Catch::Contains("cannot be read as a grid"));
  }
  SECTION("unknown words") {
    CHECK_THAT(error_of(scene_text(asc + "    values: height\n")),
               Catch::Contains("seabed.bathymetry.values") && Catch::Contains("'height'"));
    CHECK_THAT(error_of(scene_text(asc + "    nodata: ignore\n")),
               Catch::Contains("seabed.bathymetry.nodata") && Catch::Contains("'ignore'"));
  }
}

TEST_CASE("bathymetry: a relative file is found beside the scenario file") {
  testing::TempDir dir("bathymetry");
  std::filesystem::create_directories(dir.path() / "grids");
  std::filesystem::copy_file(kData + "plane_4m.xyz", dir.path() / "grids" / "site.xyz");
  const std::string yaml = (dir.path() / "site.yaml").string();
  std::ofstream(yaml) << scene_text("    file: grids/site.xyz\n    origin_xy_m: [0, 0]\n");
  const auto s = load_scene(yaml);
  REQUIRE(s.seabed.bathymetry);
  CHECK(s.seabed.bathymetry->file == (dir.path() / "grids" / "site.xyz").string());
  CHECK(seabed::relief_at(*s.seabed.bathymetry->grid, 0.0, 0.0) == Approx(0.0).margin(1e-4));
}
