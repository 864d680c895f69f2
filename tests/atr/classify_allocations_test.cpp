// Classifier::classify() runs onboard on a stream of chips: once the classifier is set up it
// allocates nothing, for valid and rejected chips alike. Eigen allocates with malloc, not with
// operator new: the counter (tests/support/allocation_counter.h) counts malloc itself.
#include <catch2/catch.hpp>
#include <cstddef>
#include <cstdlib>
#include <limits>
#include <vector>

#include "atr/subspace_classifier.h"
#include "tests/atr/synthetic_chips.h"
#include "tests/support/allocation_counter.h"

using sonarloop::testing::allocations_in;

using namespace sonarloop;
using namespace sonarloop::atr;

TEST_CASE("classify allocations: the counter sees malloc and new") {
  // the harness itself works: a vector and an Eigen vector are counted
  CHECK(allocations_in([] {
          std::vector<float> v(100);
          v[0] = 1.0f;
          REQUIRE(v[0] == 1.0f);
        }) >= 1);
  CHECK(allocations_in([] {
          Eigen::VectorXf v = Eigen::VectorXf::Ones(1000);
          REQUIRE(v.sum() == 1000.0f);
        }) >= 1);
}

TEST_CASE("classify allocations: classify() allocates nothing once set up") {
  // 64 x 64 chips, 4 classes, p = 20, multi-aspect and group subspaces: every code path
  const auto lc = testing::make_linear_classes(4, 64, 64, 3, 5);
  const std::vector<std::string> names = {"cylinder", "hemisphere", "manta", "rock"};
  Rng rng(9, RngStream::kTraining, 5);
  std::vector<LabelledChip> train;
  for (int c = 0; c < 4; ++c) {
    for (int i = 0; i < 40; ++i) {
      LabelledChip l;
      l.chip = testing::sample_linear(lc, c, rng, 0.1);
      l.label = names[static_cast<std::size_t>(c)];
      l.aspect_deg = rng.uniform(0.0, 360.0);
      train.push_back(std::move(l));
    }
  }
  TrainOptions opt;
  opt.aspect_sectors = 2;
  opt.group_subspaces = true;
  opt.class_metadata["cylinder"].mine_like = true;
  opt.class_metadata["manta"].mine_like = true;
  Classifier clf(train_model(train, opt));
  std::vector<Chip> probes;
  for (int c = 0; c < 4; ++c)
    probes.push_back(testing::sample_linear(lc, c, rng, 0.1));
  Chip constant{64, 64, std::vector<float>(4096, 2.0f)};
  Chip nan = probes[0];
  nan.pixels[100] = std::numeric_limits<float>::quiet_NaN();
  Chip wrong{32, 128, probes[0].pixels};

  int correct = 0;
  const long n = allocations_in([&] {
    for (int rep = 0; rep < 3; ++rep) {
      for (int c = 0; c < 4; ++c) {
        if (clf.classify(probes[static_cast<std::size_t>(c)].view()).ok()) {
          correct += clf.result().class_index == c;
        }
      }
      correct -= clf.classify(constant.view()).ok();
      correct -= clf.classify(nan.view()).ok();
      correct -= clf.classify(wrong.view()).ok();
    }
  });
  CHECK(n == 0);
  CHECK(correct == 12);
}

TEST_CASE("classify allocations: a pre-processing model allocates nothing either") {
  // crop, multilook, levels and a second, fused reading: the classifier's scratch and the
  // readings' vectors are sized at construction
  const auto lc = testing::make_linear_classes(3, 40, 40, 3, 6);
  const std::vector<std::string> names = {"cylinder", "manta", "rock"};
  Rng rng(10, RngStream::kTraining, 6);
  std::vector<LabelledChip> train;
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < 30; ++i) {
      LabelledChip l;
      l.chip = testing::sample_linear(lc, c, rng, 0.1, 3.0, 100.0);
      l.label = names[static_cast<std::size_t>(c)];
      train.push_back(std::move(l));
    }
  }
  TrainOptions opt;
  opt.p = 10;
  opt.preprocess = ChipPreprocess{0.5, 3, ChipLevels::kAboveSeabed, 6.0};
  opt.views = {ChipPreprocess{0.5, 1, ChipLevels::kBelowSeabed, 6.0}};
  Classifier clf(train_model(train, opt));
  REQUIRE(clf.model().feature_count() == 400);
  REQUIRE(clf.model().views.size() == 1);
  std::vector<Chip> probes;
  for (int c = 0; c < 3; ++c)
    probes.push_back(testing::sample_linear(lc, c, rng, 0.1, 3.0, 100.0));
  int ok = 0;
  const long n = allocations_in([&] {
    for (int rep = 0; rep < 3; ++rep) {
      for (const Chip& p : probes)
        ok += clf.classify(p.view()).ok();
    }
  });
  CHECK(n == 0);
  CHECK(ok == 9);
  CHECK(clf.normalised().size() == 400);
}
