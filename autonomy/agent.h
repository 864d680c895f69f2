#pragma once
// The example autonomy agent's brain (ours; docs/autonomy.md): flies a lawnmower survey with the
// vehicle model, takes the onboard consumer's contacts, re-looks each uncertain one from an aspect
// about 90° from its first look, fuses the looks and gives every object a final state. Pure: time
// is the argument of step(), nothing here reads a clock or a socket (tools/cmd_autonomy.cpp does
// the I/O), so the same inputs give the same track and decisions.
//
// Per contact (on_contact): it joins an object (the onboard's `object` id for a look it fused,
// else the nearest object within association_radius_m, else it starts one); the look's heading is
// found in the vehicle's recent track (the sample where the contact was abeam, on its side, at
// its ground range); the object's decision is made again (autonomy/contact_decision.h).
//
// Re-looks (autonomy/relook.h), when an object stays uncertain:
//   after the survey (the default): the survey is flown to its end first (a lawnmower sees most
//     objects twice, from neighbouring lines, and many doubts end there); then the objects still
//     uncertain are re-looked one at a time, the cheapest to reach from where the vehicle is
//     first, while the re-looks' time stays within relook_budget_s;
//   immediate: an uncertain object gets its re-look leg inserted at once: the survey is cut
//     where the vehicle is and resumes there after the re-look (within max_relooks).
#include <cstdint>
#include <deque>
#include <limits>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "atr/contact.h"
#include "autonomy/contact_decision.h"
#include "autonomy/guidance.h"
#include "autonomy/relook.h"
#include "autonomy/survey.h"
#include "autonomy/vehicle_model.h"

namespace sonarloop::autonomy {

// When uncertain objects are re-looked (see above).
enum class RelookTiming { kAfterSurvey, kImmediate };
const char* to_string(RelookTiming t);

struct AgentParams {
  VehicleParams vehicle;
  GuidanceParams guidance;
  RelookParams relook;
  double margin_threshold = 0.05;  // below it a look is uncertain (contact_decision.h)
  bool relooks = true;             // false: survey only, objects keep their first decision
  int max_relooks_per_object = 1;
  int max_relooks = 1 << 30;  // the mission's budget of re-looks (the first ones asked for)
  // re-look only where the doubt could change the mine / non-mine decision: an uncertain object
  // that is non-mine with a mine margin (contact_decision.h) of at least margin_threshold (e.g. a
  // rock unsure between the two hemispheres) is left as it is. false: every uncertain object
  bool relook_mine_relevant_only = true;
  RelookTiming relook_timing = RelookTiming::kAfterSurvey;
  // after the survey: the re-looks' mission time (their legs and the transits to them) may not
  // exceed this; a re-look whose estimate would is not flown
  double relook_budget_s = std::numeric_limits<double>::infinity();
  // an object whose looks' fused target probability (the onboard's contact gate, when its model
  // has one: atr/contact_gate.h) is below this is uncertain whatever its class margin
  double confirm_probability = 0.5;
  double target_altitude_m = 7.5;  // altitude keeping, when the seabed's depth is measured
  double association_radius_m = 3.0;
  double history_s = 90.0;              // track kept to find where a contact was seen from
  double look_range_tolerance_m = 8.0;  // |cross-track - ground range| of a look's sample
  double max_substep_s = 0.05;          // the vehicle model's integration step
  std::optional<SurveyArea> bounds;     // re-look legs prefer to stay inside
};

struct TrackSample {
  double t_s = 0.0;
  Point2 position;
  double heading_rad = 0.0;
};

struct RelookRecord {
  std::uint64_t object = 0;
  Point2 contact;  // where the object was when the re-look was planned
  double first_heading_rad = 0.0;
  RelookPlan plan;
  double look_t_s = 0.0;          // track time the first look was abeam the object
  double received_t_s = 0.0;      // time the contact arrived
  double inserted_t_s = 0.0;      // time the re-look leg was inserted (the new waypoint)
  bool passed = false;            // the vehicle passed abeam the contact on the leg
  double pass_heading_rad = 0.0;  // the vehicle's heading there
  double pass_range_m = 0.0;      // its measured distance across track to the contact
  double pass_turn_rate_rad_s = 0.0;
  bool second_look = false;  // a contact of the object came after the insertion
};

struct AgentObject {
  std::uint64_t id = 0;  // the contact id of its first look
  Point2 position;       // the mean of its looks
  std::vector<atr::Contact> looks;
  std::vector<double> look_headings_rad;  // per look, the vehicle's heading (NaN: not found)
  std::vector<double> look_t_s;           // per look, when it was abeam
  double last_contact_t_s = 0.0;          // when its latest look arrived
  int relooks = 0;
  bool relook_skip_reported = false;  // "not re-looked: non-mine either way" logged
  bool relook_over_budget = false;    // after the survey: its re-look did not fit the budget
  ObjectDecision decision;
};

inline constexpr std::size_t kRememberedContacts = 1u << 16;

class Agent {
 public:
  Agent(const AgentParams& params, std::vector<Leg> survey, const VehicleState& start);

