// sonarloop scene: generate a scenario's seabed and targets and write them out for inspection.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "drivers/image/npy.h"
#include "drivers/image/png.h"
#include "drivers/json/json_writer.h"
#include "products/scene_images.h"
#include "sim/scene/scene.h"
#include "sim/seabed/sediment.h"
#include "sim/targets/target_type.h"
#include "tools/args.h"
#include "tools/commands.h"
#include "tools/progress.h"
#include "tools/scenario_source.h"

namespace sonarloop::tools {
namespace {

constexpr int kMaxOutputSide = 8192;

struct Lattice {
  std::int64_t i0 = 0;  // first lattice row (north index) of the output
  std::int64_t j0 = 0;
  int rows = 0;
  int cols = 0;
  int step = 1;  // output sample every `step` lattice points
};

scene::Box2 parse_region(const std::string& text) {
  double n0 = 0, e0 = 0, n1 = 0, e1 = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf:%lf,%lf%c", &n0, &e0, &n1, &e1, &tail) != 4 || n1 <= n0 ||
      e1 <= e0) {
    throw UsageError("--region: '" + text +
                     "' is not NORTH0,EAST0:NORTH1,EAST1 with NORTH1 > NORTH0 and EAST1 > EAST0");
  }
  return scene::Box2{Vec2(n0, e0), Vec2(n1, e1)};
}

void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p);
  out << text << '\n';
  if (!out) throw std::runtime_error("cannot write '" + p.string() + "'");
}

std::string truth_json(const scene::Scene& s) {
  json::Writer w(true);
  w.begin_object().field("scenario", s.desc().name).field("seed", s.desc().seed);
  w.field("water_depth_m", s.desc().water.depth_m);
  w.key("frame").value("NED: position_m is [north, east] in metres from the scenario origin");
  w.key("targets").begin_array();
  for (const auto& t : s.targets()) {
    const auto& info = targets::target_type_info(t.desc.type);
    w.begin_object().field("name", t.desc.name).field("type", std::string(info.key));
    w.field("mine_like", info.mine_like);
    w.key("position_m")
        .begin_array()
        .value(t.desc.position_m.x())
        .value(t.desc.position_m.y())
        .end_array();
    w.field("heading_deg", t.desc.heading_deg);
    w.key("size_m").begin_array();
    for (int k = 0; k < 3; ++k)
      w.value(t.desc.size_m[k]);
    w.end_array();
    w.key("material")
        .begin_object()
        .field("density_kg_m3", t.desc.material.density_kg_m3)
        .field("sound_speed_m_s", t.desc.material.sound_speed_m_s)
        .field("impedance_rayl", t.impedance_rayl)
        .end_object();
    w.field("burial_m", t.desc.burial_m);
    w.field("base_depth_m", t.bounds_W.max().z());
    w.field("top_depth_m", t.bounds_W.min().z());
    w.end_object();
  }
  w.end_array().end_object();
  return w.str();
}

// The output region (--region, clipped to the seabed's extent) and the lattice that samples it:
// every `step` model grid points, raised until neither side exceeds kMaxOutputSide.
Lattice output_lattice(const Args& args, const seabed::SeabedModel& sb, scene::Box2& region) {
  const double d = sb.spacing_m();
  if (const auto r = args.get("--region")) region = parse_region(*r);
  region.min = region.min.cwiseMax(sb.extent_min());
  region.max = region.max.cwiseMin(sb.extent_max());
  if (!(region.max.x() > region.min.x() && region.max.y() > region.min.y())) {
    throw UsageError("--region does not overlap the seabed extent");
  }
  Lattice lat;
  lat.i0 = static_cast<std::int64_t>(std::ceil(region.min.x() / d - 1e-9));
  lat.j0 = static_cast<std::int64_t>(std::ceil(region.min.y() / d - 1e-9));
  const auto i1 = static_cast<std::int64_t>(std::floor(region.max.x() / d + 1e-9));
  const auto j1 = static_cast<std::int64_t>(std::floor(region.max.y() / d + 1e-9));
  const double out_spacing = args.get_double("--spacing", d, 1e4).value_or(d);
  lat.step = std::max(1, static_cast<int>(std::llround(out_spacing / d)));
  while ((i1 - lat.i0) / lat.step + 1 > kMaxOutputSide ||
         (j1 - lat.j0) / lat.step + 1 > kMaxOutputSide) {
    ++lat.step;
  }
  if (lat.step * d > out_spacing * 1.0001 && args.has("--spacing")) {
    std::fprintf(stderr, "note: output spacing raised to %.4g m to keep images within %d px\n",
                 lat.step * d, kMaxOutputSide);
  }
  lat.rows = static_cast<int>((i1 - lat.i0) / lat.step + 1);
  lat.cols = static_cast<int>((j1 - lat.j0) / lat.step + 1);
  return lat;
}

