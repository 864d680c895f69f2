// The resolution study's run (ranks/sweep_run.h) in a world of one: a small fig15 experiment
// with two looks renders every chip set of study::group_chip_sets, scores each condition and
// writes its files; the progress callback counts every chip; a stop request ends it early. The
// same run over two real ranks is tests/tools/mpi_cli_test.cpp.
#include "ranks/sweep_run.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <vector>

#include "tests/sim/render/strip_sonar.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop;

namespace {

ranks::SweepRun small_run(const std::filesystem::path& out) {
  ranks::SweepRun run;
  run.settings.seabeds = {render::builtin_dataset_seabed("flat")};
  run.settings.sonar = testing::pailhas_strip_sonar();
  run.settings.resolutions_cm = {20};
  run.settings.train_count = 4;
  run.settings.test_count = 2;
  run.settings.p = 2;
  run.settings.looks = 2;
  run.threads = 2;
  run.out_dir = out;
  return run;
}

}  // namespace

TEST_CASE("sweep run: every chip set rendered and scored, the files written, progress counted") {
  const testing::TempDir dir("sweep_run");
  ranks::SweepRun run = small_run(dir.path());
  const study::SweepExperiment e = study::make_sweep_experiment("fig15", run.settings);
  double last = 0.0;
  int calls = 0;
  run.progress = [&](double done) {
    CHECK(done > last);
    last = done;
    ++calls;
  };
  std::vector<study::ConditionResult> results;
  REQUIRE(ranks::run_sweep_experiment(e, run, results));
  // training chips, then both looks of the test chips: every chip of every set, once
  const double total = ranks::sweep_experiment_chips(e);
  CHECK(total == (4 + 2 * 2) * static_cast<double>(e.classes.size()));
  CHECK(run.chips_done == total);
  CHECK(last == total);
  CHECK(calls == static_cast<int>(total));
  // one result per condition (one look and two fused), complete
  REQUIRE(results.size() == e.conditions.size());
  for (const study::ConditionResult& r : results) {
    CHECK(r.complete);
    CHECK(r.confusion.total() + r.rejected == 2 * e.classes.size());
  }
  CHECK(std::filesystem::file_size(dir.path() / "fig15.csv") > 0);
  CHECK(std::filesystem::file_size(dir.path() / "fig15_confusion.csv") > 0);
}

TEST_CASE("sweep run: a stop request ends the experiment early") {
  const testing::TempDir dir("sweep_run_stop");
  ranks::SweepRun run = small_run(dir.path());
  run.stop = [] { return true; };
  const study::SweepExperiment e = study::make_sweep_experiment("fig15", run.settings);
  std::vector<study::ConditionResult> results;
  CHECK_FALSE(ranks::run_sweep_experiment(e, run, results));
  CHECK(run.chips_done < ranks::sweep_experiment_chips(e));
}
