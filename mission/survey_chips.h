#pragma once
// Training chips from surveys (ours; issue 24): the chips the onboard consumer would classify,
// cut from the live waterfall by its own chip cutter (atr/chip_cutter.h), labelled with the
// truth. A model trained on them knows the survey's along-track sampling (one ping per 13 cm at
// 2 m/s against the dataset's one per pixel), its geometry and its detector's false alarms.
//
// Each candidate that survived the detector's suppression (reported, or below its threshold:
// atr/detector.h) becomes one chip:
//   - within target_radius_m of a target: a chip of the target's type, centred on the target's
//     true position (its along-track coordinate from the ping abeam it, its slant range from the
//     ping's altitude less half the type's height), with its aspect (target heading less the
//     look direction);
//   - otherwise a false alarm: a chip of `clutter_label` (non-mine), centred on the largest
//     clutter rock within rock_radius_m of the candidate when there is one (a rock is what the
//     detector found), else on the detector's centre; aspect 0 (one subspace: clutter has no
//     aspect of its own).
// Chips whose window leaves the waterfall or the swath are skipped (counted). Clutter chips are
// kept up to max_clutter, a uniform sample of those cut.
#include <cstdint>
#include <string>
#include <vector>

#include "atr/chip.h"
#include "atr/chip_cutter.h"
#include "atr/onboard_pipeline.h"
#include "atr/subspace_classifier.h"
#include "atr/waterfall.h"
#include "common/rng.h"
#include "sim/scene/scene.h"

namespace sonarloop::mission {

struct SurveyChipOptions {
  int width = 60, height = 60;  // pixels (3 m x 3 m highlight chips)
  double target_radius_m = 3.0;
  double rock_radius_m = 1.5;
  double min_score = 0.0;  // candidates of lower detector score are skipped
  bool clutter = true;     // false: target chips only
  // at most this many clutter chips per survey, a uniform sample of them all (reservoir
  // sampling, seeded by the survey): a rocky seabed gives thousands
  int max_clutter = 400;
  std::string clutter_label = std::string(atr::kClutterClassName);
};

struct SurveyChipCounts {
  std::uint64_t targets = 0, clutter = 0, rock_centred = 0, skipped = 0;
  std::uint64_t clutter_seen = 0;  // clutter chips cut (clutter: those kept)
};

class SurveyChipCollector {
 public:
  // `seed`: the survey's (the clutter sample's randomness); `source`: each chip's source.
  SurveyChipCollector(const scene::Scene& scene, const SurveyChipOptions& options,
                      std::uint64_t seed = 0, std::string source = "survey");

  // From the pipeline's candidate sink: `w` still holds the candidate's pings.
  void on_candidate(const atr::Waterfall& w, const atr::CandidateReport& r);

  std::vector<atr::LabelledChip>& chips() { return chips_; }
  const SurveyChipCounts& counts() const { return counts_; }

 private:
  // Cuts the chip into `out`; false (counted) when it cannot be cut.
  bool cut(const atr::Waterfall& w, const atr::ChipCentre& c, const std::string& label,
           double aspect_deg, atr::LabelledChip& out);

  const scene::Scene& scene_;
  SurveyChipOptions options_;
  atr::ChipCutter cutter_;
  std::vector<atr::LabelledChip> chips_;
  SurveyChipCounts counts_;
  Rng rng_;
  std::string source_;
  std::vector<std::size_t> clutter_index_;  // chips_ indices of the clutter sample
};

// Where a point of the seabed (north, east in the waterfall's frame; an object `height_m` tall)
// lies in the waterfall on `side`: the chip centre (the along-track footprint coordinate of the
// ping abeam it, its slant range from that ping's altitude less half the height) and that ping's
// look direction (heading + 90 degrees to starboard, - 90 to port). nullopt when no ping of that
// side with an altitude is held.
struct WaterfallPoint {
  atr::ChipCentre centre;
  double look_deg = 0.0;
};
std::optional<WaterfallPoint> locate_in_waterfall(const atr::Waterfall& w, double north_m,
                                                  double east_m, double height_m, int side);

}  // namespace sonarloop::mission
