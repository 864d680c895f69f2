#pragma once
// `sonarloop mission`'s report: the agent's objects (its --report) matched against the scenario's
// targets, and the numbers of docs/autonomy.md's table.
//
// Matching: each target is matched to the nearest object within the match radius of it
// (kTargetMatchRadius_m unless `mission --match-radius`; an object matches one target at most);
// an object matched to no target is a false contact.
//   detected              targets with an object
//   identified            of those, the object's final class is the target's type
//   mine_correct          of those, the object's mine / non-mine decision is the target's
//   confirmed(_correct)   objects confirmed (and identified right) at the end
//   latency               per re-look, mission seconds from the ping abeam the object (the
//                         vehicle's track sample where its first look was abeam) to the re-look
//                         leg's insertion (the new waypoint); wall seconds = that / rate
#include <span>
#include <string>

#include "atr/onboard_pipeline.h"
#include "sim/scenario.h"
#include "study/survey_score.h"

namespace sonarloop::mission {

inline constexpr double kTargetMatchRadius_m = 3.0;

struct MissionSummary {
  int targets = 0, detected = 0, identified = 0, mine_correct = 0;
  int objects = 0, confirmed = 0, confirmed_correct = 0, false_contacts = 0;
  int relooks = 0, relooks_passed = 0, relooks_second_look = 0;
  double mission_time_s = 0.0, wall_time_s = 0.0, distance_m = 0.0;
  double relook_distance_m = 0.0, relook_time_s = 0.0;
  double latency_mean_s = 0.0, latency_max_s = 0.0;
  double aspect_change_mean_deg = 0.0, pass_range_mean_m = 0.0;
  bool mission_done = false;
};

// The mission report (JSON) from the agent's report text; *summary gets the totals. Throws
// std::runtime_error when the agent's report does not parse.
std::string mission_report_json(const std::string& agent_report, const Scenario& scenario,
                                const std::string& extra_fields_json, MissionSummary* summary,
                                double match_radius_m = kTargetMatchRadius_m);

// A few lines for the console.
void print_mission_summary(const MissionSummary& s);

// Several missions' summaries summed (their times and distances too; the means of the re-looks'
// geometry weighted by their passes, the latency maximum kept).
MissionSummary add_summaries(const MissionSummary& a, const MissionSummary& b);

// The summary as a JSON object (the "summary" of the report; with several missions, pooled).
std::string mission_summary_json(const MissionSummary& s);

// One survey's score (study/survey_score.h) as a JSON object: the covered area, every target's
// outcome, every false contact.
std::string survey_score_json(const study::SurveyScore& s);

// The pooled tables (study/survey_rows) as a JSON array of objects.
std::string survey_rows_json(std::span<const study::SurveyRow> rows);

// Console lines: the pooled "all" and per-seabed rows.
void print_survey_rows(std::span<const study::SurveyRow> rows);

// Every candidate of the detector with its fate and (when classified) class, as CSV.
std::string candidates_csv(std::span<const atr::CandidateReport> candidates);

// The per-target outcomes and the false contacts of several surveys as CSV (header first), each
// row with its seed.
std::string survey_targets_csv(std::span<const std::pair<std::uint64_t, study::SurveyScore>> s);
std::string survey_false_contacts_csv(
    std::span<const std::pair<std::uint64_t, study::SurveyScore>> s);

}  // namespace sonarloop::mission
