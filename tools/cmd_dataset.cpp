// sonarloop dataset: labelled target chips (PNG, one folder per class) plus labels.csv, for
// training and testing target recognition (Pailhas et al. 2010, Section 4). The chips come
// from sim/render/chip_renderer.h; this file chooses the options and writes the files.
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <set>

#include "config/loader/scenario_loader.h"
#include "config/loader/sonar_loader.h"
#include "drivers/image/png.h"
#include "drivers/json/json_writer.h"
#include "ranks/chip_ranks.h"
#include "ranks/mpi_world.h"
#include "sim/render/chip_renderer.h"
#include "sim/targets/target_type.h"
#include "study/chip_labels.h"
#include "tools/args.h"
#include "tools/cli_helpers.h"
#include "tools/cmd_survey_training.h"
#include "tools/commands.h"
#include "tools/progress.h"

namespace sonarloop::tools {
namespace mpi = ranks::mpi;
using ranks::dataset_jobs;
using ranks::ranks_note;
using ranks::render_chips_on_ranks;
using ranks::serve_dataset;

namespace {

namespace fs = std::filesystem;

// The default classes: the four identification targets of Pailhas et al. (2010), Fig. 11.
constexpr const char* kDefaultClasses = "manta,rockan,cuboid,cylinder";
constexpr const char* kDefaultSeabeds = "flat,ripples,clutter";
constexpr long long kDefaultCountPerClass = 100;
// Chip file names carry the index zero-padded to at least this many digits (they sort).
constexpr int kMinIndexDigits = 6;

std::vector<targets::TargetType> parse_classes(const std::string& text) {
  std::vector<targets::TargetType> out;
  if (text == "all") {
    for (const auto& info : targets::target_type_table())
      out.push_back(info.type);
    return out;
  }
  for (const std::string& key : split_comma_list(text)) {
    const auto t = targets::find_target_type(key);
    if (!t) {
      throw UsageError("--classes: unknown target type '" + key + "' (allowed: 'all' or a comma " +
                       "list of " + targets::target_type_keys_list() + ")");
    }
    if (std::find(out.begin(), out.end(), *t) != out.end()) {
      throw UsageError("--classes: '" + key + "' is listed twice");
    }
    out.push_back(*t);
  }
  if (out.empty()) throw UsageError("--classes: no class given");
  return out;
}

chips::ChipLevels parse_levels(const std::string& text) {
  double lo = 0.0, hi = 0.0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf%c", &lo, &hi, &tail) != 2 || !(lo < hi) || lo < -200.0 ||
      hi > 100.0) {
    throw UsageError("--levels-db: '" + text +
                     "' is not MIN,MAX in dB re full scale with -200 <= MIN < MAX <= 100");
  }
  return chips::ChipLevels{lo, hi};
}

double parse_resolution_cm(const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double cm = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || errno != 0 || !(cm >= 0.5 && cm <= 100.0)) {
    throw UsageError("--resolution-cm: '" + text + "' is not a number of centimetres in 0.5..100");
  }
  return cm;
}

// "5", "2.5", "0.75": the resolution in centimetres as folder names and CSV cells show it.
std::string format_cm(double resolution_m) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", resolution_m * 100.0);
  return buf;
}

std::string format_fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

constexpr const char* kCsvHeader =
    "file,class,aspect_deg,mine_like,kind,seabed,altitude_m,range_m,heading_deg,side,"
    "resolution_cm,seed,index,slant_range_m,track_heading_deg,target_row,target_col,north_m,"
    "east_m,width,height,label_file,highlight_pixels,shadow_pixels";

