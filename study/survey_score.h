#pragma once
// Scoring a survey's contact stream against the scene's truth (ours; issue 24, docs/autonomy.md
// "Survey scoring"): what a vehicle received from the onboard consumer, object by object, matched
// one to one with the targets on the ground.
//
// Objects. The onboard consumer reports one contact per look; a look it associated with an
// object seen before carries that object's id (atr/look_fusion.h, Contact::object). An object is
// therefore the contacts sharing an id: its position the mean of its looks', its class and mine /
// non-mine the latest look's fused decision (the look's own with one look).
//
// Matching. Target-object pairs closer than match_radius_m, taken in order of distance, each
// target and each object used once. 3 m by default: more than the onboard position error of a
// true detection (its centre from the chip alignment, its ground range from the class's height;
// measured in docs/autonomy.md: 99 % of matched objects within 1.2 m on mission_20) plus the
// half-length of the longest target (the 2 m cylinder), less than the 25 m between targets of the
// scenarios. An object matched to no target is a false contact.
//
// Coverage. Probability of detection counts only targets the survey saw: a target is covered
// when some ping passed it abeam (within along_window_m along track) at a ground range in the
// swath, from the nadir gap to the far edge less far_margin_m (half a 3 m chip: an object there
// cannot be cut). The nadir gap is the ping's altitude (grazing angles above 45 degrees, where
// the slant range compresses the ground and an object's shadow is shorter than its height; a
// survey's line spacing leaves that band to the neighbouring line) unless nadir_gap_m is set.
// The covered area (for false contacts per km²) is the union of the same swath bands, on a grid
// of cell_m, split by the seabed kind of each cell.
//
// Seabed kind of a point: the texture of its sediment region (scene/scene_desc.h): "flat",
// "ripples", "rocky", "clutter", or their combination joined by '+' ("ripples+clutter"). Rocks
// sparser than kClutterKindDensity_per_m2 (one per 100 m²: a few boulders, the clutter objects
// of target size the survey scenarios strew over flat, rippled and rocky seabeds) do not make
// a seabed "clutter".
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "atr/confusion.h"
#include "atr/contact.h"
#include "sim/scene/scene.h"

namespace sonarloop::study {

inline constexpr double kSurveyMatchRadius_m = 3.0;
inline constexpr double kClutterKindDensity_per_m2 = 0.01;

struct SurveyScoreOptions {
  double match_radius_m = kSurveyMatchRadius_m;
  double nadir_gap_m = -1.0;  // < 0: each ping's altitude
  double far_margin_m = 1.5;
  double along_window_m = 0.5;
  double cell_m = 1.0;
  // Throws std::invalid_argument naming the first value out of range.
  void validate() const;
};

// Where one ping looked from (true pose), and how far it saw.
struct SwathPing {
  double t_s = 0.0;
  double north_m = 0.0, east_m = 0.0;
  double heading_rad = 0.0;  // clockwise from north
  double altitude_m = 0.0;
};

// One object of the contact stream.
struct StreamObject {
  std::uint64_t id = 0;  // the contact id of its first look
  double north_m = 0.0, east_m = 0.0;
  int looks = 0;
  std::string class_name;  // empty: never classified
  bool mine_like = false;
  bool unknown = false;  // open-set: unlike every trained type
  std::string status;    // why its latest look was not classified (atr/contact.h)
};

// The objects of a contact stream, in the order of their first look.
std::vector<StreamObject> stream_objects(std::span<const atr::Contact> contacts);

// The seabed kind of a point (see above).
std::string seabed_kind(const scene::Scene& scene, double north_m, double east_m);

struct TargetOutcome {
  std::string name, type, seabed;
  bool mine_like = false;
  double north_m = 0.0, east_m = 0.0;
  bool covered = false;
  bool detected = false;
  std::string class_name;  // the matched object's
  bool identified = false;
  bool mine_correct = false;  // classified, and on the right side of mine / non-mine
  double error_m = 0.0;       // matched object to target
  int looks = 0;
};

struct FalseContact {
  std::uint64_t object = 0;
  double north_m = 0.0, east_m = 0.0;
  std::string seabed;
  std::string class_name;
  bool mine_like = false;
  int looks = 0;
  double rock_diameter_m = 0.0;  // the largest clutter rock within the match radius (0: none)
};

struct SurveyScore {
  std::vector<TargetOutcome> targets;  // in the scene's order
  std::vector<FalseContact> false_contacts;
  int objects = 0;
  double area_km2 = 0.0;                           // covered
  std::map<std::string, double> area_km2_by_kind;  // covered, per seabed kind
};

// Scores `objects` against `scene`'s targets over the swath of `pings` (max_range_m: the
// sonar's slant range).
SurveyScore score_survey(const scene::Scene& scene, std::span<const SwathPing> pings,
                         double max_range_m, std::span<const StreamObject> objects,
                         const SurveyScoreOptions& options = {});

// Counts pooled over surveys (several seeds), per group.
struct SurveyCounts {
  int targets = 0, covered = 0, detected = 0, identified = 0, mine_correct = 0;
  int mine_wrong = 0;  // detected and classified on the wrong side, or not classified
  int false_contacts = 0;
  int surveys = 0;
  double area_km2 = 0.0;
};

struct SurveyTally {
  SurveyCounts all;
  std::map<std::string, SurveyCounts> by_seabed;  // targets and false contacts by seabed kind
  std::map<std::string, SurveyCounts> by_type;    // targets by type (no false contacts)
  void add(const SurveyScore& s);
};

// The detector's FROC (detection against false contacts over its operating threshold), from
// every candidate of one pass (atr/detector.h: the contacts at threshold h are the candidates
// that survived the suppression with score >= h). At each threshold the surviving candidates
// are grouped into objects as the onboard consumer's look fusion would (each joins the nearest
// object within association_radius_m, in the order decided, else starts one) and matched to the
// covered targets as score_survey matches objects.
struct ScoredCandidate {
  double north_m = 0.0, east_m = 0.0;
  double score = 0.0;
  bool survived = false;  // not suppressed, not rejected by a gate
};

struct FrocCounts {
  double threshold = 0.0;
  int covered = 0, detected = 0, false_contacts = 0, targets = 0;
  double area_km2 = 0.0;
};

// One survey's counts at each threshold (`score`: the survey's score_survey, for the targets'
// coverage and the covered area).
std::vector<FrocCounts> froc_counts(const SurveyScore& score,
                                    std::span<const ScoredCandidate> candidates,
                                    std::span<const double> thresholds, double association_radius_m,
                                    double match_radius_m);
// Adds b's counts to a's (the same thresholds).
void add_froc(std::vector<FrocCounts>& a, std::span<const FrocCounts> b);
// As CSV: threshold, the counts, Pd with its Wilson interval, false contacts per km² and per
// target.
std::string froc_csv(std::span<const FrocCounts> froc);

// One row of the tables: the counts and their rates with 95 % Wilson intervals.
struct SurveyRow {
  std::string scope;  // "all", "seabed:KIND", "type:TYPE"
  SurveyCounts c;
  double pd = 0.0;  // detected / covered
  atr::Interval pd_ci;
  double identified = 0.0;  // identified / detected
  atr::Interval identified_ci;
  double mine_error = 0.0;  // mine_wrong / detected
  atr::Interval mine_error_ci;
  double false_per_km2 = 0.0;
  double false_per_target = 0.0;  // false contacts / targets (all, seabed rows)
};
std::vector<SurveyRow> survey_rows(const SurveyTally& t);

// The rows as CSV (header line first).
std::string survey_rows_csv(std::span<const SurveyRow> rows);

}  // namespace sonarloop::study
