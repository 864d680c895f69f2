#pragma once
// `sonarloop sweep` on rank 0: renders each experiment's chips (over the MPI ranks, if any:
// ranks/sweep_ranks.h), trains, scores every test chip (study/sweep.h defines the experiments
// and the scoring) and writes NAME.csv, NAME_confusion.csv and NAME_seabed.csv after every
// resolution. tools/cmd_sweep.cpp is the command line.
#include <filesystem>
#include <functional>
#include <vector>

#include "study/sweep.h"

namespace sonarloop::ranks {

// What every experiment of one run shares.
struct SweepRun {
  study::SweepSettings settings;
  int threads = 1;
  std::filesystem::path out_dir;
  // called with the chips rendered so far, after each chip (may be empty: a progress bar)
  std::function<void(double chips_done)> progress;
  // polled between chips (may be empty: the command's Ctrl-C flag)
  std::function<bool()> stop;
  double chips_done = 0.0;
};

// Runs one experiment (a fusion experiment as such, study::is_fusion), appending each scored
// condition to `results` and printing it (stdout); returns false when stopped (run.stop): the
// files then hold every condition scored so far.
bool run_sweep_experiment(const study::SweepExperiment& e, SweepRun& run,
                          std::vector<study::ConditionResult>& results);

// The chips an experiment renders, for the progress bar.
double sweep_experiment_chips(const study::SweepExperiment& e);

}  // namespace sonarloop::ranks
