#include "atr/contact_gate.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

namespace sonarloop::atr {
namespace {

// The classification stage's features: the detection stage's, then four of the classifier.
constexpr const char* kClassificationFeatures[] = {
    "height_m", "highlight_db", "highlight_above_db", "shadow_below_db", "log_pings",
    "along_extent_m", "log_shadow_area_m2", "ground_m", "log_highlight_area_m2",
    "highlight_mean_above_db", "log_clutter_hits_per_m",
    // the classifier's
    "target_distance", "clutter_distance", "clutter_gap", "target_margin"};
constexpr std::size_t kDetectionFeatureCount = 11;
// the classification stage adds its four to the detection stage's
static_assert(std::size(kClassificationFeatures) == kDetectionFeatureCount + 4);
// A spread below this (in the feature's units) is a constant feature: it is left out (weight 0)
// rather than divided by ~0.
constexpr double kMinScale = 1e-9;
// Shadow areas below this (m²) are taken as this in the log.
constexpr double kMinShadowArea_m2 = 1e-3;

double sigmoid(double z) {
  return z >= 0.0 ? 1.0 / (1.0 + std::exp(-z)) : std::exp(z) / (1.0 + std::exp(z));
}

}  // namespace

const char* gate_stage_name(GateStage s) {
  return s == GateStage::kDetection ? "detection" : "classification";
}

std::span<const char* const> gate_feature_names(GateStage s) {
  const std::span<const char* const> all = kClassificationFeatures;
  return s == GateStage::kDetection ? all.first(kDetectionFeatureCount) : all;
}

std::size_t gate_feature_count(GateStage s) {
  return gate_feature_names(s).size();
}

void detection_features(const Detection& d, std::vector<double>& x) {
  x.resize(kDetectionFeatureCount);
  x[0] = d.height_m;
  x[1] = d.highlight_db;
  x[2] = d.highlight_above_db;
  x[3] = d.shadow_below_db;
  x[4] = std::log(static_cast<double>(std::max(1, d.pings)));
  x[5] = d.along_extent_m;
  x[6] = std::log(std::max(d.shadow_area_m2, kMinShadowArea_m2));
  x[7] = d.ground_m;
  x[8] = std::log(std::max(d.highlight_area_m2, kMinShadowArea_m2));
  x[9] = d.highlight_mean_above_db;
  // a window without any hit but this object's own: 0.1 per metre at least
  x[10] = std::log(std::max(d.clutter_hits_per_m, 0.1));
}

std::vector<double> detection_features(const Detection& d) {
  std::vector<double> x;
  detection_features(d, x);
  return x;
}

std::vector<double> classification_features(const Detection& d, const Classification& r,
                                            const Model& m) {
  std::vector<double> x;
  classification_features(d, r, m, x);
  return x;
}

void classification_features(const Detection& d, const Classification& r, const Model& m,
                             std::vector<double>& x) {
  detection_features(d, x);
  double d1 = std::numeric_limits<double>::infinity(), d2 = d1, dc = d1;
  for (std::size_t i = 0; i < m.classes.size() && i < r.class_distance.size(); ++i) {
    const double v = r.class_distance[i];
    if (m.classes[i].clutter) {
      dc = std::min(dc, v);
    } else if (v < d1) {
      d2 = d1;
      d1 = v;
    } else if (v < d2) {
      d2 = v;
    }
  }
  const double root_n =
      std::sqrt(static_cast<double>(std::max<std::size_t>(1, m.fused_feature_count())));
  if (!std::isfinite(d1)) d1 = root_n;  // no target class: as far as an unrelated chip
  if (!std::isfinite(dc)) dc = d1;      // no clutter class: no gap
  if (!std::isfinite(d2)) d2 = d1;
  const double denom = std::max(d1, 1e-9);
  x.resize(std::size(kClassificationFeatures));
  const std::size_t n = kDetectionFeatureCount;
  x[n] = d1 / root_n;
  x[n + 1] = dc / root_n;
  x[n + 2] = (dc - d1) / denom;
  x[n + 3] = (d2 - d1) / denom;
}

std::size_t gate_term_count(std::size_t n, GateForm form) {
  return form == GateForm::kLinear ? n : n + n * (n + 1) / 2;
}

namespace {

// The terms of standardised features z into t (gate_term_count entries).
void gate_terms(std::span<const double> z, GateForm form, std::span<double> t) {
  const std::size_t n = z.size();
  std::copy(z.begin(), z.end(), t.begin());
  if (form == GateForm::kLinear) return;
  std::size_t k = n;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j)
      t[k++] = z[i] * z[j];
}

}  // namespace

