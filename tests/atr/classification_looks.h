#pragma once
// One look at an object for the fusion tests: a classification carrying only its per-class
// distances.
#include <utility>
#include <vector>

#include "atr/subspace_classifier.h"

namespace sonarloop::testing {

inline atr::Classification look(std::vector<float> class_distance) {
  atr::Classification r;
  r.class_distance = std::move(class_distance);
  return r;
}

}  // namespace sonarloop::testing
