// sonarloop sweep: the resolution study of Pailhas, Petillot & Capus (2010), Sections 3-4, in
// memory: chips from the chip renderer, the eigen-subspace classifier, misidentification with
// 95 % Wilson intervals per target and condition, CSV files and charts (tools/plot_sweep.py).
// The experiments and the scoring live in study/sweep.h; this file renders, times and writes.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>

#include "atr/fusion.h"
#include "config/loader/scenario_loader.h"
#include "config/loader/sonar_loader.h"
#include "sim/render/chip_renderer.h"
#include "study/sweep.h"
#include "tools/args.h"
#include "tools/chip_options.h"
#include "tools/chip_ranks.h"
#include "tools/cli_helpers.h"
#include "tools/commands.h"
#include "tools/mpi_world.h"
#include "tools/progress.h"
#include "tools/sweep_ranks.h"

#ifndef SONARLOOP_SWEEP_PLOT_SCRIPT
#define SONARLOOP_SWEEP_PLOT_SCRIPT "tools/plot_sweep.py"
#endif

namespace sonarloop::tools {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr const char* kDefaultSeabeds = "flat,ripples,clutter";
constexpr const char* kPython = "/usr/bin/python3";

std::vector<double> parse_resolutions_cm(const std::string& text) {
  std::vector<double> out;
  for (const std::string& t : split_comma_list(text)) {
    char* end = nullptr;
    const double cm = std::strtod(t.c_str(), &end);
    if (*end != '\0' || !(cm >= 0.5 && cm <= 100.0)) {
      throw UsageError("--resolutions-cm: '" + t + "' is not a number of centimetres in 0.5..100");
    }
    if (std::find(out.begin(), out.end(), cm) != out.end()) {
      throw UsageError("--resolutions-cm: " + t + " is listed twice");
    }
    out.push_back(cm);
  }
  if (out.empty()) throw UsageError("--resolutions-cm: no resolution given");
  return out;
}

std::vector<targets::TargetType> parse_non_mine(const std::string& text) {
  std::vector<targets::TargetType> out;
  for (const std::string& key : split_comma_list(text)) {
    const auto t = targets::find_target_type(key);
    if (!t) {
      throw UsageError("--non-mine: unknown target type '" + key +
                       "' (allowed: " + targets::target_type_keys_list() + ")");
    }
    if (targets::target_type_info(*t).mine_like) {
      throw UsageError("--non-mine: '" + key + "' is mine-like; choose among the non-mine types");
    }
    out.push_back(*t);
  }
  if (out.empty()) throw UsageError("--non-mine: no target type given");
  return out;
}

// --novel: target types never trained (open_set), none of fig13's seven; "none" for no novel type.
std::vector<targets::TargetType> parse_novel(const std::string& text,
                                             const std::vector<targets::TargetType>& trained) {
  std::vector<targets::TargetType> out;
  if (text == "none") return out;
  for (const std::string& key : split_comma_list(text)) {
    const auto t = targets::find_target_type(key);
    if (!t) {
      throw UsageError("--novel: unknown target type '" + key +
                       "' (allowed: " + targets::target_type_keys_list() + ", or none)");
    }
    if (std::find(trained.begin(), trained.end(), *t) != trained.end()) {
      throw UsageError("--novel: '" + key + "' is one of fig13's trained types");
    }
    if (std::find(out.begin(), out.end(), *t) == out.end()) out.push_back(*t);
  }
  if (out.empty()) throw UsageError("--novel: no target type given (or 'none')");
  return out;
}

void write_file(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error("cannot write '" + tmp.string() + "'");
  }
  fs::rename(tmp, path);
}

// Renders chips 0..count-1 at one resolution slot (over the MPI ranks, if any: sweep_ranks.h),
// handing them to `sink` in index order. Returns the number of chips rendered (fewer after a
// stop request) and the wall time.
std::size_t render_slot(const render::ChipRenderer& r, int slot, std::size_t count, int threads,
                        const std::function<void(const render::ChipImage&)>& sink, double* wall_s) {
  const auto t0 = Clock::now();
  const std::size_t done = render_sweep_chips(r, slot, count, threads, sink);
  *wall_s = seconds_since(t0);
  return done;
}

struct RunContext {
  study::SweepSettings settings;
  int threads = 1;
  fs::path out_dir;
  Progress* bar = nullptr;
  double chips_done = 0.0;
};

