#include "mission/agent_setup.h"

#include <algorithm>
#include <stdexcept>

namespace sonarloop::mission {

AgentSetup make_agent_setup(const Scenario& sc, const AgentOverrides& o) {
  AgentSetup s;
  s.origin = GeoPoint{sc.scene.origin.latitude_deg, sc.scene.origin.longitude_deg};
  const auto& sb = sc.scene.seabed;
  const double m = o.area_margin_m;
  s.area = o.area.value_or(autonomy::SurveyArea{
      {sb.origin_m.x() + m, sb.origin_m.y() + m},
      {sb.origin_m.x() + sb.extent_m.x() - m, sb.origin_m.y() + sb.extent_m.y() - m}});
  if (!(s.area.max.north_m > s.area.min.north_m) || !(s.area.max.east_m > s.area.min.east_m)) {
    throw std::invalid_argument(
        "the area margin leaves no area of the scenario's seabed to survey");
  }
  const auto& tr = sc.vehicle.trajectory;
  autonomy::AgentParams& p = s.params;
  p.vehicle.speed_m_s = o.speed_m_s.value_or(tr.speed_m_s);
  p.vehicle.max_turn_rate_rad_s = tr.max_turn_rate_rad_s;
  p.vehicle.max_vertical_rate_m_s = tr.depth.max_climb_rate_m_s;
  p.target_altitude_m = o.altitude_m.value_or(tr.depth.altitude_m);
  p.relook.turn_radius_m = p.vehicle.turn_radius_m();
  p.relook.pass_range_m = o.pass_range_m.value_or(p.relook.pass_range_m);
  p.margin_threshold = o.threshold.value_or(p.margin_threshold);
  p.relooks = o.relooks;
  p.relook_mine_relevant_only = !o.relook_all;
  p.max_relooks = o.max_relooks;
  // re-looks may use the seabed's whole extent
  p.bounds =
      autonomy::SurveyArea{{sb.origin_m.x(), sb.origin_m.y()},
                           {sb.origin_m.x() + sb.extent_m.x(), sb.origin_m.y() + sb.extent_m.y()}};
  s.survey = autonomy::lawnmower(s.area, o.line_spacing_m);
  p.relook_timing = o.relook_timing;
  p.relook_budget_s =
      o.relook_budget_fraction * autonomy::plan_length_m(s.survey) / p.vehicle.speed_m_s;
  s.start.position = s.survey.front().start;
  s.start.heading_rad = s.survey.front().heading_rad();
  s.start.depth_m = std::max(0.0, sc.scene.water.depth_m - p.target_altitude_m);
  return s;
}

}  // namespace sonarloop::mission
