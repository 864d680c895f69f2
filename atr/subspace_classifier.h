#pragma once
// The PCA (eigen-subspace) classifier of Pailhas, Petillot & Capus, "High-Resolution Sonars: What
// Resolution Do We Need for Target Recognition?", EURASIP J. Adv. Signal Process. 2010,
// Section 3.2 (identification) and Section 4.1.2 (mine / non-mine), with the remedy the paper
// proposes for aspect dependence (several subspaces per target, each for a range of aspects).
//
// Our reading of the method (the paper's equations are not reproduced here; this is the
// standard per-class eigen-subspace method that Section 3.2 describes):
//
//   Chips as vectors. A chip of n x m pixels is a vector x in R^(n*m) (row-major).
//   Pre-processing (ours, off by default; atr/chip_preprocess.h). A model may crop chips to
//     their centre, average speckle or keep only levels against the seabed before eq. 9; it is
//     stored in the model and applied alike in training and classification.
//   Eq. 9 (normalisation). Every chip, training or test, is centred on its own mean and divided
//     by its own standard deviation, taken over its pixels: x~ = (x - mean(x)) / std(x)
//     (atr/chip.h). This removes gain and offset.
//   Eq. 8 (mean image). For target class c with k training chips, mu_c = (1/k) sum_i x~_i.
//   Subspace. With A = [x~_1 - mu_c, ..., x~_k - mu_c] (n*m x k), the principal directions are
//     the leading eigenvectors of the covariance A A^T ((n*m)^2 entries: 16.7 M for 64 x 64
//     chips). They are found instead from the k x k Gram matrix G = A^T A: if G v = lambda v
//     then A A^T (A v) = lambda (A v), and u = A v / sqrt(lambda) is a unit eigenvector of A A^T
//     with the same eigenvalue. U_c holds the p = 20 leading u (orthonormal columns). A is
//     centred, so its rank is at most k - 1: a class with k <= p chips keeps rank k - 1 (or
//     fewer, when chips repeat), recorded as Subspace::rank(). Eigenvalues below
//     kRelativeEigenvalueFloor of the largest are dropped (their directions are rounding noise).
//   Eq. 10 (distance). A test chip y, normalised to y~, is compared with each class by the norm
//     of what its projection on the class subspace leaves out:
//        d_c(y) = | (y~ - mu_c) - U_c U_c^T (y~ - mu_c) |
//     and is identified as the class of smallest distance. Distances are in normalised units:
//     |y~| = sqrt(n) for every chip, so a chip unrelated to a class lies about sqrt(n) or more
//     from it (64 for 64 x 64 chips) and a chip the class explains well lies near 0.
//
// Multi-aspect subspaces (the paper's proposed remedy for aspect dependence). With
// aspect_sectors = N > 1, a class holds up to N subspaces, one per aspect sector
// [s * 360/N, (s + 1) * 360/N) deg, each trained only on the chips whose target aspect angle
// falls in it (training then needs every chip's aspect; sectors without chips are left out). The
// class distance is the smallest distance over its subspaces; the nearest subspace also tells
// the likely aspect range.
//
// Open-set rejection (ours). A class may carry a reject distance, calibrated on its training
// chips by cross-validation (TrainOptions::reject_quantile); a chip whose distance to the
// identified class exceeds it is reported unknown: an object of a type the model was not
// trained on should lie far from every subspace instead of being forced into the nearest one.
//
// Class metadata. Each class carries a mine_like flag, a clutter flag (a class of the detector's
// false alarms rather than of a target: onboard, what is identified as it is not reported) and,
// when known, the height of its objects above the seabed (used onboard to place a contact,
// atr/onboard_pipeline.h). Both come
// from TrainOptions::class_metadata and are stored in the model file; a class it does not list
// is not mine-like and of unknown height. The classifier knows nothing of the simulator's
// target types: `sonarloop train` fills the metadata of simulated target classes (manta, ...)
// from the simulator's table, and of any class from its --mine-like and --height options.
//
// Fused readings (ours; docs/autonomy.md, "Highlight and shadow fused"). A model may read each
// chip more than one way: besides its own pre-processing and classes, each view (ModelView)
// pre-processes the chip otherwise (the shadow only, levels below_seabed, beside a highlight-only
// model) and holds subspaces of the same classes, trained on the same chips. A chip's distance
// to a class is then the root of its summed squared eq. 10 distances over the readings,
//     D_c = sqrt(d_c^2 + sum_v d_{v,c}^2),
// eq. 10 for the readings stacked into one vector (each normalised by eq. 9 on its own) against
// the block-diagonal subspace of their subspaces; the nearest subspace of each reading is its
// own. A reading in which the chip is constant (a shadow-only reading of a chip without any
// pixel below the seabed, a highlight-only one of a cropped chip without a highlight) is blank:
// as far from every class as an unrelated chip, its n added to every class's square, which
// leaves the ranking to the other readings; in training it is left out of that reading's
// subspaces. A chip blank in every reading is unusable (constant). Distances then scale
// with sqrt(n (1 + views)) (Model::fused_feature_count). Group subspaces are the primary
// reading's only.
//
// Mine / non-mine (Section 4.1.2). On top of
// identification the classifier reports a group score for each group, the smallest class
// distance within it; the decision is the group of smaller score, which is the group of the
// identified class. Clutter classes belong to neither group. Optionally
// (TrainOptions::group_subspaces) the model also holds dedicated
// "mine" and "non_mine" subspaces, trained on all the chips of each group pooled (with the same
// aspect sectors); the group scores and the decision then come from those, and the group of the
// identified class is still reported as mine_like_by_identity.
//
// Onboard use: Classifier sizes its work vectors once; classify() does not allocate. Degenerate
// chips (wrong size, non-finite pixel, constant) are rejected with a ChipCheck that says why;
// they never produce NaN scores. Training cost per subspace: O(k^2 n) to form G, O(k^3) for its
// eigen-decomposition, O(k n p) for U; with more chips than pixels (k > n) the n x n covariance
// is decomposed instead: O(k n^2) to form it, O(n^3) for its eigen-decomposition (the same
// non-zero eigenvalues and directions). Classification costs about 4 n p flops per subspace.
// Training memory: the normalised chips once, as float (n k values), plus at most about four
// n x n or k x k double matrices for one subspace (atr/subspace_training.cpp).
#include <Eigen/Dense>
#include <cstddef>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "atr/chip.h"
#include "atr/chip_preprocess.h"
#include "atr/logistic_gate.h"