double LogisticGate::probability(std::span<const double> x) const {
  const std::size_t n = std::min({x.size(), mean.size(), scale.size()});
  double z = bias;
  if (form == GateForm::kLinear) {
    for (std::size_t i = 0; i < n && i < weights.size(); ++i)
      z += weights[i] * (x[i] - mean[i]) / scale[i];
    return sigmoid(z);
  }
  // quadratic: the linear terms, then the products (no allocation: the products on the fly)
  std::size_t k = n;
  for (std::size_t i = 0; i < n; ++i) {
    const double zi = (x[i] - mean[i]) / scale[i];
    if (i < weights.size()) z += weights[i] * zi;
    for (std::size_t j = i; j < n; ++j, ++k) {
      const double zj = (x[j] - mean[j]) / scale[j];
      if (k < weights.size()) z += weights[k] * zi * zj;
    }
  }
  return sigmoid(z);
}

void validate_gate(const LogisticGate& g) {
  const std::size_t n = gate_feature_count(g.stage);
  if (g.form != GateForm::kLinear && g.form != GateForm::kQuadratic) {
    throw std::runtime_error("contact gate: unknown form");
  }
  if (g.mean.size() != n || g.scale.size() != n || g.weights.size() != gate_term_count(n, g.form)) {
    throw std::runtime_error(std::string("contact gate (") + gate_stage_name(g.stage) +
                             "): " + std::to_string(g.weights.size()) + " weights, " +
                             std::to_string(g.mean.size()) + " means, " +
                             std::to_string(g.scale.size()) + " scales for " + std::to_string(n) +
                             " features");
  }
  for (const double w : g.weights)
    if (!std::isfinite(w)) throw std::runtime_error("contact gate: a non-finite weight");
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(g.mean[i]) || !(g.scale[i] > 0.0) || !std::isfinite(g.scale[i])) {
      throw std::runtime_error(std::string("contact gate (") + gate_stage_name(g.stage) +
                               "): feature '" + gate_feature_names(g.stage)[i] +
                               "' has a non-finite mean or weight or a scale not > 0");
    }
  }
  if (!std::isfinite(g.bias)) throw std::runtime_error("contact gate: non-finite bias");
  if (!(g.threshold >= 0.0 && g.threshold <= 1.0)) {
    throw std::runtime_error("contact gate: threshold " + std::to_string(g.threshold) +
                             " outside [0, 1]");
  }
}

