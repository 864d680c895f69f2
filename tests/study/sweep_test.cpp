// The pure parts of the resolution study (study/sweep.h): rates and intervals, experiment
// definitions, render groups, training prefixes, scoring and the CSV rows.
#include "study/sweep.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <sstream>
#include <stdexcept>

namespace sonarloop::study {
using namespace sonarloop::atr;  // the classifier the study trains and scores
namespace {

using targets::TargetType;

SweepSettings settings() {
  SweepSettings s;
  s.seabeds = {render::builtin_dataset_seabed("flat")};
  return s;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string l; std::getline(ss, l);)
    out.push_back(l);
  return out;
}

// A model with the given class names (one rank-0 subspace each, 1 x 2 chips).
Model toy_model(const std::vector<std::string>& names) {
  Model m;
  m.chip_width = 2;
  m.chip_height = 1;
  for (const auto& n : names) {
    ClassModel c;
    c.name = n;
    c.mine_like = n == "manta" || n == "rockan" || n == "cylinder" || n == "cuboid";
    Subspace s;
    s.train_count = 1;
    s.mean = Eigen::VectorXf::Zero(2);
    s.basis = Eigen::MatrixXf(2, 0);
    c.subspaces.push_back(s);
    m.classes.push_back(c);
  }
  return m;
}

// A toy model with the experiment's classes, in its order.
Model experiment_model(const SweepExperiment& e) {
  std::vector<std::string> names;
  for (TargetType t : e.classes)
    names.emplace_back(targets::target_type_info(t).key);
  return toy_model(names);
}

TEST_CASE("error_rate: rate and Wilson interval of the errors", "[sweep]") {
  const ErrorRate r = error_rate(5, 100);
  CHECK(r.rate == Approx(0.05));
  // Wilson 95 % for 5/100: 2.15 % .. 11.18 % (standard tables)
  CHECK(r.ci.lo == Approx(0.0215).margin(5e-4));
  CHECK(r.ci.hi == Approx(0.1118).margin(5e-4));
  const ErrorRate none = error_rate(0, 0);
  CHECK(none.rate == 0.0);
  CHECK(none.ci.lo == 0.0);
  CHECK(none.ci.hi == 1.0);
  const ErrorRate zero = error_rate(0, 40);
  CHECK(zero.ci.lo == 0.0);
  CHECK(zero.ci.hi > 0.05);  // 0 of 40 still allows ~9 %
}

TEST_CASE("experiments: the paper's figures and the stability studies", "[sweep]") {
  const SweepSettings s = settings();
  for (const auto& name : sweep_experiment_names())
    CHECK_FALSE(make_sweep_experiment(name, s).conditions.empty());
  CHECK_THROWS_AS(make_sweep_experiment("fig99", s), std::invalid_argument);

  const SweepExperiment f11 = make_sweep_experiment("fig11", s);
  REQUIRE(f11.conditions.size() == 15);  // 15 resolutions, 3 to 30 cm
  CHECK(f11.conditions.front().x == 3.0);
  CHECK(f11.conditions.back().x == 30.0);
  CHECK(f11.classes.size() == 4);
  CHECK(f11.conditions[2].train_count == 80);

  const SweepExperiment f13 = make_sweep_experiment("fig13", s);
  // Sec. 4.1.2: mine-like Manta, Rockan, cylinder; non-mine cuboid 100 x 50 x 40 cm, hemispheres
  // of 100 and 50 cm, box 70 x 70 x 40 cm
  CHECK(f13.classes == std::vector<TargetType>{TargetType::kManta, TargetType::kRockan,
                                               TargetType::kCylinder, TargetType::kLargeCuboid,
                                               TargetType::kHemisphere,
                                               TargetType::kSmallHemisphere, TargetType::kBox});
  for (TargetType t : f13.classes) {
    const auto& info = targets::target_type_info(t);
    CHECK(info.mine_like ==
          (t == TargetType::kManta || t == TargetType::kRockan || t == TargetType::kCylinder));
  }
  CHECK(f13.mine_groups);
  const SweepExperiment f15 = make_sweep_experiment("fig15", s);
  CHECK(f15.kind == chips::ChipKind::kShadow);
  CHECK(f15.conditions.front().x == 5.0);

  SweepSettings two = s;
  two.resolutions_cm = {5, 20};
  CHECK(make_sweep_experiment("fig11", two).conditions.size() == 2);
  // a stability study runs once per resolution, one series each
  const SweepExperiment alt = make_sweep_experiment("altitude", two);
  CHECK(alt.conditions.size() == 14);
  CHECK(alt.conditions.front().series == "5 cm");
  CHECK(alt.conditions.back().series == "20 cm");

  // p must stay below the training count (the rank of k centred chips is k - 1)
  SweepSettings few = s;
  few.train_count = 10;
  for (const auto& c : make_sweep_experiment("p", few).conditions)
    CHECK(c.p < 10);

  // --aspect-sectors: every condition trains that many subspaces per target, but the aspect
  // experiment, which compares 1, 4 and 8
  SweepSettings sectors = s;
  sectors.aspect_sectors = 4;
  for (const auto& name : {"fig11", "fig13", "fig15", "altitude", "fusion", "open_set"}) {
    for (const auto& c : make_sweep_experiment(name, sectors).conditions) {
      INFO(name << " " << c.series << " " << c.x);
      CHECK(c.aspect_sectors == 4);
    }
  }
  for (const auto& c : make_sweep_experiment("fig15", s).conditions)
    CHECK(c.aspect_sectors == 1);
  std::vector<int> compared;
  for (const auto& c : make_sweep_experiment("aspect", sectors).conditions)
    compared.push_back(c.aspect_sectors);
  CHECK(compared == std::vector<int>{1, 4, 8});
}

TEST_CASE("render_groups: conditions that render alike share chips", "[sweep]") {
  SweepSettings s = settings();
  s.resolutions_cm = {5, 10};
  const SweepExperiment p = make_sweep_experiment("train_size", s);
  const auto g = render_groups(p);
  REQUIRE(g.size() == 1);  // same altitude and source level
  REQUIRE(g[0].resolutions_m.size() == 2);
  CHECK(g[0].members[0].size() == 7);
  CHECK(g[0].train_count == 320);  // the largest training set, prefixes serve the others

  const auto snr = render_groups(make_sweep_experiment("snr", s));
  CHECK(snr.size() == 7);  // one renderer per source level
  const render::ChipDatasetSpec train = render_group_spec(p, g[0], s, false);
  const render::ChipDatasetSpec test = render_group_spec(p, g[0], s, true);
  CHECK(train.seed != test.seed);
  CHECK(train.resolutions_m == g[0].resolutions_m);
}

TEST_CASE("looks: one curve per number of looks fused, on the figures only", "[sweep]") {
  SweepSettings s = settings();
  s.resolutions_cm = {5, 10};
  s.looks = 3;
  for (const std::string name : {"fig11", "fig13", "fig15"}) {
    INFO(name);
    const SweepExperiment e = make_sweep_experiment(name, s);
    REQUIRE(e.conditions.size() == 2 * 3);
    for (std::size_t i = 0; i < e.conditions.size(); ++i) {
      const SweepCondition& c = e.conditions[i];
      CHECK(c.looks == static_cast<int>(i % 3) + 1);
      CHECK(c.series == std::vector<std::string>{"1 look", "2 looks", "3 looks"}[i % 3]);
      CHECK(c.resolution_m == Approx(i < 3 ? 0.05 : 0.10));
      // the same model serves every number of looks at one resolution
      CHECK(same_training(c, e.conditions[i - i % 3]));
      CHECK(same_training(c, e.conditions[(i + 3) % 6]) == false);
    }
    const auto g = render_groups(e);
    REQUIRE(g.size() == 1);
    CHECK(g[0].looks == 3);
    CHECK(g[0].members[0].size() == 3);
    // test chips in looks 0..2 of the test seed; training chips in look 0 only
    CHECK(render_group_spec(e, g[0], s, true, 2).look == 2);
    CHECK(render_group_spec(e, g[0], s, true, 2).seed == render_group_spec(e, g[0], s, true).seed);
    CHECK(render_group_spec(e, g[0], s, false).look == 0);
    CHECK(render_group_spec(e, g[0], s, true, 1).look_geometry ==
          render::LookGeometry::kIndependent);
    CHECK_THROWS_WITH(render_group_spec(e, g[0], s, false, 1), Catch::Contains("look 0 only"));
    CHECK_THROWS_AS(render_group_spec(e, g[0], s, true, 3), std::invalid_argument);
  }
  s.look_geometry = render::LookGeometry::kReciprocal;
  {
    const SweepExperiment e = make_sweep_experiment("fig15", s);
    CHECK(render_group_spec(e, render_groups(e)[0], s, true, 1).look_geometry ==
          render::LookGeometry::kReciprocal);
  }
  // the other experiments score single chips; one look is the paper's curve, unlabelled
  for (const auto& c : make_sweep_experiment("p", s).conditions)
    CHECK(c.looks == 1);
  CHECK(render_groups(make_sweep_experiment("p", s))[0].looks == 1);
  s.looks = 1;
  for (const auto& c : make_sweep_experiment("fig15", s).conditions) {
    CHECK(c.looks == 1);
    CHECK(c.series.empty());
  }
  // a condition that trains otherwise does not share its model
  SweepCondition a = make_sweep_experiment("fig15", s).conditions[0], b = a;
  b.looks = 2;
  CHECK(same_training(a, b));
  b.p = a.p + 1;
  CHECK_FALSE(same_training(a, b));
  b = a;
  b.register_centroid = true;
  CHECK_FALSE(same_training(a, b));
  s.looks = 0;
  CHECK_THROWS_WITH(make_sweep_experiment("fig15", s), Catch::Contains("1..8"));
  s.looks = kMaxSweepLooks + 1;
  CHECK_THROWS_AS(make_sweep_experiment("fig15", s), std::invalid_argument);
}

TEST_CASE("training_prefix keeps count chips per class", "[sweep]") {
  std::vector<LabelledChip> chips(12);
  for (std::size_t i = 0; i < chips.size(); ++i)
    chips[i].label = std::to_string(i % 3);
  const auto p = training_prefix(chips, 2, 3);
  REQUIRE(p.size() == 6);
  CHECK(p[5].label == "2");
  CHECK(training_prefix(chips, 100, 3).size() == 12);
}

TEST_CASE("score_chip and results_csv: per class, all, mine / non-mine, aspect", "[sweep]") {
  SweepSettings s = settings();
  s.resolutions_cm = {5};
  SweepExperiment e = make_sweep_experiment("fig13", s);
  e.aspect_bins = 4;
  const Model m = experiment_model(e);  // classes in e.classes order
  ConditionResult r(0, e, m);
  Classification c;
  // manta (truth 0) right twice; rockan (truth 1) called box (non-mine) once at aspect 100
  c.class_index = 0;
  c.mine_like = true;
  score_chip(r, e, m, 0, 10.0, 0, c);
  score_chip(r, e, m, 0, 200.0, 0, c);
  c.class_index = 6;
  c.mine_like = false;
  score_chip(r, e, m, 1, 100.0, 0, c);
  r.complete = true;
  CHECK(r.confusion.total() == 3);
  CHECK(r.mine_errors == 1);
  CHECK(r.aspect_errors[1 * 4 + 1] == 1);

  const auto rows = lines(results_csv(e, {r}));
  REQUIRE(rows.size() == 1 + 7 + 2 + 4 * 8);
  CHECK(rows[0].rfind("experiment,series,x_name,x,resolution_cm,class,n,errors,", 0) == 0);
  CHECK(rows[1].find(",manta,2,0,0.0000,") != std::string::npos);
  CHECK(rows[2].find(",rockan,1,1,100.0000,") != std::string::npos);
  CHECK(rows[8].find(",all,3,1,33.3333,") != std::string::npos);
  CHECK(rows[9].find(",mine_vs_non_mine,3,1,33.3333,") != std::string::npos);
  CHECK(rows[10].find("aspect_deg,45,") != std::string::npos);

  const auto conf = lines(confusion_csv(e, {r}));
  CHECK(conf.size() == 1 + 49);
  CHECK(conf[1] == "fig13,,resolution_cm,5,manta,manta,2");
}

TEST_CASE("score_chip: identification per test seabed when there are several", "[sweep]") {
  SweepSettings s = settings();
  s.seabeds.push_back(render::builtin_dataset_seabed("ripples"));
  s.resolutions_cm = {5};
  const SweepExperiment e = make_sweep_experiment("fig11", s);
  REQUIRE(e.seabed_names == std::vector<std::string>{"flat", "ripples"});
  const Model m = experiment_model(e);
  ConditionResult r(0, e, m);
  Classification c;
  c.class_index = 0;
  score_chip(r, e, m, 0, 0.0, 0, c);  // manta on flat: right
  score_chip(r, e, m, 1, 0.0, 1, c);  // rockan on ripples called manta: wrong
  score_chip(r, e, m, 0, 0.0, 1, c);  // manta on ripples: right
  CHECK(r.seabed_n == std::vector<std::size_t>{1, 2});
  CHECK(r.seabed_errors == std::vector<std::size_t>{0, 1});
  const auto rows = lines(results_csv(e, {r}));
  REQUIRE(rows.size() == 1 + 4 + 1 + 2);
  CHECK(rows[6].find(",seabed_flat,1,0,0.0000,") != std::string::npos);
  CHECK(rows[7].find(",seabed_ripples,2,1,50.0000,") != std::string::npos);

  // per target and seabed: the rockan's error is on ripples, the manta's chips split 1 + 1
  const auto per = lines(seabed_csv(e, {r}));
  REQUIRE(per.size() == 1 + 4 * 2);
  CHECK(per[0] ==
        "experiment,series,x_name,x,resolution_cm,class,seabed,n,errors,error_pct,ci_low_pct,"
        "ci_high_pct");
  CHECK(per[1].rfind("fig11,,resolution_cm,5,5,manta,flat,1,0,0.0000,", 0) == 0);
  CHECK(per[2].rfind("fig11,,resolution_cm,5,5,manta,ripples,1,0,0.0000,", 0) == 0);
  CHECK(per[3].rfind("fig11,,resolution_cm,5,5,rockan,flat,0,0,0.0000,", 0) == 0);
  CHECK(per[4].rfind("fig11,,resolution_cm,5,5,rockan,ripples,1,1,100.0000,", 0) == 0);
  for (std::size_t i = 5; i < per.size(); ++i)
    CHECK(per[i].find(",0,0,0.0000,") != std::string::npos);  // cuboid, cylinder: no chips
}

TEST_CASE("seabed_csv: the header alone with one seabed", "[sweep]") {
  SweepSettings s = settings();
  s.resolutions_cm = {5};
  const SweepExperiment e = make_sweep_experiment("fig11", s);
  REQUIRE(e.seabed_names.size() == 1);
  const Model m = experiment_model(e);
  ConditionResult r(0, e, m);
  Classification c;
  c.class_index = 0;
  score_chip(r, e, m, 1, 0.0, 0, c);
  CHECK(lines(seabed_csv(e, {r})).size() == 1);
}

TEST_CASE("ablation: every pre-processing variant at each resolution, labelled", "[sweep]") {
  SweepSettings s = settings();
  const SweepExperiment e = make_sweep_experiment("ablation", s);
  REQUIRE(e.conditions.size() % 2 == 0);
  const std::size_t variants = e.conditions.size() / 2;
  REQUIRE(variants >= 5);
  CHECK(e.conditions[0].x == 5.0);
  CHECK(e.conditions[variants].x == 15.0);
  CHECK(e.conditions[0].preprocess.is_identity());
  CHECK(e.conditions[0].series == "eq. 9 only");
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < variants; ++i) {
    validate_preprocess(e.conditions[i].preprocess);
    CHECK(e.conditions[i].series == e.conditions[i + variants].series);
    CHECK(std::find(labels.begin(), labels.end(), e.conditions[i].series) == labels.end());
    labels.push_back(e.conditions[i].series);
  }
  // one rendering per resolution: the variants share their chips
  const auto g = render_groups(e);
  REQUIRE(g.size() == 1);
  CHECK(g[0].resolutions_m.size() == 2);
}

