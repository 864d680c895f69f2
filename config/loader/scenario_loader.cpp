#include "config/loader/scenario_loader.h"

#include "config/loader/scene_loader.h"
#include "config/loader/sonar_loader.h"
#include "config/loader/vehicle_loader.h"

#include <cstdio>
#include <stdexcept>

#include "sim/render/ping_renderer.h"
#include "sim/scene/memory_estimate.h"

namespace sonarloop::config {
namespace {

// memory_limit_gb: the estimated memory (sim/scene/memory_estimate.h) a scenario may need. 4 GB
// leaves room on an 8 GB machine; default.yaml needs about 0.1 GB.
constexpr double kDefaultMemoryLimitGb = 4.0;
constexpr double kMinMemoryLimitGb = 0.1;
constexpr double kMaxMemoryLimitGb = 10000.0;
constexpr double kBytesPerGb = 1e9;
// render threads the ping buffers are estimated for (run's default --threads)
constexpr int kEstimateWorkers = 2;

std::string gb(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g GB", bytes / kBytesPerGb);
  return text;
}

std::string how_to_raise(double limit_gb) {
  char text[160];
  std::snprintf(text, sizeof text,
                "a smaller scenario, or memory_limit_gb (a top-level key, now %g) raised to at "
                "most %g if the machine has the memory",
                limit_gb, kMaxMemoryLimitGb);
  return text;
}

// Before the targets are read: their count alone, at the cheapest target's cost, must fit (a
// list of 1e5 is refused without building anything for its entries).
void check_target_count(const Field& targets, double limit_gb) {
  if (!targets.present() || !targets.is_list()) return;
  const double least = scene::least_target_bytes(targets.size());
  if (least <= limit_gb * kBytesPerGb) return;
  targets.fail(std::to_string(targets.size()) + " targets need an estimated " + gb(least) +
                   " or more (their meshes and BVH), more than memory_limit_gb " +
                   gb(limit_gb * kBytesPerGb),
               how_to_raise(limit_gb));
}

// The whole estimate, once every section is read; the error names the key of the largest part.
void check_memory(const Field& f, const Scenario& s, double limit_gb) {
  scene::PingFan fan;
  fan.workers = kEstimateWorkers;
  try {
    const render::SonarSetup setup = render::make_sonar_setup(s.sonar, s.scene.water);
    const render::Fidelity fidelity = render::default_fidelity(setup);
    fan.bins_per_side = setup.bins;
    fan.rays_per_bin = fidelity.rays_per_bin;
    fan.along_track_rays = fidelity.along_track_rays;
  } catch (const std::invalid_argument&) {
    // an impossible sonar is reported where the sonar is made, with its own message
  }
  const scene::MemoryEstimate e = scene::estimate_memory(s.scene, fan);
  if (e.total_bytes() <= limit_gb * kBytesPerGb) return;
  const Field key = e.targets_bytes >= std::max(e.tiles_bytes, e.pings_bytes) ? f.child("targets")
                    : e.tiles_bytes >= e.pings_bytes ? f.child("seabed").child("grid_spacing_m")
                                                     : f.child("sonar");
  key.fail("the scenario needs an estimated " + gb(e.total_bytes()) + " (targets " +
               gb(e.targets_bytes) + ", heightmap tiles " + gb(e.tiles_bytes) + ", ping buffers " +
               gb(e.pings_bytes) + " on " + std::to_string(fan.workers) +
               " threads), more than memory_limit_gb " + gb(limit_gb * kBytesPerGb),
           how_to_raise(limit_gb));
}

}  // namespace

Scenario parse_scenario_node(const Field& f) {
  f.expect_map("a map with seed, name, origin, water, seabed, targets, " +
               std::string(kScenarioSections));
  // the keys in reference order (the "allowed" text of an unknown key), although the limit and
  // the length of the target list are read first
  f.declare({"seed", "name", "origin", "water", "seabed", "targets", "sonar", "vehicle",
             "memory_limit_gb"});
  const double limit_gb = f.get_double("memory_limit_gb", kDefaultMemoryLimitGb,
                                       Range::closed(kMinMemoryLimitGb, kMaxMemoryLimitGb));
  check_target_count(f.child("targets"), limit_gb);
  Scenario s;
  s.scene = parse_scene_node(f, /*check_unknown_keys=*/false);
  // one line per section beside the scene keys (keep kScenarioSections in step)
  s.sonar = parse_sonar_node(f.child("sonar"));
  const Field vehicle = f.child("vehicle");
  s.vehicle = parse_vehicle_node(vehicle);
  f.finish();
  // rules between sections
  check_vehicle_over_seabed(vehicle, s.vehicle, s.scene.seabed);
  check_memory(f, s, limit_gb);
  return s;
}

Scenario parse_scenario(const std::string& yaml_text, const std::string& source_name) {
  return with_yaml_errors(
      source_name, [&] { return parse_scenario_node(parse_document(yaml_text, source_name)); });
}

Scenario load_scenario(const std::string& path) {
  return parse_scenario(read_text_file(path), path);
}

}  // namespace sonarloop::config
