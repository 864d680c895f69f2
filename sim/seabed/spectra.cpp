#include "sim/seabed/spectra.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sonarloop::seabed {
namespace {

// rotate (fx, fy) (north, east) into a frame whose x' axis points along `direction_rad`
// (clockwise from north)
void rotate_to(double fx, double fy, double direction_rad, double& fxr, double& fyr) {
  const double c = std::cos(direction_rad);
  const double s = std::sin(direction_rad);
  fxr = c * fx + s * fy;
  fyr = -s * fx + c * fy;
}

}  // namespace

std::string spectrum_key(const char* family, std::initializer_list<double> params) {
  std::string key = family;
  for (const double v : params) {
    char buf[32];
    std::snprintf(buf, sizeof buf, " %.17g", v);
    key += buf;
  }
  return key;
}

double pink_psd(double fx, double fy, double beta, double outer_scale_m, double inner_scale_m) {
  const double f2 = fx * fx + fy * fy;
  if (f2 == 0.0) return 0.0;
  const double f0 = 1.0 / outer_scale_m;
  const double smooth = inner_scale_m > 0.0 ? std::exp(-f2 * inner_scale_m * inner_scale_m) : 1.0;
  return std::pow(f2 + f0 * f0, -0.5 * beta) * smooth;
}

double ripple_psd(double fx, double fy, double wavelength_m, double direction_rad, double beta1,
                  double beta, double epsilon) {
  if (fx == 0.0 && fy == 0.0) return 0.0;
  double fxr = 0.0;
  double fyr = 0.0;
  rotate_to(fx, fy, direction_rad, fxr, fyr);
  const double fx0 = 1.0 / wavelength_m;
  const double dx = std::max(std::fabs(std::fabs(fxr) - fx0), epsilon);
  const double dy = std::max(std::fabs(fyr), epsilon);
  return std::pow(dx, -beta1) * std::pow(dy, -beta);
}

double rocky_psd(double fx, double fy, double beta, double anisotropy, double direction_rad,
                 double outer_scale_m) {
  if (fx == 0.0 && fy == 0.0) return 0.0;
  double fxr = 0.0;
  double fyr = 0.0;
  rotate_to(fx, fy, direction_rad, fxr, fyr);
  const double f0 = 1.0 / outer_scale_m;
  const double u = anisotropy * fxr;
  return std::pow(u * u + fyr * fyr + f0 * f0, -0.5 * beta);
}

}  // namespace sonarloop::seabed