TEST_CASE("open_set: each of the seven held out in turn, then the novel type; scoring and rows",
          "[sweep]") {
  SweepSettings s = settings();
  s.resolutions_cm = {5};
  const SweepExperiment e = make_sweep_experiment("open_set", s);
  REQUIRE(e.classes.size() == 8);  // fig13's seven, then the novel standing cylinder
  CHECK(e.classes.back() == TargetType::kStandingCylinder);
  CHECK(e.novel_from == 7);
  REQUIRE(e.conditions.size() == 9);  // none held out, each of the seven, the novel type
  CHECK(e.conditions[8].held_out == 7);
  CHECK(e.conditions[8].series == "held out: standing_cylinder");
  CHECK(e.conditions[0].held_out == -1);
  CHECK(e.conditions[0].series == "none held out");
  CHECK(e.conditions[2].held_out == 1);
  CHECK(e.conditions[2].series == "held out: rockan");
  for (const auto& c : e.conditions)
    CHECK(c.reject_quantile == 0.95);

  // the training set of "held out: rockan" has no rockan chip, the others keep theirs
  std::vector<LabelledChip> chips;
  for (int k = 0; k < 3; ++k) {
    for (TargetType t : e.classes) {
      LabelledChip l;
      l.label = std::string(targets::target_type_info(t).key);
      chips.push_back(l);
    }
  }
  const auto train = training_set(chips, e, e.conditions[2]);
  CHECK(train.size() == 3 * 6);
  CHECK(std::none_of(train.begin(), train.end(),
                     [](const LabelledChip& l) { return l.label == "rockan"; }));
  CHECK(training_set(chips, e, e.conditions[0]).size() == 3 * 7);  // never the novel type
  CHECK(training_set(chips, e, e.conditions[8]).size() == 3 * 7);

  // a model of the six others; its predictions gain an "unknown" column
  std::vector<std::string> names;
  for (TargetType t : e.classes) {
    if (t != TargetType::kRockan) names.emplace_back(targets::target_type_info(t).key);
  }
  const Model m = toy_model(names);  // manta, cylinder, large_cuboid, ...
  ConditionResult r(2, e, m);
  REQUIRE(r.confusion.predicted_classes().back() == "unknown");
  Classification c;
  c.class_index = 0;                  // manta
  score_chip(r, e, m, 0, 0.0, 0, c);  // manta, accepted: right
  c.unknown = true;
  score_chip(r, e, m, 0, 0.0, 0, c);  // manta, rejected: a false reject, a misidentification
  score_chip(r, e, m, 1, 0.0, 0, c);  // rockan (held out), rejected: right
  c.unknown = false;
  score_chip(r, e, m, 1, 0.0, 0, c);  // rockan, accepted as manta: wrong
  score_chip(r, e, m, 7, 0.0, 0, c);  // the novel type: another condition's, not scored here
  CHECK(r.known_n == 2);
  CHECK(r.known_rejected == 1);
  CHECK(r.unknown_n == 2);
  CHECK(r.unknown_accepted == 1);
  CHECK(r.confusion.total() == 2);  // held-out chips are not in the confusion matrix
  const auto rows = lines(results_csv(e, {r}));
  // 8 classes, all, false_reject, unknown_accepted
  REQUIRE(rows.size() == 1 + 8 + 1 + 2);
  CHECK(rows[1].find(",manta,2,1,50.0000,") != std::string::npos);
  CHECK(rows[9].find(",all,2,1,50.0000,") != std::string::npos);
  CHECK(rows[10].find(",false_reject,2,1,50.0000,") != std::string::npos);
  CHECK(rows[11].find(",unknown_accepted,2,1,50.0000,") != std::string::npos);

  // the novel type held out: the model of all seven, the novel chips are the unknown ones
  std::vector<std::string> seven;
  for (std::size_t k = 0; k < 7; ++k)
    seven.emplace_back(targets::target_type_info(e.classes[k]).key);
  const Model m7 = toy_model(seven);
  ConditionResult rn(8, e, m7);
  Classification n;
  n.class_index = 6;                    // box
  score_chip(rn, e, m7, 7, 0.0, 0, n);  // standing cylinder accepted as a box: wrong
  n.unknown = true;
  score_chip(rn, e, m7, 7, 0.0, 0, n);  // rejected: right
  CHECK(rn.unknown_n == 2);
  CHECK(rn.unknown_accepted == 1);
  CHECK(rn.confusion.total() == 0);

  // no novel type: the seven only, as before
  s.novel.clear();
  const SweepExperiment e7 = make_sweep_experiment("open_set", s);
  CHECK(e7.classes.size() == 7);
  CHECK(e7.conditions.size() == 8);
}

