// sonarloop sweep: the resolution study of Pailhas, Petillot & Capus (2010), Sections 3-4, in
// memory: chips from the chip renderer, the eigen-subspace classifier, misidentification with
// 95 % Wilson intervals per target and condition, CSV files and charts (tools/plot_sweep.py).
// The experiments and the scoring live in study/sweep.h, the run (render, train, score, write)
// in ranks/sweep_run.h; this file is the command line.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include "config/loader/scenario_loader.h"
#include "config/loader/sonar_loader.h"
#include "ranks/chip_ranks.h"
#include "ranks/mpi_world.h"
#include "ranks/sweep_ranks.h"
#include "ranks/sweep_run.h"
#include "sim/render/chip_renderer.h"
#include "study/sweep.h"
#include "tools/args.h"
#include "tools/chip_options.h"
#include "tools/cli_helpers.h"
#include "tools/commands.h"
#include "tools/progress.h"

#ifndef SONARLOOP_SWEEP_PLOT_SCRIPT
#define SONARLOOP_SWEEP_PLOT_SCRIPT "tools/plot_sweep.py"
#endif

namespace sonarloop::tools {
namespace mpi = ranks::mpi;
using ranks::ranks_note;

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
  ranks::SweepRun ctx;
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
  install_stop_flag();
  ctx.stop = [] { return stop_requested(); };
  if (!mpi::is_root()) return ranks::serve_sweep(experiments, s, ctx.threads, ctx.stop) ? 0 : 130;
  fs::create_directories(ctx.out_dir);

  double total = 0.0;
  for (const auto& e : experiments)
    total += ranks::sweep_experiment_chips(e);
  const auto t0 = Clock::now();
  bool stopped = false;
  {
    Progress bar("sweep: " + std::to_string(static_cast<long long>(total)) + " chips", total);
    ctx.progress = [&bar](double done) { bar.update(done); };
    for (const auto& e : experiments) {
      std::fprintf(stderr, "sonarloop sweep: %s: %s (%zu conditions)\n", e.name.c_str(),
                   e.title.c_str(), e.conditions.size());
      std::vector<study::ConditionResult> results;
      const bool done = ranks::run_sweep_experiment(e, ctx, results);
      if (!done) {
        stopped = true;
        break;
      }
    }
    bar.finish();
    ctx.progress = nullptr;  // the bar ends here
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