// Each target's identification per test seabed, when the experiment has several seabeds.
void write_seabed_csv(const RunContext& ctx, const study::SweepExperiment& e,
                      const std::vector<study::ConditionResult>& results) {
  if (e.seabed_names.size() < 2) return;
  write_file(ctx.out_dir / (e.name + "_seabed.csv"), study::seabed_csv(e, results));
}

// One condition being tested: its classifier and its scores.
struct Trial {
  std::unique_ptr<atr::Classifier> classifier;
  std::unique_ptr<study::ConditionResult> result;
  double classify_s = 0.0;
  std::size_t classified = 0;
  // multi-look conditions (SweepCondition::looks > 1): per test object, the looks' summed
  // scores (objects x classes) and whether a look's chip was unusable
  std::vector<float> fused;
  std::vector<std::uint8_t> unusable;
};

// Renders the chips of one slot into labelled chips (returns false when stopped).
bool render_labelled(const render::ChipRenderer& r, int slot, std::size_t count, RunContext& ctx,
                     std::vector<atr::LabelledChip>& out, double* wall_s) {
  const bool shadow_height =
      ctx.settings.shadow_height && r.spec().kind == render::ChipKind::kShadow;
  const std::size_t got = render_slot(
      r, slot, count, ctx.threads,
      [&](const render::ChipImage& c) {
        out.push_back(study::labelled_chip(c, shadow_height, ctx.settings.deripple));
        ctx.bar->update(++ctx.chips_done);
      },
      wall_s);
  return got == count;
}

void print_result(const study::SweepExperiment& e, const study::ConditionResult& r) {
  const study::SweepCondition& c = e.conditions[r.condition];
  const auto& cm = r.confusion;
  const study::ErrorRate er = study::error_rate(cm.total() - cm.correct(), cm.total());
  std::printf("%-10s %-22s %s=%-6g misidentified %6.2f %% [%5.2f, %5.2f] of %zu", e.name.c_str(),
              c.series.c_str(), c.x_name.c_str(), c.x, 100.0 * er.rate, 100.0 * er.ci.lo,
              100.0 * er.ci.hi, er.n);
  if (e.mine_groups) {
    const study::ErrorRate m = study::error_rate(r.mine_errors, r.mine_n);
    std::printf(", mine/non-mine %5.2f %% [%5.2f, %5.2f]", 100.0 * m.rate, 100.0 * m.ci.lo,
                100.0 * m.ci.hi);
  }
  if (c.reject_quantile > 0.0) {
    std::printf(", false reject %5.2f %%",
                100.0 * study::error_rate(r.known_rejected, r.known_n).rate);
  }
  if (c.held_out >= 0) {
    std::printf(", held-out type accepted %5.2f %%",
                100.0 * study::error_rate(r.unknown_accepted, r.unknown_n).rate);
  }
  if (r.rejected > 0) std::printf(", %zu degenerate chips not scored", r.rejected);
  std::printf("; render %.1f ms/chip, train %.2f s, classify %.3f ms/chip%s\n",
              1e3 * r.render_s_per_chip, r.train_s, 1e3 * r.classify_s_per_chip,
              r.complete ? "" : " (interrupted)");
  std::fflush(stdout);
}