// One labels.csv row (after `file`).
std::string csv_fields(const render::ChipImage& c, const render::ChipDatasetSpec& spec) {
  const auto& p = c.params;
  const auto& info = targets::target_type_info(p.type);
  std::string s;
  s += std::string(info.key) + ",";
  s += format_fixed(p.aspect_deg, 3) + ",";
  s += std::string(info.mine_like ? "1" : "0") + ",";
  s += std::string(chips::chip_kind_name(spec.kind)) + ",";
  s += spec.seabeds[static_cast<std::size_t>(p.seabed)].name + ",";
  s += format_fixed(p.altitude_m, 4) + ",";
  s += format_fixed(p.ground_range_m, 4) + ",";
  s += format_fixed(p.target_heading_deg, 3) + ",";
  s += std::string(p.side == 1 ? "starboard" : "port") + ",";
  s += format_cm(c.resolution_m) + ",";
  s += std::to_string(spec.seed) + ",";
  s += std::to_string(p.index) + ",";
  s += format_fixed(c.slant_range_m, 4) + ",";
  s += format_fixed(p.track_heading_deg, 3) + ",";
  s += format_fixed(c.target_row, 3) + ",";
  s += format_fixed(c.target_col, 3) + ",";
  s += format_fixed(p.target_ne_m.x(), 3) + ",";
  s += format_fixed(p.target_ne_m.y(), 3) + ",";
  s += std::to_string(c.cols) + ",";
  s += std::to_string(c.rows);
  return s;
}

// A labels.csv opened for appending rows, flushed after each (so that an interrupted run leaves
// exactly the rows of the chips on disk).
class CsvFile {
 public:
  explicit CsvFile(const fs::path& path) : path_(path) {
    f_ = std::fopen(path.string().c_str(), "wb");
    if (!f_) {
      throw std::runtime_error("cannot create '" + path.string() + "': " + std::strerror(errno));
    }
    write_line(kCsvHeader);
  }
  ~CsvFile() {
    if (f_) std::fclose(f_);
  }
  CsvFile(const CsvFile&) = delete;
  CsvFile& operator=(const CsvFile&) = delete;
  void write_line(const std::string& line) {
    if (std::fputs(line.c_str(), f_) < 0 || std::fputc('\n', f_) == EOF || std::fflush(f_) != 0) {
      throw std::runtime_error("write failed for '" + path_.string() +
                               "': " + std::strerror(errno));
    }
  }

 private:
  fs::path path_;
  std::FILE* f_ = nullptr;
};

