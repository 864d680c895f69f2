#include "atr/subspace_classifier.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "sim/targets/target_type.h"

namespace sonarloop::atr {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
// Largest deviation of U^T U from the identity accepted in a model (float storage keeps it near
// 1e-6; anything near 1e-3 means the file is not what it claims).
constexpr double kOrthonormalTolerance = 1e-3;

std::string subspace_label(const ClassModel& c, std::size_t s) {
  return "class '" + c.name + "' subspace " + std::to_string(s);
}

void validate_class(const ClassModel& c, const Model& m, const std::string& what) {
  const auto n = static_cast<Eigen::Index>(m.feature_count());
  if (c.name.empty()) throw std::runtime_error(what + ": empty class name");
  if (c.subspaces.empty()) {
    throw std::runtime_error(what + " '" + c.name + "' has no subspace");
  }
  if (!(c.reject_distance > 0.0f)) {  // NaN too; +infinity means no rejection
    throw std::runtime_error(what + " '" + c.name + "': reject distance " +
                             std::to_string(c.reject_distance) + " is not positive");
  }
  if (!(c.typical_distance >= 0.0f && std::isfinite(c.typical_distance))) {
    throw std::runtime_error(what + " '" + c.name + "': typical distance " +
                             std::to_string(c.typical_distance) +
                             " is not a finite non-negative number");
  }
  for (std::size_t s = 0; s < c.subspaces.size(); ++s) {
    const Subspace& sub = c.subspaces[s];
    const std::string where = subspace_label(c, s);
    if (!(sub.aspect_min_deg >= 0.0 && sub.aspect_min_deg < sub.aspect_max_deg &&
          sub.aspect_max_deg <= 360.0)) {
      throw std::runtime_error(where + ": aspect range [" + std::to_string(sub.aspect_min_deg) +
                               ", " + std::to_string(sub.aspect_max_deg) +
                               ") deg is not within [0, 360)");
    }
    if (sub.train_count < 1) {
      throw std::runtime_error(where + ": trained on " + std::to_string(sub.train_count) +
                               " chips (at least 1 needed)");
    }
    if (sub.mean.size() != n || sub.basis.rows() != n) {
      throw std::runtime_error(where + ": mean or basis has " + std::to_string(sub.mean.size()) +
                               " / " + std::to_string(sub.basis.rows()) + " values, the chip " +
                               std::to_string(n));
    }
    if (sub.rank() > m.p || sub.rank() > sub.train_count - 1 ||
        sub.eigenvalues.size() != sub.rank()) {
      throw std::runtime_error(where + ": rank " + std::to_string(sub.rank()) +
                               " exceeds p = " + std::to_string(m.p) +
                               " or k - 1 = " + std::to_string(sub.train_count - 1) +
                               ", or does not match its eigenvalue count");
    }
    if (!sub.mean.allFinite() || !sub.basis.allFinite() || !sub.eigenvalues.allFinite()) {
      throw std::runtime_error(where + ": non-finite value in mean, basis or eigenvalues");
    }
    for (Eigen::Index j = 0; j < sub.eigenvalues.size(); ++j) {
      if (!(sub.eigenvalues[j] > 0.0) || (j > 0 && sub.eigenvalues[j] > sub.eigenvalues[j - 1])) {
        throw std::runtime_error(where + ": eigenvalues must be positive and descending");
      }
    }
    if (sub.rank() > 0) {
      const Eigen::MatrixXd g = sub.basis.cast<double>().transpose() * sub.basis.cast<double>();
      const double dev =
          (g - Eigen::MatrixXd::Identity(sub.rank(), sub.rank())).cwiseAbs().maxCoeff();
      if (!(dev <= kOrthonormalTolerance)) {
        throw std::runtime_error(
            where + ": basis is not orthonormal (|U^T U - I| = " + std::to_string(dev) + ")");
      }
    }
  }
}

// Pairs each chip with its class index, skipping or rejecting degenerate chips.
struct Prepared {
  std::vector<std::string> names;                 // sorted class names
  std::vector<std::vector<std::size_t>> members;  // chips of each class
  Eigen::MatrixXd x;                              // normalised chips as columns (n x total)
  std::vector<int> sector;                        // aspect sector of each column
};

Prepared prepare(std::span<const LabelledChip> chips, const TrainOptions& opt,
                 TrainReport* report) {
  Prepared pr;
  if (chips.empty()) throw std::runtime_error("no training chips");
  const int w = chips[0].chip.width;
  const int h = chips[0].chip.height;
  const ChipCheck first = check_chip_size(chips[0].chip.view());
  if (!first.ok()) {
    throw std::runtime_error("training chip '" + chips[0].source + "': " + first.reason());
  }
  const int fw = cropped_size(w, opt.preprocess.crop_fraction);
  const int fh = cropped_size(h, opt.preprocess.crop_fraction);
  const auto n = static_cast<std::size_t>(fw) * static_cast<std::size_t>(fh);
  std::vector<float> normalised(n);
  PreprocessScratch scratch;
  std::vector<std::size_t> kept;  // index into chips of each column
  std::vector<Eigen::VectorXf> columns;
  for (std::size_t i = 0; i < chips.size(); ++i) {
    const LabelledChip& lc = chips[i];
    std::string name = "number ";
    name += std::to_string(i);
    if (!lc.source.empty()) {
      name = "'";
      name += lc.source;
      name += "'";
    }
    if (lc.label.empty()) throw std::runtime_error("training chip " + name + " has no class label");
    ChipCheck c = check_chip_size(lc.chip.view(), w, h);
    if (c.ok())
      c = normalise_chip(preprocess_into(lc.chip.view(), opt.preprocess, scratch), normalised);
    if (!c.ok()) {
      std::string reason = c.reason();
      if (c.status == ChipStatus::kWrongSize && c.width > 0 && c.height > 0) {
        reason = "is " + std::to_string(c.width) + " x " + std::to_string(c.height) +
                 " pixels but the first chip ('" + chips[0].source + "') is " + std::to_string(w) +
                 " x " + std::to_string(h) + ": all chips must be the same size";
      }
      if (opt.skip_degenerate) {
        if (report) report->skipped.push_back({lc.source, reason});
        continue;
      }
      throw std::runtime_error("training chip " + name + ": " + reason);
    }
    if (opt.aspect_sectors > 1) {
      if (!lc.aspect_deg) {
        throw std::runtime_error("training chip " + name + " has no aspect angle, but " +
                                 std::to_string(opt.aspect_sectors) +
                                 " aspect sectors need one for every chip (labels.csv aspect_deg)");
      }
      if (!std::isfinite(*lc.aspect_deg)) {
        throw std::runtime_error("training chip " + name + " has a non-finite aspect angle");
      }
    }
    kept.push_back(i);
    columns.emplace_back(
        Eigen::Map<const Eigen::VectorXf>(normalised.data(), static_cast<Eigen::Index>(n)));
  }
  if (kept.empty()) throw std::runtime_error("no usable training chip (all were degenerate)");

  // classes: sorted distinct labels
  std::map<std::string, std::vector<std::size_t>> by_class;
  for (std::size_t col = 0; col < kept.size(); ++col)
    by_class[chips[kept[col]].label].push_back(col);
  for (auto& [name, cols] : by_class) {
    pr.names.push_back(name);
    pr.members.push_back(cols);
  }
  pr.x.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(kept.size()));
  pr.sector.resize(kept.size(), 0);
  for (std::size_t col = 0; col < kept.size(); ++col) {
    pr.x.col(static_cast<Eigen::Index>(col)) = columns[col].cast<double>();
    const auto& a = chips[kept[col]].aspect_deg;
    pr.sector[col] = opt.aspect_sectors > 1 ? aspect_sector(*a, opt.aspect_sectors) : 0;
  }
  return pr;
}