// Runs one experiment; returns false when stopped.
bool run_experiment(const study::SweepExperiment& e, RunContext& ctx,
                    std::vector<study::ConditionResult>& results) {
  const std::size_t classes = e.classes.size();
  const auto write_all = [&] {
    write_file(ctx.out_dir / (e.name + ".csv"), study::results_csv(e, results));
    write_file(ctx.out_dir / (e.name + "_confusion.csv"), study::confusion_csv(e, results));
    write_seabed_csv(ctx, e, results);
  };
  for (const study::RenderGroup& g : study::render_groups(e)) {
    const render::ChipRenderer train_r(study::render_group_spec(e, g, ctx.settings, false));
    const render::ChipRenderer test_r(study::render_group_spec(e, g, ctx.settings, true));
    const auto look_r = study::other_look_renderers(e, g, ctx.settings);
    for (std::size_t slot = 0; slot < g.resolutions_m.size(); ++slot) {
      // training chips, shared by the conditions of this resolution
      std::vector<atr::LabelledChip> train;
      double wall_s = 0.0;
      const std::size_t n_train = static_cast<std::size_t>(g.train_count) * classes;
      if (!render_labelled(train_r, static_cast<int>(slot), n_train, ctx, train, &wall_s)) {
        return false;
      }
      const std::size_t got = train.size();
      const double train_wall_s = wall_s;

      std::vector<Trial> trials;
      for (std::size_t ci : g.members[slot]) {
        const study::SweepCondition& c = e.conditions[ci];
        const auto same = std::find_if(trials.begin(), trials.end(), [&](const Trial& t) {
          return study::same_training(e.conditions[t.result->condition], c);
        });
        if (same != trials.end()) {  // e.g. another number of looks: the same model
          Trial t;
          t.result = std::make_unique<study::ConditionResult>(ci, e, same->classifier->model());
          t.result->train_s = same->result->train_s;
          t.classifier = std::make_unique<atr::Classifier>(same->classifier->model());
          trials.push_back(std::move(t));
          continue;
        }
        atr::TrainOptions opt;
        opt.p = c.p;
        opt.aspect_sectors = c.aspect_sectors;
        opt.skip_degenerate = true;
        opt.class_metadata = sim_class_metadata();  // mine-like flags of the target types
        const auto t0 = Clock::now();
        opt.preprocess = c.preprocess;
        opt.reject_quantile = c.reject_quantile;
        std::vector<atr::LabelledChip> chips = study::training_set(train, e, c);
        if (c.window_m > 0.0) {  // registration: the training chips' window, centred
          for (atr::LabelledChip& l : chips)
            l.chip = study::registration_chip(l.chip.view(), c, 0, false);
        }
        atr::Model model = atr::train_model(chips, opt);
        Trial t;
        t.result = std::make_unique<study::ConditionResult>(ci, e, model);
        t.result->train_s = seconds_since(t0);
        t.classifier = std::make_unique<atr::Classifier>(std::move(model));
        trials.push_back(std::move(t));
      }
      train.clear();

      // test chips: every condition classifies each one; multi-look conditions add each look's
      // distances to the object's fused scores and score the object at their last look
      const std::size_t n_test = static_cast<std::size_t>(e.test_count) * classes;
      const bool shadow_height =
          ctx.settings.shadow_height && test_r.spec().kind == render::ChipKind::kShadow;
      for (Trial& t : trials) {
        if (e.conditions[t.result->condition].looks <= 1) continue;
        t.fused.assign(n_test * classes, 0.0f);
        t.unusable.assign(n_test, 0);
      }
      atr::Chip chip;
      const auto classify_look = [&](const render::ChipImage& c, int look) {
        // the training chips' treatment
        chip = study::classifier_chip(c, shadow_height, ctx.settings.deripple);
        const atr::ChipView view = chip.view();
        const auto truth = static_cast<std::size_t>(
            std::find(e.classes.begin(), e.classes.end(), c.params.type) - e.classes.begin());
        for (Trial& t : trials) {
          const study::SweepCondition& cond = e.conditions[t.result->condition];
          if (look >= cond.looks) continue;
          atr::Chip registered;
          if (cond.window_m > 0.0) {
            registered = study::registration_chip(view, cond, c.params.index, true);
          }
          const auto t0 = Clock::now();
          const atr::ChipCheck check =
              t.classifier->classify(cond.window_m > 0.0 ? registered.view() : view);
          t.classify_s += seconds_since(t0);
          if (cond.looks > 1) {
            const std::span<float> fused(t.fused.data() + c.params.index * classes, classes);
            if (check.ok()) {
              ++t.classified;
              atr::add_look(t.classifier->model(), t.classifier->result(),
                            atr::FusionNorm::kModelTypical, fused);
            } else {
              t.unusable[c.params.index] = 1;
            }
            if (look + 1 < cond.looks) continue;
            if (t.unusable[c.params.index]) {
              ++t.result->rejected;
              continue;
            }
            atr::Classification answer = t.classifier->result();
            answer.class_index = atr::fused_decision(fused);
            const auto& cls =
                t.classifier->model().classes.at(static_cast<std::size_t>(answer.class_index));
            answer.mine_like = answer.mine_like_by_identity = cls.mine_like;
            study::score_chip(*t.result, e, t.classifier->model(), truth, c.params.aspect_deg,
                              c.params.seabed, answer);
            continue;
          }
          if (!check.ok()) {
            ++t.result->rejected;
            continue;
          }
          ++t.classified;
          study::score_chip(*t.result, e, t.classifier->model(), truth, c.params.aspect_deg,
                            c.params.seabed, t.classifier->result());
        }
        ctx.bar->update(++ctx.chips_done);
      };
      std::size_t tested = render_slot(
          test_r, static_cast<int>(slot), n_test, ctx.threads,
          [&](const render::ChipImage& c) { classify_look(c, 0); }, &wall_s);
      // the other looks at the same objects; a condition is complete when its last look is
      int looks_done = tested == n_test ? 1 : 0;
      for (int look = 1; look < g.looks && looks_done == look; ++look) {
        double look_wall_s = 0.0;
        const std::size_t n = render_slot(
            *look_r[static_cast<std::size_t>(look - 1)], static_cast<int>(slot), n_test,
            ctx.threads, [&](const render::ChipImage& c) { classify_look(c, look); }, &look_wall_s);
        wall_s += look_wall_s;
        tested += n;
        if (n == n_test) ++looks_done;
      }
      // thread-seconds per chip over both sets and all ranks (including the seabed tiles made
      // on the way; the classification in the sink overlaps the workers' rendering)
      const double render_s_per_chip = (train_wall_s + wall_s) * ctx.threads * mpi::size() /
                                       static_cast<double>(got + std::max<std::size_t>(tested, 1));
      bool any = false;
      for (Trial& t : trials) {
        const int looks = e.conditions[t.result->condition].looks;
        t.result->render_s_per_chip = render_s_per_chip;
        t.result->complete = looks_done >= looks;
        t.result->classify_s_per_chip =
            t.classified ? t.classify_s / static_cast<double>(t.classified) : 0.0;
        // a single-look condition keeps the chips scored before a stop; a multi-look one
        // scores its objects at its last look only
        if (tested == 0 || (looks > 1 && !t.result->complete)) continue;
        print_result(e, *t.result);
        results.push_back(std::move(*t.result));
        any = true;
      }
      if (any) {
        std::sort(results.begin(), results.end(),
                  [](const auto& a, const auto& b) { return a.condition < b.condition; });
        write_all();
      }
      if (looks_done < g.looks) return false;
    }
  }
  return true;
}