namespace sonarloop::atr {

// p, the number of leading eigenvectors kept per subspace (Section 3.2).
inline constexpr int kDefaultSubspaceDim = 20;
// Gram eigenvalues below this fraction of the largest are dropped: chips are float
// (relative rounding 6e-8), so a direction whose eigenvalue (a squared singular value) is
// 1e-10 of the largest, i.e. whose singular value is 1e-5 of the largest, is rounding noise.
inline constexpr double kRelativeEigenvalueFloor = 1e-10;
// Names of the dedicated group subspaces (Model::groups).
inline constexpr std::string_view kMineGroupName = "mine";
inline constexpr std::string_view kNonMineGroupName = "non_mine";
// The name `sonarloop train` gives the clutter flag by default (ClassMetadata::clutter), and the
// label of the false-alarm chips of training surveys (mission/survey_chips.h).
inline constexpr std::string_view kClutterClassName = "clutter";

// One eigen-subspace: a mean image and an orthonormal basis.
struct Subspace {
  // The aspect sector of its training chips [min, max) in degrees; [0, 360) for all aspects.
  double aspect_min_deg = 0.0;
  double aspect_max_deg = 360.0;
  int train_count = 0;          // k, the chips it was trained on
  Eigen::VectorXf mean;         // mu (n): the mean normalised chip, eq. 8
  Eigen::MatrixXf basis;        // U (n x rank): orthonormal columns, leading eigenvectors first
  Eigen::VectorXd eigenvalues;  // (rank) Gram eigenvalues, descending (squared singular values)