// One subspace per aspect sector that has chips, from the given columns of pr.x.
ClassModel fit_class(const Prepared& pr, const std::vector<std::size_t>& cols,
                     const std::string& name, bool mine_like, const TrainOptions& opt) {
  ClassModel cm;
  cm.name = name;
  cm.mine_like = mine_like;
  const double width_deg = 360.0 / opt.aspect_sectors;
  for (int s = 0; s < opt.aspect_sectors; ++s) {
    std::vector<Eigen::Index> in;
    for (const std::size_t c : cols) {
      if (pr.sector[c] == s) in.push_back(static_cast<Eigen::Index>(c));
    }
    if (in.empty()) continue;
    Eigen::MatrixXd x(pr.x.rows(), static_cast<Eigen::Index>(in.size()));
    for (std::size_t j = 0; j < in.size(); ++j)
      x.col(static_cast<Eigen::Index>(j)) = pr.x.col(in[j]);
    Subspace sub = fit_subspace(x, opt.p);
    sub.aspect_min_deg = s * width_deg;
    sub.aspect_max_deg = s + 1 == opt.aspect_sectors ? 360.0 : (s + 1) * width_deg;
    cm.subspaces.push_back(std::move(sub));
  }
  return cm;
}

// The class distance of a normalised chip: the smallest eq. 10 residual over the class's
// subspaces, and in *best_subspace the index of that subspace (-1 without any). work_p must hold
// the largest rank. Used by Classifier and by the cross-validation.
float nearest_subspace(const ClassModel& c, const Eigen::VectorXf& x, Eigen::VectorXf& work_n,
                       Eigen::VectorXf& work_p, int* best_subspace) {
  float best = kInfinity;
  *best_subspace = -1;
  for (std::size_t s = 0; s < c.subspaces.size(); ++s) {
    const float d = subspace_residual(c.subspaces[s], x, work_n, work_p);
    if (d < best) {
      best = d;
      *best_subspace = static_cast<int>(s);
    }
  }
  return best;
}