// The dataset's description; `written`: the chips an interrupted run wrote (the first ones of
// the job order: indices 0 .. written - 1), said beside count_per_class, which it asked for.
void write_dataset_json(const fs::path& path, const render::ChipRenderer& r,
                        const std::string& sonar_name, long long count_per_class,
                        std::optional<std::size_t> written = std::nullopt) {
  const render::ChipDatasetSpec& spec = r.spec();
  json::Writer w(true);
  w.begin_object();
  w.field("generator", std::string("sonarloop dataset ") + SONARLOOP_VERSION);
  w.field("seed", spec.seed).field("kind", chips::chip_kind_name(spec.kind));
  w.field("count_per_class", static_cast<std::int64_t>(count_per_class));
  if (written) {
    w.field("interrupted", true);
    w.field("chips_written", static_cast<std::uint64_t>(*written));
  }
  w.key("classes").begin_array();
  for (auto t : spec.classes)
    w.value(targets::target_type_info(t).key);
  w.end_array();
  w.key("seabeds").begin_array();
  for (const auto& s : spec.seabeds)
    w.value(s.name);
  w.end_array();
  w.field("sonar", sonar_name);
  w.key("resolutions_cm").begin_array();
  for (double res : spec.resolutions_m)
    w.value(res * 100.0, 6);
  w.end_array();
  w.key("chip_pixels").begin_array();
  for (std::size_t k = 0; k < spec.resolutions_m.size(); ++k) {
    w.begin_object()
        .field("width", r.cols(static_cast<int>(k)))
        .field("height", r.rows(static_cast<int>(k)))
        .end_object();
  }
  w.end_array();
  const bool shadow = spec.kind == chips::ChipKind::kShadow;
  w.field("chip_along_track_m", shadow ? chips::kShadowChipAlong_m : chips::kHighlightChipAlong_m,
          6);
  w.field("chip_slant_range_m", shadow ? chips::kShadowChipRange_m : chips::kHighlightChipRange_m,
          6);
  w.field("altitude_m", std::string(format_fixed(spec.altitude_min_m, 2) + ".." +
                                    format_fixed(spec.altitude_max_m, 2)));
  w.field("ground_range_m",
          shadow ? format_fixed(chips::kShadowGroundRange_m, 2)
                 : format_fixed(spec.range_min_m, 2) + ".." + format_fixed(spec.range_max_m, 2));
  w.field("pixel_min_db", spec.levels.min_db, 6).field("pixel_max_db", spec.levels.max_db, 6);
  w.field("pixels",
          "8-bit grey: round(255 * (L - pixel_min_db) / (pixel_max_db - pixel_min_db)) clipped to "
          "0..255, L = 20 log10(amplitude re full scale) after TVG (sim/render/quantise.h)");
  w.field("labels",
          "<index>_label.png next to each chip, the same size: 8-bit values 0 seabed, 1 target "
          "highlight, 2 target shadow (not grey levels), from the render's physics "
          "(docs/rendering.md, Labels)");
  w.field("axes",
          "columns = slant range near to far, rows = pings along track; starboard chips have "
          "the last ping in row 0, port chips the first, so every chip is the seabed seen from "
          "above (not mirrored), turned so that the sonar looks to the right");
  w.field("aspect",
          "aspect_deg = target heading - look direction (track heading +90 starboard, -90 port), "
          "0..360, clockwise: 0 = long axis pointing right in the chip, 90 = down");
  w.end_object();
  std::ofstream out(path);
  out << w.str() << '\n';
  if (!out) throw std::runtime_error("cannot write '" + path.string() + "'");
}

// --resolution-cm, repeatable (default 5), in metres; each at most once.
std::vector<double> parse_resolutions_m(const Args& args) {
  std::vector<double> resolutions_m;
  std::vector<std::string> res_text = args.get_all("--resolution-cm");
  if (res_text.empty()) res_text = {"5"};
  for (const std::string& t : res_text) {
    const double cm = parse_resolution_cm(t);
    for (double r : resolutions_m) {
      if (format_cm(r) == format_cm(cm / 100.0)) {
        throw UsageError("--resolution-cm " + t + " is given twice");
      }
    }
    resolutions_m.push_back(cm / 100.0);
  }
  return resolutions_m;
}

// The chip kind, classes, seed, sonar, levels, seabeds and renderer into spec.
void parse_chip_options(const Args& args, render::ChipDatasetSpec& spec) {
  const std::string kind = args.get_or("--kind", "highlight");
  if (kind == "highlight") {
    spec.kind = chips::ChipKind::kHighlight;
  } else if (kind == "shadow") {
    spec.kind = chips::ChipKind::kShadow;
  } else {
    throw UsageError("--kind: '" + kind + "' is not 'highlight' or 'shadow'");
  }
  spec.classes = parse_classes(args.get_or("--classes", kDefaultClasses));
  spec.seed = static_cast<std::uint64_t>(
      args.get_int("--seed", 0, std::numeric_limits<long long>::max()).value_or(0));
}

// An existing non-empty folder is never overwritten or mixed into.
void create_new_folder(const fs::path& out_dir) {
  std::error_code ec;
  if (fs::exists(out_dir, ec) && !fs::is_empty(out_dir, ec)) {
    throw std::runtime_error("'" + out_dir.string() +
                             "' already exists and is not empty: choose a new --out folder (a "
                             "dataset is never written over or into another)");
  }
  fs::create_directories(out_dir);
}