TEST_CASE("fusion: the same objects in both datasets; one series per input and norm", "[sweep]") {
  SweepSettings s = settings();
  s.resolutions_cm = {10};
  const SweepExperiment e = make_sweep_experiment("fusion", s);
  REQUIRE(e.conditions.size() == 5);  // highlight, shadow, both x 3 normalisations
  CHECK(is_fusion(e));
  CHECK(e.classes.size() == 4);
  CHECK_FALSE(e.mine_groups);
  const SweepExperiment e13 = make_sweep_experiment("fusion13", s);  // fig13's seven
  CHECK(is_fusion(e13));
  CHECK(e13.classes == fig13_classes(s));
  CHECK(e13.mine_groups);
  CHECK(e13.conditions.size() == 5);
  CHECK_FALSE(is_fusion(make_sweep_experiment("fig13", s)));
  CHECK(e.conditions[0].fusion == FusionInput::kHighlight);
  CHECK(e.conditions[1].fusion == FusionInput::kShadow);
  CHECK(e.conditions[3].series == "both (model_typical)");
  const auto groups = render_groups(e);
  REQUIRE(groups.size() == 1);
  const auto [h, sh] = fusion_specs(e, groups[0], s, true);
  CHECK(h.kind == chips::ChipKind::kHighlight);
  CHECK(sh.kind == chips::ChipKind::kShadow);
  CHECK(h.seed == s.seed + kTestSeedOffset);
  // chip i is the same object in both: every drawn parameter agrees
  for (std::uint64_t i = 0; i < 20; ++i) {
    const render::ChipParams a = render::chip_params(h, i), b = render::chip_params(sh, i);
    CHECK(a.type == b.type);
    CHECK(a.ground_range_m == b.ground_range_m);
    CHECK(a.target_heading_deg == b.target_heading_deg);
    CHECK(a.track_heading_deg == b.track_heading_deg);
    CHECK(a.altitude_m == b.altitude_m);
    CHECK(a.target_ne_m == b.target_ne_m);
  }
}