// The fusion experiment (atr/fusion.h): per resolution, a highlight model and a shadow model,
// calibrated, trained on the same objects; each test object is scored from its highlight chip,
// its shadow chip and both. Returns false when stopped.
bool run_fusion_experiment(const study::SweepExperiment& e, RunContext& ctx,
                           std::vector<study::ConditionResult>& results) {
  const std::size_t classes = e.classes.size();
  for (const study::RenderGroup& g : study::render_groups(e)) {
    const auto [train_hl, train_sh] = study::fusion_specs(e, g, ctx.settings, false);
    const auto [test_hl, test_sh] = study::fusion_specs(e, g, ctx.settings, true);
    const render::ChipRenderer rh(train_hl), rs(train_sh), th(test_hl), ts(test_sh);
    for (std::size_t slot = 0; slot < g.resolutions_m.size(); ++slot) {
      const auto& members = g.members[slot];
      const study::SweepCondition& c0 = e.conditions[members.front()];
      const std::size_t n_train = static_cast<std::size_t>(g.train_count) * classes;
      const std::size_t n_test = static_cast<std::size_t>(e.test_count) * classes;
      const int islot = static_cast<int>(slot);
      double wall = 0.0, render_s = 0.0;
      std::vector<atr::LabelledChip> hl, sh;
      if (!render_labelled(rh, islot, n_train, ctx, hl, &wall)) return false;
      render_s += wall;
      if (!render_labelled(rs, islot, n_train, ctx, sh, &wall)) return false;
      render_s += wall;
      atr::TrainOptions opt;
      opt.p = c0.p;
      opt.skip_degenerate = true;
      opt.calibrate = true;
      opt.class_metadata = sim_class_metadata();
      opt.preprocess = c0.preprocess;
      const auto t0 = Clock::now();
      atr::Classifier ch(atr::train_model(study::training_set(hl, e, c0), opt));
      opt.preprocess.crop_fraction = ctx.settings.preprocess.crop_fraction;  // not crop auto
      atr::Classifier cs(atr::train_model(study::training_set(sh, e, c0), opt));
      atr::check_same_classes(ch.model(), cs.model());
      const double train_s = seconds_since(t0);
      std::vector<study::ConditionResult> rs_out;
      for (std::size_t ci : members)
        rs_out.emplace_back(ci, e, ch.model());

      // highlight test chips first, then each shadow chip scored with its object's highlight
      hl.clear();
      if (!render_labelled(th, islot, n_test, ctx, hl, &wall)) return false;
      render_s += wall;
      std::vector<std::optional<atr::Classification>> by_highlight(hl.size());
      for (std::size_t i = 0; i < hl.size(); ++i) {
        if (ch.classify(hl[i].chip.view()).ok()) by_highlight[i] = ch.result();
      }
      std::vector<float> fused(classes);
      atr::Chip shadow_chip;
      double classify_s = 0.0;
      const std::size_t tested = render_slot(
          ts, islot, n_test, ctx.threads,
          [&](const render::ChipImage& c) {
            ctx.bar->update(++ctx.chips_done);
            shadow_chip =
                study::classifier_chip(c, ctx.settings.shadow_height, ctx.settings.deripple);
            const auto t1 = Clock::now();
            const bool shadow_ok = cs.classify(shadow_chip.view()).ok();
            classify_s += seconds_since(t1);
            const auto& h = by_highlight.at(c.params.index);
            const auto truth = static_cast<std::size_t>(
                std::find(e.classes.begin(), e.classes.end(), c.params.type) - e.classes.begin());
            for (std::size_t k = 0; k < members.size(); ++k) {
              const study::SweepCondition& cond = e.conditions[members[k]];
              study::ConditionResult& r = rs_out[k];
              if (!shadow_ok || !h) {  // both chips are needed for a like-for-like comparison
                ++r.rejected;
                continue;
              }
              atr::Classification answer =
                  cond.fusion == study::FusionInput::kShadow ? cs.result() : *h;
              if (cond.fusion == study::FusionInput::kFused) {
                std::fill(fused.begin(), fused.end(), 0.0f);
                atr::add_look(ch.model(), *h, cond.fusion_norm, fused);
                atr::add_look(cs.model(), cs.result(), cond.fusion_norm, fused);
                answer.class_index = atr::fused_decision(fused);
                // the mine / non-mine decision is the fused class's group (Sec. 4.1.2)
                answer.mine_like =
                    ch.model().classes.at(static_cast<std::size_t>(answer.class_index)).mine_like;
              }
              study::score_chip(r, e, ch.model(), truth, c.params.aspect_deg, c.params.seabed,
                                answer);
            }
          },
          &wall);
      render_s += wall;
      for (study::ConditionResult& r : rs_out) {
        r.render_s_per_chip =
            render_s * ctx.threads * mpi::size() / static_cast<double>(2 * (n_train + n_test));
        r.train_s = train_s;
        r.classify_s_per_chip = tested ? classify_s / static_cast<double>(tested) : 0.0;
        r.complete = tested == n_test;
        if (tested == 0) continue;
        print_result(e, r);
        results.push_back(std::move(r));
      }
      std::sort(results.begin(), results.end(),
                [](const auto& a, const auto& b) { return a.condition < b.condition; });
      write_file(ctx.out_dir / (e.name + ".csv"), study::results_csv(e, results));
      write_file(ctx.out_dir / (e.name + "_confusion.csv"), study::confusion_csv(e, results));
      write_seabed_csv(ctx, e, results);
      if (tested < n_test) return false;
    }
  }
  return true;
}