// The dataset's files: one root per resolution (out_dir itself, or out_dir/res_<R>cm) with its
// labels.csv, and with several resolutions a labels.csv in out_dir listing them all.
struct DatasetFiles {
  std::vector<fs::path> roots;
  std::vector<std::unique_ptr<CsvFile>> csvs;
  std::unique_ptr<CsvFile> all_csv;  // every resolution, paths relative to out_dir
  int digits = 1;                    // of the zero-padded chip index
  std::set<fs::path> made_dirs;
};

DatasetFiles open_dataset_files(const fs::path& out_dir, const render::ChipDatasetSpec& spec,
                                std::uint64_t total) {
  DatasetFiles files;
  const bool several = spec.resolutions_m.size() > 1;
  for (double r : spec.resolutions_m) {
    files.roots.push_back(several ? out_dir / ("res_" + format_cm(r) + "cm") : out_dir);
    fs::create_directories(files.roots.back());
    files.csvs.push_back(std::make_unique<CsvFile>(files.roots.back() / "labels.csv"));
  }
  if (several) files.all_csv = std::make_unique<CsvFile>(out_dir / "labels.csv");
  for (std::uint64_t v = total - 1; v >= 10; v /= 10)
    ++files.digits;
  files.digits = std::max(files.digits, kMinIndexDigits);
  return files;
}

// One chip: its PNG (written to a dot-file, which chip readers ignore, then renamed), then its
// labels.csv rows, flushed.
void write_chip(DatasetFiles& files, const render::ChipImage& c,
                const render::ChipDatasetSpec& spec) {
  const std::string cls(targets::target_type_info(c.params.type).key);
  char name[48];
  std::snprintf(name, sizeof name, "%0*llu.png", files.digits,
                static_cast<unsigned long long>(c.params.index));
  const fs::path& root = files.roots[static_cast<std::size_t>(c.resolution)];
  const fs::path dir = root / cls;
  if (files.made_dirs.insert(dir).second) fs::create_directories(dir);
  const fs::path tmp = dir / (std::string(".") + name + ".tmp");
  study::write_chip_label_png(dir, name, c);  // <index>_label.png, before the chip it labels
  image::write_png_gray8(tmp.string(), c.cols, c.rows, c.pixels);
  fs::rename(tmp, dir / name);
  const std::string fields = csv_fields(c, spec) + "," + study::chip_label_csv_fields(name, c);
  const std::string rel = cls + "/" + name;
  files.csvs[static_cast<std::size_t>(c.resolution)]->write_line(rel + "," + fields);
  if (files.all_csv) {
    files.all_csv->write_line(fs::path(root.filename() / rel).generic_string() + "," + fields);
  }
}