TEST_CASE("experiments: no series label holds a comma (the CSV has no quoting)", "[sweep]") {
  const SweepSettings s = settings();
  for (const std::string& name : sweep_experiment_names()) {
    for (const auto& c : make_sweep_experiment(name, s).conditions) {
      INFO(name << ": " << c.series);
      CHECK(c.series.find(',') == std::string::npos);
    }
  }
}

TEST_CASE("crop auto: per resolution on highlight experiments only", "[sweep]") {
  SweepSettings s = settings();
  s.crop_auto = true;
  s.resolutions_cm = {5, 20};
  const SweepExperiment f11 = make_sweep_experiment("fig11", s);
  CHECK(f11.conditions[0].preprocess.crop_fraction == Approx(0.4));
  CHECK(f11.conditions[1].preprocess.crop_fraction == Approx(2.0 / 3.0));
  for (const auto& c : make_sweep_experiment("fig15", s).conditions)
    CHECK(c.preprocess.crop_fraction == 1.0);  // shadow chips keep their length
  const SweepExperiment ab = make_sweep_experiment("ablation", s);
  CHECK(ab.conditions[0].preprocess.is_identity());  // the ablation sets its own
}

TEST_CASE("burial: one render group per burial; training chips always proud", "[sweep]") {
  SweepSettings s = settings();
  const SweepExperiment e = make_sweep_experiment("burial", s);
  REQUIRE(e.conditions.size() == 6);
  CHECK(e.classes.size() == 7);
  CHECK(e.mine_groups);
  CHECK(e.conditions[5].x_name == "burial_pct");
  CHECK(e.conditions[5].burial_fraction == Approx(0.5));
  const auto groups = render_groups(e);
  REQUIRE(groups.size() == 6);
  CHECK(render_group_spec(e, groups[5], s, true).burial_fraction == Approx(0.5));
  CHECK(render_group_spec(e, groups[5], s, false).burial_fraction == 0.0);
}

