#include "config/loader/scene_loader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "config/loader/bathymetry_loader.h"
#include "sim/seabed/sediment.h"
#include "sim/targets/material.h"
#include "sim/targets/target_type.h"

namespace sonarloop::config {
namespace {

using scene::BathymetryDesc;
using scene::ClutterDesc;
using scene::ElevationDesc;
using scene::GeoOrigin;
using scene::MaterialDesc;
using scene::PartitionDesc;
using scene::RegionDesc;
using scene::RipplesDesc;
using scene::RockyDesc;
using scene::SceneDesc;
using scene::SeabedDesc;
using scene::TargetDesc;
using scene::TextureDesc;
using scene::WaterDesc;

// Tiles are generated lazily, so large areas are fine; beyond 1e12 heightmap cells (a 1000 km²
// area at 3 cm) the input is taken to be a mistake.
constexpr double kMaxGridCells = 1e12;
constexpr std::size_t kMaxRegions = 3;
constexpr std::string_view kNorthEast = "north, east";

// --- name tables -----------------------------------------------------------------------------

const NameTable<seabed::SedimentId>& sediment_names() {
  static const NameTable<seabed::SedimentId> table = [] {
    NameTable<seabed::SedimentId> t;
    t.noun = "sediment";
    std::vector<std::string> aliases;
    for (const auto& s : seabed::sediment_table()) {
      t.names.emplace_back(s.key);
      std::string_view a = s.aliases;
      while (!a.empty()) {
        const auto comma = a.find(',');
        aliases.emplace_back(a.substr(0, comma));
        if (comma == std::string_view::npos) break;
        a.remove_prefix(comma + 1);
      }
    }
    t.allowed = seabed::sediment_keys_list() + " (aliases: " + join_names(aliases) + ")";
    t.names.insert(t.names.end(), aliases.begin(), aliases.end());
    t.find = [](std::string_view n) { return seabed::find_sediment(n); };
    return t;
  }();
  return table;
}

const NameTable<targets::TargetType>& target_type_names() {
  static const NameTable<targets::TargetType> table = [] {
    NameTable<targets::TargetType> t;
    t.noun = "target type";
    for (const auto& info : targets::target_type_table())
      t.names.emplace_back(info.key);
    t.allowed = targets::target_type_keys_list();
    t.find = [](std::string_view n) { return targets::find_target_type(n); };
    return t;
  }();
  return table;
}

const NameTable<targets::NamedMaterial>& material_names() {
  static const NameTable<targets::NamedMaterial> table = [] {
    NameTable<targets::NamedMaterial> t;
    t.noun = "material";
    for (const auto& m : targets::material_table())
      t.names.emplace_back(m.key);
    t.allowed = targets::material_keys_list() +
                ", or a map {density_kg_m3: 500 .. 25000, sound_speed_m_s: 300 .. 15000}";
    t.find = [](std::string_view n) { return targets::find_material(n); };
    return t;
  }();
  return table;
}

seabed::SedimentId default_sediment() {
  return *seabed::find_sediment("medium_sand");
}

std::string vec2_text(const Vec2& v) {
  return "[" + format_number(v.x()) + ", " + format_number(v.y()) + "]";
}

// --- sections --------------------------------------------------------------------------------

GeoOrigin parse_origin(const Field& f) {
  f.expect_map("a map with latitude_deg, longitude_deg");
  GeoOrigin o;
  o.latitude_deg = f.get_double("latitude_deg", o.latitude_deg, Range::closed(-89.0, 89.0));
  o.longitude_deg = f.get_double("longitude_deg", o.longitude_deg, Range::closed(-180.0, 180.0));
  f.finish();
  return o;
}

WaterDesc parse_water(const Field& f) {
  f.expect_map("a map with temperature_c, salinity_ppt, ph, depth_m");
  WaterDesc w;
  w.temperature_c = f.get_double("temperature_c", w.temperature_c, Range::closed(-2.0, 35.0));
  w.salinity_ppt = f.get_double("salinity_ppt", w.salinity_ppt, Range::closed(0.0, 45.0));
  w.ph = f.get_double("ph", w.ph, Range::closed(7.0, 9.0));
  w.depth_m = f.get_double("depth_m", w.depth_m, Range::closed(2.0, 1000.0));
  f.finish();
  return w;
}

ElevationDesc parse_elevation(const Field& f, const SeabedDesc& s) {
  f.expect_map("a map with slope, rms_m, beta, outer_scale_m, inner_scale_m, spacing_m");
  // reference order for "allowed" lists; the scales are read in dependency order below
  f.declare({"slope", "rms_m", "beta", "outer_scale_m", "inner_scale_m", "spacing_m"});
  ElevationDesc e;
  e.slope = f.get_vec2("slope", e.slope, Range::closed(-0.5, 0.5), kNorthEast);
  e.rms_m = f.get_double("rms_m", e.rms_m, Range::closed(0.0, 50.0));
  e.beta = f.get_double("beta", e.beta, Range::closed(0.5, 3.5));
  e.spacing_m = f.get_double(
      "spacing_m", e.spacing_m,
      Range::closed(s.grid_spacing_m, std::min(10.0, s.extent_m.minCoeff()))
          .with_note("at least seabed.grid_spacing_m; at most 10 and the smaller seabed extent"));
  e.inner_scale_m = f.get_double("inner_scale_m", e.inner_scale_m,
                                 Range{e.spacing_m, 10000.0, false, true, {}}.with_note(
                                     "at least elevation.spacing_m, below outer_scale_m"));
  e.outer_scale_m = f.get_double(
      "outer_scale_m", e.outer_scale_m,
      Range{e.inner_scale_m, 10000.0, true, false, {}}.with_note("more than inner_scale_m"));
  f.finish();
  return e;
}

PartitionDesc parse_partition(const Field& f) {
  f.expect_map("a map with border_warp_m, border_beta, border_scale_m, blend_width_m");
  PartitionDesc p;
  p.border_warp_m = f.get_double("border_warp_m", p.border_warp_m, Range::closed(0.0, 1000.0));
  p.border_beta = f.get_double("border_beta", p.border_beta, Range::closed(1.0, 3.5));
  p.border_scale_m = f.get_double("border_scale_m", p.border_scale_m, Range::closed(0.1, 10000.0));
  p.blend_width_m = f.get_double("blend_width_m", p.blend_width_m, Range::closed(0.0, 100.0));
  f.finish();
  return p;
}

RipplesDesc parse_ripples(const Field& f) {
  f.expect_map("a map with wavelength_m, direction_deg, beta1, beta, height_m");
  RipplesDesc r;
  r.wavelength_m = f.get_double("wavelength_m", r.wavelength_m, Range::closed(0.05, 20.0));
  r.direction_deg = f.get_double("direction_deg", r.direction_deg, Range::closed(0.0, 360.0));
  r.beta1 = f.get_double("beta1", r.beta1, Range::closed(0.5, 6.0));
  r.beta = f.get_double("beta", r.beta, Range::closed(0.5, 6.0));
  r.height_m = f.get_double("height_m", r.height_m, Range::closed(0.0, 2.0));
  f.finish();
  return r;
}

RockyDesc parse_rocky(const Field& f) {
  f.expect_map("a map with rms_m, beta, anisotropy, direction_deg, outer_scale_m");
  RockyDesc r;
  r.rms_m = f.get_double("rms_m", r.rms_m, Range::closed(0.0, 5.0));
  r.beta = f.get_double("beta", r.beta, Range::closed(2.0, 5.0));
  r.anisotropy = f.get_double("anisotropy", r.anisotropy, Range::closed(1.0, 20.0));
  r.direction_deg = f.get_double("direction_deg", r.direction_deg, Range::closed(0.0, 360.0));
  r.outer_scale_m = f.get_double("outer_scale_m", r.outer_scale_m, Range::closed(0.1, 100.0));
  f.finish();
  return r;
}

ClutterDesc parse_clutter(const Field& f) {
  f.expect_map(
      "a map with density_per_m2, median_diameter_m, sigma_ln, height_ratio, max_diameter_m");
  ClutterDesc c;
  c.density_per_m2 = f.get_double("density_per_m2", c.density_per_m2, Range::closed(0.0, 10.0));
  c.median_diameter_m =
      f.get_double("median_diameter_m", c.median_diameter_m, Range::closed(0.02, 5.0));
  c.sigma_ln = f.get_double("sigma_ln", c.sigma_ln, Range::closed(0.0, 2.0));
  c.height_ratio = f.get_double("height_ratio", c.height_ratio, Range::closed(0.05, 2.0));
  c.max_diameter_m =
      f.get_double("max_diameter_m", c.max_diameter_m,
                   Range::at_least(c.median_diameter_m).with_note("at least median_diameter_m"));
  f.finish();
  return c;
}

TextureDesc parse_texture(const Field& f) {
  const std::string allowed = "flat, or a map with any of ripples, rocky, clutter";
  if (f.is_null()) return {};
  if (f.is_scalar()) {
    if (f.node().Scalar() == "flat") return {};
    f.fail(f.describe_value() + " is not a texture", allowed,
           closest_name(f.node().Scalar(), {"flat"}).value_or(""));
  }
  f.expect_map(allowed);
  TextureDesc t;
  if (f.has("ripples")) t.ripples = parse_ripples(f.child("ripples"));
  if (f.has("rocky")) t.rocky = parse_rocky(f.child("rocky"));
  if (f.has("clutter")) t.clutter = parse_clutter(f.child("clutter"));
  f.finish();
  return t;
}

RegionDesc parse_region(const Field& f) {
  f.expect_map("a map with sediment, centre_m, texture");
  RegionDesc r;
  r.sediment = f.get_enum("sediment", default_sediment(), sediment_names());
  r.centre_m = f.get_vec2("centre_m", Vec2::Zero(), Range::any(), kNorthEast);
  r.texture = parse_texture(f.child("texture"));
  f.finish();
  return r;
}

std::vector<RegionDesc> parse_regions(const Field& f) {
  const std::string allowed =
      "a list of 1 .. 3 regions, each a map with sediment, centre_m, texture";
  if (!f.present()) {
    RegionDesc r;
    r.sediment = default_sediment();
    return {r};
  }
  f.expect_list(allowed);
  if (f.size() == 0) f.fail("has no regions", allowed);
  if (f.size() > kMaxRegions) {
    f.fail("has " + std::to_string(f.size()) + " regions", allowed);
  }
  std::vector<RegionDesc> regions;
  for (std::size_t i = 0; i < f.size(); ++i) {
    regions.push_back(parse_region(f.item(i)));
    for (std::size_t j = 0; j < i; ++j) {
      if (regions[j].centre_m == regions[i].centre_m) {
        f.item(i)
            .child("centre_m")
            .fail(vec2_text(regions[i].centre_m) + " is also the centre of " + f.path() + "[" +
                      std::to_string(j) + "]",
                  "a centre different from every other region's");
      }
    }
  }
  return regions;
}

// seabed.bathymetry's keys (the file is read later, once the origin and water depth are known)
std::optional<BathymetryDesc> parse_bathymetry(const Field& f) {
  if (f.is_null()) return std::nullopt;
  f.expect_map("a map with file, values, nodata, origin_xy_m");
  f.declare({"file", "values", "nodata", "origin_xy_m"});
  BathymetryDesc b;
  const std::string file = f.get_string("file", "");
  if (file.empty()) {
    f.child("file").fail("is not set",
                         "the path of a GeoTIFF (.tif), ESRI ASCII (.asc) or XYZ (.xyz) grid, "
                         "relative to the scenario file's folder");
  }
  // relative to the scenario file's folder (to the working folder for a scenario with no file)
  std::filesystem::path path(file);
  const std::filesystem::path scenario(f.file());
  std::error_code ec;
  if (path.is_relative() && std::filesystem::is_regular_file(scenario, ec)) {
    path = scenario.parent_path() / path;
  }
  b.file = path.lexically_normal().string();
  // key: one of two words, the first the default; true for the first
  const auto first_of_two = [&f](std::string_view key, const std::string& first,
                                 const std::string& second, const std::string& allowed) {
    const std::string word = f.get_string(key, first);
    if (word != first && word != second) f.child(key).fail("is '" + word + "'", allowed);
    return word == first;
  };
  b.values_are_depths = first_of_two(
      "values", "depth", "elevation",
      "depth (m, positive down) or elevation (m, positive up, negative below the surface)");
  b.fill_nodata = !first_of_two("nodata", "refuse", "fill",
                                "refuse (cells without data in the seabed's extent are an error) "
                                "or fill (from their neighbours)");
  if (f.has("origin_xy_m")) {
    b.origin_xy_m = f.get_vec2("origin_xy_m", Vec2::Zero(), Range::any(), "X (east), Y (north)");
  }
  f.finish();
  return b;
}

SeabedDesc parse_seabed(const Field& f) {
  f.expect_map(
      "a map with origin_m, extent_m, grid_spacing_m, elevation, partition, regions, bathymetry");
  f.declare({"origin_m", "extent_m", "grid_spacing_m", "elevation", "partition", "regions",
             "bathymetry"});
  SeabedDesc s;
  s.origin_m = f.get_vec2("origin_m", s.origin_m, Range::any(), kNorthEast);
  s.extent_m = f.get_vec2("extent_m", s.extent_m, Range::closed(1.0, 100000.0), kNorthEast);
  // the upper bound also keeps the spacing within the extent (which is at least 1 m)
  s.grid_spacing_m = f.get_double("grid_spacing_m", s.grid_spacing_m,
                                  Range::closed(0.005, std::min(1.0, s.extent_m.minCoeff())));
  const double cells = (s.extent_m.x() / s.grid_spacing_m) * (s.extent_m.y() / s.grid_spacing_m);
  if (cells > kMaxGridCells) {
    const Field g = f.child("grid_spacing_m");
    const double min_spacing = std::sqrt(s.extent_m.x() * s.extent_m.y() / kMaxGridCells);
    g.fail((g.present() ? format_number(s.grid_spacing_m)
                        : "is not set, and its default " + format_number(s.grid_spacing_m)) +
               " gives " + format_number(cells) + " grid cells over the " +
               format_number(s.extent_m.x()) + " x " + format_number(s.extent_m.y()) + " m extent",
           ">= " + format_number(std::ceil(min_spacing * 1e6) / 1e6) +
               " for this extent (at most " + format_number(kMaxGridCells) + " grid cells)");
  }
  s.elevation = parse_elevation(f.child("elevation"), s);
  s.partition = parse_partition(f.child("partition"));
  s.regions = parse_regions(f.child("regions"));
  s.bathymetry = parse_bathymetry(f.child("bathymetry"));
  f.finish();
  return s;
}

MaterialDesc parse_material(const Field& f) {
  const auto& names = material_names();
  MaterialDesc m;
  if (f.is_null()) return m;
  if (f.is_scalar()) {
    const auto named = f.as_enum(names);
    m.density_kg_m3 = named.density_kg_m3;
    m.sound_speed_m_s = named.sound_speed_m_s;
    return m;
  }
  f.expect_map(names.allowed);
  m.density_kg_m3 = f.get_double("density_kg_m3", m.density_kg_m3, Range::closed(500.0, 25000.0));
  m.sound_speed_m_s =
      f.get_double("sound_speed_m_s", m.sound_speed_m_s, Range::closed(300.0, 15000.0));
  f.finish();
  return m;
}

TargetDesc parse_target(const Field& f, const SeabedDesc& s) {
  f.expect_map(
      "a map with type, name, position_m, heading_deg, size_m or scale, material, burial_m");
  TargetDesc t;
  t.type = f.get_enum("type", t.type, target_type_names());
  t.name = f.get_string("name", "");
  const Vec2 lo = s.origin_m;
  const Vec2 hi = s.origin_m + s.extent_m;
  const std::string inside = "inside the seabed extent";
  t.position_m = f.get_vec2("position_m", t.position_m,
                            {Range::closed(lo.x(), hi.x()).with_note(inside),
                             Range::closed(lo.y(), hi.y()).with_note(inside)},
                            kNorthEast);
  t.heading_deg = f.get_double("heading_deg", t.heading_deg, Range::closed(0.0, 360.0));
  const Vec3 nominal = targets::target_type_info(t.type).size_m;
  const bool has_size = f.has("size_m");
  if (has_size && f.has("scale")) {
    const Field scale = f.child("scale");
    scale.fail(scale.describe_value() + " is given together with size_m",
               "either size_m or scale, not both");
  }
  if (has_size) {
    t.size_m = f.get_vec3("size_m", nominal, Range::closed(0.05, 20.0), "length, width, height");
  } else {
    t.size_m = nominal * f.get_double("scale", 1.0, Range::closed(0.1, 10.0));
  }
  t.material = parse_material(f.child("material"));
  t.burial_m = f.get_double("burial_m", t.burial_m,
                            Range::closed(0.0, t.size_m.z()).with_note("the target's height"));
  f.finish();
  return t;
}

std::vector<TargetDesc> parse_targets(const Field& f, const SeabedDesc& s) {
  f.expect_list("a list of targets, each a map with type, name, position_m, ...");
  std::vector<TargetDesc> out;
  std::map<targets::TargetType, int> count_of_type;
  std::map<std::string, std::size_t> index_of_name;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const Field item = f.item(i);
    TargetDesc t = parse_target(item, s);
    const int n = ++count_of_type[t.type];
    const bool named = !t.name.empty();
    if (!named) {
      t.name = std::string(targets::target_type_info(t.type).key) + "-" + std::to_string(n);
    }
    // by name, not by comparing with every earlier target: a list of 1e5 took 20 s
    const auto [first, inserted] = index_of_name.emplace(t.name, out.size());
    if (!inserted) {
      item.child("name").fail((named ? "'" + t.name + "'" : "the default name '" + t.name + "'") +
                                  " is already used by " + f.path() + "[" +
                                  std::to_string(first->second) + "]",
                              "a name no other target has");
    }
    out.push_back(std::move(t));
  }
  // position_m has no default: a target silently at the origin is never what was meant
  // (checked after every other key of every target, so those errors come first)
  const Vec2 lo = s.origin_m;
  const Vec2 hi = s.origin_m + s.extent_m;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const Field item = f.item(i);
    if (item.has("position_m")) continue;
    item.child("position_m")
        .fail("is not set: every target needs its position",
              "[north, east] in metres inside the seabed extent ([" + format_number(lo.x()) + ", " +
                  format_number(hi.x()) + "] x [" + format_number(lo.y()) + ", " +
                  format_number(hi.y()) + "])");
  }
  return out;
}

}  // namespace

SceneDesc parse_scene_node(const Field& f, bool check_unknown_keys) {
  f.expect_map("a map with seed, name, origin, water, seabed, targets");
  SceneDesc s;
  s.seed = f.get_uint64("seed", s.seed);
  s.name = f.get_string("name", "");
  if (s.name.empty()) s.name = std::filesystem::path(f.file()).stem().string();
  s.origin = parse_origin(f.child("origin"));
  s.water = parse_water(f.child("water"));
  s.seabed = parse_seabed(f.child("seabed"));
  if (s.seabed.bathymetry) load_bathymetry(f.child("seabed").child("bathymetry"), s);
  s.targets = parse_targets(f.child("targets"), s.seabed);
  if (check_unknown_keys) f.finish();
  return s;
}

SceneDesc parse_scene(const std::string& yaml_text, const std::string& source_name) {
  return with_yaml_errors(source_name,
                          [&] { return parse_scene_node(parse_document(yaml_text, source_name)); });
}

SceneDesc load_scene(const std::string& path) {
  return parse_scene(read_text_file(path), path);
}

}  // namespace sonarloop::config
