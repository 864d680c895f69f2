// The aligned classifier finds both the class and the offset of a chip placed off-centre in a
// larger context, where the centred window alone scores it worse.
#include <catch2/catch.hpp>

#include <vector>

#include "atr/aligned_classifier.h"
#include "atr/chip_cutter.h"
#include "tests/atr/synthetic_chips.h"

using namespace sonarloop;

namespace {

constexpr int kSize = 24;
constexpr double kNoise = 0.05;
const std::vector<std::string> kShapeNames = {"bar", "ell", "tee"};

atr::Model train_shapes() {
  Rng rng(11, RngStream::kTraining, 20);
  const auto shapes = testing::rotation_shapes();
  std::vector<atr::LabelledChip> chips;
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < 30; ++i) {
      atr::LabelledChip lc;
      // a small spread of aspects around 20 deg
      lc.chip = testing::draw_rotated(shapes[static_cast<std::size_t>(c)], 20.0 + 0.3 * i, kSize,
                                      rng, kNoise);
      lc.label = kShapeNames[static_cast<std::size_t>(c)];
      chips.push_back(std::move(lc));
    }
  }
  atr::TrainOptions o;
  o.p = 6;
  return atr::train_model(chips, o);
}

// A context chip with margins (mr, mc) holding `chip` at window offset (dr, dc), noise around.
atr::Chip embed(const atr::Chip& chip, int mr, int mc, int dr, int dc, Rng& rng) {
  atr::Chip ctx;
  ctx.height = chip.height + 2 * mr;
  ctx.width = chip.width + 2 * mc;
  ctx.pixels.resize(static_cast<std::size_t>(ctx.width) * ctx.height);
  for (float& p : ctx.pixels)
    p = static_cast<float>(kNoise * rng.normal());
  for (int r = 0; r < chip.height; ++r)
    for (int c = 0; c < chip.width; ++c)
      ctx.pixels[static_cast<std::size_t>(r + mr + dr) * ctx.width + (c + mc + dc)] =
          chip.pixels[static_cast<std::size_t>(r) * chip.width + c];
  return ctx;
}

}  // namespace

TEST_CASE("aligned classifier: class and offset of an off-centre chip") {
  atr::Classifier classifier(train_shapes());
  atr::AlignmentSearch search;
  search.rows = 4;
  search.cols = 6;
  search.coarse_step = 2;
  atr::AlignedClassifier aligned(classifier, search);
  Rng rng(12, RngStream::kTraining, 21);
  const auto shapes = testing::rotation_shapes();
  for (int c = 0; c < 3; ++c) {
    for (const auto& [dr, dc] : {std::pair{3, -5}, {-4, 6}, {0, 0}, {1, 1}}) {
      INFO("class " << kShapeNames[static_cast<std::size_t>(c)] << " at " << dr << ", " << dc);
      const atr::Chip chip =
          testing::draw_rotated(shapes[static_cast<std::size_t>(c)], 24.0, kSize, rng, kNoise);
      const atr::Chip ctx = embed(chip, search.rows, search.cols, dr, dc, rng);
      const atr::AlignedClassification& a = aligned.classify(ctx, search.rows, search.cols);
      REQUIRE(a.check.ok());
      CHECK(a.result.class_index == c);
      CHECK(a.dr == dr);
      CHECK(a.dc == dc);
      // the reported distances are each class's best over the windows tried
      CHECK(a.result.distance == a.result.class_distance[static_cast<std::size_t>(c)]);
      CHECK(a.result.runner_up_distance > a.result.distance);
      // coarse grid (5 x 7) and the neighbours of each class's best: fewer than all 9 x 13
      CHECK(a.windows < 9 * 13);
      if (dr != 0 || dc != 0) {
        // the centred window alone is a worse fit
        atr::Chip centred;
        atr::copy_window(ctx, search.rows, search.cols, 0, 0, centred);
        REQUIRE(classifier.classify(centred.view()).ok());
        CHECK(classifier.result().class_distance[static_cast<std::size_t>(c)] >
              a.result.distance + 1.0f);
      }
    }
  }
}

TEST_CASE("aligned classifier: a blank context is rejected with the classifier's reason") {
  atr::Classifier classifier(train_shapes());
  atr::AlignedClassifier aligned(classifier, atr::AlignmentSearch{2, 2, 1});
  atr::Chip ctx;
  ctx.width = kSize + 4;
  ctx.height = kSize + 4;
  ctx.pixels.assign(static_cast<std::size_t>(ctx.width) * ctx.height, 7.0f);
  const atr::AlignedClassification& a = aligned.classify(ctx, 2, 2);
  CHECK(a.result.class_index == -1);
  CHECK(a.check.status == atr::ChipStatus::kConstant);
  CHECK(a.windows == 25);
  // a context of the wrong size, or too small a margin, is an error
  CHECK_THROWS_AS(aligned.classify(ctx, 1, 1), std::invalid_argument);
}