// The q-quantile (nearest rank) of sorted values.
float quantile_of_sorted(const std::vector<float>& sorted, double q) {
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size())));
  return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

// Cross-validation of one class: its chips' distances to subspaces fitted, fold by fold,
// without them, sorted. Needs at least two chips per fold's training part; empty when the class
// is too small.
std::vector<float> cross_validated_distances(const Prepared& pr,
                                             const std::vector<std::size_t>& cols,
                                             const TrainOptions& opt) {
  const std::size_t folds =
      std::min<std::size_t>(static_cast<std::size_t>(opt.reject_folds), cols.size());
  if (folds < 2) return {};
  std::vector<float> d;
  Eigen::VectorXf x(pr.x.rows()), work_n(pr.x.rows()), work_p(std::max(opt.p, 1));
  int sub = -1;
  for (std::size_t f = 0; f < folds; ++f) {
    std::vector<std::size_t> train, held;
    for (std::size_t i = 0; i < cols.size(); ++i)
      (i % folds == f ? held : train).push_back(cols[i]);
    if (train.size() < 2) continue;
    const ClassModel c = fit_class(pr, train, "fold", false, opt);
    for (const std::size_t h : held) {
      // a fold whose training part left the class no subspace at all: nothing to score against
      if (c.subspaces.empty()) continue;
      x = pr.x.col(static_cast<Eigen::Index>(h)).cast<float>();
      d.push_back(nearest_subspace(c, x, work_n, work_p, &sub));
    }
  }
  std::sort(d.begin(), d.end());
  return d;
}

}  // namespace

