// classify's scores (study/classify_report.h): the confusion matrix of a labelled folder, the
// mine / non-mine accuracy over the chips whose truth is known (a class of the model, a simulated
// type, or the clutter of training surveys), rejected chips left out, accuracy by true aspect.
#include "study/classify_report.h"

#include <catch2/catch.hpp>
#include <vector>

using namespace sonarloop;

namespace {

atr::Model two_class_model() {
  atr::Model m;
  for (const auto& [name, mine] : {std::pair{"box", false}, std::pair{"manta", true}}) {
    atr::ClassModel c;
    c.name = name;
    c.mine_like = mine;
    m.classes.push_back(c);
  }
  return m;
}

atr::LabelledChip chip(const char* label, double aspect_deg) {
  atr::LabelledChip c;
  c.label = label;
  c.aspect_deg = aspect_deg;
  return c;
}

study::ClassifiedChip row(const atr::LabelledChip& c, int class_index, bool mine_like,
                          bool ok = true) {
  study::ClassifiedChip r;
  r.chip = &c;
  if (!ok) r.check.status = atr::ChipStatus::kConstant;
  r.result.class_index = class_index;
  r.result.mine_like = mine_like;
  return r;
}

}  // namespace

TEST_CASE("classify report: confusion, mine / non-mine over known truths, accuracy by aspect") {
  const atr::Model m = two_class_model();
  study::ChipFolder folder;
  folder.labelled = true;
  folder.classes = {"box", "clutter", "manta", "tyre"};
  folder.chips = {chip("box", 10),     chip("manta", 100), chip("manta", 200),
                  chip("clutter", 10), chip("tyre", 300),  chip("box", 20)};
  folder.aspect_count = folder.chips.size();
  const auto& c = folder.chips;
  const std::vector<study::ClassifiedChip> rows = {
      row(c[0], 0, false),         // box as box: right
      row(c[1], 1, true),          // manta as manta: right
      row(c[2], 0, false),         // manta as box: wrong, and a mine missed
      row(c[3], 1, true),          // clutter as manta: wrong, a false mine (clutter is no mine)
      row(c[4], 0, false),         // tyre: no known mine-likeness, not in the mine score
      row(c[5], 1, true, false)};  // rejected: in no score
  const study::ClassifyScores s = study::score_chips(m, folder, rows, 5, 4);
  REQUIRE(s.confusion);
  CHECK(s.confusion->total() == 5);
  CHECK(s.confusion->correct() == 2);
  CHECK(s.confusion->count(2, 0) == 1);  // manta -> box
  CHECK(s.confusion->count(1, 1) == 1);  // clutter -> manta
  CHECK(s.mine_total == 4);
  CHECK(s.mine_correct == 2);
  // four bins of 90 degrees: [0, 90) holds box (right) and clutter (wrong)
  REQUIRE(s.bins.size() == 4);
  CHECK(s.bins[0].total == 2);
  CHECK(s.bins[0].correct == 1);
  CHECK(s.bins[1].total == 1);
  CHECK(s.bins[1].correct == 1);
  CHECK(s.bins[2].correct == 0);
  CHECK(s.bins[3].total == 1);
  // an unlabelled folder, or nothing classified: nothing to score
  folder.labelled = false;
  CHECK_FALSE(study::score_chips(m, folder, rows, 5, 4).confusion);
  folder.labelled = true;
  CHECK_FALSE(study::score_chips(m, folder, rows, 0, 4).confusion);
}
