// Training (atr/subspace_training.cpp): the covariance route for classes with more chips than
// pixels agrees with the Gram route; chips read one at a time through a loader give the same
// model as chips in memory; unreadable chips are skipped with a reason, or stop training.
#include <catch2/catch.hpp>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "atr/subspace_classifier.h"
#include "tests/atr/synthetic_chips.h"

using namespace sonarloop;
using namespace sonarloop::atr;

namespace {

// k chips of a rank-3 class with noise, as normalised columns (n x k), in float.
Eigen::MatrixXf normalised_columns(int w, int h, int k, std::uint64_t seed) {
  const auto lc = testing::make_linear_classes(1, w, h, 3, seed);
  Rng rng(seed, RngStream::kTraining, 3);
  Eigen::MatrixXf x(w * h, k);
  for (int j = 0; j < k; ++j) {
    const Chip c = testing::sample_linear(lc, 0, rng, 0.2);
    REQUIRE(normalise_chip(c.view(), std::span<float>(x.col(j).data(), c.pixels.size())).ok());
  }
  return x;
}

// The projector U U^T of a subspace, in double.
Eigen::MatrixXd projector(const Subspace& s) {
  const Eigen::MatrixXd u = s.basis.cast<double>();
  return u * u.transpose();
}

std::vector<LabelledChip> two_classes(int per_class) {
  const auto lc = testing::make_linear_classes(2, 8, 6, 2, 41);
  Rng rng(5, RngStream::kTraining, 4);
  std::vector<LabelledChip> out;
  for (int c = 0; c < 2; ++c) {
    for (int i = 0; i < per_class; ++i) {
      LabelledChip l;
      l.chip = testing::sample_linear(lc, c, rng, 0.1);
      l.label.assign(1, c == 0 ? 'a' : 'b');
      char source[32];
      std::snprintf(source, sizeof source, "%s/%d.png", l.label.c_str(), i);
      l.source = source;
      out.push_back(std::move(l));
    }
  }
  return out;
}

}  // namespace

TEST_CASE("subspace training: more chips than pixels, the covariance route equals the Gram route") {
  // 4 x 4 chips (n = 16), 60 of them: k > n takes the covariance route
  const Eigen::MatrixXf x = normalised_columns(4, 4, 60, 17);
  std::vector<Eigen::Index> all(60);
  std::iota(all.begin(), all.end(), Eigen::Index{0});
  const Subspace cov = fit_subspace(x, all, 5);
  // the Gram route on the same data (k x k = 60 x 60), written out here
  const Eigen::MatrixXd xd = x.cast<double>();
  const Eigen::VectorXd mu = xd.rowwise().mean();
  const Eigen::MatrixXd a = xd.colwise() - mu;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(a.transpose() * a);
  REQUIRE(cov.rank() == 5);
  for (int j = 0; j < 5; ++j)
    CHECK(cov.eigenvalues[j] == Approx(eig.eigenvalues()[59 - j]).epsilon(1e-9));
  Eigen::MatrixXd u(16, 5);
  for (int j = 0; j < 5; ++j)
    u.col(j) = (a * eig.eigenvectors().col(59 - j)).normalized();
  CHECK((projector(cov) - u * u.transpose()).cwiseAbs().maxCoeff() < 1e-5);
  CHECK((cov.mean.cast<double>() - mu).cwiseAbs().maxCoeff() < 1e-6);
  CHECK(cov.train_count == 60);
  // the double overload takes the same route for the same data
  const Subspace cov_d = fit_subspace(xd, 5);
  CHECK((projector(cov_d) - projector(cov)).cwiseAbs().maxCoeff() < 1e-6);
  // a subset of columns: the same as those columns alone
  const std::vector<Eigen::Index> some = {1, 3, 5, 7, 9, 11, 13};
  const Eigen::MatrixXd xs = xd(Eigen::all, some);
  const Subspace sub = fit_subspace(x, some, 5);
  const Subspace ref = fit_subspace(xs, 5);
  CHECK((projector(sub) - projector(ref)).cwiseAbs().maxCoeff() < 1e-6);
  // rank is capped at the data: 3 directions plus noise; p = 40 > n keeps at most n
  CHECK(fit_subspace(x, all, 40).rank() <= 16);
}

TEST_CASE("subspace training: a loader gives the model of chips in memory") {
  const std::vector<LabelledChip> chips = two_classes(12);
  const Model in_memory = train_model(chips);
  std::vector<LabelledChip> listed = chips;
  for (auto& c : listed)
    c.chip = {};  // labels only
  std::size_t calls = 0;
  Chip buffer;
  const ChipLoader load = [&](std::size_t i) {
    ++calls;
    buffer = chips[i].chip;
    return buffer.view();
  };
  std::vector<std::string> stages;
  TrainOptions opt;
  opt.progress = [&](std::string_view s, std::size_t, std::size_t) {
    if (stages.empty() || stages.back() != s) stages.emplace_back(s);
  };
  const Model streamed = train_model(listed, load, opt);
  CHECK(calls == chips.size());
  CHECK(stages == std::vector<std::string>{"reading chips", "fitting subspaces"});
  REQUIRE(streamed.classes.size() == 2);
  for (std::size_t c = 0; c < 2; ++c) {
    const Subspace& a = in_memory.classes[c].subspaces[0];
    const Subspace& b = streamed.classes[c].subspaces[0];
    CHECK(a.mean == b.mean);
    CHECK(a.basis == b.basis);
  }
}

TEST_CASE("subspace training: unreadable and wrong-size chips are skipped one by one, or stop") {
  std::vector<LabelledChip> chips = two_classes(8);
  chips[0].chip = {};       // the first chip cannot be read: the next sets the size
  chips[3].chip.width = 6;  // wrong size: 6 x 8 pixels
  chips[3].chip.height = 8;
  chips[9].chip.pixels.assign(chips[9].chip.pixels.size(), 5.0f);  // constant
  const ChipLoader load = [&](std::size_t i) {
    if (chips[i].chip.pixels.empty()) throw std::runtime_error("not a PNG or JPEG image");
    return chips[i].chip.view();
  };
  TrainOptions opt;
  opt.skip_degenerate = true;
  TrainReport report;
  const Model m = train_model(chips, load, opt, &report);
  REQUIRE(report.skipped.size() == 3);
  CHECK(report.skipped[0].source == "a/0.png");
  CHECK_THAT(report.skipped[0].reason, Catch::Contains("not a PNG"));
  CHECK(report.skipped[1].source == "a/3.png");
  CHECK_THAT(report.skipped[1].reason, Catch::Contains("6 x 8") && Catch::Contains("a/1.png"));
  CHECK(report.skipped[2].source == "b/1.png");
  CHECK_THAT(report.skipped[2].reason, Catch::Contains("constant"));
  CHECK(m.chip_width == 8);
  CHECK(m.classes[0].subspaces[0].train_count == 6);
  CHECK(m.classes[1].subspaces[0].train_count == 7);
  // without skipping, the first bad chip stops training, named
  CHECK_THROWS_WITH(train_model(chips, load, TrainOptions{}),
                    Catch::Contains("a/0.png") && Catch::Contains("not a PNG"));
}
