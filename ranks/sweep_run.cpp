// `sonarloop sweep` on rank 0 (ranks/sweep_run.h): render, train, score, write.
#include "ranks/sweep_run.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "atr/fusion.h"
#include "ranks/chip_ranks.h"
#include "ranks/mpi_world.h"
#include "ranks/sweep_ranks.h"
#include "sim/render/chip_renderer.h"

namespace sonarloop::ranks {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// One more chip rendered: the progress callback told.
void advance(SweepRun& ctx) {
  ++ctx.chips_done;
  if (ctx.progress) ctx.progress(ctx.chips_done);
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
std::size_t render_slot(const render::ChipRenderer& r, int slot, std::size_t count,
                        const SweepRun& ctx,
                        const std::function<void(const render::ChipImage&)>& sink, double* wall_s) {
  const auto t0 = Clock::now();
  const std::size_t done = render_sweep_chips(r, slot, count, ctx.threads, sink, ctx.stop);
  *wall_s = seconds_since(t0);
  return done;
}

// Each target's identification per test seabed, when the experiment has several seabeds.
void write_seabed_csv(const SweepRun& ctx, const study::SweepExperiment& e,
                      const std::vector<study::ConditionResult>& results) {
  if (e.seabed_names.size() < 2) return;
  write_file(ctx.out_dir / (e.name + "_seabed.csv"), study::seabed_csv(e, results));
}

// A render group's chip sets at one resolution slot, taken in study::group_chip_sets' order, the
// order in which the serving ranks render them (ranks/sweep_ranks.h): take() checks that the set
// asked for is the next one.
class SlotSets {
 public:
  explicit SlotSets(const std::vector<study::ChipSet>& sets) : sets_(sets) {}
  const study::ChipSet& take(study::ChipSetRole role, int look = 0) {
    if (next_ >= sets_.size() || sets_[next_].role != role || sets_[next_].look != look) {
      throw std::logic_error("sweep: chip sets taken out of study::group_chip_sets' order");
    }
    return sets_[next_++];
  }

 private:
  const std::vector<study::ChipSet>& sets_;
  std::size_t next_ = 0;
};

// One condition being tested: its classifier and its scores.
struct Trial {
  std::unique_ptr<atr::Classifier> classifier;
  std::unique_ptr<study::ConditionResult> result;
  double classify_s = 0.0;
  std::size_t classified = 0;
  // the first trial (this one or an earlier) with the same model and the same test chips (e.g.
  // the same condition with fewer looks): its classification of a chip serves this one too
  std::size_t same_as = 0;
  // multi-look conditions (SweepCondition::looks > 1): per test object, the looks' summed
  // scores (objects x classes) and whether a look's chip was unusable
  std::vector<float> fused;
  std::vector<std::uint8_t> unusable;
};

// Renders the chips of one slot into labelled chips (returns false when stopped).
bool render_labelled(const render::ChipRenderer& r, int slot, std::size_t count, SweepRun& ctx,
                     std::vector<atr::LabelledChip>& out, double* wall_s) {
  const bool shadow_height =
      ctx.settings.shadow_height && r.spec().kind == render::ChipKind::kShadow;
  const std::size_t got = render_slot(
      r, slot, count, ctx,
      [&](const render::ChipImage& c) {
        out.push_back(study::labelled_chip(c, shadow_height, ctx.settings.deripple));
        advance(ctx);
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
bool run_experiment(const study::SweepExperiment& e, SweepRun& ctx,
                    std::vector<study::ConditionResult>& results) {
  const std::size_t classes = e.classes.size();
  const auto write_all = [&] {
    write_file(ctx.out_dir / (e.name + ".csv"), study::results_csv(e, results));
    write_file(ctx.out_dir / (e.name + "_confusion.csv"), study::confusion_csv(e, results));
    write_seabed_csv(ctx, e, results);
  };
  for (const study::RenderGroup& g : study::render_groups(e)) {
    const std::vector<study::ChipSet> sets = study::group_chip_sets(e, g, ctx.settings);
    for (std::size_t slot = 0; slot < g.resolutions_m.size(); ++slot) {
      SlotSets order(sets);
      // training chips, shared by the conditions of this resolution
      std::vector<atr::LabelledChip> train;
      double wall_s = 0.0;
      const study::ChipSet& train_set = order.take(study::ChipSetRole::kTrain);
      if (!render_labelled(*train_set.renderer, static_cast<int>(slot), train_set.count, ctx, train,
                           &wall_s)) {
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
          // registration conditions of one model cut their test chips differently
          const auto chips_alike = std::find_if(trials.begin(), trials.end(), [&](const Trial& o) {
            const study::SweepCondition& oc = e.conditions[o.result->condition];
            return study::same_training(oc, c) && oc.misregister_m == c.misregister_m;
          });
          t.same_as = chips_alike != trials.end()
                          ? static_cast<std::size_t>(chips_alike - trials.begin())
                          : trials.size();
          trials.push_back(std::move(t));
          continue;
        }
        atr::TrainOptions opt;
        opt.p = c.p;
        opt.aspect_sectors = c.aspect_sectors;
        opt.skip_degenerate = true;
        opt.class_metadata = study::target_class_metadata();  // mine-like flags of the target types
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
        t.same_as = trials.size();
        t.result = std::make_unique<study::ConditionResult>(ci, e, model);
        t.result->train_s = seconds_since(t0);
        t.classifier = std::make_unique<atr::Classifier>(std::move(model));
        trials.push_back(std::move(t));
      }
      train.clear();

      // test chips: every condition classifies each one; multi-look conditions add each look's
      // distances to the object's fused scores and score the object at their last look
      const study::ChipSet& test_set = order.take(study::ChipSetRole::kTest, 0);
      const std::size_t n_test = test_set.count;
      const bool shadow_height =
          ctx.settings.shadow_height && test_set.renderer->spec().kind == render::ChipKind::kShadow;
      for (Trial& t : trials) {
        if (e.conditions[t.result->condition].looks <= 1) continue;
        t.fused.assign(n_test * classes, 0.0f);
        t.unusable.assign(n_test, 0);
      }
      atr::Chip chip;
      // per chip, by the trial that classified it (Trial::same_as): its check and time
      std::vector<std::optional<atr::ChipCheck>> checked(trials.size());
      std::vector<double> checked_s(trials.size(), 0.0);
      const auto classify_look = [&](const render::ChipImage& c, int look) {
        // the training chips' treatment
        chip = study::classifier_chip(c, shadow_height, ctx.settings.deripple);
        const atr::ChipView view = chip.view();
        const auto truth = static_cast<std::size_t>(
            std::find(e.classes.begin(), e.classes.end(), c.params.type) - e.classes.begin());
        std::fill(checked.begin(), checked.end(), std::nullopt);
        for (Trial& t : trials) {
          const study::SweepCondition& cond = e.conditions[t.result->condition];
          if (look >= cond.looks) continue;
          Trial& by = trials[t.same_as];
          if (!checked[t.same_as]) {
            atr::Chip registered;
            if (cond.window_m > 0.0) {
              registered = study::registration_chip(view, cond, c.params.index, true);
            }
            const auto t0 = Clock::now();
            checked[t.same_as] =
                by.classifier->classify(cond.window_m > 0.0 ? registered.view() : view);
            checked_s[t.same_as] = seconds_since(t0);
          }
          t.classify_s += checked_s[t.same_as];
          const atr::ChipCheck& check = *checked[t.same_as];
          const atr::Classification& classified = by.classifier->result();
          if (cond.looks > 1) {
            const std::span<float> fused(t.fused.data() + c.params.index * classes, classes);
            if (check.ok()) {
              ++t.classified;
              atr::add_look(t.classifier->model(), classified, atr::FusionNorm::kModelTypical,
                            fused);
            } else {
              t.unusable[c.params.index] = 1;
            }
            if (look + 1 < cond.looks) continue;
            if (t.unusable[c.params.index]) {
              ++t.result->rejected;
              continue;
            }
            atr::Classification answer = classified;
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
                            c.params.seabed, classified);
        }
        advance(ctx);
      };
      std::size_t tested = render_slot(
          *test_set.renderer, static_cast<int>(slot), n_test, ctx,
          [&](const render::ChipImage& c) { classify_look(c, 0); }, &wall_s);
      // the other looks at the same objects; a condition is complete when its last look is
      int looks_done = tested == n_test ? 1 : 0;
      for (int look = 1; look < g.looks && looks_done == look; ++look) {
        double look_wall_s = 0.0;
        const std::size_t n = render_slot(
            *order.take(study::ChipSetRole::kTest, look).renderer, static_cast<int>(slot), n_test,
            ctx, [&](const render::ChipImage& c) { classify_look(c, look); }, &look_wall_s);
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
bool run_fusion_experiment(const study::SweepExperiment& e, SweepRun& ctx,
                           std::vector<study::ConditionResult>& results) {
  const std::size_t classes = e.classes.size();
  for (const study::RenderGroup& g : study::render_groups(e)) {
    const std::vector<study::ChipSet> sets = study::group_chip_sets(e, g, ctx.settings);
    for (std::size_t slot = 0; slot < g.resolutions_m.size(); ++slot) {
      SlotSets order(sets);
      const auto& members = g.members[slot];
      const study::SweepCondition& c0 = e.conditions[members.front()];
      const study::ChipSet& train_hl = order.take(study::ChipSetRole::kTrain);
      const study::ChipSet& train_sh = order.take(study::ChipSetRole::kTrainShadow);
      const std::size_t n_train = train_hl.count;
      const int islot = static_cast<int>(slot);
      double wall = 0.0, render_s = 0.0;
      std::vector<atr::LabelledChip> hl, sh;
      if (!render_labelled(*train_hl.renderer, islot, n_train, ctx, hl, &wall)) return false;
      render_s += wall;
      if (!render_labelled(*train_sh.renderer, islot, n_train, ctx, sh, &wall)) return false;
      render_s += wall;
      atr::TrainOptions opt;
      opt.p = c0.p;
      opt.skip_degenerate = true;
      opt.calibrate = true;
      opt.class_metadata = study::target_class_metadata();
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
      const study::ChipSet& test_hl = order.take(study::ChipSetRole::kTest);
      const std::size_t n_test = test_hl.count;
      if (!render_labelled(*test_hl.renderer, islot, n_test, ctx, hl, &wall)) return false;
      render_s += wall;
      std::vector<std::optional<atr::Classification>> by_highlight(hl.size());
      for (std::size_t i = 0; i < hl.size(); ++i) {
        if (ch.classify(hl[i].chip.view()).ok()) by_highlight[i] = ch.result();
      }
      std::vector<float> fused(classes);
      atr::Chip shadow_chip;
      double classify_s = 0.0;
      const std::size_t tested = render_slot(
          *order.take(study::ChipSetRole::kTestShadow).renderer, islot, n_test, ctx,
          [&](const render::ChipImage& c) {
            advance(ctx);
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

}  // namespace

double sweep_experiment_chips(const study::SweepExperiment& e) {
  double total = 0.0;
  for (const study::RenderGroup& g : study::render_groups(e)) {
    total += static_cast<double>(g.resolutions_m.size()) * static_cast<double>(e.classes.size()) *
             (g.train_count + g.looks * e.test_count);
  }
  return study::is_fusion(e) ? 2.0 * total : total;  // a highlight and a shadow chip per object
}

bool run_sweep_experiment(const study::SweepExperiment& e, SweepRun& run,
                          std::vector<study::ConditionResult>& results) {
  return study::is_fusion(e) ? run_fusion_experiment(e, run, results)
                             : run_experiment(e, run, results);
}

}  // namespace sonarloop::ranks