// Total chips an experiment renders, for the progress bar.
double experiment_chips(const study::SweepExperiment& e) {
  double total = 0.0;
  for (const study::RenderGroup& g : study::render_groups(e)) {
    total += static_cast<double>(g.resolutions_m.size()) * static_cast<double>(e.classes.size()) *
             (g.train_count + g.looks * e.test_count);
  }
  return study::is_fusion(e) ? 2.0 * total : total;  // a highlight and a shadow chip per object
}

bool matplotlib_available(const std::string& python) {
  const std::string cmd = python + " -c 'import matplotlib' >/dev/null 2>&1";
  return std::system(cmd.c_str()) == 0;
}

void plot(const fs::path& out_dir, bool enabled) {
  const std::string script = SONARLOOP_SWEEP_PLOT_SCRIPT;
  const std::string python = fs::exists(kPython) ? kPython : "python3";
  const std::string cmd = python + " '" + script + "' '" + out_dir.string() + "'";
  if (!enabled) return;
  if (!fs::exists(script) || !matplotlib_available(python)) {
    std::printf("charts: matplotlib or %s not found; run: %s\n", script.c_str(), cmd.c_str());
    return;
  }
  if (std::system(cmd.c_str()) != 0) {
    std::fprintf(stderr, "sonarloop sweep: the chart script failed: %s\n", cmd.c_str());
  }
}

