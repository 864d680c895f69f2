#pragma once
// Multi-look fusion in the onboard consumer (ours; issue 9, Sec. 3): when an object is seen again
// (another pass, another aspect), its looks' eq. 10 distances are combined and the fused
// decision reported with the number of looks it used.
//
// Association: a classified contact joins the nearest known object within radius_m (in the
// stream's north / east metres) whose side of the track does not matter (a re-look from the
// other side is the point); otherwise it starts a new object. The navigation's position error
// and the detector's centre set the radius: 2 m by default, more than the onboard position
// error measured on the emulator's stream (docs), less than the spacing of distinct targets
// the scenarios lay out.
//
// Fusion: atr/fusion.h, with one scale per model (FusionNorm::kModelTypical): D_c = sum over the
// looks of d_c / T. The fused class is argmin D_c, its mine-likeness the class's.
#include <cstdint>
#include <string>
#include <vector>

#include "atr/subspace_classifier.h"

namespace sonarloop::atr {

inline constexpr double kDefaultLookRadius_m = 2.0;

struct FusedObject {
  std::uint64_t id = 0;                // the contact id of its first look
  double north_m = 0.0, east_m = 0.0;  // the mean position of its looks
  std::vector<float> fused;            // (classes) D_c
  int looks = 0;
  int class_index = -1;  // argmin D_c
};

class LookFusion {
 public:
  // radius_m > 0 (std::invalid_argument otherwise).
  explicit LookFusion(double radius_m = kDefaultLookRadius_m);

  // Adds one classified look of contact `contact_id` at (north, east): joins the nearest object
  // within the radius or starts one. Returns that object (valid until the next call).
  const FusedObject& add(std::uint64_t contact_id, double north_m, double east_m, const Model& m,
                         const Classification& r);

  const std::vector<FusedObject>& objects() const { return objects_; }

 private:
  double radius_m_;
  std::vector<FusedObject> objects_;
};

}  // namespace sonarloop::atr