// The seabed's elevation and sediment at the lattice points, north row by row.
products::SceneImages sample_lattice(const seabed::SeabedModel& sb, const Lattice& lat) {
  const double d = sb.spacing_m();
  products::SceneImages img;
  img.rows = lat.rows;
  img.cols = lat.cols;
  img.spacing_m = lat.step * d;
  img.origin_m = Vec2(static_cast<double>(lat.i0) * d, static_cast<double>(lat.j0) * d);
  const auto n = static_cast<std::size_t>(lat.rows) * static_cast<std::size_t>(lat.cols);
  img.elevation_m.resize(n);
  img.sediment.resize(n);
  {
    std::vector<float> row_h(static_cast<std::size_t>((lat.cols - 1) * lat.step + 1));
    std::vector<std::uint8_t> row_s(row_h.size());
    for (int r = 0; r < lat.rows; ++r) {
      sb.copy_region(lat.i0 + static_cast<std::int64_t>(r) * lat.step, lat.j0, 1,
                     static_cast<int>(row_h.size()), row_h.data(), row_s.data());
      for (int c = 0; c < lat.cols; ++c) {
        const std::size_t m = static_cast<std::size_t>(r) * lat.cols + c;
        img.elevation_m[m] = row_h[static_cast<std::size_t>(c) * lat.step];
        img.sediment[m] = row_s[static_cast<std::size_t>(c) * lat.step];
      }
    }
  }
  return img;
}

// What building the scene cost, for scene.json.
struct BuildCost {
  std::chrono::steady_clock::time_point t_start;  // of the command
  int threads = 1;
  double setup_s = 0.0, generate_s = 0.0, view_s = 0.0;
  std::size_t tiles = 0;
  double view_buffer_bytes = 0.0;  // the Embree view's (0 with --no-view)
  double build_peak_mib = 0.0;
};

// scene.json: how to read the files, and what it cost.
std::string scene_json(const scene::SceneDesc& desc, const products::SceneImages& img,
                       const Lattice& lat, double d, std::pair<double, double> range,
                       const BuildCost& cost) {
  json::Writer w(true);
  w.begin_object().field("scenario", desc.name).field("seed", desc.seed);
  w.field("water_depth_m", desc.water.depth_m);
  w.field("grid_spacing_m", img.spacing_m, 12);
  w.field("model_grid_spacing_m", d, 12);
  w.field("frame",
          "positions are [north, east] in metres from the scenario origin (latitude/longitude "
          "in origin): the frame of truth.json and of the onboard consumer's contacts");
  w.key("origin")
      .begin_object()
      .field("latitude_deg", desc.origin.latitude_deg, 9)
      .field("longitude_deg", desc.origin.longitude_deg, 9)
      .end_object();
  if (desc.seabed.bathymetry && desc.seabed.bathymetry->grid) {
    const auto& g = *desc.seabed.bathymetry->grid;
    w.key("bathymetry")
        .begin_object()
        .field("source", g.source)
        .field("cells_read", g.rows * g.cols)
        .field("cell_along_rows_m", g.row_step_m.norm(), 6)
        .field("cell_along_columns_m", g.col_step_m.norm(), 6)
        .end_object();
  }
  w.key("origin_m")
      .begin_array()
      .value(img.origin_m.x(), 12)
      .value(img.origin_m.y(), 12)
      .end_array();
  w.field("rows", lat.rows).field("cols", lat.cols);
  w.field("heightmap_npy",
          "float32 elevation in metres, positive up from the mean seabed (depth = water_depth_m - "
          "elevation); element [r][c] is at north = origin_m[0] + r*grid_spacing_m, east = "
          "origin_m[1] + c*grid_spacing_m (row 0 is the southern edge)");
  w.key("heightmap_png")
      .begin_object()
      .field("encoding", "16-bit grey: elevation = min_m + value/65535*(max_m - min_m); north up")
      .field("min_m", range.first, 8)
      .field("max_m", range.second, 8)
      .end_object();
  w.key("sediments").begin_array();
  for (const auto id : products::sediments_present(img)) {
    const auto c = products::sediment_colour(id);
    w.begin_object().field("id", id).field("name", std::string(seabed::sediment_table()[id].key));
    w.key("colour_rgb").begin_array().value(c[0]).value(c[1]).value(c[2]).end_array();
    w.end_object();
  }
  w.end_array();
  w.key("build")
      .begin_object()
      .field("threads", cost.threads)
      .field("scene_setup_s", cost.setup_s, 4)
      .field("heightmap_tiles", static_cast<std::uint64_t>(cost.tiles))
      .field("generate_s", cost.generate_s, 4)
      .field("embree_view_s", cost.view_s, 4)
      .field("embree_buffers_mib", cost.view_buffer_bytes / 1048576.0, 4)
      .field("peak_rss_after_build_mib", cost.build_peak_mib, 5)
      .field("total_s", seconds_since(cost.t_start), 4)
      .field("peak_rss_mib", peak_rss_mib(), 5)
      .end_object();
  w.end_object();
  return w.str();
}

