#include "config/loader/bathymetry_loader.h"

#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "common/geodesy.h"

namespace sonarloop::config {
namespace {

// GDAL's objects, closed on every path out
struct Dataset {
  GDALDatasetH h = nullptr;
  ~Dataset() {
    if (h) GDALClose(h);
  }
};
struct SpatialRef {
  OGRSpatialReferenceH h = nullptr;
  ~SpatialRef() {
    if (h) OSRRelease(h);
  }
};
struct Transform {
  OGRCoordinateTransformationH h = nullptr;
  ~Transform() {
    if (h) OCTDestroyCoordinateTransformation(h);
  }
};

// GDAL's last error message, or `fallback`
std::string gdal_error(const std::string& fallback) {
  const char* m = CPLGetLastErrorMsg();
  return m && *m ? std::string(m) : fallback;
}

// 2 x 2 matrices as columns: W (north, east) -> grid (X, Y) and back
struct Affine2 {
  Vec2 north;                         // grid displacement per metre north
  Vec2 east;                          // per metre east
  Vec2 apply_inverse(Vec2 d) const {  // grid displacement -> W (north, east)
    const double det = north.x() * east.y() - east.x() * north.y();
    return {(east.y() * d.x() - east.x() * d.y()) / det,
            (-north.y() * d.x() + north.x() * d.y()) / det};
  }
};

// Where W's origin and axes lie in the grid's (X, Y) coordinates.
struct Placement {
  Vec2 origin_xy;
  Affine2 axes;
  std::string crs;  // the CRS's name, or "no CRS"
};

Placement place_with_crs(const Field& f, OGRSpatialReferenceH grid_srs, const scene::GeoOrigin& o) {
  SpatialRef wgs84{OSRNewSpatialReference(nullptr)};
  if (OSRImportFromEPSG(wgs84.h, 4326) != OGRERR_NONE) {
    f.fail("GDAL has no WGS84 (EPSG:4326) definition: " + gdal_error("no message"),
           "a GDAL installation with its data files (gdal-data)");
  }
  OSRSetAxisMappingStrategy(wgs84.h, OAMS_TRADITIONAL_GIS_ORDER);  // x = longitude, y = latitude
  SpatialRef target{OSRClone(grid_srs)};
  OSRSetAxisMappingStrategy(target.h, OAMS_TRADITIONAL_GIS_ORDER);  // x = east(ing), y = north
  Transform t{OCTNewCoordinateTransformation(wgs84.h, target.h)};
  const char* name = OSRGetName(grid_srs);
  const std::string crs = name ? name : "an unnamed CRS";
  if (!t.h) {
    f.fail("its CRS (" + crs + ") cannot be reached from WGS84: " + gdal_error("no message"),
           "a grid in a projected or geographic CRS GDAL can transform to");
  }
  // W's origin and points 100 m north and east of it (the tangent plane of common/geodesy.h)
  constexpr double kStep_m = 100.0;
  const LocalTangentPlane plane(GeoPoint{o.latitude_deg, o.longitude_deg});
  std::array<double, 3> x{}, y{}, z{};
  const std::array<Vec2, 3> w = {Vec2(0.0, 0.0), Vec2(kStep_m, 0.0), Vec2(0.0, kStep_m)};
  for (std::size_t k = 0; k < 3; ++k) {
    const GeoPoint g = plane.to_geodetic(w[k].x(), w[k].y());
    x[k] = g.longitude_deg;
    y[k] = g.latitude_deg;
  }
  if (!OCTTransform(t.h, 3, x.data(), y.data(), z.data())) {
    f.fail("the scenario's origin (" + format_number(o.latitude_deg) + ", " +
               format_number(o.longitude_deg) + ") cannot be transformed into its CRS (" + crs +
               "): " + gdal_error("no message"),
           "a grid whose CRS covers the scenario's origin");
  }
  Placement p;
  p.origin_xy = {x[0], y[0]};
  p.axes.north = Vec2(x[1] - x[0], y[1] - y[0]) / kStep_m;
  p.axes.east = Vec2(x[2] - x[0], y[2] - y[0]) / kStep_m;
  p.crs = crs;
  return p;
}

// Fills each cell without data (NaN) with the mean of its neighbours that have data, in passes
// from the edges of the gaps inwards. Returns false when no cell has data.
bool fill_gaps(std::vector<float>& v, int rows, int cols) {
  // the cells still without data; each pass looks at them only, not at the whole grid
  std::vector<std::size_t> gaps;
  for (std::size_t m = 0; m < v.size(); ++m)
    if (std::isnan(v[m])) gaps.push_back(m);
  std::vector<std::pair<std::size_t, float>> filled;
  std::vector<std::size_t> left;
  while (!gaps.empty()) {
    filled.clear();
    left.clear();
    for (const std::size_t m : gaps) {
      const int r = static_cast<int>(m / static_cast<std::size_t>(cols));
      const int c = static_cast<int>(m % static_cast<std::size_t>(cols));
      double sum = 0.0;
      int n = 0;
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          const int rr = r + dr;
          const int cc = c + dc;
          if (rr < 0 || rr >= rows || cc < 0 || cc >= cols) continue;
          const float u = v[static_cast<std::size_t>(rr) * cols + cc];
          if (!std::isnan(u)) {
            sum += u;
            ++n;
          }
        }
      }
      if (n > 0) {
        filled.emplace_back(m, static_cast<float>(sum / n));
      } else {
        left.push_back(m);
      }
    }
    if (filled.empty()) return false;
    // a pass reads the grid as the previous pass left it
    for (const auto& [m, value] : filled)
      v[m] = value;
    gaps.swap(left);
  }
  return true;
}

