#pragma once
// Synthetic chips with a known answer, for the classifier tests.
//
// Linear classes: class c is a random mean pattern m_c plus a random 3-dimensional subspace B_c
// (both with zero pixel-mean); a chip is  offset + gain * (m_c + B_c a + noise * e)  with
// a, e ~ N(0, 1). Normalisation (eq. 9) removes gain and offset, so without noise the normalised
// chips of class c lie exactly in span(m_c, B_c) (4 dimensions): a subspace of p >= 4 trained on
// them leaves a zero residual for every chip of the class.
//
// Rotated shapes: line drawings (sums of blurred segments) rotated by an aspect angle, whose
// appearance changes with the angle, for the multi-aspect tests.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "atr/chip.h"
#include "atr/subspace_classifier.h"
#include "common/rng.h"

namespace sonarloop::testing {

struct LinearClasses {
  int width = 0;
  int height = 0;
  std::vector<Eigen::VectorXd> mean;   // (n) per class
  std::vector<Eigen::MatrixXd> basis;  // (n x dim) per class
};

inline Eigen::VectorXd random_pattern(Rng& rng, Eigen::Index n) {
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i)
    v[i] = rng.normal();
  v.array() -= v.mean();
  return v;
}

inline LinearClasses make_linear_classes(int classes, int width, int height, int dim,
                                         std::uint64_t seed) {
  LinearClasses lc;
  lc.width = width;
  lc.height = height;
  const Eigen::Index n = static_cast<Eigen::Index>(width) * height;
  Rng rng(seed, RngStream::kTraining, 1);
  for (int c = 0; c < classes; ++c) {
    lc.mean.push_back(random_pattern(rng, n));
    Eigen::MatrixXd b(n, dim);
    for (int j = 0; j < dim; ++j)
      b.col(j) = random_pattern(rng, n);
    lc.basis.push_back(b);
  }
  return lc;
}

inline atr::Chip sample_linear(const LinearClasses& lc, int c, Rng& rng, double noise,
                               double gain = 1.0, double offset = 0.0) {
  const auto& b = lc.basis[static_cast<std::size_t>(c)];
  Eigen::VectorXd a(b.cols());
  for (Eigen::Index j = 0; j < a.size(); ++j)
    a[j] = rng.normal();
  Eigen::VectorXd x = lc.mean[static_cast<std::size_t>(c)] + b * a;
  for (Eigen::Index i = 0; i < x.size(); ++i)
    x[i] += noise * rng.normal();
  atr::Chip chip;
  chip.width = lc.width;
  chip.height = lc.height;
  chip.pixels.resize(static_cast<std::size_t>(x.size()));
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    chip.pixels[static_cast<std::size_t>(i)] = static_cast<float>(offset + gain * x[i]);
  }
  return chip;
}

// Linear-class chips scaled into 0..255 (for PNG files): offset 128, gain to fit.
inline std::vector<std::uint8_t> to_gray8(const atr::Chip& chip) {
  float lo = chip.pixels[0], hi = chip.pixels[0];
  for (float v : chip.pixels) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  std::vector<std::uint8_t> out(chip.pixels.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double u = (chip.pixels[i] - lo) / std::max(1e-12f, hi - lo);
    out[i] = static_cast<std::uint8_t>(std::lround(10.0 + 235.0 * u));
  }
  return out;
}

// A segment from (x0, y0) to (x1, y1) in shape units (the shape spans about -1..1).
struct Segment {
  double x0, y0, x1, y1;
};

// Three line drawings that look alike at some aspects: a bar, the bar with a short leg at one
// end (an "L") and the bar with a short stem in the middle (a "T").
inline std::vector<std::vector<Segment>> rotation_shapes() {
  return {
      {{-0.8, 0.0, 0.8, 0.0}},
      {{-0.8, -0.1, 0.8, -0.1}, {-0.8, -0.1, -0.8, 0.25}},
      {{-0.8, 0.0, 0.8, 0.0}, {0.0, 0.0, 0.0, 0.25}},
  };
}

// The shape rotated by aspect_deg, drawn into a size x size chip with blurred strokes, plus
// noise.
inline atr::Chip draw_rotated(const std::vector<Segment>& shape, double aspect_deg, int size,
                              Rng& rng, double noise) {
  const double th = aspect_deg * std::numbers::pi / 180.0;
  const double c = std::cos(th), s = std::sin(th);
  const double half = 0.5 * (size - 1);
  const double scale = 0.45 * size;  // shape units to pixels
  const double sigma_px = 0.9;       // stroke blur
  atr::Chip chip;
  chip.width = size;
  chip.height = size;
  chip.pixels.assign(static_cast<std::size_t>(size) * size, 0.0f);
  for (int r = 0; r < size; ++r) {
    for (int col = 0; col < size; ++col) {
      double v = 0.0;
      for (const auto& seg : shape) {
        const double ax = half + scale * (c * seg.x0 - s * seg.y0);
        const double ay = half + scale * (s * seg.x0 + c * seg.y0);
        const double bx = half + scale * (c * seg.x1 - s * seg.y1);
        const double by = half + scale * (s * seg.x1 + c * seg.y1);
        const double dx = bx - ax, dy = by - ay;
        const double t =
            std::clamp(((col - ax) * dx + (r - ay) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
        const double ex = col - (ax + t * dx), ey = r - (ay + t * dy);
        v = std::max(v, std::exp(-(ex * ex + ey * ey) / (2.0 * sigma_px * sigma_px)));
      }
      chip.pixels[static_cast<std::size_t>(r) * size + col] =
          static_cast<float>(v + noise * rng.normal());
    }
  }
  return chip;
}

// A small two-class model ("a", "b"; 8 x 6 chips, p = 4; no gates, no clutter class): every
// object the onboard pipeline sees with it is classified and reported.
inline atr::Model small_two_class_model() {
  const auto lc = make_linear_classes(2, 8, 6, 3, 77);
  std::vector<atr::LabelledChip> chips;
  Rng rng(3, RngStream::kTraining, 4);
  for (int c = 0; c < 2; ++c) {
    for (int i = 0; i < 12; ++i)
      chips.push_back({sample_linear(lc, c, rng, 0.2), c ? "b" : "a", std::nullopt, ""});
  }
  atr::TrainOptions train;
  train.p = 4;
  return atr::train_model(chips, train);
}

}  // namespace sonarloop::testing
