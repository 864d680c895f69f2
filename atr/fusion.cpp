#include "atr/fusion.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace sonarloop::atr {
namespace {

// t_c, or sqrt(feature pixels) for an uncalibrated class.
double class_scale(const Model& m, std::size_t c) {
  const float t = m.classes[c].typical_distance;
  return t > 0.0f ? t : std::sqrt(static_cast<double>(m.fused_feature_count()));
}

double model_scale(const Model& m) {
  double sum = 0.0;
  for (std::size_t c = 0; c < m.classes.size(); ++c)
    sum += class_scale(m, c);
  return sum / static_cast<double>(m.classes.size());
}

}  // namespace

const char* fusion_norm_name(FusionNorm n) {
  switch (n) {
    case FusionNorm::kClassTypical:
      return "class_typical";
    case FusionNorm::kModelTypical:
      return "model_typical";
    case FusionNorm::kLookZScore:
      return "look_zscore";
  }
  return "?";
}

void add_look(const Model& m, const Classification& r, FusionNorm norm, std::span<float> fused) {
  const std::size_t k = m.classes.size();
  if (fused.size() != k || r.class_distance.size() != k || k == 0) {
    throw std::invalid_argument("add_look: " + std::to_string(fused.size()) +
                                " fused scores for a model of " + std::to_string(k) + " classes");
  }
  double mean = 0.0, sd = 1.0;
  if (norm == FusionNorm::kLookZScore) {
    for (const float d : r.class_distance)
      mean += d;
    mean /= static_cast<double>(k);
    double ss = 0.0;
    for (const float d : r.class_distance)
      ss += (d - mean) * (d - mean);
    sd = std::sqrt(ss / static_cast<double>(k));
    if (!(sd > 0.0)) sd = 1.0;  // all classes equally far: the look adds nothing
  }
  const double t_model = norm == FusionNorm::kModelTypical ? model_scale(m) : 1.0;
  for (std::size_t c = 0; c < k; ++c) {
    const double d = r.class_distance[c];
    double s = 0.0;
    switch (norm) {
      case FusionNorm::kClassTypical:
        s = d / class_scale(m, c);
        break;
      case FusionNorm::kModelTypical:
        s = d / t_model;
        break;
      case FusionNorm::kLookZScore:
        s = (d - mean) / sd;
        break;
    }
    fused[c] += static_cast<float>(s);
  }
}

int fused_decision(std::span<const float> fused) {
  int best = -1;
  for (std::size_t i = 0; i < fused.size(); ++i) {
    if (best < 0 || fused[i] < fused[static_cast<std::size_t>(best)]) best = static_cast<int>(i);
  }
  return best;
}

void check_same_classes(const Model& a, const Model& b) {
  bool same = a.classes.size() == b.classes.size();
  for (std::size_t i = 0; same && i < a.classes.size(); ++i)
    same = a.classes[i].name == b.classes[i].name;
  if (!same) {
    const auto list = [](const Model& m) {
      std::string s;
      for (const auto& c : m.classes)
        s += (s.empty() ? "" : ", ") + c.name;
      return s;
    };
    throw std::invalid_argument("fusion: the models' classes differ (" + list(a) + " against " +
                                list(b) + ")");
  }
}

}  // namespace sonarloop::atr
