#pragma once
// Scoring a classifier against the truth: a confusion matrix and the accuracy with its Wilson
// score interval.
#include <cstddef>
#include <string>
#include <vector>

namespace sonarloop::atr {

// The standard normal quantile for a two-sided 95 % interval, Phi^-1(0.975).
inline constexpr double kZ95 = 1.959963984540054;

struct Interval {
  double lo = 0.0;
  double hi = 1.0;
};

// The Wilson score interval for a binomial proportion (E. B. Wilson, "Probable inference, the
// law of succession, and statistical inference", J. Am. Stat. Assoc. 22 (1927) 209-212):
//   centre = (x/n + z^2/(2n)) / (1 + z^2/n)
//   half   = z / (1 + z^2/n) * sqrt( x/n (1 - x/n) / n + z^2 / (4 n^2) )
// for x successes in n trials. Unlike the normal (Wald) interval it stays inside [0, 1] and is
// not empty at x = 0 or x = n. n = 0 gives [0, 1].
Interval wilson_interval(std::size_t successes, std::size_t trials, double z = kZ95);

// Counts of (true class, predicted class). Truth and prediction lists may differ (a test folder
// may hold classes the model does not know); a prediction is correct when the names are equal.
class ConfusionMatrix {
 public:
  ConfusionMatrix(std::vector<std::string> truth_classes,
                  std::vector<std::string> predicted_classes);

  void add(std::size_t truth, std::size_t predicted);

  const std::vector<std::string>& truth_classes() const { return truth_; }
  const std::vector<std::string>& predicted_classes() const { return predicted_; }
  std::size_t count(std::size_t truth, std::size_t predicted) const;
  std::size_t row_total(std::size_t truth) const;
  std::size_t total() const { return total_; }
  std::size_t correct() const;
  double accuracy() const;  // correct / total (0 when empty)
  Interval accuracy_interval(double z = kZ95) const;

  // An aligned text table: rows are the truth, columns the prediction, with row totals and the
  // per-class recall.
  std::string to_text() const;

 private:
  std::vector<std::string> truth_;
  std::vector<std::string> predicted_;
  std::vector<std::size_t> counts_;  // (truth x predicted)
  std::size_t total_ = 0;
};

}  // namespace sonarloop::atr
