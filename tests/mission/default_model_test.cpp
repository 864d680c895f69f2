// The default model's recipe and cache place (mission/default_model.h): the five built-in survey
// scenarios behind a one-ping detector, p = 10 and 8 aspect sectors, a file under
// $SONARLOOP_CACHE_DIR named by the recipe's key. Building it (minutes) is not tested here:
// tests/tools/train_surveys_cli_test.cpp checks that a mission takes the file at that place.
#include "mission/default_model.h"

#include <catch2/catch.hpp>
#include <cstdlib>
#include <string>

using namespace sonarloop;

TEST_CASE("default model: the recipe, and its place in the cache") {
  const mission::TrainingSurveys t = mission::default_training_surveys();
  REQUIRE(t.scenarios.size() == 5);
  CHECK(t.scenarios[0].scene.name == "survey_flat");
  CHECK(t.scenarios[4].scene.name == "mission_20");
  CHECK(t.types.size() == 7);
  CHECK(t.first_seed == 100000);
  CHECK(t.detector_rules == atr::DetectorRules{1, 0.0});
  CHECK_FALSE(t.agent.relooks);
  const mission::SurveyModelOptions o = mission::default_model_options();
  CHECK(o.train.p == 10);
  CHECK(o.train.aspect_sectors == 8);

  ::setenv("SONARLOOP_CACHE_DIR", "/tmp/sonarloop-default-model-test", 1);
  const std::string path = mission::default_model_path();
  CHECK(path.rfind("/tmp/sonarloop-default-model-test/models/default-", 0) == 0);
  CHECK(path.size() > 6);
  CHECK(path.substr(path.size() - 6) == ".slpca");
  CHECK(mission::default_model_path() == path);  // the key is stable
  ::unsetenv("SONARLOOP_CACHE_DIR");
  CHECK(mission::is_default_model("default"));
  CHECK_FALSE(mission::is_default_model("out/atr.slpca"));
}
