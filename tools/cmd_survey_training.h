#pragma once
// Training on surveys (mission/survey_training.h) from the command line:
//   `sonarloop dataset --surveys SCENARIOS`: the onboard consumer's chips from lock-step surveys
//     of the scenarios' seabeds with random target layouts, as a chip folder `train` reads;
//   `sonarloop train --surveys SCENARIOS`: the whole survey-trained model, PCA classes with a
//     clutter class and both contact gates (atr/contact_gate.h).
#include <string>
#include <vector>

#include "mission/survey_training.h"

namespace sonarloop::tools {

int run_survey_dataset(const std::vector<std::string>& argv);
int run_survey_train(const std::vector<std::string>& argv);

// The training surveys of the common options (--surveys, --surveys-per-scenario, --per-type,
// --classes, --seed, --threads) of both commands.
mission::TrainingSurveys training_surveys_of(const class Args& args);

// Writes chips as DIR/<label>/<index>.png (8-bit: the chips' pixels are whole grey levels) and
// DIR/labels.csv (file,class,aspect_deg,mine_like,source). DIR must be new or empty.
void write_chip_folder(const std::string& dir, const std::vector<atr::LabelledChip>& chips);

}  // namespace sonarloop::tools