int run_sweep(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--experiment", true, true},
                         {"--test-count"},
                         {"--train-count"},
                         {"--resolutions-cm"},
                         {"--p"},
                         {"--aspect-sectors"},
                         {"--seed"},
                         {"--threads"},
                         {"--out"},
                         {"--seabed"},
                         {"--non-mine"},
                         {"--novel"},
                         {"--sonar"},
                         {"--no-plot", false},
                         {"--shadow-height", false},
                         {"--deripple", false},
                         {"--looks"},
                         {"--look-geometry"},
                         {"--renderer"},
                         {"--crop"},
                         {"--multilook"},
                         {"--levels"},
                         {"--threshold-db"},
                         {"--reject-quantile"}});
  if (!args.positionals().empty()) {
    throw UsageError("unexpected argument '" + args.positionals()[0] + "'");
  }
  RunContext ctx;
  study::SweepSettings& s = ctx.settings;
  s.seed = static_cast<std::uint64_t>(
      args.get_int("--seed", 0, std::numeric_limits<long long>::max() - 1).value_or(0));
  s.train_count = static_cast<int>(args.get_int("--train-count", 2, 100000).value_or(80));
  s.test_count = static_cast<int>(args.get_int("--test-count", 1, 10'000'000).value_or(100));
  s.p = static_cast<int>(args.get_int("--p", 1, 4096).value_or(atr::kDefaultSubspaceDim));
  s.aspect_sectors = static_cast<int>(args.get_int("--aspect-sectors", 1, 360).value_or(1));
  if (const auto r = args.get("--resolutions-cm")) s.resolutions_cm = parse_resolutions_cm(*r);
  if (const auto n = args.get("--non-mine")) s.non_mine = parse_non_mine(*n);
  if (const auto n = args.get("--novel")) s.novel = parse_novel(*n, study::fig13_classes(s));
  s.seabeds = dataset_seabeds_option(args.get_or("--seabed", kDefaultSeabeds));
  s.renderer = renderer_option(args);
  s.preprocess = preprocess_options(args, &s.crop_auto);
  s.shadow_height = args.has("--shadow-height");
  s.deripple = args.has("--deripple");
  s.looks = static_cast<int>(args.get_int("--looks", 1, study::kMaxSweepLooks).value_or(1));
  if (const auto g = args.get("--look-geometry")) {
    const auto parsed = render::parse_look_geometry(*g);
    if (!parsed) {
      throw UsageError("--look-geometry: '" + *g + "' is not independent or reciprocal");
    }
    s.look_geometry = *parsed;
  }
  s.reject_quantile = args.get_double("--reject-quantile", 0.01, 0.9999).value_or(0.95);
  const std::string sonar_arg = args.get_or("--sonar", std::string(config::kDefaultSonarPreset));
  s.sonar =
      is_yaml_path(sonar_arg) ? config::load_sonar(sonar_arg) : config::builtin_sonar(sonar_arg);
  ctx.threads =
      static_cast<int>(args.get_int("--threads", 1, 256).value_or(mpi::default_threads()));
  ctx.out_dir = args.get_or("--out", "sweep_out");

  std::vector<std::string> names = args.get_all("--experiment");
  if (names.empty()) names = {"fig11"};
  if (std::find(names.begin(), names.end(), "all") != names.end())
    names = study::sweep_experiment_names();
  std::vector<study::SweepExperiment> experiments;
  for (const std::string& n : names) {
    try {
      experiments.push_back(study::make_sweep_experiment(n, s));
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--experiment: ") + e.what());
    }
    if (experiments.back().conditions.empty()) {
      throw UsageError("--experiment " + n + ": no condition left (e.g. every p >= --train-count)");
    }
  }
  // under mpirun: rank 0 runs the sweep, the others render their share of its chips
  mpi::start();
  if (!mpi::is_root()) return serve_sweep(experiments, s, ctx.threads) ? 0 : 130;
  fs::create_directories(ctx.out_dir);

  double total = 0.0;
  for (const auto& e : experiments)
    total += experiment_chips(e);
  install_stop_flag();
  const auto t0 = Clock::now();
  bool stopped = false;
  {
    Progress bar("sweep: " + std::to_string(static_cast<long long>(total)) + " chips", total);
    ctx.bar = &bar;
    for (const auto& e : experiments) {
      std::fprintf(stderr, "sonarloop sweep: %s: %s (%zu conditions)\n", e.name.c_str(),
                   e.title.c_str(), e.conditions.size());
      std::vector<study::ConditionResult> results;
      const bool done = study::is_fusion(e) ? run_fusion_experiment(e, ctx, results)
                                            : run_experiment(e, ctx, results);
      if (!done) {
        stopped = true;
        break;
      }
    }
    bar.finish();
  }
  const double secs = seconds_since(t0);
  std::printf("rendered %.0f chips in %.1f s (%.1f chips/s, %d threads%s); results in %s\n",
              ctx.chips_done, secs, ctx.chips_done / std::max(secs, 1e-9), ctx.threads,
              ranks_note().c_str(), ctx.out_dir.string().c_str());
  if (stopped) {
    std::fprintf(stderr,
                 "sonarloop sweep: interrupted; the CSV files in '%s' hold every condition "
                 "scored so far (complete = 0 marks a partly tested one)\n",
                 ctx.out_dir.string().c_str());
  }
  std::fflush(stdout);  // before the chart script writes to the same stream
  plot(ctx.out_dir, !args.has("--no-plot"));
  return stopped ? 130 : 0;
}

}  // namespace

