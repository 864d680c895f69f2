#pragma once
// The default model (issue 24): what `sonarloop mission` (and `--model default` anywhere) uses
// when no model is given, so that a new user's first mission needs no other command. It is the
// survey-trained model of `sonarloop train --surveys` (mission/survey_training.h) with the
// documented recipe below, built once on first use and cached:
//
//   training seabeds   the built-in scenarios survey_flat, survey_ripples, survey_clutter,
//                      survey_rocky and mission_20 (config/default_scenario.h), their targets
//                      replaced by random layouts of the seven types of Fig. 13 (8 of each, at
//                      least 15 m apart), 2 surveys each per pass, seeds from 100000 (never a
//                      seed or layout a mission is reported on)
//   classifier         p = 10, 8 aspect sectors, a clutter class of at most 400 false alarms
//                      per survey; each chip cropped to its central 40 % (1.2 m of 3 m) and
//                      read twice, the highlight (levels above_seabed) and the shadow
//                      (below_seabed), the two readings fused (atr/subspace_classifier.h,
//                      "Fused readings")
//   detector           objects from one ping up (TrainingSurveys::detector_rules, recorded in
//                      the model)
//   gates              quadratic logistic gates (atr/contact_gate.h): the detection gate keeps
//                      99 % of the training targets (a target is kept when one of its detections
//                      passes), the classification gate holds each seabed to 0.1 false
//                      detections per target where that keeps 97 % of its targets
//                      (choose_gate_threshold)
//
// Cache: $SONARLOOP_CACHE_DIR, else $XDG_CACHE_HOME/sonarloop, else ~/.cache/sonarloop; the file
// models/default-<key>.slpca, whose key hashes the recipe, the training scenarios' text and this
// build's version, so that a new recipe or scenario builds a new model. Training is deterministic:
// the same key gives the same file. Written to a temporary name and renamed, so an interrupted
// build leaves no half file.
#include <string>

#include "mission/survey_training.h"

namespace sonarloop::mission {

// The recipe's training surveys and options.
TrainingSurveys default_training_surveys();
SurveyModelOptions default_model_options();

// Where the default model is (or will be) cached.
std::string default_model_path();

// The default model's path, built first if it is not cached yet (progress on stderr unless
// quiet; `stop` (may be empty; the commands' Ctrl-C flag) ends the build with an error). Throws
// std::runtime_error when it cannot be built or written.
std::string ensure_default_model(bool quiet, const StopFn& stop);

// `--model` as the commands take it: "default" (or none where a command requires a model) is the
// default model.
bool is_default_model(const std::string& spec);

}  // namespace sonarloop::mission
