#pragma once
// The contact gate (ours; issue 24): how likely a detection is to be a target rather than
// clutter (a rock, relief, a ripple crest), from what the onboard consumer measured of it, so
// that the contacts a vehicle receives are the targets and not the seabed.
//
// The detector (atr/detector.h) finds every object proud of the seabed: on a cluttered or rocky
// seabed most of them are rocks as tall as the targets. What tells a steel target from a rock is
// spread over several measurements: the strength of its echo above the seabed's, the depth and
// length of its shadow, its along-track extent, and how well the target classes' subspaces, and
// the clutter class's (hard negatives, atr/subspace_classifier.h ClassMetadata::clutter), explain
// its chip. The gate combines them by logistic regression (Cox 1958; e.g. Hastie, Tibshirani &
// Friedman, "The Elements of Statistical Learning", 2nd ed., Sec. 4.4):
//     p(target | x) = 1 / (1 + exp(-(b + sum_k w_k t_k(z))))
// over the terms t_k of the features standardised by their training mean m_i and spread s_i,
// z_i = (x_i - m_i) / s_i: the z_i themselves and, for the quadratic form (the default), their
// pairwise products z_i z_j (how strong an echo must be to be a target depends on the seabed
// around it). w and b are fitted by Newton's method (iteratively reweighted least squares) on the
// candidates of training surveys labelled by the truth (mission/survey_training.h), with a ridge
// penalty. A candidate is reported when p >= the gate's threshold, chosen on the training
// candidates so that a given fraction of the targets pass (a target passes when one of its
// detections does).
//
// Two stages, each optional in a model:
//   detection      the detector's features only (detection_features): applied before the chip
//                  is classified, it spares the classifier the obvious clutter (a rocky seabed
//                  gives the detector thousands of candidates per km²);
//   classification the same and the classifier's distances (classification_features): the
//                  nearest target class's distance, the clutter class's, their relative gap,
//                  and the runner-up margin among the target classes.
// The probability is also the contact's calibrated confidence (Contact::target_probability),
// for an agent that re-looks where it is unsure.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "atr/detector.h"
#include "atr/logistic_gate.h"
#include "atr/subspace_classifier.h"

namespace sonarloop::atr {

// The feature names of a stage, in order.
std::span<const char* const> gate_feature_names(GateStage s);
std::size_t gate_feature_count(GateStage s);

// The detector's features of a detection (gate_feature_names(kDetection) order), into `out`
// (resized; no allocation once it has the capacity).
void detection_features(const Detection& d, std::vector<double>& out);
// Those and the classification's (kClassification order): `r` must be a classification by
// `m` (class_index >= 0).
void classification_features(const Detection& d, const Classification& r, const Model& m,
                             std::vector<double>& out);
// The same, returned (for tests and tools).
std::vector<double> detection_features(const Detection& d);
std::vector<double> classification_features(const Detection& d, const Classification& r,
                                            const Model& m);

struct GateFitOptions {
  GateForm form = GateForm::kQuadratic;
  double ridge = 0.1;  // L2 penalty on the weights (not the bias), in standardised units
  int max_iterations = 50;
  // the threshold: the largest that keeps this fraction of the targets, each kept when at least
  // one of its detections passes (a survey sees most targets from two lines: the gate need not
  // pass every look to find every target), or of the target detections when no target ids are
  // given
  double keep_targets = 0.99;
};

// Fits a gate on labelled feature rows (label 1: target, 0: clutter); `target_ids` (empty, or
// one per row) names the target of each target row, for the threshold. Throws
// std::invalid_argument for empty or inconsistent data, or data of one label only.
LogisticGate fit_gate(GateStage stage, const std::vector<std::vector<double>>& features,
                      const std::vector<int>& labels, const GateFitOptions& options = {},
                      std::span<const std::int64_t> target_ids = {});

}  // namespace sonarloop::atr
