// sonarloop classify: classify PNG or JPEG chips with a trained PCA model; score against the truth
// when the chips come in class subfolders.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "atr/chip_folder.h"
#include "atr/confusion.h"
#include "atr/model_file.h"
#include "atr/subspace_classifier.h"
#include "drivers/json/json_writer.h"
#include "tools/args.h"
#include "tools/chip_options.h"
#include "tools/commands.h"
#include "tools/progress.h"

namespace sonarloop::tools {
namespace {

// One chip's outcome.
struct Row {
  const atr::LabelledChip* chip = nullptr;
  atr::ChipCheck check;
  atr::Classification result;  // valid when check.ok()
};

// Whether a true class is mine-like: the model's flag for a class it knows, else the
// simulator's for a target type, else unknown.
std::optional<bool> truth_mine_like(const atr::Model& m, const std::string& name) {
  if (const int i = m.find_class(name); i >= 0)
    return m.classes[static_cast<std::size_t>(i)].mine_like;
  const auto sim = sim_class_metadata();
  if (const auto it = sim.find(name); it != sim.end()) return it->second.mine_like;
  return std::nullopt;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string number(double v) {
  if (!std::isfinite(v)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

void write_csv(const std::string& path, const atr::Model& m, const std::vector<Row>& rows) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot create '" + path + "'");
  out << "file,truth,status,predicted,distance,runner_up,runner_up_distance,mine_like,"
         "mine_distance,non_mine_distance,aspect_min_deg,aspect_max_deg";
  for (const auto& c : m.classes)
    out << "," << csv_field("distance_" + c.name);
  out << ",reason\n";
  for (const Row& r : rows) {
    out << csv_field(r.chip->source) << "," << csv_field(r.chip->label) << ","
        << atr::chip_status_name(r.check.status);
    if (r.check.ok()) {
      const auto& x = r.result;
      const auto& cls = m.classes[static_cast<std::size_t>(x.class_index)];
      const auto& sub = cls.subspaces[static_cast<std::size_t>(x.subspace_index)];
      out << "," << csv_field(cls.name) << "," << number(x.distance) << ","
          << (x.runner_up >= 0 ? csv_field(m.classes[static_cast<std::size_t>(x.runner_up)].name)
                               : "")
          << "," << number(x.runner_up_distance) << ",";
      if (m.has_mine_like_class()) {
        out << (x.mine_like ? 1 : 0) << "," << number(x.mine_distance) << ","
            << number(x.non_mine_distance);
      } else {
        out << ",,";
      }
      out << "," << number(sub.aspect_min_deg) << "," << number(sub.aspect_max_deg);
      for (float d : x.class_distance)
        out << "," << number(d);
      out << ",\n";
    } else {
      out << ",,,,,,,,,";
      for (std::size_t i = 0; i < m.classes.size(); ++i)
        out << ",";
      out << "," << csv_field(r.check.reason()) << "\n";
    }
  }
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
}

// The chips of a folder (labelled when it has class subfolders), listed without their pixels;
// or one image file, read.
atr::ChipFolder list_input(const std::string& input, bool skip_bad,
                           const std::optional<atr::ChipSize>& size) {
  atr::ChipFolder folder;
  if (std::filesystem::is_directory(input)) {
    atr::ChipFolderOptions fo;
    fo.require_classes = false;
    fo.require_same_size = false;  // the classifier rejects each chip of the wrong size
    fo.read_pixels = false;
    fo.skip_bad = skip_bad;
    folder = atr::read_chip_folder(input, fo);
  } else {
    folder.root = input;
    folder.chips.push_back(atr::read_chip_file(input, size));
  }
  return folder;
}

int run_classify(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--csv"},
                         {"--json"},
                         {"--quiet", false},
                         {"--aspect-bins"},
                         {"--size"},
                         {"--skip-bad-chips", false}});
  if (args.positionals().size() != 2) throw UsageError("expected MODEL and CHIPS_DIR or CHIP.png");
  const int aspect_bins = static_cast<int>(args.get_int("--aspect-bins", 0, 360).value_or(12));
  const bool quiet = args.has("--quiet");
  const bool skip_bad = args.has("--skip-bad-chips");
  const std::optional<atr::ChipSize> size = chip_size_option(args);
  const std::string& model_path = args.positionals()[0];
  const std::string& input = args.positionals()[1];

  atr::Classifier clf(load_model_with_metadata(model_path));
  const atr::Model& m = clf.model();
  const bool mine_decision = m.has_mine_like_class();
  const bool one_file = !std::filesystem::is_directory(input);
  atr::ChipFolder folder = list_input(input, skip_bad, size);
  for (const auto& s : folder.skipped)
    std::fprintf(stderr, "skipped '%s': %s\n", s.source.c_str(), s.reason.c_str());

  // classify chip by chip (read, resample, classify), timing the classifier alone
  std::vector<Row> rows;
  rows.reserve(folder.chips.size());
  double classify_s = 0.0;
  std::size_t classified = 0, unreadable = 0;
  Progress bar("classifying " + std::to_string(folder.chips.size()) + " chips",
               static_cast<double>(folder.chips.size()));
  for (std::size_t i = 0; i < folder.chips.size(); ++i) {
    bar.update(static_cast<double>(i));
    atr::Chip chip;
    try {
      chip = one_file ? std::move(folder.chips[i].chip) : atr::read_folder_chip(folder, i, size);
    } catch (const std::runtime_error& e) {
      if (!skip_bad) throw;
      std::fprintf(stderr, "skipped '%s': %s\n", folder.chips[i].source.c_str(), e.what());
      ++unreadable;
      continue;
    }
    Row& row = rows.emplace_back();
    row.chip = &folder.chips[i];
    const auto t = std::chrono::steady_clock::now();
    row.check = clf.classify(chip.view());
    classify_s += seconds_since(t);
    if (row.check.ok()) {
      row.result = clf.result();
      ++classified;
    }
  }
  bar.finish();

  // per-chip lines
  for (const Row& r : rows) {
    if (!r.check.ok()) {
      std::fprintf(stderr, "rejected '%s': %s\n", r.chip->source.c_str(), r.check.reason().c_str());
      continue;
    }
    if (quiet) continue;
    const auto& x = r.result;
    const std::string& pred = m.classes[static_cast<std::size_t>(x.class_index)].name;
    std::printf("%-32s %-16s d=%-9.4g", r.chip->source.c_str(), pred.c_str(),
                static_cast<double>(x.distance));
    if (x.runner_up >= 0) {
      std::printf(" next %-12s d=%-9.4g",
                  m.classes[static_cast<std::size_t>(x.runner_up)].name.c_str(),
                  static_cast<double>(x.runner_up_distance));
    }
    if (mine_decision) std::printf(" %-9s", x.mine_like ? "mine" : "non-mine");
    if (x.unknown)
      std::printf(" UNKNOWN (open-set score %.2f)", static_cast<double>(x.open_set_score));
    if (!r.chip->label.empty())
      std::printf(" truth %s%s", r.chip->label.c_str(), r.chip->label == pred ? "" : "  WRONG");
    std::printf("\n");
  }

  const std::size_t rejected = rows.size() - classified;
  const std::size_t skipped = folder.skipped.size() + unreadable;
  std::printf("classified %zu chip%s (%zu rejected) with %s: %d x %d pixels, %zu classes, p = %d\n",
              classified, classified == 1 ? "" : "s", rejected, model_path.c_str(), m.chip_width,
              m.chip_height, m.classes.size(), m.p);
  if (skipped) std::printf("skipped %zu unreadable files (listed on stderr)\n", skipped);
  const double per_chip_us = classified ? 1e6 * classify_s / static_cast<double>(classified) : 0.0;
  if (classified) std::printf("classify time: %.1f us per chip\n", per_chip_us);

  // scoring against the truth
  std::optional<atr::ConfusionMatrix> confusion;
  std::size_t mine_total = 0, mine_correct = 0;
  struct AspectBin {
    std::size_t total = 0, correct = 0;
  };
  std::vector<AspectBin> bins;
  if (folder.labelled && classified) {
    std::vector<std::string> predicted;
    for (const auto& c : m.classes)
      predicted.push_back(c.name);
    confusion.emplace(folder.classes, predicted);
    const bool by_aspect = aspect_bins > 0 && folder.aspect_count > 0;
    if (by_aspect) bins.resize(static_cast<std::size_t>(aspect_bins));
    for (const Row& r : rows) {
      if (!r.check.ok()) continue;
      const auto truth = static_cast<std::size_t>(
          std::find(folder.classes.begin(), folder.classes.end(), r.chip->label) -
          folder.classes.begin());
      confusion->add(truth, static_cast<std::size_t>(r.result.class_index));
      const bool ok =
          m.classes[static_cast<std::size_t>(r.result.class_index)].name == r.chip->label;
      const auto mine = mine_decision ? truth_mine_like(m, r.chip->label) : std::nullopt;
      if (mine) {
        ++mine_total;
        mine_correct += r.result.mine_like == *mine;
      }
      if (by_aspect && r.chip->aspect_deg) {
        auto& b =
            bins[static_cast<std::size_t>(atr::aspect_sector(*r.chip->aspect_deg, aspect_bins))];
        ++b.total;
        b.correct += ok;
      }
    }
    std::printf("\nconfusion matrix (rows: truth, columns: prediction):\n%s",
                confusion->to_text().c_str());
    const auto ci = confusion->accuracy_interval();
    std::printf("accuracy: %.2f %% (%zu of %zu), 95 %% Wilson interval %.2f-%.2f %%\n",
                100.0 * confusion->accuracy(), confusion->correct(), confusion->total(),
                100.0 * ci.lo, 100.0 * ci.hi);
    if (mine_total) {
      const auto mci = atr::wilson_interval(mine_correct, mine_total);
      std::printf(
          "mine / non-mine: %.2f %% correct (%zu of %zu), 95 %% Wilson interval %.2f-%.2f %%\n",
          100.0 * static_cast<double>(mine_correct) / static_cast<double>(mine_total), mine_correct,
          mine_total, 100.0 * mci.lo, 100.0 * mci.hi);
    }
    if (!bins.empty()) {
      std::printf("accuracy by true aspect (labels.csv aspect_deg):\n");
      const double w = 360.0 / aspect_bins;
      for (std::size_t b = 0; b < bins.size(); ++b) {
        if (!bins[b].total) continue;
        const auto bi = atr::wilson_interval(bins[b].correct, bins[b].total);
        std::printf(
            "  %5.1f-%5.1f deg  %6.2f %%  (%zu of %zu, 95 %% %.1f-%.1f %%)\n",
            static_cast<double>(b) * w, static_cast<double>(b + 1) * w,
            100.0 * static_cast<double>(bins[b].correct) / static_cast<double>(bins[b].total),
            bins[b].correct, bins[b].total, 100.0 * bi.lo, 100.0 * bi.hi);
      }
    }
  }

  if (const auto csv = args.get("--csv")) write_csv(*csv, m, rows);
  if (const auto json_path = args.get("--json")) {
    json::Writer w(true);
    w.begin_object().field("model", model_path).field("input", folder.root);
    w.field("chip_width", m.chip_width).field("chip_height", m.chip_height).field("p", m.p);
    w.key("classes").begin_array();
    for (const auto& c : m.classes)
      w.value(c.name);
    w.end_array();
    w.key("chips").begin_array();
    for (const Row& r : rows) {
      w.begin_object().field("file", r.chip->source);
      if (!r.chip->label.empty()) w.field("truth", r.chip->label);
      if (r.chip->aspect_deg) w.field("aspect_deg", *r.chip->aspect_deg);
      w.field("status", atr::chip_status_name(r.check.status));
      if (!r.check.ok()) {
        w.field("reason", r.check.reason()).end_object();
        continue;
      }
      const auto& x = r.result;
      const auto& cls = m.classes[static_cast<std::size_t>(x.class_index)];
      const auto& sub = cls.subspaces[static_cast<std::size_t>(x.subspace_index)];
      w.field("predicted", cls.name).field("distance", static_cast<double>(x.distance), 7);
      w.key("aspect_range_deg")
          .begin_array()
          .value(sub.aspect_min_deg)
          .value(sub.aspect_max_deg)
          .end_array();
      if (mine_decision) {
        w.field("mine_like", x.mine_like).field("mine_like_by_identity", x.mine_like_by_identity);
        w.field("mine_distance", static_cast<double>(x.mine_distance), 7);
        w.field("non_mine_distance", static_cast<double>(x.non_mine_distance), 7);
      }
      if (std::isfinite(cls.reject_distance)) {
        w.field("unknown", x.unknown)
            .field("open_set_score", static_cast<double>(x.open_set_score), 7);
      }
      w.key("distances").begin_object();
      for (std::size_t i = 0; i < m.classes.size(); ++i) {
        w.field(m.classes[i].name, static_cast<double>(x.class_distance[i]), 7);
      }
      w.end_object().end_object();
    }
    w.end_array();
    w.key("summary").begin_object();
    w.field("classified", static_cast<std::uint64_t>(classified));
    w.field("rejected", static_cast<std::uint64_t>(rejected));
    w.field("skipped", static_cast<std::uint64_t>(skipped));
    w.field("classify_us_per_chip", per_chip_us, 4);
    if (confusion) {
      const auto ci = confusion->accuracy_interval();
      w.field("correct", static_cast<std::uint64_t>(confusion->correct()));
      w.field("accuracy", confusion->accuracy(), 6);
      w.key("accuracy_ci95").begin_array().value(ci.lo, 6).value(ci.hi, 6).end_array();
      w.key("confusion").begin_object();
      w.key("truth").begin_array();
      for (const auto& t : confusion->truth_classes())
        w.value(t);
      w.end_array();
      w.key("predicted").begin_array();
      for (const auto& p : confusion->predicted_classes())
        w.value(p);
      w.end_array();
      w.key("counts").begin_array();
      for (std::size_t i = 0; i < confusion->truth_classes().size(); ++i) {
        w.begin_array();
        for (std::size_t j = 0; j < confusion->predicted_classes().size(); ++j) {
          w.value(static_cast<std::uint64_t>(confusion->count(i, j)));
        }
        w.end_array();
      }
      w.end_array().end_object();
      if (mine_total) {
        const auto mci = atr::wilson_interval(mine_correct, mine_total);
        w.key("mine_non_mine").begin_object();
        w.field("correct", static_cast<std::uint64_t>(mine_correct));
        w.field("total", static_cast<std::uint64_t>(mine_total));
        w.field("accuracy", static_cast<double>(mine_correct) / static_cast<double>(mine_total), 6);
        w.key("accuracy_ci95").begin_array().value(mci.lo, 6).value(mci.hi, 6).end_array();
        w.end_object();
      }
      if (!bins.empty()) {
        w.key("by_aspect").begin_array();
        const double bw = 360.0 / aspect_bins;
        for (std::size_t b = 0; b < bins.size(); ++b) {
          w.begin_object();
          w.key("aspect_deg")
              .begin_array()
              .value(static_cast<double>(b) * bw)
              .value(static_cast<double>(b + 1) * bw)
              .end_array();
          w.field("correct", static_cast<std::uint64_t>(bins[b].correct));
          w.field("total", static_cast<std::uint64_t>(bins[b].total));
          w.end_object();
        }
        w.end_array();
      }
    }
    w.end_object().end_object();
    std::ofstream out(*json_path);
    out << w.str() << '\n';
    if (!out) throw std::runtime_error("cannot write '" + *json_path + "'");
  }
  if (!classified) {
    throw std::runtime_error("no chip could be classified (" + std::to_string(rejected) +
                             " rejected, reasons above)");
  }
  return 0;
}

}  // namespace

const Command kClassifyCommand{
    "classify",
    "classify PNG or JPEG chips with a trained model; confusion matrix and accuracy if labelled",
    R"(usage: sonarloop classify MODEL CHIPS_DIR|CHIP.png|CHIP.jpg [options]

Classifies each chip with the eigen-subspace model written by 'sonarloop train': the chip is
normalised by its own mean and standard deviation and given the class whose subspace leaves the
smallest residual (Pailhas, Petillot & Capus 2010, eq. 10); the mine / non-mine decision
(Section 4.1.2) follows when the model has a mine-like class (see train --mine-like; without
one, no mine / non-mine column or score is printed). Prints one line per chip: file, predicted
class and distance, the runner-up, mine / non-mine, and the truth when known.

CHIPS_DIR is either a folder with one subfolder per class (as for 'sonarloop train': the truth
is the subfolder), or a folder of PNG or JPEG chips without classes. With class subfolders the
command also prints the confusion matrix, the accuracy with its 95 % Wilson score interval, the
mine / non-mine accuracy, and, when CHIPS_DIR/labels.csv gives aspect_deg, the accuracy by true
aspect angle. A class the model does not know always counts as wrong. Chips are read one at a
time (a progress bar shows on stderr after a second).

Degenerate chips (constant, non-finite, of another size than the model's) are rejected with a
reason on stderr and left out of the scores. Files that are not PNG or JPEG, unreadable images
and nested folders stop the command, unless --skip-bad-chips. The exit status is 0 when at
least one chip was classified, 1 otherwise or on error, 2 on a usage error.

options:
  --csv FILE          one row per chip: predictions, distances to every class, reasons
  --json FILE         per-chip predictions and the summary (confusion matrix, accuracy, CIs)
  --quiet             no per-chip lines (rejections and the summary only)
  --aspect-bins N     bins for the accuracy by aspect (default 12, 0 = off)
  --size WxH          resample every chip to W x H pixels (area average) first, e.g. the
                      model's size when the chips were cut at another
  --skip-bad-chips    skip unreadable files, non-images and nested folders, one line each on
                      stderr, instead of stopping at the first

examples:
  sonarloop classify out/atr.slpca out/test_chips
  sonarloop classify out/atr.slpca out/test_chips --quiet --json out/scores.json
  sonarloop classify out/atr.slpca contact_0042.png
  sonarloop classify survey.slpca ~/survey/test_chips --size 64x64 --skip-bad-chips
)",
    run_classify, 61};
SONARLOOP_REGISTER_COMMAND(kClassifyCommand);

}  // namespace sonarloop::tools
