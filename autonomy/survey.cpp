#include "autonomy/survey.h"

#include <cmath>
#include <stdexcept>

namespace sonarloop::autonomy {

const char* to_string(LegKind k) {
  return k == LegKind::kRelook ? "relook" : "survey";
}

std::vector<Leg> lawnmower(const SurveyArea& area, double line_spacing_m) {
  if (!(line_spacing_m > 0.0) || !std::isfinite(line_spacing_m)) {
    throw std::invalid_argument("survey: the line spacing must be > 0 m");
  }
  if (!(area.max.north_m > area.min.north_m) || !(area.max.east_m > area.min.east_m)) {
    throw std::invalid_argument("survey: the area must have a positive extent north and east");
  }
  std::vector<Leg> legs;
  double east = area.min.east_m + 0.5 * line_spacing_m;
  for (;;) {
    const double e = std::min(east, area.max.east_m);
    const bool north = legs.size() % 2 == 0;
    Leg leg;
    leg.start = {north ? area.min.north_m : area.max.north_m, e};
    leg.end = {north ? area.max.north_m : area.min.north_m, e};
    legs.push_back(leg);
    // the strip east of this line is covered up to e + spacing/2
    if (e + 0.5 * line_spacing_m >= area.max.east_m) break;
    east += line_spacing_m;
  }
  return legs;
}

double plan_length_m(const std::vector<Leg>& legs) {
  double total = 0.0;
  for (std::size_t i = 0; i < legs.size(); ++i) {
    total += legs[i].length_m();
    if (i > 0) total += distance_m(legs[i - 1].end, legs[i].start);
  }
  return total;
}

}  // namespace sonarloop::autonomy