  int rank() const { return static_cast<int>(basis.cols()); }
};

// The largest class height accepted (m): beyond it a value is a mistake (units), not an object.
inline constexpr double kMaxClassHeight_m = 100.0;
// Whether h is a usable class height: finite, 0 to kMaxClassHeight_m.
bool valid_class_height(double h_m);

// What a class is, beyond its chips: stored per class in the model.
struct ClassMetadata {
  bool mine_like = false;
  // height of the class's objects above the seabed (m); unset: unknown, and the onboard
  // pipeline places the contact with the detector's shadow height instead
  std::optional<double> height_m;
  // a class of the detector's false alarms (rocks, relief: hard negatives from training
  // surveys, mission/survey_training.h), not of a target: the onboard consumer does not report
  // an object identified as it, and it takes no part in the mine / non-mine group scores
  bool clutter = false;
};

// One target class (or one mine / non-mine group).
struct ClassModel {
  std::string name;
  bool mine_like = false;
  bool clutter = false;             // see ClassMetadata; never mine-like
  std::optional<double> height_m;   // see ClassMetadata; unset for groups
  std::vector<Subspace> subspaces;  // one per aspect sector that had training chips
  // Open-set rejection: a chip identified as this class whose distance exceeds this is reported
  // as unknown; +infinity (the default) never rejects. See TrainOptions::reject_quantile.
  float reject_distance = std::numeric_limits<float>::infinity();
  // The class's typical distance: the median of its own chips' cross-validated distances (see
  // TrainOptions::calibrate); 0 when not calibrated. Distances divided by it compare across
  // classes and models (highlight + shadow fusion, atr/fusion.h).
  float typical_distance = 0.0f;
};

// Another reading of a model's chips (see "Fused readings" above).
struct ModelView {
  ChipPreprocess preprocess;  // with the model's crop fraction (the same feature count)
  // one per model class, in the model's order and with its name, mine_like, clutter and
  // height; only their subspaces are read (reject and typical distances are the model
  // classes', on the fused distance, so these keep +infinity and 0)
  std::vector<ClassModel> classes;
};
inline constexpr std::size_t kMaxModelViews = 3;

// The detector's object rules a model's gates were trained behind (atr/detector.h,
// DetectorOptions::min_pings and min_along_m): a gate's threshold is chosen on what that detector
// reports, so the onboard pipeline runs its detector with the rules of the model it classifies
// with (atr/onboard_pipeline.h). train --surveys records them (mission/survey_training.h).
struct DetectorRules {
  int min_pings = 2;
  double min_along_m = 0.1;
  friend bool operator==(const DetectorRules&, const DetectorRules&) = default;
};
inline constexpr int kMaxDetectorRulePings = 1000;
inline constexpr double kMaxDetectorRuleAlong_m = 100.0;

// A trained model: plain data, saved and loaded by atr/model_file.h.
struct Model {
  int chip_width = 0;           // pixels of the chips the model takes
  int chip_height = 0;          // pixels
  int p = kDefaultSubspaceDim;  // requested subspace dimension (a subspace may hold fewer)
  int aspect_sectors = 1;
  // applied to every chip before eq. 9, in training and classification (atr/chip_preprocess.h);
  // the subspaces live in the pre-processed (feature) size
  ChipPreprocess preprocess;
  std::vector<ClassModel> classes;  // identification classes, in training order (sorted names)
  std::vector<ClassModel> groups;   // empty, or {"mine", "non_mine"} (Section 4.1.2)
  // the onboard consumer's contact gates (atr/contact_gate.h), when trained: on the detector's
  // features before a chip is classified, and on those and the classification after
  std::optional<LogisticGate> detection_gate;
  std::optional<LogisticGate> classification_gate;
  // the detector's rules the gates were trained behind; none: the detector's own options
  std::optional<DetectorRules> detector_rules;
  // further readings of each chip, fused with the primary one (empty: none)
  std::vector<ModelView> views;

