#pragma once
// What `sonarloop train` and `classify` share: the chip size option, the class metadata a model
// stores (mine-like, height), and model loading with the metadata older model files lack.
//
// Class metadata. The classifier (atr/) knows nothing of the simulator; the tools give it:
//   - classes named after a simulator target type (manta, rockan, cylinder, cuboid, ...) take
//     its mine_like flag and nominal height (sim/targets/target_type.h);
//   - --mine-like A,B replaces every class's mine-likeness (only A and B are mine-like);
//   - --height A=0.5,B=0.3 sets heights in metres (over the simulator's);
//   - any other class is not mine-like, of unknown height (onboard then places its contacts
//     with the detector's shadow height).
// Model files older than version 3 store no heights: loading fills those of classes named after
// a simulator target type and leaves the others unknown (their mine_like flag was stored).
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "atr/subspace_classifier.h"
#include "study/chip_folder.h"
#include "tools/args.h"

namespace sonarloop::tools {

// --size WxH (e.g. 64x64; each side 1 to 8192): resample every chip to it. The command must
// declare the option. Throws UsageError for a malformed value.
std::optional<study::ChipSize> chip_size_option(const Args& args);

// The simulator's target types as class metadata, by key.
std::map<std::string, atr::ClassMetadata, std::less<>> sim_class_metadata();

// The metadata of `classes` for training: the simulator's table when the chips are the
// simulator's (`simulated`: a folder `sonarloop dataset` wrote, with its dataset.json; a real
// class named like a simulated type, "cylinder", takes nothing from it), then --mine-like (or its
// older spelling --mine-classes) and --height. Names given in the options must be among
// `classes` (UsageError otherwise, naming them).
std::map<std::string, atr::ClassMetadata, std::less<>> class_metadata_options(
    const Args& args, const std::vector<std::string>& classes, bool simulated);

// For a model read from a file of format version < 3: each class named after a simulator target
// type gets its height. Newer models are left as they are (their heights were decided when
// training).
void fill_legacy_class_heights(atr::Model& m, std::uint16_t file_version);

// atr::load_model, then fill_legacy_class_heights.
atr::Model load_model_with_metadata(const std::string& path);

// Loads a model file (older formats: class heights from the simulator, as above),
// or nullopt when no path is given; "default" is the default model (mission/default_model.h),
// built and cached the first time.
std::optional<atr::Model> load_model_if(const std::optional<std::string>& path);

// --gate-threshold P: the classification gate's operating point (its target probability, 0 to
// 1) instead of the one training chose; a point of the mission report's gate_froc.csv. Throws
// UsageError when `model` has no classification gate (a model of `train --surveys` has one).
void set_gate_threshold(std::optional<atr::Model>& model, std::optional<double> threshold);

}  // namespace sonarloop::tools
