// `sonarloop train --surveys` and `sonarloop dataset --surveys` as a user runs them, on a small
// cluttered scenario: the chips are the targets and the detector's false alarms, the model has a
// clutter class and both contact gates, and `mission` with it reports the gate's probability on
// its contacts and writes the gate's FROC; --gate-threshold moves its operating point.
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "atr/model_file.h"
#include "autonomy/json_line.h"
#include "tests/support/temp_dir.h"
#include "tests/tools/sonarloop_cli.h"

using namespace sonarloop;
using sonarloop::testing::run_logged;
using sonarloop::testing::slurp;

namespace {

const std::string kSmallSurvey =
    std::string(SONARLOOP_SOURCE_DIR) + "/tests/data/mission/small_survey.yaml";
// two 50 m lines, six targets a survey, the same seabed in both passes
const std::string kSurveyOptions = " --surveys " + kSmallSurvey +
                                   " --surveys-per-scenario 1 --per-type 2 --classes "
                                   "manta,cylinder,box --area-margin 35 --min-separation 8";

}  // namespace

TEST_CASE("dataset --surveys: target chips and clutter chips in a chip folder") {
  testing::TempDir dir("survey_dataset");
  REQUIRE(run_logged(dir, "dataset --out " + dir.file("chips") + kSurveyOptions, "dataset") == 0);
  INFO(slurp(dir.file("dataset.err")));
  const std::string labels = slurp(dir.file("chips/labels.csv"));
  CHECK(labels.rfind("file,class,aspect_deg,mine_like,source\n", 0) == 0);
  CHECK(labels.find("clutter/000000.png,clutter,") != std::string::npos);
  CHECK(std::filesystem::exists(dir.file("chips/clutter/000000.png")));
  // at least one of the two targets was found and cut
  CHECK((labels.find(",manta,") != std::string::npos ||
         labels.find(",cylinder,") != std::string::npos));
  // the folder trains like any other
  REQUIRE(run_logged(dir, "train " + dir.file("chips") + " --out " + dir.file("m.slpca"),
                     "train") == 0);
  CHECK(slurp(dir.file("train.out")).find("clutter") != std::string::npos);
}

TEST_CASE("train --surveys: a clutter class and both gates; mission reports the gate") {
  testing::TempDir dir("survey_train");
  const std::string model = dir.file("surveys.slpca");
  REQUIRE(run_logged(dir, "train --out " + model + kSurveyOptions + " --keep-targets 0.9",
                     "train") == 0);
  INFO(slurp(dir.file("train.err")) << slurp(dir.file("train.out")));
  const atr::Model m = atr::load_model(model);
  const int clutter = m.find_class("clutter");
  REQUIRE(clutter >= 0);
  CHECK(m.classes[static_cast<std::size_t>(clutter)].clutter);
  CHECK_FALSE(m.classes[static_cast<std::size_t>(clutter)].mine_like);
  REQUIRE(m.detection_gate);
  REQUIRE(m.classification_gate);
  CHECK(m.detection_gate->threshold > 0.0);
  CHECK(m.detection_gate->threshold < 1.0);
  // the gates were trained behind a detector of objects from one ping up, and the model says so
  REQUIRE(m.detector_rules);
  CHECK(*m.detector_rules == atr::DetectorRules{1, 0.0});
  // the recipe's readings: the chip's centre, its highlight, and its shadow fused with it
  CHECK(m.preprocess.crop_fraction == 0.4);
  CHECK(m.preprocess.levels == atr::ChipLevels::kAboveSeabed);
  REQUIRE(m.views.size() == 1);
  CHECK(m.views[0].preprocess.levels == atr::ChipLevels::kBelowSeabed);
  // a mission with it: the contacts carry the gate's probability, the gate's FROC is written
  REQUIRE(run_logged(dir,
                     "mission " + kSmallSurvey + " --model " + model +
                         " --no-relook --area-margin 35 --quiet --report " +
                         dir.file("mission.json") + " --out " + dir.file("mission"),
                     "mission") == 0);
  const std::string froc = slurp(dir.file("mission/gate_froc.csv"));
  CHECK(froc.rfind("threshold,targets,covered,detected", 0) == 0);
  const std::string contacts = slurp(dir.file("mission/seed_5_contacts.jsonl"));
  if (!contacts.empty()) CHECK(contacts.find("\"target_probability\":") != std::string::npos);
  const std::string candidates = slurp(dir.file("mission/seed_5_candidates.csv"));
  CHECK(candidates.find(",reported,") != std::string::npos);
  std::string parse_error;
  const auto report = autonomy::JsonLine::parse(slurp(dir.file("mission.json")), parse_error);
  REQUIRE(report);
  CHECK(report->object("run")->number("gate_threshold").value_or(-1) ==
        Approx(m.classification_gate->threshold).margin(1e-6));

  // --gate-threshold moves the operating point: every contact then has that probability at least
  REQUIRE(run_logged(dir,
                     "mission " + kSmallSurvey + " --model " + model +
                         " --no-relook --area-margin 35 --quiet --gate-threshold 0.9 --report " +
                         dir.file("high.json") + " --out " + dir.file("high"),
                     "high") == 0);
  std::string error;
  const auto high = autonomy::JsonLine::parse(slurp(dir.file("high.json")), error);
  REQUIRE(high);
  CHECK(high->object("run")->number("gate_threshold").value_or(-1) == Approx(0.9));
  const std::string high_contacts = slurp(dir.file("high/seed_5_contacts.jsonl"));
  std::size_t lines = 0;
  for (std::size_t at = 0; at < high_contacts.size();) {
    const std::size_t end = high_contacts.find('\n', at);
    const auto c = autonomy::JsonLine::parse(high_contacts.substr(at, end - at), error);
    REQUIRE(c);
    CHECK(c->number("target_probability").value_or(-1) >= 0.9);
    ++lines;
    at = end == std::string::npos ? high_contacts.size() : end + 1;
  }
  std::size_t default_lines = 0;
  for (const char ch : contacts)
    default_lines += ch == '\n';
  CHECK(lines <= default_lines);
  // out of range, or without a model that has the gate: usage errors
  CHECK(run_logged(dir, "mission " + kSmallSurvey + " --model " + model + " --gate-threshold 1.5",
                   "bad") == 2);
  CHECK(run_logged(dir, "run --rate max --duration 1 --gate-threshold 0.5", "run") == 2);
  CHECK(slurp(dir.file("run.err")).find("--gate-threshold needs --classify") != std::string::npos);
}

