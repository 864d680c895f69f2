#include "autonomy/agent.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace sonarloop::autonomy {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Track samples are kept at this spacing in time at least.
constexpr double kTrackSpacing_s = 0.1;

std::string format(const char* fmt, auto... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, fmt, args...);
  return buf;
}

}  // namespace

const char* to_string(RelookTiming t) {
  return t == RelookTiming::kAfterSurvey ? "after_survey" : "immediate";
}

Agent::Agent(const AgentParams& params, std::vector<Leg> survey, const VehicleState& start)
    : params_(params),
      plan_(std::move(survey), start.position, params.guidance),
      state_(start),
      depth_command_m_(start.depth_m) {
  params_.vehicle.validate();
  track_.push_back({state_.t_s, state_.position, state_.heading_rad});
}

void Agent::step(double dt_s, std::optional<double> seabed_depth_m) {
  if (!(dt_s > 0.0)) return;
  const int n = std::max(1, static_cast<int>(std::ceil(dt_s / params_.max_substep_s)));
  for (int i = 0; i < n; ++i)
    substep(dt_s / n, seabed_depth_m);
}

void Agent::substep(double dt_s, std::optional<double> seabed_depth_m) {
  if (plan_.done() && params_.relooks && params_.relook_timing == RelookTiming::kAfterSurvey) {
    schedule_relook_after_survey();
  }
  const bool detour = plan_.on_detour();
  VehicleCommand cmd;
  cmd.heading_rad = plan_.done() ? state_.heading_rad : plan_.update(state_.position);
  if (seabed_depth_m) {
    depth_command_m_ = std::max(0.0, *seabed_depth_m - params_.target_altitude_m);
  }
  cmd.depth_m = depth_command_m_;
  const VehicleState before = state_;
  state_ = step_vehicle(before, cmd, params_.vehicle, dt_s);
  const double moved = distance_m(before.position, state_.position);
  travelled_m_ += moved;
  if (detour) {
    detour_m_ += moved;
    detour_s_ += dt_s;
  }
  if (state_.t_s - track_.back().t_s >= kTrackSpacing_s) {
    track_.push_back({state_.t_s, state_.position, state_.heading_rad});
    while (!track_.empty() && track_.front().t_s < state_.t_s - params_.history_s)
      track_.pop_front();
  }
  check_pass();
}

// A re-look being flown: record the vehicle's heading and range when the contact is abeam.
void Agent::check_pass() {
  if (plan_.done() || plan_.approaching() || plan_.current().kind != LegKind::kRelook) return;
  const Leg& leg = plan_.current();
  for (RelookRecord& r : relooks_) {
    if (r.passed || r.object != leg.object) continue;
    const LegProgress g = leg_progress(leg, state_.position);
    if (g.along_m < params_.relook.run_in_m) continue;
    r.passed = true;
    r.pass_heading_rad = state_.heading_rad;
    r.pass_turn_rate_rad_s = state_.turn_rate_rad_s;
    const Point2 right = direction(state_.heading_rad + 0.5 * std::numbers::pi);
    const Point2 rel = r.contact - state_.position;
    r.pass_range_m = std::fabs(rel.north_m * right.north_m + rel.east_m * right.east_m);
    events_.push_back(format(
        "relook of object %llu: passed at %.1f m across track, heading %.1f deg (%.1f deg from "
        "the first look)",
        static_cast<unsigned long long>(r.object), r.pass_range_m, degrees(r.pass_heading_rad),
        degrees(heading_difference_rad(r.pass_heading_rad, r.first_heading_rad))));
  }
}

