#pragma once
// The survey plan of the autonomy agent (ours): a lawnmower over a rectangle of the mission frame,
// lines running north and south in turn, `line_spacing_m` apart in east, the first half a spacing
// inside the western edge. A point of the rectangle is then at most half a spacing across track
// from a line: with a spacing below the sonar's range less its nadir gap, every point is seen
// by the swath of one line or its neighbour (docs/autonomy.md).
#include <cstdint>
#include <vector>

#include "autonomy/geometry.h"

namespace sonarloop::autonomy {

// What a leg is flown for.
enum class LegKind : std::uint8_t {
  kSurvey,  // a lawnmower line (or what is left of one after a re-look)
  kRelook,  // a re-look pass: run-in, pass abeam a contact, run-out
};

const char* to_string(LegKind k);

struct Leg {
  Point2 start;
  Point2 end;
  LegKind kind = LegKind::kSurvey;
  std::uint64_t object = 0;  // kRelook: the object re-looked
  double heading_rad() const { return bearing_rad(start, end); }
  double length_m() const { return distance_m(start, end); }
};

// A rectangle of the mission frame.
struct SurveyArea {
  Point2 min;  // south-west corner
  Point2 max;  // north-east corner
  bool contains(Point2 p, double margin_m = 0.0) const {
    return p.north_m >= min.north_m - margin_m && p.north_m <= max.north_m + margin_m &&
           p.east_m >= min.east_m - margin_m && p.east_m <= max.east_m + margin_m;
  }
};

// The lawnmower over `area`: lines at east = min.east + spacing/2 + k spacing while inside the
// area (at least one, and one more when the last leaves more than half a spacing uncovered),
// the first flown northwards. Throws std::invalid_argument for an empty area or a spacing that is
// not > 0.
std::vector<Leg> lawnmower(const SurveyArea& area, double line_spacing_m);

// The survey's length: the legs and the straight transits between them.
double plan_length_m(const std::vector<Leg>& legs);

}  // namespace sonarloop::autonomy