int run_dataset(const std::vector<std::string>& argv) {
  for (const std::string& a : argv) {
    if (a == "--surveys" || a.rfind("--surveys=", 0) == 0) return run_survey_dataset(argv);
  }
  const Args args(argv, {{"--out"},
                         {"--resolution-cm", true, true},
                         {"--count"},
                         {"--kind"},
                         {"--classes"},
                         {"--seabed"},
                         {"--seed"},
                         {"--threads"},
                         {"--sonar"},
                         {"--levels-db"},
                         {"--renderer"}});
  if (!args.positionals().empty()) {
    throw UsageError("unexpected argument '" + args.positionals()[0] + "'");
  }
  const auto out_arg = args.get("--out");
  if (!out_arg) throw UsageError("--out DIR is required");
  const fs::path out_dir(*out_arg);

  render::ChipDatasetSpec spec;
  spec.resolutions_m = parse_resolutions_m(args);
  const long long count = args.get_int("--count", 1, 10'000'000).value_or(kDefaultCountPerClass);
  parse_chip_options(args, spec);
  const int threads =
      static_cast<int>(args.get_int("--threads", 1, 256).value_or(mpi::default_threads()));
  const std::string sonar_arg = args.get_or("--sonar", std::string(config::kDefaultSonarPreset));
  spec.sonar =
      is_yaml_path(sonar_arg) ? config::load_sonar(sonar_arg) : config::builtin_sonar(sonar_arg);
  if (const auto l = args.get("--levels-db")) spec.levels = parse_levels(*l);
  spec.seabeds = dataset_seabeds_option(args.get_or("--seabed", kDefaultSeabeds));
  spec.renderer = renderer_option(args);

  // under mpirun: rank 0 writes the dataset, the others render their share (ranks/chip_ranks.h)
  mpi::start();
  if (!mpi::is_root()) {
    install_stop_flag();
    return serve_dataset(spec, static_cast<std::uint64_t>(count) * spec.classes.size(), threads,
                         [] { return stop_requested(); });
  }
  create_new_folder(out_dir);

  const auto t0 = std::chrono::steady_clock::now();
  const render::ChipRenderer renderer(spec);
  write_dataset_json(out_dir / "dataset.json", renderer, spec.sonar.name, count);
  const auto total = static_cast<std::uint64_t>(count) * spec.classes.size();
  DatasetFiles files = open_dataset_files(out_dir, spec, total);
  const std::vector<render::ChipJob> jobs = dataset_jobs(total, spec.resolutions_m.size());

  Progress bar("rendering " + std::to_string(jobs.size()) + " chips",
               static_cast<double>(jobs.size()));
  std::size_t written = 0;
  install_stop_flag();  // polled by the chip workers between chips
  const std::size_t done = render_chips_on_ranks(
      renderer, jobs, threads,
      [&](const render::ChipImage& c) {
        write_chip(files, c, spec);
        ++written;
        bar.update(static_cast<double>(written));
      },
      [] { return stop_requested(); });
  bar.finish();
  const double secs = seconds_since(t0);
  if (done < jobs.size()) {
    // what the folder holds, not what was asked
    write_dataset_json(out_dir / "dataset.json", renderer, spec.sonar.name, count, written);
    std::fprintf(stderr,
                 "sonarloop dataset: interrupted after %zu of %zu chips; '%s' holds them, each "
                 "with its labels.csv row\n",
                 done, jobs.size(), out_dir.string().c_str());
    return 130;
  }
  std::printf(
      "wrote %zu chips (%llu per class x %zu classes x %zu resolutions) in %.1f s "
      "(%.1f chips/s, %d threads%s): %s\n",
      done, static_cast<unsigned long long>(count), spec.classes.size(), spec.resolutions_m.size(),
      secs, static_cast<double>(done) / secs, threads, ranks_note().c_str(),
      out_dir.string().c_str());
  return 0;
}

}  // namespace