int run_scene(const std::vector<std::string>& argv) {
  const Args args(argv,
                  {{"--out"}, {"--region"}, {"--spacing"}, {"--threads"}, {"--no-view", false}});
  if (args.positionals().size() > 1) throw UsageError("expected at most one SCENARIO.yaml");
  const auto out_dir = args.get("--out");
  if (!out_dir) throw UsageError("--out DIR is required");
  const int threads =
      static_cast<int>(args.get_int("--threads", 1, 256)
                           .value_or(std::max(1u, std::thread::hardware_concurrency())));
  const auto t_start = std::chrono::steady_clock::now();

  const scene::SceneDesc desc = load_scene_or_default(
      args.positionals().empty() ? std::nullopt : std::optional(args.positionals()[0]));
  const auto t_setup = std::chrono::steady_clock::now();
  const scene::Scene sc(desc);
  const double setup_s = seconds_since(t_setup);
  const auto& sb = sc.seabed();
  const double d = sb.spacing_m();

  // the output region (clipped to the extent) and its lattice
  scene::Box2 region{sb.extent_min(), sb.extent_max()};
  const Lattice lat = output_lattice(args, sb, region);

  // generate the heightmap tiles
  const auto t_gen = std::chrono::steady_clock::now();
  {
    Progress bar("generating seabed", 1.0);
    sb.prepare(region.min.x(), region.min.y(), region.max.x(), region.max.y(), threads,
               [&](double f) { bar.update(f); });
  }
  const double gen_s = seconds_since(t_gen);
  const std::size_t tiles = sb.cached_tile_count();

  // build the Embree view (the scene a ping would be rendered from)
  double view_s = 0.0;
  std::shared_ptr<const scene::SceneView> view;
  if (!args.has("--no-view")) {
    const auto t_view = std::chrono::steady_clock::now();
    view = sc.view(region, threads);
    view_s = seconds_since(t_view);
  }
  const double build_peak_mib = peak_rss_mib();

  // sample the output lattice
  products::SceneImages img = sample_lattice(sb, lat);
  products::draw_targets(sc, view.get(), img);

  namespace fs = std::filesystem;
  const fs::path dir(*out_dir);
  fs::create_directories(dir);
  image::write_npy_f32((dir / "heightmap.npy").string(), static_cast<std::size_t>(lat.rows),
                       static_cast<std::size_t>(lat.cols), img.elevation_m);
  const auto range = products::write_heightmap_png((dir / "heightmap.png").string(), img);
  products::write_sediments_png((dir / "sediments.png").string(), img);
  products::write_relief_png((dir / "relief.png").string(), img);
  write_text(dir / "truth.json", truth_json(sc));

  BuildCost cost;
  cost.t_start = t_start;
  cost.threads = threads;
  cost.setup_s = setup_s;
  cost.generate_s = gen_s;
  cost.view_s = view_s;
  cost.tiles = tiles;
  cost.view_buffer_bytes = view ? static_cast<double>(view->buffer_bytes()) : 0.0;
  cost.build_peak_mib = build_peak_mib;
  write_text(dir / "scene.json", scene_json(desc, img, lat, d, range, cost));
  std::printf(
      "scene '%s': %d x %d points at %.4g m; setup %.2f s, %zu tiles generated in %.2f s, Embree "
      "view in %.2f s (peak %.0f MiB); wrote %s (peak %.0f MiB)\n",
      desc.name.c_str(), lat.rows, lat.cols, img.spacing_m, setup_s, tiles, gen_s, view_s,
      build_peak_mib, dir.string().c_str(), peak_rss_mib());
  return 0;
}

}  // namespace

const Command kSceneCommand{
    "scene",
    "generate a scenario's seabed and targets; write heightmap, sediment and relief images",
    R"(usage: sonarloop scene [SCENARIO.yaml] --out DIR [options]

Generates the scenario's synthetic seabed (partition, elevation and texture layers) and places
its targets, builds the Embree scene a ping would be rendered from, and writes:
  heightmap.npy   float32 elevation (m, positive up), row 0 = south; see scene.json
  heightmap.png   the same as 16-bit grey, north up (range in scene.json)
  sediments.png   sediment map, one colour per sediment (legend in scene.json)
  relief.png      shaded relief tinted by sediment, targets in red, for people
  truth.json      every target: type, position, heading, size, material, burial, depths
  scene.json      grid spacing and origin, file encodings, build time and peak memory
Without SCENARIO.yaml the embedded default scenario (config/default.yaml) is used.

options:
  --out DIR            output folder (created if needed)
  --region N0,E0:N1,E1 only this rectangle, metres north/east (default: the whole extent)
  --spacing M          output sample spacing in metres (default: the scenario's grid spacing;
                       raised automatically to keep images within 8192 px a side)
  --threads N          threads for tile generation and the BVH build (default: all cores)
  --no-view            skip building the Embree scene (outputs are the same, faster)

examples:
  sonarloop scene config/default.yaml --out out/scene
  sonarloop scene config/seabed_rocky.yaml --out out/rocky --region -10,-10:10,10
  sonarloop scene --out out/default-coarse --spacing 0.1
)",
    run_scene, 20};
SONARLOOP_REGISTER_COMMAND(kSceneCommand);

}  // namespace sonarloop::tools