int Model::find_class(std::string_view name) const {
  for (std::size_t i = 0; i < classes.size(); ++i) {
    if (classes[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

void validate_model(const Model& m) {
  if (m.chip_width <= 0 || m.chip_height <= 0) {
    throw std::runtime_error("model chip size " + std::to_string(m.chip_width) + " x " +
                             std::to_string(m.chip_height) + " is not positive");
  }
  if (m.p < 1) throw std::runtime_error("model p = " + std::to_string(m.p) + " (must be >= 1)");
  try {
    validate_preprocess(m.preprocess);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("model ") + e.what());
  }
  if (m.aspect_sectors < 1) {
    throw std::runtime_error("model aspect_sectors = " + std::to_string(m.aspect_sectors) +
                             " (must be >= 1)");
  }
  if (m.classes.empty()) throw std::runtime_error("model has no class");
  for (std::size_t i = 0; i < m.classes.size(); ++i) {
    validate_class(m.classes[i], m, "class " + std::to_string(i));
    for (std::size_t j = 0; j < i; ++j) {
      if (m.classes[j].name == m.classes[i].name) {
        throw std::runtime_error("model has two classes named '" + m.classes[i].name + "'");
      }
    }
  }
  if (!m.groups.empty()) {
    if (m.groups.size() != 2 || m.groups[0].name != kMineGroupName || !m.groups[0].mine_like ||
        m.groups[1].name != kNonMineGroupName || m.groups[1].mine_like) {
      throw std::runtime_error(
          "model groups must be exactly 'mine' (mine-like) then 'non_mine' (not mine-like)");
    }
    for (const auto& g : m.groups)
      validate_class(g, m, "group");
  }
}

bool default_mine_like(std::string_view class_name) {
  const auto t = targets::find_target_type(class_name);
  return t && targets::target_type_info(*t).mine_like;
}

int aspect_sector(double aspect_deg, int sectors) {
  if (sectors <= 1) return 0;
  double a = std::fmod(aspect_deg, 360.0);
  if (a < 0.0) a += 360.0;
  const int s = static_cast<int>(std::floor(a * sectors / 360.0));
  return std::clamp(s, 0, sectors - 1);
}

Subspace fit_subspace(const Eigen::MatrixXd& x, int p) {
  if (x.cols() < 1 || x.rows() < 1) throw std::invalid_argument("fit_subspace: no chips");
  if (p < 1) throw std::invalid_argument("fit_subspace: p must be >= 1");
  Subspace s;
  s.train_count = static_cast<int>(x.cols());
  // eq. 8: the mean image, and the centred data A (n x k)
  const Eigen::VectorXd mu = x.rowwise().mean();
  const Eigen::MatrixXd a = x.colwise() - mu;
  // the k x k Gram matrix A^T A shares its non-zero eigenvalues with the covariance A A^T
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(a.cols(), a.cols());
  g.selfadjointView<Eigen::Lower>().rankUpdate(a.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(g.selfadjointView<Eigen::Lower>());
  if (eig.info() != Eigen::Success) {
    throw std::runtime_error("fit_subspace: eigen-decomposition of the Gram matrix failed");
  }
  // eigenvalues come ascending: take from the top, while significant
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  const Eigen::Index k = lambda.size();
  const double lambda_max = std::max(lambda[k - 1], 0.0);
  const int max_rank = std::min<int>(p, static_cast<int>(k) - 1);
  int rank = 0;
  while (rank < max_rank) {
    const double l = lambda[k - 1 - rank];
    if (!(l > 0.0) || l <= kRelativeEigenvalueFloor * lambda_max) break;
    ++rank;
  }
  // u_j = A v_j / sqrt(lambda_j), then one modified Gram-Schmidt pass against rounding
  Eigen::MatrixXd u(a.rows(), rank);
  s.eigenvalues.resize(rank);
  for (int j = 0; j < rank; ++j) {
    const Eigen::Index e = k - 1 - j;
    s.eigenvalues[j] = lambda[e];
    u.col(j) = a * eig.eigenvectors().col(e) / std::sqrt(lambda[e]);
  }
  for (int j = 0; j < rank; ++j) {
    for (int i = 0; i < j; ++i)
      u.col(j) -= u.col(i).dot(u.col(j)) * u.col(i);
    u.col(j).normalize();
  }
  s.mean = mu.cast<float>();
  s.basis = u.cast<float>();
  return s;
}

float subspace_residual(const Subspace& s, const Eigen::Ref<const Eigen::VectorXf>& x,
                        Eigen::Ref<Eigen::VectorXf> work_n, Eigen::Ref<Eigen::VectorXf> work_p) {
  work_n = x - s.mean;
  const Eigen::Index r = s.basis.cols();
  if (r > 0) {
    auto c = work_p.head(r);
    c.noalias() = s.basis.transpose() * work_n;
    work_n.noalias() -= s.basis * c;
  }
  return work_n.norm();
}

Model train_model(std::span<const LabelledChip> chips, const TrainOptions& opt,
                  TrainReport* report) {
  if (opt.p < 1) throw std::runtime_error("p = " + std::to_string(opt.p) + " (must be >= 1)");
  try {
    validate_preprocess(opt.preprocess);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
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
  const Prepared pr = prepare(chips, opt, report);
  Model m;
  m.chip_width = chips[0].chip.width;
  m.chip_height = chips[0].chip.height;
  m.p = opt.p;
  m.aspect_sectors = opt.aspect_sectors;
  m.preprocess = opt.preprocess;

  // mine-like flags
  std::vector<bool> mine(pr.names.size(), false);
  for (std::size_t c = 0; c < pr.names.size(); ++c)
    mine[c] = default_mine_like(pr.names[c]);
  if (opt.mine_classes) {
    std::fill(mine.begin(), mine.end(), false);
    for (const auto& name : *opt.mine_classes) {
      const auto it = std::find(pr.names.begin(), pr.names.end(), name);
      if (it == pr.names.end()) {
        std::string all;
        for (const auto& n : pr.names)
          all += (all.empty() ? "" : ", ") + n;
        throw std::runtime_error("mine class '" + name + "' is not a class of the training set (" +
                                 all + ")");
      }
      mine[static_cast<std::size_t>(it - pr.names.begin())] = true;
    }
  }

  for (std::size_t c = 0; c < pr.names.size(); ++c) {
    m.classes.push_back(fit_class(pr, pr.members[c], pr.names[c], mine[c], opt));
    if (opt.reject_quantile > 0.0 || opt.calibrate) {
      const std::vector<float> d = cross_validated_distances(pr, pr.members[c], opt);
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
      auto& dst = mine[c] ? mine_cols : other_cols;
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
    m.groups.push_back(fit_class(pr, mine_cols, std::string(kMineGroupName), true, opt));
    m.groups.push_back(fit_class(pr, other_cols, std::string(kNonMineGroupName), false, opt));
  }
  validate_model(m);
  return m;
}

Classifier::Classifier(Model model) : model_(std::move(model)) {
  validate_model(model_);
  scratch_.reserve(model_.chip_width, model_.chip_height);
  const auto n = static_cast<Eigen::Index>(model_.feature_count());
  int max_rank = 0;
  for (const auto* list : {&model_.classes, &model_.groups}) {
    for (const auto& c : *list) {
      for (const auto& s : c.subspaces)
        max_rank = std::max(max_rank, s.rank());
    }
  }
  x_.setZero(n);
  work_n_.setZero(n);
  work_p_.setZero(std::max(max_rank, 1));
  result_.class_distance.assign(model_.classes.size(), 0.0f);
  result_.class_subspace.assign(model_.classes.size(), -1);
}

float Classifier::class_distance(const ClassModel& c, int* best_subspace) {
  return nearest_subspace(c, x_, work_n_, work_p_, best_subspace);
}

ChipCheck Classifier::classify(ChipView chip) {
  Classification& r = result_;
  r.class_index = -1;
  r.subspace_index = -1;
  r.runner_up = -1;
  ChipCheck check = check_chip_size(chip, model_.chip_width, model_.chip_height);
  if (!check.ok()) return check;
  const ChipView features =
      model_.preprocess.is_identity() ? chip : preprocess_into(chip, model_.preprocess, scratch_);
  const ChipCheck norm =
      normalise_chip(features, std::span<float>(x_.data(), model_.feature_count()));
  if (!norm.ok()) {
    check = norm;
    check.expected_width = model_.chip_width;
    check.expected_height = model_.chip_height;
    return check;
  }

  // identification: the nearest class (eq. 10), and the runner-up
  float best = kInfinity, second = kInfinity;
  int best_i = -1, second_i = -1;
  for (std::size_t i = 0; i < model_.classes.size(); ++i) {
    int sub = -1;
    const float d = class_distance(model_.classes[i], &sub);
    r.class_distance[i] = d;
    r.class_subspace[i] = sub;
    if (d < best) {
      second = best;
      second_i = best_i;
      best = d;
      best_i = static_cast<int>(i);
    } else if (d < second) {
      second = d;
      second_i = static_cast<int>(i);
    }
  }
  r.class_index = best_i;
  r.distance = best;
  r.subspace_index = r.class_subspace[static_cast<std::size_t>(best_i)];
  r.runner_up = second_i;
  r.runner_up_distance = second;
  const float tau = model_.classes[static_cast<std::size_t>(best_i)].reject_distance;
  r.open_set_score = std::isfinite(tau) ? best / tau : 0.0f;
  r.unknown = r.open_set_score > 1.0f;

  // mine / non-mine (Section 4.1.2)
  r.mine_like_by_identity = model_.classes[static_cast<std::size_t>(best_i)].mine_like;
  if (!model_.groups.empty()) {
    int sub = -1;
    r.mine_distance = class_distance(model_.groups[0], &sub);
    r.non_mine_distance = class_distance(model_.groups[1], &sub);
    r.by_group_subspaces = true;
    r.mine_like = r.mine_distance < r.non_mine_distance;
  } else {
    r.mine_distance = kInfinity;
    r.non_mine_distance = kInfinity;
    for (std::size_t i = 0; i < model_.classes.size(); ++i) {
      float& g = model_.classes[i].mine_like ? r.mine_distance : r.non_mine_distance;
      g = std::min(g, r.class_distance[i]);
    }
    r.by_group_subspaces = false;
    r.mine_like = r.mine_like_by_identity;
  }
  return check;
}

}  // namespace sonarloop::atr