const Command kDatasetCommand{
    "dataset", "labelled target chips (PNG per class + labels.csv) at any pixel resolution",
    R"(usage: sonarloop dataset --out DIR [options]

Renders chips of single targets for training and testing target recognition, as in Pailhas,
Petillot & Capus (2010), Section 4: each chip is one target (balanced over the classes) on a
random seabed, seen by the strip sonar with square pixels of R (range bin = along-track
resolution = ping spacing) from a random altitude (2-10 m above the target's base) and ground
range (5-50 m), on a random track heading and side, at a random target heading.
  highlight chips  3 m along track x 3 m slant range, centred on the target
  shadow chips     3 m along track x 10 m slant range from 1 m before the target's centre,
                   the target at a fixed 25 m ground range (Section 4.2)
A chip is round(size / R) pixels a side (highlight: 60 x 60 at 5 cm, 10 x 10 at 30 cm).
Columns run in slant range from near to far, rows along track (starboard: last ping at the
top; port: first ping at the top), so every chip is the seabed seen from above, not mirrored,
turned so that the sonar looks to the right. Pixels are 8-bit: 0..255 for -60..0 dB re
full scale (the sonar's TVG-corrected level, sim/render/quantise.h), clipped, the same mapping
for every chip; speckle and noise are on.

Chip i depends only on (seed, i) and the options: the same command gives byte-identical files
whatever --threads, and --count only adds or removes chips at the end.

Writes:
  DIR/<class>/<index>.png    one folder per class (manta, rockan, ...), index zero-padded
  DIR/<class>/<index>_label.png
                             its label image, the same size: per pixel 0 seabed, 1 target
                             highlight, 2 target shadow (values, not grey levels), from the
                             render's physics (docs/rendering.md); chip readers skip these
  DIR/labels.csv             file,class,aspect_deg,mine_like,kind,seabed,altitude_m,range_m,
                             heading_deg,side,resolution_cm,seed,index,slant_range_m,
                             track_heading_deg,target_row,target_col,north_m,east_m,width,height,
                             label_file,highlight_pixels,shadow_pixels
                             (file relative to DIR; aspect_deg = target heading - look direction;
                             range_m = ground range; target_row/col = the target's centre in
                             pixels; north_m/east_m = the target's position; label_file = the
                             label image in the chip's folder, with its pixel counts)
  DIR/dataset.json           the options and the conventions above (after Ctrl-C also
                             "interrupted": true and "chips_written": N)
With several --resolution-cm, each resolution is a dataset of its own in DIR/res_<R>cm/ (with
its labels.csv) and DIR/labels.csv lists them all (file relative to DIR).
Under `mpirun -np N` (MPI builds: docs/sweep.md) every rank renders every N-th chip and rank 0
writes them all: the same files as one process.
`sonarloop train` and `classify` read a dataset folder directly. Ctrl-C stops cleanly: every PNG
on disk then has its labels.csv row, and every row its PNG.

Chips from surveys (--surveys SCENARIOS): instead of single targets, the chips the onboard
consumer cuts from lock-step surveys of the scenarios' seabeds (files or built-in names) with
their targets drawn afresh: every target the detector found, centred on the truth, and its false
alarms as a "clutter" class (pass 1 of `train --surveys`; mission/survey_chips.h). Writes
DIR/<class>/<index>.png and DIR/labels.csv (file,class,aspect_deg,mine_like,source); takes
--surveys-per-scenario N (default 2), --per-type N (default 8), --classes, --seed (default
100000), --min-separation M, --area-margin M, --max-clutter N (default 400), --no-clutter,
--threads.

options:
  --out DIR              output folder: new or empty (required)
  --resolution-cm R      pixel size in cm, 0.5..100 (repeatable; default 5)
  --count N              chips per class (default 100)
  --kind K               highlight (default) or shadow
  --classes LIST         comma list of target types, or 'all' (default
                         manta,rockan,cuboid,cylinder)
  --seabed LIST          comma list of seabed kinds: flat, ripples, clutter, rocky, or scenario
                         files NAME.yaml whose seed, water and seabed are used (default
                         flat,ripples,clutter); chip i lies on kind (i / classes) mod kinds
  --seed S               dataset seed (default 0)
  --threads N            worker threads, one chip each (default: all cores; under mpirun the
                         cores it binds each rank to)
  --sonar NAME|FILE      sonar preset or YAML file (default pailhas_strip); its bin size, pulse
                         and range are replaced per resolution
  --levels-db MIN,MAX    dB re full scale of pixels 0 and 255 (default -60,0)
  --renderer R           profile (default: heightfield profile renderer) or raytrace (Embree)

examples:
  sonarloop dataset --out out/chips --resolution-cm 5 --count 200
  sonarloop dataset --out out/study --resolution-cm 3 --resolution-cm 10 --resolution-cm 30
  sonarloop dataset --out out/shadows --kind shadow --classes all --seed 7
  mpirun -np 4 sonarloop dataset --out out/big --count 100000 --threads 2
  sonarloop dataset --surveys survey_clutter,survey_rocky --out out/survey_chips
)",
    run_dataset, 40};
SONARLOOP_REGISTER_COMMAND(kDatasetCommand);

}  // namespace sonarloop::tools