const Command kSweepCommand{
    "sweep", "the paper's resolution study: misidentification against pixel resolution and more",
    R"(usage: sonarloop sweep [--experiment NAME ...] [options]

Reproduces the resolution study of Pailhas, Petillot & Capus (2010), Sections 3-4, in memory:
for each condition it renders training chips (dataset seed S) and test chips (seed S + 1) with
the chip renderer of `sonarloop dataset`, trains the eigen-subspace classifier of
`sonarloop train` and scores every test chip: misidentification per target with a 95 % Wilson
interval, the confusion matrix, render and classification time per chip.

experiments (--experiment, repeatable, or 'all'; default fig11):
  fig11       Manta, Rockan, cuboid, cylinder from highlights, 15 resolutions 3-30 cm (Fig. 11)
  fig13       mine-like Manta, Rockan, cylinder and four non-mine shapes (--non-mine): the
              identification among the seven and the mine / non-mine decision error against
              resolution (Fig. 13, Sec. 4.1.2)
  fig15       the four targets from their shadows, 5-30 cm (Fig. 15)
  aspect      error per 30 deg of target aspect, one subspace per target against 4 and 8
              aspect-sector subspaces, trained on 2 x --train-count chips per target
  snr         source level 210 down to 130 dB (the noise stays: SNR falls dB for dB), 5 cm
  altitude    fixed sonar altitudes 2-20 m (grazing angle), 5 cm
  burial      test targets buried by 0-50 % of their height (trained proud), fig13's
              seven with the mine / non-mine decision, 5 cm
  train_size  5-320 training chips per target, 5 cm
  p           subspace dimension 1-79 (below --train-count), 5 cm
  open_set    open-set rejection on fig13's seven targets: each left out of training in
              turn (its chips should be called unknown), then each --novel type (never
              trained), and none left out; the known chips' false-reject rate; 5 and 15 cm
              (or --resolutions-cm)
  fusion      highlight + shadow fusion: the same objects (four targets at 25 m ground
              range) identified from the highlight chip, the shadow chip, and both (each
              model's distances normalised three ways, atr/fusion.h, and summed); 5-20 cm
  fusion13    the same with fig13's seven targets and the mine / non-mine decision of the
              fused class
  registration  the four targets' highlights in a 1.2 m window cut 0-0.5 m off the target
              (a detector's position error), as cut and re-centred on the highlight
              centroid (atr/chip_register.h); 5 cm (or --resolutions-cm)
  ablation    chip pre-processing before eq. 9 (crop to the chip centre, multilook
              speckle averaging, levels against the seabed), each alone and combined, at
              5 and 15 cm (or --resolutions-cm), the four targets' highlights
The stability studies (aspect, snr, altitude, burial, train_size, p) run at 5 cm, or at each of
--resolutions-cm (one curve each); fig11/13/15 take --resolutions-cm as their x axis.

Writes to --out DIR (rewritten after every resolution, so an interrupted run keeps its results):
  NAME.csv            experiment,series,x_name,x,resolution_cm,class,n,errors,error_pct,
                      ci_low_pct,ci_high_pct,train_per_class,p,aspect_sectors,
                      render_ms_per_chip,train_s,classify_ms_per_chip,complete
                      (class: a target, 'all', 'mine_vs_non_mine', 'seabed_NAME' for
                      the test chips on one seabed, 'false_reject' / 'unknown_accepted' for
                      open_set; render time is thread-seconds per chip)
  NAME_confusion.csv  experiment,series,x_name,x,truth,predicted,count
  NAME_seabed.csv     experiment,series,x_name,x,resolution_cm,class,seabed,n,errors,
                      error_pct,ci_low_pct,ci_high_pct: each target on each test seabed
                      (written when there are several seabeds)
  *.png               charts by tools/plot_sweep.py (run when matplotlib is available,
                      otherwise the command is printed)
The paper used 80 training chips per target and 40,000 test chips per resolution; the default
--test-count 100 per target takes minutes and gives intervals of about +-5-9 points.

options:
  --experiment NAME    see above (repeatable; 'all' for every one)
  --test-count N       test chips per target and condition (default 100)
  --train-count N      training chips per target (default 80, as the paper)
  --resolutions-cm L   comma list of pixel sizes in cm (default: per experiment)
  --p N                leading eigenvectors per subspace (default 20)
  --aspect-sectors N   one subspace per target and aspect sector of 360/N deg, for every
                       experiment but aspect (which compares 1, 4 and 8); as `sonarloop train`
                       (default 1)
  --seed S             training dataset seed; the test set uses S + 1 (default 0)
  --threads N          render threads (default: all cores)
  --out DIR            output folder (default sweep_out)
  --seabed LIST        seabed kinds: flat, ripples, clutter, rocky, or scenario files
                       NAME.yaml (their seabed) (default flat,ripples,clutter)
  --novel LIST         open_set's types never trained, unlike the seven (default
                       standing_cylinder; 'none' for none)
  --non-mine LIST      fig13's non-mine shapes (default: the paper's
                       large_cuboid,hemisphere,small_hemisphere,box)
  --sonar NAME|FILE    sonar preset or YAML (default pailhas_strip; bin and pulse set per R)
  --no-plot            do not run the chart script
  --renderer R         profile (default: heightfield profile renderer) or raytrace (Embree)
  --crop F, --multilook K, --levels L, --threshold-db T
                       chip pre-processing before eq. 9 for every experiment but ablation,
                       as `sonarloop train` (default none, as the paper); --crop auto crops
                       highlight chips per resolution to max(1.2 m, 10 pixels) a side
  --shadow-height      resample shadow chips (fig15, fusion) from slant range to the height
                       whose shadow ends there, with each chip's altitude and range, so that a
                       target's shadow has one length from any altitude (ours; default off)
  --deripple           notch the sand ripples' periodic texture out of every chip (the
                       isolated peaks of its 2-D spectrum) before anything else (ours;
                       default off)
  --looks N            fig11, fig13, fig15: see each test object in N looks (the same object
                       from N passes: another altitude, track heading, side and speckle;
                       shadow chips keep their 25 m ground range, highlight chips draw a new
                       one) and draw one curve per number of looks fused, 1 to N: the class of
                       the smallest sum of the looks' distances (ours; default 1, the paper's
                       single chip; at most 8; the other experiments score single chips)
  --look-geometry G    how --looks are flown: independent (default: each look a pass of its
                       own) or reciprocal (a lawnmower's neighbouring line at the same
                       altitude and range, past the object's other side: seen from the
                       opposite direction; a third look repeats the first line)
  --reject-quantile Q  open_set's calibration quantile (default 0.95), as `sonarloop train`