TEST_CASE("registration: windows cut off the centre, and re-centred on the highlight", "[sweep]") {
  SweepSettings s = settings();
  s.resolutions_cm = {5};
  s.crop_auto = true;  // the window replaces any crop
  const SweepExperiment e = make_sweep_experiment("registration", s);
  REQUIRE(e.conditions.size() == 10);  // 5 offsets, as cut and registered
  for (const SweepCondition& c : e.conditions) {
    CHECK(c.window_m == 1.2);
    CHECK(c.preprocess.is_identity());
  }
  CHECK(e.conditions[0].misregister_m == 0.0);
  CHECK(e.conditions[4].misregister_m == 0.5);
  CHECK_FALSE(e.conditions[4].register_centroid);
  CHECK(e.conditions[9].register_centroid);

  // a 3 m chip at 5 cm (60 x 60) of seabed with a bright 5 x 5 target at its centre
  Chip chip;
  chip.width = chip.height = 60;
  chip.pixels.assign(3600, 100.0f);
  for (int r = 27; r < 32; ++r)
    for (int k = 27; k < 32; ++k)
      chip.pixels[static_cast<std::size_t>(r) * 60 + k] = 200.0f;
  const SweepCondition& as_cut = e.conditions[3];  // 0.3 m off, as cut
  const SweepCondition& registered = e.conditions[8];
  const Chip centred = registration_chip(chip.view(), as_cut, 7, false);  // training: centred
  REQUIRE(centred.width == 24);
  REQUIRE(centred.height == 24);
  // test chips: cut off the centre (a different place per index), the same for one index
  // registered training chips are centred on the highlight centroid (here the target's
  // centre, (29, 29), half a pixel from the chip's)
  const Chip on_target = registration_chip(chip.view(), registered, 7, false);
  CHECK(on_target.pixels[12 * 24 + 12] == 200.0f);
  CHECK(on_target.pixels[(12 - 2) * 24 + (12 - 2)] == 200.0f);
  int moved = 0;
  for (std::uint64_t i = 0; i < 20; ++i) {
    const Chip t = registration_chip(chip.view(), as_cut, i, true);
    moved += t.pixels != centred.pixels ? 1 : 0;
    CHECK(t.pixels == registration_chip(chip.view(), as_cut, i, true).pixels);
    // registered: back on the target, whatever the offset
    CHECK(registration_chip(chip.view(), registered, i, true).pixels == on_target.pixels);
  }
  CHECK(moved >= 15);
  CHECK(registration_chip(chip.view(), e.conditions[0], 3, true).pixels == centred.pixels);
}