LogisticGate fit_gate(GateStage stage, const std::vector<std::vector<double>>& features,
                      const std::vector<int>& labels, const GateFitOptions& o,
                      std::span<const std::int64_t> target_ids) {
  const std::size_t n = gate_feature_count(stage);
  const std::size_t rows = features.size();
  if (rows == 0 || labels.size() != rows) {
    throw std::invalid_argument("fit_gate: " + std::to_string(rows) + " feature rows and " +
                                std::to_string(labels.size()) + " labels");
  }
  std::size_t positives = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    if (features[r].size() != n) {
      throw std::invalid_argument("fit_gate: row " + std::to_string(r) + " has " +
                                  std::to_string(features[r].size()) + " features, the " +
                                  gate_stage_name(stage) + " stage has " + std::to_string(n));
    }
    for (const double v : features[r])
      if (!std::isfinite(v)) throw std::invalid_argument("fit_gate: a non-finite feature");
    if (labels[r] != 0 && labels[r] != 1) throw std::invalid_argument("fit_gate: labels are 0/1");
    positives += static_cast<std::size_t>(labels[r]);
  }
  if (positives == 0 || positives == rows) {
    throw std::invalid_argument("fit_gate: the training candidates are all of one label (" +
                                std::to_string(positives) + " targets of " + std::to_string(rows) +
                                ")");
  }
  if (!target_ids.empty() && target_ids.size() != rows) {
    throw std::invalid_argument("fit_gate: " + std::to_string(target_ids.size()) +
                                " target ids for " + std::to_string(rows) + " rows");
  }
  if (!(o.keep_targets > 0.0 && o.keep_targets <= 1.0) || !(o.ridge >= 0.0)) {
    throw std::invalid_argument("fit_gate: keep_targets must be in (0, 1], ridge >= 0");
  }
  LogisticGate g;
  g.stage = stage;
  g.form = o.form;
  g.mean.assign(n, 0.0);
  g.scale.assign(n, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    double s = 0.0, ss = 0.0;
    for (const auto& x : features) {
      s += x[i];
      ss += x[i] * x[i];
    }
    const double count = static_cast<double>(rows);
    const double mean = s / count;
    const double var = std::max(0.0, ss / count - mean * mean);
    g.mean[i] = mean;
    g.scale[i] = std::sqrt(var) > kMinScale ? std::sqrt(var) : 1.0;
  }
  // Newton / IRLS on the terms of the standardised features, the bias in the last column
  const std::size_t terms = gate_term_count(n, g.form);
  const auto cols = static_cast<Eigen::Index>(terms + 1);
  Eigen::MatrixXd z(static_cast<Eigen::Index>(rows), cols);
  Eigen::VectorXd y(static_cast<Eigen::Index>(rows));
  std::vector<double> zs(n), t(terms);
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t i = 0; i < n; ++i)
      zs[i] = (features[r][i] - g.mean[i]) / g.scale[i];
    gate_terms(zs, g.form, t);
    for (std::size_t k = 0; k < terms; ++k)
      z(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k)) = t[k];
    z(static_cast<Eigen::Index>(r), cols - 1) = 1.0;
    y(static_cast<Eigen::Index>(r)) = labels[r];
  }
  Eigen::VectorXd w = Eigen::VectorXd::Zero(cols);
  Eigen::VectorXd penalty = Eigen::VectorXd::Constant(cols, o.ridge);
  penalty(cols - 1) = 0.0;
  // a tiny penalty on the bias too keeps the Hessian invertible when the classes separate
  penalty(cols - 1) = 1e-9;
  for (int it = 0; it < o.max_iterations; ++it) {
    const Eigen::VectorXd eta = z * w;
    Eigen::VectorXd p(eta.size()), wt(eta.size());
    for (Eigen::Index r = 0; r < eta.size(); ++r) {
      p(r) = sigmoid(eta(r));
      wt(r) = std::max(p(r) * (1.0 - p(r)), 1e-12);
    }
    const Eigen::VectorXd grad = z.transpose() * (p - y) + penalty.cwiseProduct(w);
    Eigen::MatrixXd h = z.transpose() * wt.asDiagonal() * z;
    h.diagonal() += penalty;
    const Eigen::VectorXd step = h.ldlt().solve(grad);
    w -= step;
    if (step.norm() < 1e-10 * (1.0 + w.norm())) break;
  }
  g.weights.assign(w.data(), w.data() + terms);
  g.bias = w(cols - 1);
  // the threshold: keep keep_targets of the targets (their best detection) or of the target rows
  std::vector<double> target_p;
  if (target_ids.empty()) {
    for (std::size_t r = 0; r < rows; ++r)
      if (labels[r] == 1) target_p.push_back(g.probability(features[r]));
  } else {
    std::map<std::int64_t, double> best;
    for (std::size_t r = 0; r < rows; ++r) {
      if (labels[r] != 1) continue;
      const double p = g.probability(features[r]);
      auto [it, added] = best.try_emplace(target_ids[r], p);
      if (!added) it->second = std::max(it->second, p);
    }
    for (const auto& [id, p] : best)
      target_p.push_back(p);
  }
  std::sort(target_p.begin(), target_p.end());
  const auto drop = static_cast<std::size_t>(
      std::floor((1.0 - o.keep_targets) * static_cast<double>(target_p.size())));
  g.threshold = drop == 0 ? std::max(0.0, target_p.front() - 1e-12) : target_p[drop];
  g.threshold = std::clamp(g.threshold, 0.0, 1.0);
  validate_gate(g);
  return g;
}

}  // namespace sonarloop::atr
