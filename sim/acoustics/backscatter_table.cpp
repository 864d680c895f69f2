#include "sim/acoustics/backscatter_table.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "sim/acoustics/bottom_backscatter_apl.h"

namespace sonarloop::acoustics {

BackscatterTable::BackscatterTable(const std::function<double(double)>& sigma_linear,
                                   double step_rad)
    : step_rad_(step_rad), inv_step_(0.0), last_index_(0.0) {
  constexpr double kHalfPi = std::numbers::pi / 2.0;
  if (!(step_rad > 0.0) || step_rad > kHalfPi) {
    throw std::invalid_argument("BackscatterTable: step " + std::to_string(step_rad) +
                                " rad must be in (0, pi/2]");
  }
  // whole number of intervals; the step is shrunk slightly so that the last point is π/2
  const auto intervals = static_cast<std::size_t>(std::ceil(kHalfPi / step_rad - 1e-9));
  step_rad_ = kHalfPi / static_cast<double>(intervals);
  inv_step_ = 1.0 / step_rad_;
  last_index_ = static_cast<double>(intervals);
  values_.resize(intervals + 2);
  for (std::size_t i = 0; i <= intervals; ++i) {
    const double th = i == intervals ? kHalfPi : static_cast<double>(i) * step_rad_;
    const double v = sigma_linear(th);
    if (!(std::isfinite(v) && v >= 0.0)) {
      throw std::invalid_argument("BackscatterTable: cross section at grazing " +
                                  std::to_string(th) + " rad is " + std::to_string(v) +
                                  "; it must be finite and >= 0");
    }
    values_[i] = v;
  }
  values_[intervals + 1] = values_[intervals];
}

double BackscatterTable::sigma_db(double grazing_rad) const {
  return 10.0 * std::log10(sigma(grazing_rad));
}

BackscatterTable make_backscatter_table(seabed::SedimentId id, double freq_hz, BottomModel model,
                                        double c1_m_s, double lambert_mu_db, double step_rad) {
  switch (model) {
    case BottomModel::kApl: {
      const AplBackscatterSetup setup =
          make_apl_backscatter_setup(freq_hz, apl_sediment(id), c1_m_s);
      return BackscatterTable([&setup](double th) { return apl_backscatter_linear(th, setup); },
                              step_rad);
    }
    case BottomModel::kLambert: {
      const double mu = std::pow(10.0, lambert_mu_db / 10.0);
      return BackscatterTable([mu](double th) { return lambert_backscatter_linear(th, mu); },
                              step_rad);
    }
  }
  throw std::invalid_argument("make_backscatter_table: unknown bottom model " +
                              std::to_string(static_cast<int>(model)));
}

}  // namespace sonarloop::acoustics
