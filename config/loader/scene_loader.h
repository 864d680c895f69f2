#pragma once
// Loads a scenario's scene part (seed, name, origin, water, seabed, targets) from YAML into
// scene::SceneDesc, with every default of config/reference.yaml filled in and every range and
// cross-field rule checked. Every problem throws ConfigError (config/loader/yaml_fields.h) whose
// message names the file, the key path, the bad value and what is allowed.
//
// Rules beyond the per-key ranges of reference.yaml:
// - seabed: grid cells (extent_m / grid_spacing_m)^2 at most 1e12; no spacing (grid_spacing_m or
//   elevation.spacing_m) larger than the smaller extent; elevation.spacing_m >= grid_spacing_m;
//   inner_scale_m >= elevation.spacing_m; inner_scale_m < outer_scale_m <= 10000.
// - regions: 1 to 3 (absent = one flat medium_sand region at [0, 0]); centres distinct; texture
//   is the word "flat" or a map of ripples/rocky/clutter; max_diameter_m >= median_diameter_m.
// - targets: position_m inside the seabed extent (edges included); size_m and scale exclusive;
//   size_m absent = the type's nominal size times scale (stored explicitly in TargetDesc::size_m);
//   burial_m <= the target's height; names unique, default "<type>-<n>" where n is the target's
//   ordinal among the targets of its type (from 1), so an explicit name can collide with a default.
// - name: empty or absent = the stem of the source name ("scenario.yaml" -> "scenario").
#include <string>

#include "config/loader/yaml_fields.h"
#include "sim/scene/scene_desc.h"

namespace sonarloop::config {

// Reads and parses a scenario file. A missing file -> ConfigError "<path>: (file): no such file".
scene::SceneDesc load_scene(const std::string& path);

// Parses scenario text; `source_name` is used in messages and for the default name.
scene::SceneDesc parse_scene(const std::string& yaml_text, const std::string& source_name);

// Parses the scene keys of the map `f` (which may be a sub-map of a larger document). With
// `check_unknown_keys` false the caller reports unknown keys itself by calling f.finish() after
// reading its own keys (the record of known keys is shared by copies of a Field).
scene::SceneDesc parse_scene_node(const Field& f, bool check_unknown_keys = true);

}  // namespace sonarloop::config
