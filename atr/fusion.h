#pragma once
// Fusing eq. 10 distances from several chips of one object (ours): the highlight and the shadow
// chip (which Pailhas, Petillot & Capus 2010, Sec. 4.2, study apart and whose combination they
// motivate but do not try), or several looks at the object from other passes.
//
// A highlight chip (3 x 3 m) and a shadow chip (3 x 10 m) differ in pixel count, so their
// distances differ in scale (an unrelated chip lies about sqrt(n) away); each look's distances
// d_{l,c} are therefore put on a common scale before they are summed over the looks l,
//     D_c = sum_l s_l(d_{l,c}),   identified class = argmin_c D_c,
// with one of three normalisations s (FusionNorm):
//   class_typical  d / t_c, t_c the class's typical distance (the median of its own chips'
//                  cross-validated distances, ClassModel::typical_distance, set by
//                  TrainOptions::calibrate; sqrt(n) when uncalibrated);
//   model_typical  d / T, T the mean of the model's t_c: one scale per model, so each model's
//                  own ranking of the classes is kept;
//   look_zscore    (d - mean_c d) / std_c d over the classes of that look: no calibration, every
//                  look weighs the same whatever its scale.
// The choice matters: the information is in distance differences of a few per cent of the
// distance itself, so per-class scales that differ by more than that hand the decision to the
// class with the broadest scatter (docs/sweep.md measures all three).
#include <cstdint>
#include <span>

#include "atr/subspace_classifier.h"

namespace sonarloop::atr {

enum class FusionNorm : std::uint8_t { kClassTypical, kModelTypical, kLookZScore };

const char* fusion_norm_name(FusionNorm n);  // "class_typical", "model_typical", "look_zscore"

// Adds one look (a classification by model m) to the fused scores, class by class. The models
// of all looks must have the same classes in the same order (check_same_classes); `fused` holds
// one score per class and starts at 0. Throws std::invalid_argument on a size mismatch.
void add_look(const Model& m, const Classification& r, FusionNorm norm, std::span<float> fused);

// The class of smallest fused score (-1 for an empty span).
int fused_decision(std::span<const float> fused);

// Throws std::invalid_argument unless the two models have the same class names, in order.
void check_same_classes(const Model& a, const Model& b);

}  // namespace sonarloop::atr
