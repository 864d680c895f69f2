// End-to-end: the label image next to every chip of `sonarloop dataset` (NAME_label.png) and its
// labels.csv columns, read back with the project's PNG reader: the labels mark the target where
// labels.csv puts it, bright where they say highlight and dark where they say shadow; the chip
// readers skip them.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "drivers/image/png.h"
#include "tests/support/temp_dir.h"
#include "tests/tools/sonarloop_cli.h"

namespace {

namespace fs = std::filesystem;

using sonarloop::testing::kBinary;
using sonarloop::testing::run_quiet;
using sonarloop::testing::slurp;

// labels.csv as rows of column name -> value (the dataset writes no quoted fields).
std::vector<std::map<std::string, std::string>> read_labels_csv(const fs::path& path) {
  std::istringstream in(slurp(path.string()));
  std::string line;
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ','))
      f.push_back(cell);
    if (header.empty()) {
      header = f;
      continue;
    }
    REQUIRE(f.size() == header.size());
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < f.size(); ++i)
      row[header[i]] = f[i];
    rows.push_back(row);
  }
  return rows;
}

struct ChipStats {
  long count[3] = {0, 0, 0};
  double mean_grey[3] = {0, 0, 0};  // chip pixel means per label
  double far_highlight_px = 0.0;    // largest distance of a highlight pixel from the target
  double shadow_col = 0.0;          // mean column of the shadow pixels
};

ChipStats chip_stats(const fs::path& chip, const fs::path& label, double target_row,
                     double target_col) {
  const auto c = sonarloop::image::read_png_gray8(chip.string());
  const auto l = sonarloop::image::read_png_gray8(label.string());
  REQUIRE(l.width == c.width);
  REQUIRE(l.height == c.height);
  ChipStats s;
  for (int y = 0; y < l.height; ++y) {
    for (int x = 0; x < l.width; ++x) {
      const int v = l.at(y, x);
      REQUIRE(v <= 2);
      ++s.count[v];
      s.mean_grey[v] += c.at(y, x);
      if (v == 1) {
        s.far_highlight_px =
            std::max(s.far_highlight_px, std::hypot(y - target_row, x - target_col));
      }
      if (v == 2) s.shadow_col += x;
    }
  }
  for (int v = 0; v < 3; ++v)
    if (s.count[v] > 0) s.mean_grey[v] /= static_cast<double>(s.count[v]);
  if (s.count[2] > 0) s.shadow_col /= static_cast<double>(s.count[2]);
  return s;
}

}  // namespace

TEST_CASE("dataset cli: every chip has a label image with the target where labels.csv puts it") {
  sonarloop::testing::TempDir dir("dataset-labels");
  const double res_m = 0.1;
  REQUIRE(run_quiet("dataset --out " + dir.file("h") + " --count 3 --resolution-cm 10 --seed 4") ==
          0);
  const auto rows = read_labels_csv(dir.path() / "h/labels.csv");
  REQUIRE(rows.size() == 12);
  int bright = 0;
  for (const auto& r : rows) {
    const fs::path chip = dir.path() / "h" / r.at("file");
    const fs::path label = chip.parent_path() / r.at("label_file");
    INFO(r.at("file"));
    CHECK(r.at("label_file") == chip.stem().string() + "_label.png");
    const ChipStats s =
        chip_stats(chip, label, std::stod(r.at("target_row")), std::stod(r.at("target_col")));
    CHECK(std::to_string(s.count[1]) == r.at("highlight_pixels"));
    CHECK(std::to_string(s.count[2]) == r.at("shadow_pixels"));
    // a highlight, within a target's half size (at most 0.7 m) and a pixel of its centre
    CHECK(s.count[1] > 0);
    CHECK(s.far_highlight_px <= 0.8 / res_m + 1.5);
    if (s.count[1] > 0 && s.mean_grey[1] > s.mean_grey[0]) ++bright;
  }
  // the highlight is brighter than the seabed around it (speckle aside: nearly always)
  CHECK(bright >= 10);
  // the same command writes the same label images
  REQUIRE(run_quiet("dataset --out " + dir.file("h2") + " --count 3 --resolution-cm 10 --seed 4") ==
          0);
  CHECK(slurp(dir.file("h/manta/000004_label.png")) ==
        slurp(dir.file("h2/manta/000004_label.png")));
  // the trainer reads the chips and skips the label images
  const std::string out = dir.file("train.txt");
  REQUIRE(sonarloop::testing::run_command(kBinary + " train " + dir.file("h") + " --out " +
                                          dir.file("m.slpca") + " > " + out + " 2>&1") == 0);
  INFO(slurp(out));
  CHECK(slurp(out).find("trained on 12 chips") != std::string::npos);
}

TEST_CASE("dataset cli: shadow chips label a dark shadow beyond the target") {
  sonarloop::testing::TempDir dir("dataset-labels-shadow");
  REQUIRE(run_quiet("dataset --out " + dir.file("s") +
                    " --kind shadow --count 2 --resolution-cm 10 --seed 9 --seabed flat") == 0);
  const auto rows = read_labels_csv(dir.path() / "s/labels.csv");
  REQUIRE(rows.size() == 8);
  for (const auto& r : rows) {
    const fs::path chip = dir.path() / "s" / r.at("file");
    const double target_col = std::stod(r.at("target_col"));
    const ChipStats s = chip_stats(chip, chip.parent_path() / r.at("label_file"),
                                   std::stod(r.at("target_row")), target_col);
    INFO(r.at("file") << " shadow " << s.count[2] << " px, mean grey " << s.mean_grey[2]
                      << " vs seabed " << s.mean_grey[0] << ", mean column " << s.shadow_col
                      << " target column " << target_col);
    REQUIRE(s.count[2] > 0);
    CHECK(s.shadow_col > target_col);
    CHECK(s.mean_grey[2] < 0.5 * s.mean_grey[0]);
  }
}
