// Training of the eigen-subspace classifier (atr/subspace_classifier.h): chips in, Model out.
//
// Memory. The training set is held once, as its normalised (pre-processed) chips in one float
// matrix of n x k values (n features, k chips: 4 bytes a pixel; 819 MB for 50,000 chips of
// 64 x 64); chips are read one at a time through the ChipLoader, so their raw pixels are never
// all in memory. Each subspace then works on a class's columns: in double through the k x k Gram
// matrix when the class has k <= n chips (its columns copied once to double and centred in
// place, at most n x n values, plus the k x k Gram matrix and its eigenvectors), or through the
// n x n covariance accumulated 256 columns at a time when k > n, which never copies the class's
// columns.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>

#include "atr/subspace_classifier.h"

namespace sonarloop::atr {
namespace {

// Columns converted to double at a time when accumulating a covariance.
constexpr Eigen::Index kCovarianceBlock = 256;

// The training set: normalised chips as columns, with their classes and aspect sectors.
struct Prepared {
  int width = 0, height = 0;                      // chip size (the first usable chip's)
  std::vector<std::string> names;                 // sorted class names
  std::vector<std::vector<std::size_t>> members;  // columns of each class
  Eigen::MatrixXf x;  // normalised chips as columns (n x listed; the first `used` filled)
  std::vector<unsigned char> blank;  // with views: the chips constant in the first reading
  // the same for each view's reading (TrainOptions::views), and which chips are constant in it
  // (blank: left out of that reading's subspaces, as far as an unrelated chip from them)
  std::vector<Eigen::MatrixXf> view_x;
  std::vector<std::vector<unsigned char>> view_blank;
  std::size_t used = 0;     // columns filled
  std::vector<int> sector;  // aspect sector of each column
};

std::string chip_name(const LabelledChip& lc, std::size_t i) {
  if (lc.source.empty()) return "number " + std::to_string(i);
  return "'" + lc.source + "'";
}

void report_progress(const TrainOptions& opt, std::string_view stage, std::size_t done,
                     std::size_t total) {
  if (opt.progress) opt.progress(stage, done, total);
}

// Why a chip is unusable, or an empty string. Writes its normalised features to column `col`
// of pr.x and of each view's matrix (and whether it is blank in that view).
std::string load_features(ChipView view, Prepared& pr, const std::string& first_source,
                          const TrainOptions& opt, PreprocessScratch& scratch, Eigen::Index col) {
  const auto column = [col](Eigen::MatrixXf& x) {
    return std::span<float>(x.col(col).data(), static_cast<std::size_t>(x.rows()));
  };
  ChipCheck c = check_chip_size(view, pr.width, pr.height);
  if (c.ok()) c = normalise_chip(preprocess_into(view, opt.preprocess, scratch), column(pr.x));
  // with further readings, a chip constant in one of them is blank there (left out of its
  // subspaces), unusable only when blank in every one (Classifier::classify does the same)
  const auto at = static_cast<std::size_t>(col);
  bool usable = c.ok();
  if (!opt.views.empty() && (c.ok() || c.status == ChipStatus::kConstant)) {
    pr.blank[at] = c.ok() ? 0 : 1;
    for (std::size_t v = 0; v < opt.views.size(); ++v) {
      // the chip passed the size and finite checks: only constant remains
      const ChipCheck cv =
          normalise_chip(preprocess_into(view, opt.views[v], scratch), column(pr.view_x[v]));
      pr.view_blank[v][at] = cv.ok() ? 0 : 1;
      usable = usable || cv.ok();
    }
  }
  if (usable) return {};
  if (c.status == ChipStatus::kWrongSize && c.width > 0 && c.height > 0) {
    return "is " + std::to_string(c.width) + " x " + std::to_string(c.height) +
           " pixels but the first chip ('" + first_source + "') is " + std::to_string(pr.width) +
           " x " + std::to_string(pr.height) + ": all chips must be the same size";
  }
  return c.reason();
}

void check_aspect(const LabelledChip& lc, const std::string& name, const TrainOptions& opt) {
  if (opt.aspect_sectors <= 1) return;
  if (!lc.aspect_deg) {
    throw std::runtime_error("training chip " + name + " has no aspect angle, but " +
                             std::to_string(opt.aspect_sectors) +
                             " aspect sectors need one for every chip (labels.csv aspect_deg)");
  }
  if (!std::isfinite(*lc.aspect_deg)) {
    throw std::runtime_error("training chip " + name + " has a non-finite aspect angle");
  }
}

// Reads, checks and normalises every chip into pr.x, skipping or rejecting unusable chips.
Prepared prepare(std::span<const LabelledChip> chips, const ChipLoader& load,
                 const TrainOptions& opt, TrainReport* report) {
  Prepared pr;
  if (chips.empty()) throw std::runtime_error("no training chips");
  PreprocessScratch scratch;
  std::string first_source;
  std::vector<std::size_t> kept;  // index into chips of each column
  for (std::size_t i = 0; i < chips.size(); ++i) {
    report_progress(opt, "reading chips", i, chips.size());
    const LabelledChip& lc = chips[i];
    const std::string name = chip_name(lc, i);
    if (lc.label.empty()) throw std::runtime_error("training chip " + name + " has no class label");
    std::string reason;
    try {
      const ChipView view = load(i);
      if (pr.x.size() == 0) {
        // the first readable chip sets the size
        const ChipCheck first = check_chip_size(view);
        if (!first.ok()) throw std::runtime_error(first.reason());
        pr.width = view.width;
        pr.height = view.height;
        first_source = lc.source;
        const auto n =
            static_cast<Eigen::Index>(cropped_size(pr.width, opt.preprocess.crop_fraction) *
                                      cropped_size(pr.height, opt.preprocess.crop_fraction));
        pr.x.resize(n, static_cast<Eigen::Index>(chips.size() - i));
        pr.view_x.assign(opt.views.size(), Eigen::MatrixXf(pr.x.rows(), pr.x.cols()));
        pr.blank.assign(static_cast<std::size_t>(pr.x.cols()), 0);
        pr.view_blank.assign(opt.views.size(), pr.blank);
      }
      reason =
          load_features(view, pr, first_source, opt, scratch, static_cast<Eigen::Index>(pr.used));
    } catch (const std::runtime_error& e) {
      reason = e.what();
    }
    if (!reason.empty()) {
      if (!opt.skip_degenerate) throw std::runtime_error("training chip " + name + ": " + reason);
      if (report) report->skipped.push_back({lc.source, reason});
      continue;
    }
    check_aspect(lc, name, opt);
    kept.push_back(i);
    ++pr.used;
  }
  report_progress(opt, "reading chips", chips.size(), chips.size());
  if (kept.empty()) throw std::runtime_error("no usable training chip (all were unusable)");

  // classes: sorted distinct labels
  std::map<std::string, std::vector<std::size_t>> by_class;
  for (std::size_t col = 0; col < kept.size(); ++col)
    by_class[chips[kept[col]].label].push_back(col);
  for (auto& [name, cols] : by_class) {
    pr.names.push_back(name);
    pr.members.push_back(cols);
  }
  pr.sector.resize(kept.size(), 0);
  for (std::size_t col = 0; col < kept.size(); ++col) {
    const auto& a = chips[kept[col]].aspect_deg;
    pr.sector[col] = opt.aspect_sectors > 1 ? aspect_sector(*a, opt.aspect_sectors) : 0;
  }
  return pr;
}

// The number of leading eigenvalues kept: at most max_rank, each positive and above
// kRelativeEigenvalueFloor of the largest. `lambda` is ascending (as Eigen returns it).
int significant_rank(const Eigen::VectorXd& lambda, int max_rank) {
  const Eigen::Index k = lambda.size();
  const double lambda_max = std::max(lambda[k - 1], 0.0);
  int rank = 0;
  while (rank < max_rank) {
    const double l = lambda[k - 1 - rank];
    if (!(l > 0.0) || l <= kRelativeEigenvalueFloor * lambda_max) break;
    ++rank;
  }
  return rank;
}

// One modified Gram-Schmidt pass over the columns, against rounding.
void orthonormalise(Eigen::MatrixXd& u) {
  for (Eigen::Index j = 0; j < u.cols(); ++j) {
    for (Eigen::Index i = 0; i < j; ++i)
      u.col(j) -= u.col(i).dot(u.col(j)) * u.col(i);
    u.col(j).normalize();
  }
}

// The covariance route for k > n chips (the Gram matrix would be the larger): the n x n matrix
// A A^T = sum over chips of (x - mu)(x - mu)^T, accumulated a block of columns at a time; its
// leading eigenvectors are the basis directly.
template <class Matrix>
Subspace covariance_subspace(const Matrix& x, std::span<const Eigen::Index> cols, int p) {
  const Eigen::Index n = x.rows();
  const auto k = static_cast<Eigen::Index>(cols.size());
  Subspace s;
  s.train_count = static_cast<int>(k);
  Eigen::VectorXd mu = Eigen::VectorXd::Zero(n);
  for (const Eigen::Index c : cols)
    mu += x.col(c).template cast<double>();
  mu /= static_cast<double>(k);
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd block(n, std::min(kCovarianceBlock, k));
  for (Eigen::Index start = 0; start < k; start += kCovarianceBlock) {
    const Eigen::Index b = std::min(kCovarianceBlock, k - start);
    for (Eigen::Index j = 0; j < b; ++j)
      block.col(j) = x.col(cols[static_cast<std::size_t>(start + j)]).template cast<double>() - mu;
    cov.selfadjointView<Eigen::Lower>().rankUpdate(block.leftCols(b));
  }
  block.resize(0, 0);
  // only the lower triangle is read; the solver keeps its own copy, so free ours
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(cov);
  cov.resize(0, 0);
  if (eig.info() != Eigen::Success) {
    throw std::runtime_error("fit_subspace: eigen-decomposition of the covariance failed");
  }
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  const int max_rank = static_cast<int>(std::min<Eigen::Index>(p, k - 1));
  const int rank = significant_rank(lambda, max_rank);
  Eigen::MatrixXd u(n, rank);
  s.eigenvalues.resize(rank);
  for (int j = 0; j < rank; ++j) {
    s.eigenvalues[j] = lambda[n - 1 - j];
    u.col(j) = eig.eigenvectors().col(n - 1 - j);
  }
  orthonormalise(u);
  s.mean = mu.cast<float>();
  s.basis = u.cast<float>();
  return s;
}

// The Gram route for k <= n chips, the columns of `a` (n x k), centred in place: eq. 8, then the
// k x k Gram matrix A^T A, which shares its non-zero eigenvalues with the covariance A A^T: if
// G v = lambda v then u = A v / sqrt(lambda) is a unit eigenvector of A A^T.
Subspace gram_subspace(Eigen::MatrixXd a, int p) {
  Subspace s;
  s.train_count = static_cast<int>(a.cols());
  const Eigen::VectorXd mu = a.rowwise().mean();
  a.colwise() -= mu;
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(a.cols(), a.cols());
  g.selfadjointView<Eigen::Lower>().rankUpdate(a.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(g.selfadjointView<Eigen::Lower>());
  if (eig.info() != Eigen::Success) {
    throw std::runtime_error("fit_subspace: eigen-decomposition of the Gram matrix failed");
  }
  // eigenvalues come ascending: take from the top, while significant
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  const Eigen::Index k = lambda.size();
  const int rank = significant_rank(lambda, std::min<int>(p, static_cast<int>(k) - 1));
  // u_j = A v_j / sqrt(lambda_j), then one modified Gram-Schmidt pass against rounding
  Eigen::MatrixXd u(a.rows(), rank);
  s.eigenvalues.resize(rank);
  for (int j = 0; j < rank; ++j) {
    const Eigen::Index e = k - 1 - j;
    s.eigenvalues[j] = lambda[e];
    u.col(j) = a * eig.eigenvectors().col(e) / std::sqrt(lambda[e]);
  }
  orthonormalise(u);
  s.mean = mu.cast<float>();
  s.basis = u.cast<float>();
  return s;
}

// One reading of the training chips: pr.x or a view's, with its blank chips.
struct Reading {
  const Eigen::MatrixXf& x;
  const std::vector<unsigned char>* blank = nullptr;
  bool is_blank(std::size_t col) const { return blank && (*blank)[col] != 0; }
};

// One subspace per aspect sector that has chips not blank in the reading, from the given columns.
ClassModel fit_class(const Reading& reading, const Prepared& pr,
                     const std::vector<std::size_t>& cols, const std::string& name,
                     const ClassMetadata& meta, const TrainOptions& opt) {
  ClassModel cm;
  cm.name = name;
  cm.mine_like = meta.mine_like;
  cm.clutter = meta.clutter;
  cm.height_m = meta.height_m;
  const double width_deg = 360.0 / opt.aspect_sectors;
  for (int s = 0; s < opt.aspect_sectors; ++s) {
    std::vector<Eigen::Index> in;
    for (const std::size_t c : cols) {
      if (pr.sector[c] == s && !reading.is_blank(c)) in.push_back(static_cast<Eigen::Index>(c));
    }
    if (in.empty()) continue;
    Subspace sub = fit_subspace(reading.x, in, opt.p);
    sub.aspect_min_deg = s * width_deg;
    sub.aspect_max_deg = s + 1 == opt.aspect_sectors ? 360.0 : (s + 1) * width_deg;
    cm.subspaces.push_back(std::move(sub));
  }
  return cm;
}

// The q-quantile (nearest rank) of sorted values.
float quantile_of_sorted(const std::vector<float>& sorted, double q) {
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size())));
  return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

// Cross-validation of one class: its chips' distances to subspaces fitted, fold by fold,
// without them, in one reading, in fold order (the same chips in the same order for every
// reading: a chip blank in the reading, or scored by a fold left without a subspace, is as far
// as an unrelated chip, sqrt(n)). Needs at least two chips per fold's training part; empty when
// the class is too small.
std::vector<float> cross_validated_distances(const Reading& reading, const Prepared& pr,
                                             const std::vector<std::size_t>& cols,
                                             const TrainOptions& opt) {
  const Eigen::MatrixXf& x_all = reading.x;
  const auto unrelated = static_cast<float>(std::sqrt(static_cast<double>(x_all.rows())));
  const std::size_t folds =
      std::min<std::size_t>(static_cast<std::size_t>(opt.reject_folds), cols.size());
  if (folds < 2) return {};
  std::vector<float> d;
  Eigen::VectorXf x(x_all.rows()), work_n(x_all.rows()), work_p(std::max(opt.p, 1));
  int sub = -1;
  for (std::size_t f = 0; f < folds; ++f) {
    std::vector<std::size_t> train, held;
    for (std::size_t i = 0; i < cols.size(); ++i)
      (i % folds == f ? held : train).push_back(cols[i]);
    if (train.size() < 2) continue;
    const ClassModel c = fit_class(reading, pr, train, "fold", {}, opt);
    for (const std::size_t h : held) {
      if (c.subspaces.empty() || reading.is_blank(h)) {
        d.push_back(unrelated);
        continue;
      }
      x = x_all.col(static_cast<Eigen::Index>(h));
      d.push_back(nearest_subspace(c, x, work_n, work_p, &sub));
    }
  }
  return d;
}

// The class's cross-validated distances fused over the readings (subspace_classifier.h,
// "Fused readings"), sorted.
std::vector<float> fused_cross_validated_distances(const Prepared& pr,
                                                   const std::vector<std::size_t>& cols,
                                                   const TrainOptions& opt) {
  std::vector<float> d = cross_validated_distances(Reading{pr.x, &pr.blank}, pr, cols, opt);
  if (!pr.view_x.empty()) {
    for (float& v : d)
      v *= v;
    for (std::size_t k = 0; k < pr.view_x.size(); ++k) {
      const std::vector<float> dv =
          cross_validated_distances(Reading{pr.view_x[k], &pr.view_blank[k]}, pr, cols, opt);
      for (std::size_t i = 0; i < d.size() && i < dv.size(); ++i)
        d[i] += dv[i] * dv[i];
    }
    for (float& v : d)
      v = std::sqrt(v);
  }
  std::sort(d.begin(), d.end());
  return d;
}

[[noreturn]] void throw_all_blank(const std::string& name, const ChipPreprocess& reading) {
  throw std::runtime_error("class '" + name + "': every chip is constant in its " +
                           preprocess_label(reading) +
                           " reading (nothing to train that reading on)");
}

void check_options(const TrainOptions& opt) {
  if (opt.p < 1) throw std::runtime_error("p = " + std::to_string(opt.p) + " (must be >= 1)");
  try {
    validate_preprocess(opt.preprocess);
    for (const ChipPreprocess& v : opt.views)
      validate_preprocess(v);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  if (opt.views.size() > kMaxModelViews) {
    throw std::runtime_error(std::to_string(opt.views.size()) + " views (at most " +
                             std::to_string(kMaxModelViews) + ")");
  }
  for (const ChipPreprocess& v : opt.views) {
    if (v.crop_fraction != opt.preprocess.crop_fraction) {
      throw std::runtime_error("a view's crop fraction (" + std::to_string(v.crop_fraction) +
                               ") differs from the model's (" +
                               std::to_string(opt.preprocess.crop_fraction) + ")");
    }
  }
  if (!(opt.reject_quantile >= 0.0 && opt.reject_quantile < 1.0)) {
    throw std::runtime_error("reject quantile " + std::to_string(opt.reject_quantile) +
                             " (allowed 0, off, or in (0, 1))");
  }
  if (opt.reject_folds < 2 || opt.reject_folds > 100) {
    throw std::runtime_error("reject folds = " + std::to_string(opt.reject_folds) +
                             " (allowed 2 to 100)");
  }
  if (opt.aspect_sectors < 1 || opt.aspect_sectors > 360) {
    throw std::runtime_error("aspect sectors = " + std::to_string(opt.aspect_sectors) +
                             " (allowed 1 to 360)");
  }
  for (const auto& [name, meta] : opt.class_metadata) {
    if (meta.clutter && meta.mine_like) {
      throw std::runtime_error("class '" + name + "' is both clutter and mine-like");
    }
    if (meta.height_m && !valid_class_height(*meta.height_m)) {
      throw std::runtime_error("class '" + name + "': height " + std::to_string(*meta.height_m) +
                               " m (allowed 0 to " + std::to_string(kMaxClassHeight_m) + " m)");
    }
  }
}

}  // namespace

Subspace fit_subspace(const Eigen::MatrixXd& x, int p) {
  if (x.cols() < 1 || x.rows() < 1) throw std::invalid_argument("fit_subspace: no chips");
  if (p < 1) throw std::invalid_argument("fit_subspace: p must be >= 1");
  if (x.cols() > x.rows()) {
    std::vector<Eigen::Index> all(static_cast<std::size_t>(x.cols()));
    std::iota(all.begin(), all.end(), Eigen::Index{0});
    return covariance_subspace(x, all, p);
  }
  return gram_subspace(Eigen::MatrixXd(x), p);
}

Subspace fit_subspace(const Eigen::MatrixXf& x, std::span<const Eigen::Index> cols, int p) {
  if (cols.empty() || x.rows() < 1) throw std::invalid_argument("fit_subspace: no chips");
  if (p < 1) throw std::invalid_argument("fit_subspace: p must be >= 1");
  if (static_cast<Eigen::Index>(cols.size()) > x.rows()) return covariance_subspace(x, cols, p);
  // k <= n: the class's columns in double (at most n x n values), through the Gram matrix
  Eigen::MatrixXd xd(x.rows(), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t j = 0; j < cols.size(); ++j)
    xd.col(static_cast<Eigen::Index>(j)) = x.col(cols[j]).cast<double>();
  return gram_subspace(std::move(xd), p);
}

Model train_model(std::span<const LabelledChip> chips, const TrainOptions& opt,
                  TrainReport* report) {
  return train_model(
      chips, [chips](std::size_t i) { return chips[i].chip.view(); }, opt, report);
}

Model train_model(std::span<const LabelledChip> chips, const ChipLoader& load,
                  const TrainOptions& opt, TrainReport* report) {
  check_options(opt);
  const Prepared pr = prepare(chips, load, opt, report);
  Model m;
  m.chip_width = pr.width;
  m.chip_height = pr.height;
  m.p = opt.p;
  m.aspect_sectors = opt.aspect_sectors;
  m.preprocess = opt.preprocess;

  // class metadata: listed, or not mine-like with an unknown height
  std::vector<ClassMetadata> meta(pr.names.size());
  for (std::size_t c = 0; c < pr.names.size(); ++c) {
    if (const auto it = opt.class_metadata.find(pr.names[c]); it != opt.class_metadata.end())
      meta[c] = it->second;
  }
  const bool calibrate = opt.reject_quantile > 0.0 || opt.calibrate;
  const std::size_t steps =
      pr.names.size() * (1 + opt.views.size()) + (opt.group_subspaces ? 2 : 0);
  for (std::size_t c = 0; c < pr.names.size(); ++c) {
    report_progress(opt, "fitting subspaces", c, steps);
    m.classes.push_back(
        fit_class(Reading{pr.x, &pr.blank}, pr, pr.members[c], pr.names[c], meta[c], opt));
    if (m.classes.back().subspaces.empty()) throw_all_blank(pr.names[c], opt.preprocess);
    if (calibrate) {
      const std::vector<float> d = fused_cross_validated_distances(pr, pr.members[c], opt);
      if (!d.empty()) {
        m.classes.back().typical_distance = quantile_of_sorted(d, 0.5);
        if (opt.reject_quantile > 0.0)
          m.classes.back().reject_distance = quantile_of_sorted(d, opt.reject_quantile);
      }
    }
  }
  if (opt.group_subspaces) {
    std::vector<std::size_t> mine_cols, other_cols;
    for (std::size_t c = 0; c < pr.names.size(); ++c) {
      if (meta[c].clutter) continue;  // neither group
      auto& dst = meta[c].mine_like ? mine_cols : other_cols;
      dst.insert(dst.end(), pr.members[c].begin(), pr.members[c].end());
    }
    if (mine_cols.empty() || other_cols.empty()) {
      throw std::runtime_error(
          "group subspaces need chips of both mine-like and non-mine classes (mine-like: " +
          std::to_string(mine_cols.size()) +
          " chips, non-mine: " + std::to_string(other_cols.size()) + ")");
    }
    std::sort(mine_cols.begin(), mine_cols.end());
    std::sort(other_cols.begin(), other_cols.end());
    report_progress(opt, "fitting subspaces", pr.names.size(), steps);
    m.groups.push_back(fit_class(Reading{pr.x, &pr.blank}, pr, mine_cols,
                                 std::string(kMineGroupName), {true, {}}, opt));
    report_progress(opt, "fitting subspaces", pr.names.size() + 1, steps);
    m.groups.push_back(fit_class(Reading{pr.x, &pr.blank}, pr, other_cols,
                                 std::string(kNonMineGroupName), {}, opt));
  }
  for (std::size_t v = 0; v < opt.views.size(); ++v) {
    ModelView view;
    view.preprocess = opt.views[v];
    for (std::size_t c = 0; c < pr.names.size(); ++c) {
      report_progress(opt, "fitting subspaces",
                      steps - (opt.views.size() - v) * pr.names.size() + c, steps);
      const Reading reading{pr.view_x[v], &pr.view_blank[v]};
      view.classes.push_back(fit_class(reading, pr, pr.members[c], pr.names[c], meta[c], opt));
      if (view.classes.back().subspaces.empty()) throw_all_blank(pr.names[c], view.preprocess);
    }
    m.views.push_back(std::move(view));
  }
  report_progress(opt, "fitting subspaces", steps, steps);
  validate_model(m);
  return m;
}

}  // namespace sonarloop::atr
