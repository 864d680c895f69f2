#include "atr/subspace_classifier.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

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
  if (c.height_m && !valid_class_height(*c.height_m)) {
    throw std::runtime_error(what + " '" + c.name + "': height " + std::to_string(*c.height_m) +
                             " m (allowed 0 to " + std::to_string(kMaxClassHeight_m) + " m)");
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

// The index of c's subspace of s's aspect sector, -1 when it has none.
int same_sector(const ClassModel& c, const Subspace& s) {
  for (std::size_t k = 0; k < c.subspaces.size(); ++k) {
    if (c.subspaces[k].aspect_min_deg == s.aspect_min_deg &&
        c.subspaces[k].aspect_max_deg == s.aspect_max_deg)
      return static_cast<int>(k);
  }
  return -1;
}

}  // namespace

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

int Model::find_class(std::string_view name) const {
  for (std::size_t i = 0; i < classes.size(); ++i) {
    if (classes[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

bool Model::has_mine_like_class() const {
  return std::any_of(classes.begin(), classes.end(),
                     [](const ClassModel& c) { return c.mine_like; });
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
    if (m.classes[i].clutter && m.classes[i].mine_like) {
      throw std::runtime_error("model class '" + m.classes[i].name +
                               "' is both clutter and mine-like");
    }
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
    if (m.groups[0].clutter || m.groups[1].clutter) {
      throw std::runtime_error("model groups cannot be clutter");
    }
    for (const auto& g : m.groups)
      validate_class(g, m, "group");
  }
  if (m.detection_gate) {
    if (m.detection_gate->stage != GateStage::kDetection) {
      throw std::runtime_error("model detection gate is of the classification stage");
    }
    validate_gate(*m.detection_gate);
  }
  if (m.classification_gate) {
    if (m.classification_gate->stage != GateStage::kClassification) {
      throw std::runtime_error("model classification gate is of the detection stage");
    }
    validate_gate(*m.classification_gate);
  }
  if (m.views.size() > kMaxModelViews) {
    throw std::runtime_error("model has " + std::to_string(m.views.size()) + " views (at most " +
                             std::to_string(kMaxModelViews) + ")");
  }
  for (std::size_t v = 0; v < m.views.size(); ++v) {
    const ModelView& view = m.views[v];
    const std::string what = "view " + std::to_string(v) + " class";
    try {
      validate_preprocess(view.preprocess);
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error("model view " + std::to_string(v) + ": " + e.what());
    }
    if (view.preprocess.crop_fraction != m.preprocess.crop_fraction) {
      throw std::runtime_error("model view " + std::to_string(v) +
                               ": its crop fraction differs from the model's (the readings "
                               "must have the same feature count)");
    }
    if (view.classes.size() != m.classes.size()) {
      throw std::runtime_error("model view " + std::to_string(v) + " has " +
                               std::to_string(view.classes.size()) + " classes, the model " +
                               std::to_string(m.classes.size()));
    }
    for (std::size_t i = 0; i < view.classes.size(); ++i) {
      const ClassModel& c = view.classes[i];
      if (c.name != m.classes[i].name) {
        throw std::runtime_error("model view " + std::to_string(v) + " class " + std::to_string(i) +
                                 " is '" + c.name + "', the model's '" + m.classes[i].name + "'");
      }
      if (std::isfinite(c.reject_distance) || c.typical_distance != 0.0f) {
        throw std::runtime_error("model view " + std::to_string(v) + " class '" + c.name +
                                 "' has its own reject or typical distance (the model's "
                                 "classes hold them, on the fused distance)");
      }
      validate_class(c, m, what);
    }
  }
  if (m.detector_rules) {
    const DetectorRules& d = *m.detector_rules;
    if (d.min_pings < 1 || d.min_pings > kMaxDetectorRulePings) {
      throw std::runtime_error("model detector rules: min_pings = " + std::to_string(d.min_pings) +
                               " (allowed 1 to " + std::to_string(kMaxDetectorRulePings) + ")");
    }
    if (!(d.min_along_m >= 0.0 && d.min_along_m <= kMaxDetectorRuleAlong_m)) {
      throw std::runtime_error("model detector rules: min_along_m = " +
                               std::to_string(d.min_along_m) + " (allowed 0 to 100 m)");
    }
  }
}

bool valid_class_height(double h_m) {
  return std::isfinite(h_m) && h_m >= 0.0 && h_m <= kMaxClassHeight_m;
}

int aspect_sector(double aspect_deg, int sectors) {
  if (sectors <= 1) return 0;
  double a = std::fmod(aspect_deg, 360.0);
  if (a < 0.0) a += 360.0;
  const int s = static_cast<int>(std::floor(a * sectors / 360.0));
  return std::clamp(s, 0, sectors - 1);
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

Classifier::Classifier(Model model) : model_(std::move(model)) {
  validate_model(model_);
  scratch_.reserve(model_.chip_width, model_.chip_height);
  const auto n = static_cast<Eigen::Index>(model_.feature_count());
  int max_rank = 0;
  auto widen = [&max_rank](const std::vector<ClassModel>& list) {
    for (const auto& c : list) {
      for (const auto& s : c.subspaces)
        max_rank = std::max(max_rank, s.rank());
    }
  };
  widen(model_.classes);
  widen(model_.groups);
  for (const ModelView& v : model_.views)
    widen(v.classes);
  view_x_.assign(model_.views.size(), Eigen::VectorXf::Zero(n));
  view_blank_.assign(model_.views.size(), 0);
  x_.setZero(n);
  work_n_.setZero(n);
  work_p_.setZero(std::max(max_rank, 1));
  result_.class_distance.assign(model_.classes.size(), 0.0f);
  result_.class_subspace.assign(model_.classes.size(), -1);
}

ChipCheck Classifier::with_expected_size(ChipCheck check) const {
  check.expected_width = model_.chip_width;
  check.expected_height = model_.chip_height;
  return check;
}

float Classifier::class_distance(const ClassModel& c, int* best_subspace) {
  return nearest_subspace(c, x_, work_n_, work_p_, best_subspace);
}

void Classifier::read_views(ChipView chip) {
  for (std::size_t v = 0; v < model_.views.size(); ++v) {
    const ChipView features = preprocess_into(chip, model_.views[v].preprocess, scratch_);
    const ChipCheck c =
        normalise_chip(features, std::span<float>(view_x_[v].data(), model_.feature_count()));
    // the chip passed the primary reading's checks (size, finite): only constant remains
    view_blank_[v] = c.ok() ? 0 : 1;
  }
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
  // with further readings, a chip constant in the first one is blank there (a chip without a
  // highlight, read with a shadow reading beside); a chip blank in every reading is unusable
  const bool blank = !norm.ok() && norm.status == ChipStatus::kConstant && !model_.views.empty();
  if (!norm.ok() && !blank) return with_expected_size(norm);
  read_views(chip);
  if (blank &&
      std::all_of(view_blank_.begin(), view_blank_.end(), [](unsigned char b) { return b != 0; }))
    return with_expected_size(norm);
  // a blank reading is as far from every class as an unrelated chip: n
  const auto blank_square = static_cast<float>(model_.feature_count());

  // identification: the nearest class (eq. 10, fused over the readings), and the runner-up
  float best = kInfinity, second = kInfinity;
  int best_i = -1, second_i = -1;
  for (std::size_t i = 0; i < model_.classes.size(); ++i) {
    int sub = -1;
    float d = blank ? 0.0f : class_distance(model_.classes[i], &sub);
    if (!model_.views.empty()) {
      float square = blank ? blank_square : d * d;
      for (std::size_t v = 0; v < model_.views.size(); ++v) {
        int view_sub = -1;
        const float dv = view_blank_[v] ? 0.0f
                                        : nearest_subspace(model_.views[v].classes[i], view_x_[v],
                                                           work_n_, work_p_, &view_sub);
        square += view_blank_[v] ? blank_square : dv * dv;
        // blank in the first reading: the aspect sector of the first other reading's nearest
        // subspace (-1 when the class's first reading has no subspace of that sector)
        if (blank && sub < 0 && view_sub >= 0) {
          sub =
              same_sector(model_.classes[i],
                          model_.views[v].classes[i].subspaces[static_cast<std::size_t>(view_sub)]);
        }
      }
      d = std::sqrt(square);
    }
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
  if (!model_.groups.empty() && !blank) {
    int sub = -1;
    r.mine_distance = class_distance(model_.groups[0], &sub);
    r.non_mine_distance = class_distance(model_.groups[1], &sub);
    r.by_group_subspaces = true;
    r.mine_like = r.mine_distance < r.non_mine_distance;
  } else {
    r.mine_distance = kInfinity;
    r.non_mine_distance = kInfinity;
    for (std::size_t i = 0; i < model_.classes.size(); ++i) {
      if (model_.classes[i].clutter) continue;
      float& g = model_.classes[i].mine_like ? r.mine_distance : r.non_mine_distance;
      g = std::min(g, r.class_distance[i]);
    }
    r.by_group_subspaces = false;
    r.mine_like = r.mine_like_by_identity;
  }
  return check;
}

Classification without_clutter(const Classification& r, const Model& m) {
  if (r.class_index < 0 || !m.classes[static_cast<std::size_t>(r.class_index)].clutter) return r;
  Classification t = r;
  int best = -1, second = -1;
  for (std::size_t i = 0; i < m.classes.size(); ++i) {
    if (m.classes[i].clutter) continue;
    const int k = static_cast<int>(i);
    if (best < 0 || r.class_distance[i] < r.class_distance[static_cast<std::size_t>(best)]) {
      second = best;
      best = k;
    } else if (second < 0 ||
               r.class_distance[i] < r.class_distance[static_cast<std::size_t>(second)]) {
      second = k;
    }
  }
  t.class_index = best;
  if (best < 0) return t;
  const auto b = static_cast<std::size_t>(best);
  t.distance = r.class_distance[b];
  t.subspace_index = r.class_subspace[b];
  t.runner_up = second;
  t.runner_up_distance = second >= 0 ? r.class_distance[static_cast<std::size_t>(second)]
                                     : std::numeric_limits<float>::infinity();
  const float tau = m.classes[b].reject_distance;
  t.open_set_score = std::isfinite(tau) ? t.distance / tau : 0.0f;
  t.unknown = t.open_set_score > 1.0f;
  t.mine_like_by_identity = m.classes[b].mine_like;
  if (!t.by_group_subspaces) t.mine_like = t.mine_like_by_identity;
  return t;
}

}  // namespace sonarloop::atr