  std::size_t pixel_count() const {
    return static_cast<std::size_t>(chip_width) * static_cast<std::size_t>(chip_height);
  }
  // The size of a chip after pre-processing (the crop), which the subspaces work in.
  int feature_width() const { return cropped_size(chip_width, preprocess.crop_fraction); }
  int feature_height() const { return cropped_size(chip_height, preprocess.crop_fraction); }
  std::size_t feature_count() const {
    return static_cast<std::size_t>(feature_width()) * static_cast<std::size_t>(feature_height());
  }
  // The features of every reading together: a chip unrelated to a class lies about the root of
  // it away (feature_count() without views).
  std::size_t fused_feature_count() const { return feature_count() * (1 + views.size()); }
  // Index of the class called `name`, or -1.
  int find_class(std::string_view name) const;
  // Whether any class is mine-like: without one the mine / non-mine decision means nothing, and
  // the tools do not report it.
  bool has_mine_like_class() const;
};

// Throws std::runtime_error naming the first inconsistency: sizes, counts, ranks, non-finite
// values, a basis that is not orthonormal (to 1e-3), duplicate or empty names, bad groups, a gate
// of the wrong stage or size (validate_gate).
void validate_model(const Model& m);

// The aspect sector (0 .. sectors-1) of an aspect angle: [s * 360/N, (s + 1) * 360/N) after
// wrapping the angle to [0, 360).
int aspect_sector(double aspect_deg, int sectors);

// Eq. 8 and the eigen-decomposition for one subspace. `x` holds k >= 1 normalised chips as
// columns (n x k). Keeps at most p directions (and at most the rank of the centred data).
// Through the k x k Gram matrix when k <= n, else through the n x n covariance. Computed in
// double; stored in float.
Subspace fit_subspace(const Eigen::MatrixXd& x, int p);
// The same for the columns `cols` of a float matrix, without copying them all in double when
// there are more of them than rows (the covariance is then accumulated a block at a time).
Subspace fit_subspace(const Eigen::MatrixXf& x, std::span<const Eigen::Index> cols, int p);

// The class distance of a normalised chip x (n): the smallest eq. 10 residual over the class's
// subspaces, and in *best_subspace the index of that subspace (-1 without any). work_n (n);
// work_p must hold the largest rank. Allocation-free.
float nearest_subspace(const ClassModel& c, const Eigen::VectorXf& x, Eigen::VectorXf& work_n,
                       Eigen::VectorXf& work_p, int* best_subspace);

// Eq. 10: | r - U U^T r | with r = x - mu, for a normalised chip x (n). work_n (n) receives the
// residual vector r - U U^T r; work_p must hold at least rank() values. Allocation-free.
float subspace_residual(const Subspace& s, const Eigen::Ref<const Eigen::VectorXf>& x,
                        Eigen::Ref<Eigen::VectorXf> work_n, Eigen::Ref<Eigen::VectorXf> work_p);

struct TrainOptions {
  int p = kDefaultSubspaceDim;   // leading eigenvectors per subspace, >= 1
  int aspect_sectors = 1;        // N >= 1; N > 1 needs every chip's aspect_deg
  bool group_subspaces = false;  // also train pooled "mine" / "non_mine" subspaces
  ChipPreprocess preprocess;     // stored in the model, applied before eq. 9
  // further readings of every chip (Model::views), each with the model's crop fraction; a chip
  // constant in one reading (the first included) is left out of that reading's subspaces (and,
  // calibrating, is as far from them as an unrelated chip, as in classification)
  std::vector<ChipPreprocess> views;
  // Open-set rejection (ours; the paper always picks a known class). When in (0, 1), each
  // class's reject_distance is the reject_quantile-quantile of its own chips' distances to
  // its subspaces in a reject_folds-fold cross-validation over the training chips (each chip
  // scored by a subspace trained without it), so that about 1 - q of a known class's chips are
  // expected to be rejected. 0 leaves rejection off.
  double reject_quantile = 0.0;
  int reject_folds = 5;
  // Cross-validate each class's distances (reject_folds folds) to set typical_distance; also
  // done whenever reject_quantile > 0. Costs about reject_folds extra fits per class.
  bool calibrate = false;
  // Metadata of classes by name, stored in the model. Names that are not classes of the
  // training set are ignored (a table of every known type may be passed); a class not listed is
  // not mine-like and of unknown height.
  std::map<std::string, ClassMetadata, std::less<>> class_metadata;
  // Unusable chips (unreadable, constant, non-finite, of another size than the first usable
  // one): skipped and listed in the report when true, an error naming the chip when false.
  bool skip_degenerate = false;
  // Called as training goes: stage ("reading chips", "fitting subspaces"), done, total.
  std::function<void(std::string_view stage, std::size_t done, std::size_t total)> progress;
};

struct TrainReport {
  using Skipped = SkippedChip;
  std::vector<Skipped> skipped;
};

// Trains one class per distinct label (sorted by name) from labelled chips, which must all have
// the same size. Throws std::runtime_error naming the chip or option at fault.
Model train_model(std::span<const LabelledChip> chips, const TrainOptions& options = {},
                  TrainReport* report = nullptr);

// Supplies the pixels of chip `index` of a training set; the view stays valid until the next
// call. Throws std::runtime_error when the chip cannot be read (skipped with skip_degenerate).
using ChipLoader = std::function<ChipView(std::size_t index)>;

// The same, for chips read one at a time: `chips` gives labels, sources and aspect angles (their
// pixels are not used), `load` the pixels, each chip once, in order. Training then holds the
// normalised chips only, never all the raw ones (study/chip_folder.h read_folder_chip).
Model train_model(std::span<const LabelledChip> chips, const ChipLoader& load,
                  const TrainOptions& options, TrainReport* report = nullptr);

// The outcome of classifying one chip.
struct Classification {
  int class_index = -1;   // the identified class (index into Model::classes), -1 if none
  float distance = 0.0f;  // its eq. 10 distance
  // its nearest subspace (aspect sector); -1, aspect unknown, for a chip blank in the first of
  // several readings whose class has no subspace of the other reading's sector
  int subspace_index = -1;
  int runner_up = -1;                 // the second-nearest class, -1 when the model has one class
  float runner_up_distance = 0.0f;    // +infinity when there is no runner-up
  std::vector<float> class_distance;  // (classes) distance to each class: min over its subspaces
  std::vector<int> class_subspace;    // (classes) index of that nearest subspace (or -1)
  // Mine / non-mine (Section 4.1.2).
  bool mine_like = false;              // the decision
  bool mine_like_by_identity = false;  // the identified class's mine_like flag
  bool by_group_subspaces = false;     // scores come from the model's dedicated group subspaces
  float mine_distance = 0.0f;          // group scores; +infinity for a group without any class
  float non_mine_distance = 0.0f;
  // Open-set rejection: distance / the identified class's reject_distance (0 when it has none);
  // above 1 the chip is unknown (class_index still names the nearest class).
  float open_set_score = 0.0f;
  bool unknown = false;
};

// The classification `r` by `m` with its clutter classes left out: the nearest target class
// identified (its distance, subspace, runner-up among the target classes, mine-likeness); `r`
// itself when it identified a target class or `m` has no clutter class; class_index -1 when
// `m` has no target class. For reporting a detection that a contact gate passed although its
// nearest class is clutter.
Classification without_clutter(const Classification& r, const Model& m);

// Classifies chips with a fixed model. Not thread-safe (one per thread); classify() does not
// allocate.
class Classifier {
 public:
  // Validates the model (throws std::runtime_error) and sizes the work vectors.
  explicit Classifier(Model model);

