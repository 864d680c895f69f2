#pragma once
// `sonarloop mission` in lock-step (its default): every seed flown by mission/lockstep.h in this
// process, scored against the truth (study/survey_score.h); one JSON report for all the seeds
// (mission/mission_report.h) and the tables and per-seed files in --out.
#include <string>

#include "config/loader/scenario_loader.h"
#include "tools/args.h"

namespace sonarloop::tools {

// Runs the missions `args` asks for (--seed, --seeds, --layout, --threads, --rate, ...) with the
// model at `model_path`; 0, or 1 when a stop request cut them short.
int run_lockstep_missions(const Args& args, const std::string& model_path,
                          const config::Scenario& scenario);

}  // namespace sonarloop::tools
