#pragma once
// The scenario as plain data (docs/style.md habit 1): what a YAML scenario file says, after
// validation, with every default filled in. config/reference.yaml documents each field.
// Nothing here allocates Embree objects or generates terrain; see scene.h for that.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sim/frames.h"
#include "sim/seabed/relief_grid.h"
#include "sim/seabed/sediment.h"
#include "sim/targets/target_type.h"

namespace sonarloop::scene {

// Geographic anchor of the world frame W (frames.h): lat/long of x = y = 0.
struct GeoOrigin {
  double latitude_deg = 55.9;
  double longitude_deg = -3.2;
};

// Water column properties (Francois–Garrison inputs, docs/physics.md §1).
struct WaterDesc {
  double temperature_c = 10.0;
  double salinity_ppt = 35.0;
  double ph = 8.0;
  double depth_m = 30.0;  // mean seabed depth below the surface
};

// Large-scale relief: a plane plus smoothed pink noise (Pailhas et al. 2010, Sec. 2.1).
// Profiles have PSD ∝ f^-beta between the outer and inner scales (beta is the 1-D exponent: 1 to
// 2 is pink; the 2-D spectrum is (|f|^2 + f0^2)^(-(beta+1)/2) · exp(-(|f|·inner_scale_m)^2),
// f0 = 1/outer_scale_m, see spectra.h); scaled to rms_m.
struct ElevationDesc {
  Vec2 slope = Vec2::Zero();  // rise per metre along north and east (dimensionless)
  double rms_m = 0.2;
  double beta = 1.8;            // 1-D (profile) spectral exponent
  double outer_scale_m = 40.0;  // correlation (outer) scale
  double inner_scale_m = 5.0;   // smoothing scale (textures carry the finer relief)
  double spacing_m = 0.5;       // grid on which the layer is synthesised, then interpolated
};

// Sand ripples, Pailhas et al. (2010) eq. (1): F(fx, fy) = 1/(|fx - fx0|^beta1 · |fy - fy0|^beta)
// in a frame rotated so that x is the ripple propagation direction (normal to the crests).
struct RipplesDesc {
  double wavelength_m = 0.6;
  double direction_deg = 45.0;  // ripple propagation direction, clockwise from north
  double beta1 = 2.0;           // exponent across the crests (sets crest-to-crest regularity)
  double beta = 2.5;            // exponent along the crests (sets crest length)
  double height_m = 0.04;       // rms height
};

// Rocky seabed with anisotropic erosion: NOT Pailhas eq. (2), which is unreadable; the labelled
// stand-in of docs/physics.md §5: F = ((alpha·fx')^2 + fy'^2 + f0^2)^(-beta/2), x' along direction,
// so features are alpha times longer along the erosion direction than across it.
struct RockyDesc {
  double rms_m = 0.08;
  double beta = 3.2;           // exponent of the 2-D spectrum (as docs/physics.md §5 writes it)
  double anisotropy = 3.0;     // alpha: correlation length along x' is alpha times that along y'
  double direction_deg = 0.0;  // erosion direction x', clockwise from north
  double outer_scale_m = 3.0;  // largest feature scale
};

// Clutter: Poisson-distributed rocks with log-normal sizes (docs/physics.md §3).
struct ClutterDesc {
  double density_per_m2 = 0.05;
  double median_diameter_m = 0.25;
  double sigma_ln = 0.5;        // std of ln(diameter)
  double height_ratio = 0.5;    // rock height / diameter
  double max_diameter_m = 1.5;  // larger draws are clipped
};

// One texture layer description per region; any combination (none = flat).
struct TextureDesc {
  std::optional<RipplesDesc> ripples;
  std::optional<RockyDesc> rocky;
  std::optional<ClutterDesc> clutter;
};

// A sediment region: every point belongs to the region whose centre is nearest after the
// fractal border warp (PartitionDesc), so borders are fractal curves.
struct RegionDesc {
  seabed::SedimentId sediment = 0;
  Vec2 centre_m = Vec2::Zero();
  TextureDesc texture;
};

struct PartitionDesc {
  double border_warp_m = 4.0;    // rms displacement of the borders
  double border_beta = 1.8;      // 1-D spectral exponent of the warp (border roughness)
  double border_scale_m = 25.0;  // outer scale of the warp
  double blend_width_m = 0.5;    // textures cross-fade over this width at a border
};

// Large-scale relief from a bathymetry grid file (seabed.bathymetry in a scenario): it replaces
// nothing, it is added to the elevation layer (whose fractal detail then covers the scales the
// grid cannot show), the textures and the clutter. The loader reads the file and places it in W
// (config/loader/bathymetry_loader.h).
struct BathymetryDesc {
  std::string file;                 // the path, as resolved against the scenario's folder
  bool values_are_depths = true;    // depths (m, positive down); false: elevations (positive up)
  bool fill_nodata = false;         // fill cells without data from their neighbours (or refuse)
  std::optional<Vec2> origin_xy_m;  // a grid without a CRS: its (X = east, Y = north) at W's origin
  std::shared_ptr<const seabed::ReliefGrid> grid;  // relative to water.depth_m, positive up
};

struct SeabedDesc {
  Vec2 origin_m = Vec2(-50.0, -50.0);  // south-west corner (north, east) of the extent
  Vec2 extent_m = Vec2(100.0, 100.0);  // size along north and east
  double grid_spacing_m = 0.025;       // heightmap spacing
  std::vector<RegionDesc> regions;     // 1 to 3
  PartitionDesc partition;
  ElevationDesc elevation;
  std::optional<BathymetryDesc> bathymetry;
};

struct MaterialDesc {
  double density_kg_m3 = 7850.0;  // steel by default
  double sound_speed_m_s = 5900.0;
};

struct TargetDesc {
  std::string name;  // unique label, defaults to "<type>-<index>"
  targets::TargetType type = targets::TargetType::kManta;
  Vec2 position_m = Vec2::Zero();  // north, east of the target's centre
  double heading_deg = 0.0;        // long axis, clockwise from north
  Vec3 size_m = Vec3::Zero();      // length, width, height; zero = the type's nominal size
  MaterialDesc material;
  double burial_m = 0.0;  // depth of the target's base below the local seabed
};

struct SceneDesc {
  std::uint64_t seed = 0;
  std::string name;  // scenario name (file stem by default)
  GeoOrigin origin;
  WaterDesc water;
  SeabedDesc seabed;
  std::vector<TargetDesc> targets;
};

}  // namespace sonarloop::scene