  const Model& model() const { return model_; }

  // Checks the chip (model size, finite, not constant), normalises it (eq. 9) and scores it
  // against every subspace (eq. 10). On success result() holds the answer; on failure the
  // returned check says why and result().class_index is -1. Allocation-free.
  ChipCheck classify(ChipView chip);
  const Classification& result() const { return result_; }

  // The normalised (pre-processed) chip of the last classify() call (feature_count), for
  // inspection.
  const Eigen::VectorXf& normalised() const { return x_; }

 private:
  float class_distance(const ClassModel& c, int* best_subspace);
  // A failed check of a chip, with the model's chip size as the expected one.
  ChipCheck with_expected_size(ChipCheck check) const;
  // Normalises the chip's reading by each view into view_x_; a constant one is marked blank.
  void read_views(ChipView chip);

  Model model_;
  PreprocessScratch scratch_;
  Eigen::VectorXf x_;                      // normalised chip (n)
  std::vector<Eigen::VectorXf> view_x_;    // each view's normalised reading (n)
  std::vector<unsigned char> view_blank_;  // the chip is constant in that view's reading
  Eigen::VectorXf work_n_;                 // residual (n)
  Eigen::VectorXf work_p_;                 // projection coefficients (max rank)
  Classification result_;
};

}  // namespace sonarloop::atr
