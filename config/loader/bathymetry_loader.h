#pragma once
// seabed.bathymetry: reads a bathymetry grid file with GDAL (GeoTIFF, ESRI ASCII grid .asc with
// its optional .prj, XYZ) and places the part the seabed's extent needs in the world frame W
// (sim/seabed/relief_grid.h). docs/usage.md, "A seabed from your own bathymetry".
//
// Where the grid lies:
// - a grid with a CRS (GeoTIFF, .asc with a .prj): the scenario's origin (latitude, longitude)
//   is transformed into the grid's CRS, and so are points 100 m north and east of it, so the
//   grid's cells are placed in W with their spacing, and turned by the projection's meridian
//   convergence, as the file says;
// - a grid without one (XYZ, .asc alone): origin_xy_m gives the grid's X (east) and Y (north) at
//   W's origin, in metres.
// The grid must cover the seabed's extent (which holds every target and the vehicle's path);
// cells without data inside it are refused, or filled from their neighbours when asked.
#include <memory>

#include "config/loader/yaml_fields.h"
#include "sim/scene/scene_desc.h"

namespace sonarloop::config {

// Reads seabed.bathymetry's file for the scene `s` (origin, water depth and seabed extent
// already parsed) into s.seabed.bathymetry->grid. `f` is the seabed.bathymetry field (for
// messages); every problem throws ConfigError naming it.
void load_bathymetry(const Field& f, scene::SceneDesc& s);

// The largest window of cells read (floats): 64 Mi cells, 256 MB.
inline constexpr double kMaxBathymetryCells = 64.0 * 1024 * 1024;

}  // namespace sonarloop::config