Ctrl-C stops after the chip in progress; the CSV files keep every condition scored so far.
Same --seed and counts give the same counts and rates on any --threads (times differ).

On a cluster (MPI, when this build found it: docs/sweep.md): run the same command under
`mpirun -np N`. Every rank renders every N-th chip of each chip set with --threads threads
(default: the cores mpirun binds it to); rank 0 trains, scores, prints and writes, with the
same counts and confusion files as one process (only the times differ).

examples:
  sonarloop sweep --experiment fig11 --out out/sweep
  sonarloop sweep --experiment fig11 --resolutions-cm 5,20 --train-count 40 --test-count 50
  sonarloop sweep --experiment all --test-count 1000 --out /tmp/sweep_big
  sonarloop sweep --experiment ablation --test-count 1000 --out /tmp/ablation
  sonarloop sweep --experiment fig13 --crop auto --out /tmp/fig13_crop
  sonarloop sweep --experiment fig15 --shadow-height --out /tmp/fig15_height
  sonarloop sweep --experiment fusion13 --shadow-height --deripple --crop auto \
      --train-count 320 --out /tmp/fused
  sonarloop sweep --experiment fig15 --shadow-height --deripple --looks 3 \
      --resolutions-cm 5,10 --out /tmp/fig15_looks
  mpirun -np 8 sonarloop sweep --experiment fig11 --test-count 10000 --out /scratch/fig11
)",
    run_sweep, 65};
SONARLOOP_REGISTER_COMMAND(kSweepCommand);

}  // namespace sonarloop::tools