TEST_CASE("train --surveys: usage errors") {
  testing::TempDir dir("survey_train_usage");
  CHECK(run_logged(dir, "train --surveys " + kSmallSurvey, "a") == 2);  // no --out
  CHECK(slurp(dir.file("a.err")).find("--out") != std::string::npos);
  CHECK(run_logged(dir, "train chips --surveys " + kSmallSurvey + " --out m", "b") == 2);
  CHECK(run_logged(dir, "train --surveys no_such_scenario --out " + dir.file("m"), "c") != 0);
  CHECK(run_logged(dir, "train --surveys " + kSmallSurvey + " --classes manta,dragon --out m",
                   "d") == 2);
  CHECK(slurp(dir.file("d.err")).find("dragon") != std::string::npos);
  // the model's own reading cannot also be a fused one
  CHECK(run_logged(dir,
                   "train --surveys " + kSmallSurvey + " --out " + dir.file("m") +
                       " --levels db --fuse-levels db",
                   "e") == 2);
  CHECK(slurp(dir.file("e.err")).find("the model's own reading") != std::string::npos);
}

TEST_CASE("the default model: its cached file is what a mission without --model uses") {
  testing::TempDir dir("default_model");
  const std::string cache = "SONARLOOP_CACHE_DIR=" + dir.file("cache") + " ";
  // where it lives (nothing is built by --path)
  REQUIRE(testing::run_command(cache + testing::kBinary + " train --default --path > " +
                               dir.file("path.out")) == 0);
  std::string path = slurp(dir.file("path.out"));
  while (!path.empty() && path.back() == '\n')
    path.pop_back();
  CHECK(path.rfind(dir.file("cache") + "/models/default-", 0) == 0);
  CHECK(path.size() > 6);
  CHECK(path.substr(path.size() - 6) == ".slpca");
  CHECK_FALSE(std::filesystem::exists(path));
  // a model put there as if built: the mission takes it (a build would take many minutes)
  REQUIRE(run_logged(dir, "train --out " + dir.file("m.slpca") + kSurveyOptions, "train") == 0);
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::filesystem::copy_file(dir.file("m.slpca"), path);
  REQUIRE(testing::run_command(cache + testing::kBinary + " mission " + kSmallSurvey +
                               " --no-relook --area-margin 35 --quiet --report " +
                               dir.file("mission.json") + " --out " + dir.file("mission") + " > " +
                               dir.file("mission.out") + " 2> " + dir.file("mission.err")) == 0);
  INFO(slurp(dir.file("mission.err")));
  const std::string report = slurp(dir.file("mission.json"));
  CHECK(report.find("\"model\":\"" + path + "\"") != std::string::npos);
  CHECK(slurp(dir.file("mission.err")).find("training it once") == std::string::npos);
}
