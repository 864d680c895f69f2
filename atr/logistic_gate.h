#pragma once
// A logistic gate's parameters (atr/contact_gate.h says what it is for and how it is trained):
// plain data, held by a model (atr/subspace_classifier.h Model) and stored in its file.
#include <cstdint>
#include <span>
#include <vector>

namespace sonarloop::atr {

enum class GateStage : std::uint8_t { kDetection = 0, kClassification = 1 };
const char* gate_stage_name(GateStage s);

// The gate's terms in its standardised features z_i = (x_i - mean_i) / scale_i: linear (the z_i)
// or quadratic (the z_i, then every product z_i z_j, i <= j, in the order i = 0.., j = i..).
enum class GateForm : std::uint8_t { kLinear = 0, kQuadratic = 1 };

// How many terms a gate of `features` features and `form` has.
std::size_t gate_term_count(std::size_t features, GateForm form);

struct LogisticGate {
  GateStage stage = GateStage::kDetection;
  GateForm form = GateForm::kLinear;
  std::vector<double> mean, scale;  // per feature: standardisation
  std::vector<double> weights;      // per term (gate_term_count)
  double bias = 0.0;
  double threshold = 0.5;  // a candidate passes when p >= threshold

  double probability(std::span<const double> features) const;
  bool passes(std::span<const double> features) const { return probability(features) >= threshold; }
};

// Throws std::runtime_error naming what is wrong: sizes against the stage, non-finite values,
// scales not > 0, a threshold outside [0, 1].
void validate_gate(const LogisticGate& g);

}  // namespace sonarloop::atr