std::optional<TrackSample> Agent::look_sample(const atr::Contact& c) const {
  const Point2 p{c.north_m, c.east_m};
  const TrackSample* best = nullptr;
  double best_along = std::numeric_limits<double>::infinity();
  for (const TrackSample& s : track_) {
    const Point2 rel = p - s.position;
    const Point2 d = direction(s.heading_rad);
    const Point2 right = direction(s.heading_rad + 0.5 * std::numbers::pi);
    const double along = rel.north_m * d.north_m + rel.east_m * d.east_m;
    const double cross = rel.north_m * right.north_m + rel.east_m * right.east_m;
    if ((cross > 0) != (c.side == 1)) continue;
    if (std::isfinite(c.ground_range_m) &&
        std::fabs(std::fabs(cross) - c.ground_range_m) > params_.look_range_tolerance_m) {
      continue;
    }
    // the latest sample of smallest |along| (<=: a later pass wins a tie)
    if (std::fabs(along) <= best_along) {
      best_along = std::fabs(along);
      best = &s;
    }
  }
  if (!best) return std::nullopt;
  return *best;
}

AgentObject& Agent::object_for(const atr::Contact& c) {
  const Point2 p{c.north_m, c.east_m};
  // the onboard consumer's association first
  if (c.looks >= 2 && c.object != 0) {
    for (AgentObject& o : objects_)
      if (o.id == c.object) return o;
  }
  AgentObject* nearest = nullptr;
  double nearest_m = params_.association_radius_m;
  for (AgentObject& o : objects_) {
    const double d = distance_m(o.position, p);
    if (d <= nearest_m) {
      nearest_m = d;
      nearest = &o;
    }
  }
  if (nearest) return *nearest;
  AgentObject o;
  o.id = c.object != 0 ? c.object : c.id;
  o.position = p;
  objects_.push_back(o);
  return objects_.back();
}

void Agent::on_contact(const atr::Contact& c) {
  std::string text = atr::contact_json(c);
  if (const auto it = seen_.find(c.id); it != seen_.end()) {
    if (it->second == text) {
      ++duplicates_;
    } else {
      ++conflicts_;
      events_.push_back(format("contact %llu reported again with other content: ignored",
                               static_cast<unsigned long long>(c.id)));
    }
    return;
  }
  seen_.emplace(c.id, std::move(text));
  seen_order_.push_back(c.id);
  if (seen_order_.size() > kRememberedContacts) {
    seen_.erase(seen_order_.front());
    seen_order_.pop_front();
  }
  AgentObject& o = object_for(c);
  const std::optional<TrackSample> seen = look_sample(c);
  o.looks.push_back(c);
  o.last_contact_t_s = state_.t_s;
  o.look_headings_rad.push_back(seen ? seen->heading_rad : kNaN);
  o.look_t_s.push_back(seen ? seen->t_s : state_.t_s);
  const double k = static_cast<double>(o.looks.size());
  o.position = o.position + (1.0 / k) * (Point2{c.north_m, c.east_m} - o.position);
  for (RelookRecord& r : relooks_)
    if (r.object == o.id && o.looks.size() >= 2) r.second_look = true;
  o.decision = decide(o.looks, params_.margin_threshold, params_.confirm_probability);
  events_.push_back(
      format("contact %llu -> object %llu (look %zu): %s, margin %.3f -> %s %s%s",
             static_cast<unsigned long long>(c.id), static_cast<unsigned long long>(o.id),
             o.looks.size(), c.class_name.empty() ? "unclassified" : c.class_name.c_str(),
             decision_margin(c), to_string(o.decision.state),
             o.decision.fused.class_name.empty() ? "-" : o.decision.fused.class_name.c_str(),
             o.decision.fused.class_name.empty()
                 ? ""
                 : (o.decision.fused.mine_like ? " (mine)" : " (non-mine)")));
  if (params_.relook_timing == RelookTiming::kImmediate) {
    maybe_relook(o);
  } else if (params_.relooks) {
    relook_due_ = true;  // looked at again once the survey is done
  }
}

