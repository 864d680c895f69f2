#include "atr/look_fusion.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "atr/fusion.h"

namespace sonarloop::atr {

LookFusion::LookFusion(double radius_m) : radius_m_(radius_m) {
  if (!(radius_m > 0.0 && std::isfinite(radius_m))) {
    throw std::invalid_argument("look fusion: the association radius must be positive, not " +
                                std::to_string(radius_m));
  }
}

const FusedObject& LookFusion::add(std::uint64_t contact_id, double north_m, double east_m,
                                   const Model& m, const Classification& r) {
  FusedObject* best = nullptr;
  double best_d2 = radius_m_ * radius_m_;
  for (FusedObject& o : objects_) {
    const double dn = o.north_m - north_m, de = o.east_m - east_m;
    const double d2 = dn * dn + de * de;
    if (d2 <= best_d2 && o.fused.size() == m.classes.size()) {
      best = &o;
      best_d2 = d2;
    }
  }
  if (!best) {
    objects_.push_back(FusedObject{contact_id, north_m, east_m,
                                   std::vector<float>(m.classes.size(), 0.0f), 0, -1});
    best = &objects_.back();
  }
  FusedObject& o = *best;
  add_look(m, r, FusionNorm::kModelTypical, o.fused);
  // the running mean of the looks' positions
  o.north_m += (north_m - o.north_m) / (o.looks + 1);
  o.east_m += (east_m - o.east_m) / (o.looks + 1);
  ++o.looks;
  // the fused class among the target classes (a clutter class is never a contact's class)
  int best_class = -1;
  for (std::size_t i = 0; i < o.fused.size(); ++i) {
    if (m.classes[i].clutter) continue;
    if (best_class < 0 || o.fused[i] < o.fused[static_cast<std::size_t>(best_class)])
      best_class = static_cast<int>(i);
  }
  o.class_index = best_class >= 0 ? best_class : fused_decision(o.fused);
  return o;
}

}  // namespace sonarloop::atr
