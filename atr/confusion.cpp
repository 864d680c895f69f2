#include "atr/confusion.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace sonarloop::atr {

Interval wilson_interval(std::size_t successes, std::size_t trials, double z) {
  if (trials == 0) return {0.0, 1.0};
  const double n = static_cast<double>(trials);
  const double p = static_cast<double>(std::min(successes, trials)) / n;
  const double z2 = z * z;
  const double denom = 1.0 + z2 / n;
  const double centre = (p + z2 / (2.0 * n)) / denom;
  const double half = z / denom * std::sqrt(p * (1.0 - p) / n + z2 / (4.0 * n * n));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

ConfusionMatrix::ConfusionMatrix(std::vector<std::string> truth_classes,
                                 std::vector<std::string> predicted_classes)
    : truth_(std::move(truth_classes)),
      predicted_(std::move(predicted_classes)),
      counts_(truth_.size() * predicted_.size(), 0) {}

void ConfusionMatrix::add(std::size_t truth, std::size_t predicted) {
  if (truth >= truth_.size() || predicted >= predicted_.size()) {
    throw std::out_of_range("ConfusionMatrix::add: class index out of range");
  }
  ++counts_[truth * predicted_.size() + predicted];
  ++total_;
}

std::size_t ConfusionMatrix::count(std::size_t truth, std::size_t predicted) const {
  return counts_.at(truth * predicted_.size() + predicted);
}

std::size_t ConfusionMatrix::row_total(std::size_t truth) const {
  std::size_t s = 0;
  for (std::size_t j = 0; j < predicted_.size(); ++j)
    s += count(truth, j);
  return s;
}

std::size_t ConfusionMatrix::correct() const {
  std::size_t s = 0;
  for (std::size_t i = 0; i < truth_.size(); ++i) {
    for (std::size_t j = 0; j < predicted_.size(); ++j) {
      if (truth_[i] == predicted_[j]) s += count(i, j);
    }
  }
  return s;
}

double ConfusionMatrix::accuracy() const {
  return total_ ? static_cast<double>(correct()) / static_cast<double>(total_) : 0.0;
}

Interval ConfusionMatrix::accuracy_interval(double z) const {
  return wilson_interval(correct(), total_, z);
}

std::string ConfusionMatrix::to_text() const {
  std::size_t label_w = std::string("truth \\ predicted").size();
  for (const auto& t : truth_)
    label_w = std::max(label_w, t.size());
  std::vector<std::size_t> col_w(predicted_.size());
  for (std::size_t j = 0; j < predicted_.size(); ++j) {
    col_w[j] = std::max<std::size_t>(predicted_[j].size(), 5);
  }
  std::string out;
  char buf[64];
  const auto pad = [&](const std::string& s, std::size_t w, bool left) {
    const std::string fill(w > s.size() ? w - s.size() : 0, ' ');
    out += left ? s + fill : fill + s;
  };
  pad("truth \\ predicted", label_w, true);
  for (std::size_t j = 0; j < predicted_.size(); ++j) {
    out += "  ";
    pad(predicted_[j], col_w[j], false);
  }
  out += "  total  recall\n";
  for (std::size_t i = 0; i < truth_.size(); ++i) {
    pad(truth_[i], label_w, true);
    std::size_t hit = 0;
    for (std::size_t j = 0; j < predicted_.size(); ++j) {
      out += "  ";
      pad(std::to_string(count(i, j)), col_w[j], false);
      if (truth_[i] == predicted_[j]) hit += count(i, j);
    }
    const std::size_t row = row_total(i);
    out += "  ";
    pad(std::to_string(row), 5, false);
    if (row) {
      std::snprintf(buf, sizeof buf, "  %5.1f%%",
                    100.0 * static_cast<double>(hit) / static_cast<double>(row));
    } else {
      std::snprintf(buf, sizeof buf, "       -");
    }
    out += buf;
    out += '\n';
  }
  return out;
}

}  // namespace sonarloop::atr
