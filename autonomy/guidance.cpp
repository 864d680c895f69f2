#include "autonomy/guidance.h"

#include <cmath>

namespace sonarloop::autonomy {

LegProgress leg_progress(const Leg& leg, Point2 p) {
  const double h = leg.heading_rad();
  const Point2 d = direction(h);
  const Point2 right = direction(h + 0.5 * std::numbers::pi);
  const Point2 r = p - leg.start;
  return {r.north_m * d.north_m + r.east_m * d.east_m,
          r.north_m * right.north_m + r.east_m * right.east_m};
}

double los_heading_rad(const Leg& leg, Point2 p, double lookahead_m) {
  const LegProgress g = leg_progress(leg, p);
  return wrap_to_pi(leg.heading_rad() - std::atan2(g.cross_track_m, lookahead_m));
}

MissionPlan::MissionPlan(std::vector<Leg> survey, Point2 from, GuidanceParams params)
    : params_(params), legs_(survey.begin(), survey.end()) {
  if (!legs_.empty()) begin_next(from);
}

Point2 MissionPlan::line_start() const {
  const Leg& leg = legs_.front();
  if (leg.kind != LegKind::kRelook) return leg.start;
  return leg.start - params_.relook_lead_m * direction(leg.heading_rad());
}

void MissionPlan::begin_next(Point2 p) {
  approach_from_ = p;
  approaching_ = distance_m(p, line_start()) > params_.approach_acceptance_m;
}

Leg MissionPlan::steering_leg() const {
  Leg a = legs_.front();
  if (!approaching_) {
    a.start = line_start();
    return a;
  }
  a.end = line_start();
  a.start = approach_from_;
  return a;
}

bool MissionPlan::on_detour() const {
  if (legs_.empty()) return false;
  return legs_.front().kind == LegKind::kRelook || (after_relook_ && approaching_);
}

double MissionPlan::update(Point2 p) {
  // a few transitions at most per call (an approach, then a leg already passed)
  for (int guard = 0; guard < 8 && !legs_.empty(); ++guard) {
    if (approaching_) {
      const Leg a = steering_leg();
      const bool arrived = distance_m(p, a.end) <= params_.approach_acceptance_m ||
                           leg_progress(a, p).along_m >= a.length_m();
      if (!arrived) break;
      approaching_ = false;
      continue;
    }
    const Leg& leg = legs_.front();
    if (leg_progress(leg, p).along_m < leg.length_m()) break;
    after_relook_ = leg.kind == LegKind::kRelook;
    legs_.pop_front();
    if (!legs_.empty()) begin_next(p);
  }
  if (legs_.empty()) return 0.0;
  return los_heading_rad(steering_leg(), p, params_.lookahead_m);
}

void MissionPlan::insert_relook(const Leg& relook, Point2 p) {
  if (legs_.empty()) {
    legs_.push_back(relook);
    after_relook_ = false;
    begin_next(p);
    return;
  }
  if (legs_.front().kind == LegKind::kSurvey) {
    // cut the survey leg where the vehicle is (its projection on the leg, not before its start)
    Leg& survey = legs_.front();
    if (!approaching_) {
      const double along = leg_progress(survey, p).along_m;
      if (along > 0.0) survey.start = survey.start + along * direction(survey.heading_rad());
    }
    legs_.push_front(relook);
    after_relook_ = false;
    begin_next(p);
    return;
  }
  // behind the re-looks already queued
  auto it = legs_.begin();
  while (it != legs_.end() && it->kind == LegKind::kRelook)
    ++it;
  legs_.insert(it, relook);
}

}  // namespace sonarloop::autonomy