TEST_CASE("group_chip_sets: the one render order of a group's chip sets, with their counts",
          "[sweep]") {
  SweepSettings s = settings();
  s.resolutions_cm = {5};
  s.looks = 3;
  const SweepExperiment e = make_sweep_experiment("fig15", s);
  const RenderGroup g = render_groups(e)[0];
  const std::size_t classes = e.classes.size();
  const std::vector<ChipSet> sets = group_chip_sets(e, g, s);
  // training chips, then the test chips of each look
  REQUIRE(sets.size() == 4);
  CHECK(sets[0].role == ChipSetRole::kTrain);
  CHECK(sets[0].count == static_cast<std::size_t>(g.train_count) * classes);
  CHECK(sets[0].renderer->spec().seed == render_group_spec(e, g, s, false).seed);
  for (int look = 0; look < 3; ++look) {
    const ChipSet& t = sets[static_cast<std::size_t>(look) + 1];
    CHECK(t.role == ChipSetRole::kTest);
    CHECK(t.look == look);
    CHECK(t.count == static_cast<std::size_t>(e.test_count) * classes);
    CHECK(t.renderer->spec().look == look);
    CHECK(t.renderer->spec().seed == render_group_spec(e, g, s, true).seed);
  }
  // fusion: highlight then shadow, training then test
  const SweepExperiment f = make_sweep_experiment("fusion", s);
  const RenderGroup fg = render_groups(f)[0];
  const std::vector<ChipSet> fs = group_chip_sets(f, fg, s);
  REQUIRE(fs.size() == 4);
  const ChipSetRole roles[] = {ChipSetRole::kTrain, ChipSetRole::kTrainShadow, ChipSetRole::kTest,
                               ChipSetRole::kTestShadow};
  const chips::ChipKind kinds[] = {chips::ChipKind::kHighlight, chips::ChipKind::kShadow,
                                   chips::ChipKind::kHighlight, chips::ChipKind::kShadow};
  for (std::size_t i = 0; i < 4; ++i) {
    INFO("set " << i);
    CHECK(fs[i].role == roles[i]);
    CHECK(fs[i].renderer->spec().kind == kinds[i]);
    CHECK(fs[i].count ==
          static_cast<std::size_t>(i < 2 ? fg.train_count : f.test_count) * f.classes.size());
  }
  CHECK(fs[2].renderer->spec().seed == fusion_specs(f, fg, s, true).first.seed);
}

}  // namespace
}  // namespace sonarloop::study