std::string rect_text(Vec2 lo, Vec2 hi) {
  return "north [" + format_number(lo.x()) + ", " + format_number(hi.x()) + "] x east [" +
         format_number(lo.y()) + ", " + format_number(hi.y()) + "] m";
}

}  // namespace

void load_bathymetry(const Field& f, scene::SceneDesc& s) {
  scene::BathymetryDesc& b = *s.seabed.bathymetry;
  const Field file_field = f.child("file");
  std::error_code ec;
  const auto status = std::filesystem::status(b.file, ec);
  if (!std::filesystem::exists(status))
    file_field.fail("'" + b.file + "': no such file", "a grid file");
  if (!std::filesystem::is_regular_file(status)) {
    file_field.fail("'" + b.file + "' is not a regular file", "a GeoTIFF, .asc or .xyz grid file");
  }
  static std::once_flag registered;
  std::call_once(registered, [] { GDALAllRegister(); });
  CPLPushErrorHandler(CPLQuietErrorHandler);
  struct PopHandler {
    ~PopHandler() { CPLPopErrorHandler(); }
  } pop;
  CPLErrorReset();
  const char* const drivers[] = {"GTiff", "AAIGrid", "XYZ", nullptr};
  Dataset ds{
      GDALOpenEx(b.file.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, drivers, nullptr, nullptr)};
  if (!ds.h) {
    file_field.fail("'" + b.file + "' cannot be read as a grid: " + gdal_error("unknown format"),
                    "a GeoTIFF (.tif), an ESRI ASCII grid (.asc) or an XYZ grid (.xyz)");
  }
  const int cols = GDALGetRasterXSize(ds.h);
  const int rows = GDALGetRasterYSize(ds.h);
  if (GDALGetRasterCount(ds.h) < 1 || rows < 2 || cols < 2) {
    file_field.fail("'" + b.file + "' has no grid of at least 2 x 2 cells", "a bathymetry grid");
  }
  std::array<double, 6> gt{};
  if (GDALGetGeoTransform(ds.h, gt.data()) != CE_None) {
    file_field.fail("'" + b.file + "' says nothing of its cells' positions and size",
                    "a grid with a geotransform (a GeoTIFF's georeferencing, an .asc header)");
  }
  // where W lies in the grid's coordinates
  Placement place;
  OGRSpatialReferenceH srs = GDALGetSpatialRef(ds.h);
  if (srs) {
    if (b.origin_xy_m) {
      f.child("origin_xy_m")
          .fail("is set, but '" + b.file + "' has a CRS (" +
                    std::string(OSRGetName(srs) ? OSRGetName(srs) : "unnamed") +
                    "): the grid is placed from the scenario's origin (latitude, longitude)",
                "absent for a grid with a CRS");
    }
    place = place_with_crs(f, srs, s.origin);
  } else {
    if (!b.origin_xy_m) {
      f.child("origin_xy_m")
          .fail("is not set, and '" + b.file + "' has no CRS to place it by",
                "[X, Y]: the grid's easting and northing (m) at the scenario's origin, or a grid "
                "with a CRS (a GeoTIFF, an .asc with its .prj)");
    }
    place.origin_xy = *b.origin_xy_m;
    place.axes.north = Vec2(0.0, 1.0);  // Y is north
    place.axes.east = Vec2(1.0, 0.0);   // X is east
    place.crs = "no CRS, X east and Y north in metres";
  }
  // cell (row, col) centre -> W, and W -> cell
  const auto xy_of_cell = [&](double row, double col) {
    return Vec2(gt[0] + (col + 0.5) * gt[1] + (row + 0.5) * gt[2],
                gt[3] + (col + 0.5) * gt[4] + (row + 0.5) * gt[5]);
  };
  const auto w_of_cell = [&](double row, double col) {
    return place.axes.apply_inverse(xy_of_cell(row, col) - place.origin_xy);
  };
  const Vec2 row_step = w_of_cell(1, 0) - w_of_cell(0, 0);
  const Vec2 col_step = w_of_cell(0, 1) - w_of_cell(0, 0);
  const Vec2 origin = w_of_cell(0, 0);
  seabed::ReliefGrid whole;
  whole.rows = rows;
  whole.cols = cols;
  whole.origin_m = origin;
  whole.row_step_m = row_step;
  whole.col_step_m = col_step;
  if (!(std::abs(row_step.x() * col_step.y() - col_step.x() * row_step.y()) > 0.0)) {
    file_field.fail("'" + b.file + "' has cells of no area in the scenario's frame",
                    "a grid with a valid geotransform");
  }
  // the cells the seabed's extent reaches (corners; the map is affine), with the 2 cells the
  // interpolation reads beyond them
  const Vec2 lo = s.seabed.origin_m;
  const Vec2 hi = s.seabed.origin_m + s.seabed.extent_m;
  double r_lo = 1e300, r_hi = -1e300, c_lo = 1e300, c_hi = -1e300;
  for (const Vec2& p : {lo, Vec2(lo.x(), hi.y()), Vec2(hi.x(), lo.y()), hi}) {
    const Vec2 cell = seabed::relief_cell_of(whole, p.x(), p.y());
    r_lo = std::min(r_lo, cell.x());
    r_hi = std::max(r_hi, cell.x());
    c_lo = std::min(c_lo, cell.y());
    c_hi = std::max(c_hi, cell.y());
  }
  if (r_lo < -0.5 || c_lo < -0.5 || r_hi > rows - 0.5 || c_hi > cols - 0.5) {
    Vec2 g_lo(1e300, 1e300), g_hi(-1e300, -1e300);
    for (const auto& [r, c] : std::array<std::pair<double, double>, 4>{
             {{-0.5, -0.5}, {-0.5, cols - 0.5}, {rows - 0.5, -0.5}, {rows - 0.5, cols - 0.5}}}) {
      const Vec2 p = w_of_cell(r, c);
      g_lo = g_lo.cwiseMin(p);
      g_hi = g_hi.cwiseMax(p);
    }
    file_field.fail("'" + b.file + "' (" + std::to_string(cols) + " x " + std::to_string(rows) +
                        " cells, " + place.crs + ") does not cover the seabed's extent " +
                        rect_text(lo, hi) + " from the scenario's origin: the grid spans " +
                        rect_text(g_lo, g_hi),
                    "a grid that covers seabed.origin_m to origin_m + extent_m (which hold the "
                    "vehicle's path and the targets): a smaller extent, or another origin");
  }
  const int r0 = std::max(0, static_cast<int>(std::floor(r_lo)) - 2);
  const int r1 = std::min(rows, static_cast<int>(std::ceil(r_hi)) + 3);
  const int c0 = std::max(0, static_cast<int>(std::floor(c_lo)) - 2);
  const int c1 = std::min(cols, static_cast<int>(std::ceil(c_hi)) + 3);
  const double cells = static_cast<double>(r1 - r0) * static_cast<double>(c1 - c0);
  if (cells > kMaxBathymetryCells) {
    file_field.fail(
        "the seabed's extent covers " + format_number(cells) + " cells of '" + b.file + "'",
        "at most " + format_number(kMaxBathymetryCells) +
            " cells: a coarser grid or a smaller seabed.extent_m");
  }
  // read the window
  auto grid = std::make_shared<seabed::ReliefGrid>();
  grid->rows = r1 - r0;
  grid->cols = c1 - c0;
  grid->origin_m = w_of_cell(r0, c0);
  grid->row_step_m = row_step;
  grid->col_step_m = col_step;
  grid->source = b.file + " (" + place.crs + ")";
  auto& v = grid->elevation_m;
  v.assign(static_cast<std::size_t>(grid->rows) * static_cast<std::size_t>(grid->cols), 0.0f);
  GDALRasterBandH band = GDALGetRasterBand(ds.h, 1);
  if (GDALRasterIO(band, GF_Read, c0, r0, grid->cols, grid->rows, v.data(), grid->cols, grid->rows,
                   GDT_Float32, 0, 0) != CE_None) {
    file_field.fail("'" + b.file + "' could not be read: " + gdal_error("read error"),
                    "a readable grid file");
  }
  int has_nodata = 0;
  const double nodata = GDALGetRasterNoDataValue(band, &has_nodata);
  std::size_t gaps = 0;
  std::size_t first_gap = 0;
  for (std::size_t m = 0; m < v.size(); ++m) {
    const bool gap = !std::isfinite(v[m]) ||
                     (has_nodata &&
                      static_cast<double>(v[m]) == static_cast<double>(static_cast<float>(nodata)));
    if (gap) {
      if (gaps++ == 0) first_gap = m;
      v[m] = std::numeric_limits<float>::quiet_NaN();
    }
  }
  if (gaps > 0) {
    const auto gr = static_cast<int>(first_gap / static_cast<std::size_t>(grid->cols));
    const auto gc = static_cast<int>(first_gap % static_cast<std::size_t>(grid->cols));
    const Vec2 at = w_of_cell(r0 + gr, c0 + gc);
    if (!b.fill_nodata) {
      f.child("nodata").fail(
          "is refuse, and '" + b.file + "' has " + std::to_string(gaps) +
              " cells without data where the seabed's extent reaches, the first at north " +
              format_number(std::round(at.x() * 10) / 10) + ", east " +
              format_number(std::round(at.y() * 10) / 10) + " m (row " + std::to_string(r0 + gr) +
              ", column " + std::to_string(c0 + gc) + ")",
          "fill (each gap takes the mean of its neighbours, from its edges inwards), or a "
          "seabed.extent_m inside the surveyed cells");
    }
    if (!fill_gaps(v, grid->rows, grid->cols)) {
      file_field.fail("'" + b.file + "' has no data where the seabed's extent reaches",
                      "a grid with data over seabed.origin_m to origin_m + extent_m");
    }
  }
  // elevations relative to the scenario's mean depth, positive up; the seabed must be under water
  const double depth = s.water.depth_m;
  for (std::size_t m = 0; m < v.size(); ++m) {
    const double value = v[m];
    const double elevation = b.values_are_depths ? depth - value : value + depth;
    if (!(elevation < depth)) {
      const auto gr = static_cast<int>(m / static_cast<std::size_t>(grid->cols));
      const auto gc = static_cast<int>(m % static_cast<std::size_t>(grid->cols));
      f.child("values").fail(
          std::string("is ") + (b.values_are_depths ? "depth" : "elevation") + ", and cell (row " +
              std::to_string(r0 + gr) + ", column " + std::to_string(c0 + gc) + ") of '" + b.file +
              "' holds " + format_number(value) + ": the seabed there is not under water",
          "depths (positive down) or elevations (negative below the surface) of a seabed; "
          "'values: elevation' for a grid of elevations");
    }
    v[m] = static_cast<float>(elevation);
  }
  b.grid = std::move(grid);
}

}  // namespace sonarloop::config