  // Advances the vehicle by dt_s. seabed_depth_m: the measured depth of the seabed below the
  // surface (navigation depth + altitude), for altitude keeping; without it, depth is held.
  void step(double dt_s, std::optional<double> seabed_depth_m);
  // A contact of the onboard consumer, received now (state().t_s). An id names one report: a
  // contact whose id was taken already is ignored and counted, whether its content is the same
  // (a datagram delivered twice) or not (a conflicting report), so that a repeat can never add a
  // look (the last kRememberedContacts ids are remembered).
  void on_contact(const atr::Contact& c);
  std::uint64_t duplicate_contacts() const { return duplicates_; }
  std::uint64_t conflicting_contacts() const { return conflicts_; }

  const VehicleState& state() const { return state_; }
  const AgentParams& params() const { return params_; }
  const MissionPlan& plan() const { return plan_; }
  // The plan is flown, and after the survey no uncertain object is left to re-look.
  bool mission_done() const { return plan_.done() && !relook_due_; }
  const std::vector<AgentObject>& objects() const { return objects_; }
  const std::vector<RelookRecord>& relooks() const { return relooks_; }
  double travelled_m() const { return travelled_m_; }
  double detour_distance_m() const { return detour_m_; }
  double detour_time_s() const { return detour_s_; }
  // Lines describing what happened since the last call (new legs, decisions), for logs.
  std::vector<std::string> take_events();

 private:
  void substep(double dt_s, std::optional<double> seabed_depth_m);
  AgentObject& object_for(const atr::Contact& c);
  std::optional<TrackSample> look_sample(const atr::Contact& c) const;
  // Whether `o` is one to re-look (uncertain, mine-relevant, re-looks left); logs a skip once.
  bool wants_relook(AgentObject& o);
  void maybe_relook(AgentObject& o);
  // After the survey: the next re-look, the cheapest to reach, if one fits the budget.
  void schedule_relook_after_survey();
  RelookRecord make_relook(const AgentObject& o) const;
  void check_pass();

  AgentParams params_;
  MissionPlan plan_;
  VehicleState state_;
  double depth_command_m_;
  std::deque<TrackSample> track_;
  std::vector<AgentObject> objects_;
  std::vector<RelookRecord> relooks_;
  std::vector<std::string> events_;
  double travelled_m_ = 0.0, detour_m_ = 0.0, detour_s_ = 0.0;
  bool relook_due_ = false;  // after the survey: an object may still be re-looked
  // the ids taken (with each contact's JSON form), oldest first
  std::unordered_map<std::uint64_t, std::string> seen_;
  std::deque<std::uint64_t> seen_order_;
  std::uint64_t duplicates_ = 0, conflicts_ = 0;
};

}  // namespace sonarloop::autonomy