bool Agent::wants_relook(AgentObject& o) {
  if (!params_.relooks || o.decision.state == FinalState::kConfirmed ||
      o.relooks >= params_.max_relooks_per_object ||
      static_cast<int>(relooks_.size()) >= params_.max_relooks || o.relook_over_budget) {
    return false;
  }
  const FusedDecision& f = o.decision.fused;
  const bool surely_non_mine =
      !f.mine_like && std::isfinite(f.mine_margin) && f.mine_margin >= params_.margin_threshold &&
      !(std::isfinite(f.target_probability) && f.target_probability < params_.confirm_probability);
  if (params_.relook_mine_relevant_only && surely_non_mine) {
    if (!o.relook_skip_reported) {
      o.relook_skip_reported = true;
      events_.push_back(format("object %llu not re-looked: non-mine either way (mine margin %.3f)",
                               static_cast<unsigned long long>(o.id), f.mine_margin));
    }
    return false;
  }
  return true;
}

RelookRecord Agent::make_relook(const AgentObject& o) const {
  // the first look's heading (the track sample where it was abeam); else the vehicle's now
  double first_heading = state_.heading_rad;
  double look_t = state_.t_s;
  for (std::size_t i = 0; i < o.looks.size(); ++i) {
    if (std::isfinite(o.look_headings_rad[i])) {
      first_heading = o.look_headings_rad[i];
      look_t = o.look_t_s[i];
      break;
    }
  }
  RelookRecord r;
  r.object = o.id;
  r.contact = o.position;
  r.first_heading_rad = first_heading;
  r.plan = plan_relook(o.position, first_heading, o.id, state_.position, state_.heading_rad,
                       params_.relook, params_.bounds);
  r.look_t_s = look_t;
  r.received_t_s = o.last_contact_t_s;
  r.inserted_t_s = state_.t_s;
  return r;
}

void Agent::maybe_relook(AgentObject& o) {
  if (!wants_relook(o)) return;
  RelookRecord r = make_relook(o);
  plan_.insert_relook(r.plan.leg, state_.position);
  ++o.relooks;
  relooks_.push_back(r);
  events_.push_back(format(
      "relook of object %llu inserted: heading %.1f deg (first look %.1f deg), contact to %s at "
      "%.1f m, run-in from (%.1f, %.1f)",
      static_cast<unsigned long long>(o.id), degrees(r.plan.heading_rad),
      degrees(r.first_heading_rad), r.plan.side == 1 ? "starboard" : "port",
      params_.relook.pass_range_m, r.plan.leg.start.north_m, r.plan.leg.start.east_m));
}

void Agent::schedule_relook_after_survey() {
  relook_due_ = false;
  // the cheapest re-look to reach from here among the objects that want one
  AgentObject* best = nullptr;
  RelookRecord best_r;
  for (AgentObject& o : objects_) {
    if (!wants_relook(o)) continue;
    RelookRecord r = make_relook(o);
    if (!best || r.plan.cost_m < best_r.plan.cost_m) {
      best = &o;
      best_r = r;
    }
  }
  if (!best) return;
  // its time: the transit (the planner's cost, turns included) and the leg, at the speed
  const double estimate_s =
      (best_r.plan.cost_m + best_r.plan.leg.length_m()) / params_.vehicle.speed_m_s;
  if (detour_s_ + estimate_s > params_.relook_budget_s) {
    // none fits (the cheapest does not): the budget is spent
    for (AgentObject& o : objects_) {
      if (!wants_relook(o)) continue;
      o.relook_over_budget = true;
      events_.push_back(format("object %llu not re-looked: the re-look budget (%.0f s) is spent",
                               static_cast<unsigned long long>(o.id), params_.relook_budget_s));
    }
    return;
  }
  plan_.insert_relook(best_r.plan.leg, state_.position);
  ++best->relooks;
  relooks_.push_back(best_r);
  relook_due_ = true;  // more may follow once this one is flown
  events_.push_back(format(
      "relook of object %llu after the survey: heading %.1f deg (first look %.1f deg), about "
      "%.0f s (%.0f s of the %.0f s budget used)",
      static_cast<unsigned long long>(best->id), degrees(best_r.plan.heading_rad),
      degrees(best_r.first_heading_rad), estimate_s, detour_s_, params_.relook_budget_s));
}

std::vector<std::string> Agent::take_events() {
  std::vector<std::string> out;
  out.swap(events_);
  return out;
}

}  // namespace sonarloop::autonomy
