// End-to-end: `sonarloop train` and `sonarloop classify` on a small generated folder of PNG
// chips, as a user runs them (real binary, real files; the JSON is read back by Python).
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "atr/model_file.h"
#include "drivers/image/png.h"
#include "tests/atr/synthetic_chips.h"
#include "tests/support/temp_dir.h"

namespace fs = std::filesystem;
using namespace sonarloop;

namespace {

const std::string kBinary = std::string(SONARLOOP_BINARY_DIR) + "/tools/sonarloop";

using sonarloop::testing::slurp;

// Runs the binary; stdout and stderr go to files in `dir`.
int run(const testing::TempDir& dir, const std::string& args) {
  return testing::run_command(kBinary + " " + args + " > " + dir.file("stdout.txt") + " 2> " +
                              dir.file("stderr.txt"));
}

// A folder of 16 x 16 PNG chips: 3 classes with a known answer, `per_class` chips each, and a
// labels.csv with aspect angles.
void write_chip_folder(const fs::path& root, int per_class, std::uint64_t seed) {
  const auto lc = testing::make_linear_classes(3, 16, 16, 3, 99);
  const std::vector<std::string> names = {"cylinder", "manta", "rock"};
  Rng rng(seed, RngStream::kTraining, 6);
  std::ofstream csv;
  fs::create_directories(root);
  csv.open(root / "labels.csv");
  csv << "file,class,aspect_deg,resolution_cm\n";
  for (int c = 0; c < 3; ++c) {
    const fs::path dir = root / names[static_cast<std::size_t>(c)];
    fs::create_directories(dir);
    for (int i = 0; i < per_class; ++i) {
      const atr::Chip chip = testing::sample_linear(lc, c, rng, 0.02);
      char name[32];
      std::snprintf(name, sizeof name, "%03d.png", i);
      image::write_png_gray8((dir / name).string(), 16, 16, testing::to_gray8(chip));
      csv << names[static_cast<std::size_t>(c)] << "/" << name << ","
          << names[static_cast<std::size_t>(c)] << "," << (i * 37) % 360 << ",5\n";
    }
  }
}

}  // namespace

TEST_CASE("train/classify cli: train on PNG chips, classify a labelled test folder") {
  testing::TempDir dir("train-classify-cli");
  const fs::path train = dir.path() / "train";
  const fs::path test = dir.path() / "test";
  write_chip_folder(train, 12, 1);
  write_chip_folder(test, 10, 2);
  // a degenerate chip among the test chips: rejected with a reason, not scored
  image::write_png_gray8((test / "rock" / "flat.png").string(), 16, 16,
                         std::vector<std::uint8_t>(256, 77));
  const std::string model = dir.file("atr.slpca");

  REQUIRE(run(dir, "train " + train.string() + " --out " + model) == 0);
  const std::string train_out = slurp(dir.file("stdout.txt"));
  CHECK_THAT(train_out, Catch::Contains("36 chips") && Catch::Contains("manta") &&
                            Catch::Contains("mine-like") && Catch::Contains("rank 11"));
  const atr::Model m = atr::load_model(model);
  REQUIRE(m.classes.size() == 3);
  CHECK(m.classes[0].name == "cylinder");
  CHECK(m.classes[0].mine_like);
  CHECK(m.classes[2].name == "rock");
  CHECK_FALSE(m.classes[2].mine_like);
  CHECK(m.p == 20);
  CHECK(m.chip_width == 16);

  const std::string csv = dir.file("scores.csv");
  const std::string json = dir.file("scores.json");
  REQUIRE(run(dir, "classify " + model + " " + test.string() + " --csv " + csv + " --json " +
                       json) == 0);
  const std::string out = slurp(dir.file("stdout.txt"));
  CHECK_THAT(out, Catch::Contains("classified 30 chips (1 rejected)") &&
                      Catch::Contains("accuracy: 100.00 % (30 of 30)") &&
                      Catch::Contains("Wilson") && Catch::Contains("confusion matrix") &&
                      Catch::Contains("mine / non-mine: 100.00 %") &&
                      Catch::Contains("accuracy by true aspect") && Catch::Contains("us per chip"));
  CHECK_THAT(slurp(dir.file("stderr.txt")),
             Catch::Contains("rock/flat.png") && Catch::Contains("constant chip"));

  // the JSON, read by Python: accuracy 1, a diagonal confusion matrix, the Wilson interval of
  // 30 of 30 (lower bound 30 / (30 + z^2) = 0.8865), one rejection
  const std::string py =
      std::string(SONARLOOP_PYTHON) +
      " -c \"import json,sys; j=json.load(open(sys.argv[1])); s=j['summary']; "
      "c=s['confusion']['counts']; "
      "ok = s['accuracy']==1 and s['classified']==30 and s['rejected']==1 and "
      "abs(s['accuracy_ci95'][0]-0.88648)<1e-4 and s['accuracy_ci95'][1]==1 and "
      "all(c[i][k]==(10 if i==k else 0) for i in range(3) for k in range(3)) and "
      "s['mine_non_mine']['accuracy']==1 and len(j['chips'])==31 and "
      "[x for x in j['chips'] if x['status']!='ok'][0]['status']=='constant' and "
      "all(x['predicted']==x['truth'] for x in j['chips'] if x['status']=='ok'); "
      "sys.exit(0 if ok else 1)\" " +
      json;
  CHECK(testing::run_command(py) == 0);

  // the CSV: a header and one row per chip, the prediction equal to the truth
  std::istringstream rows(slurp(csv));
  std::string line;
  std::getline(rows, line);
  CHECK(line.rfind("file,truth,status,predicted,distance,", 0) == 0);
  CHECK_THAT(line, Catch::Contains("distance_cylinder,distance_manta,distance_rock,reason"));
  int n = 0, rejected = 0;
  while (std::getline(rows, line)) {
    ++n;
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string x;
    while (std::getline(ss, x, ','))
      f.push_back(x);
    REQUIRE(f.size() >= 4);
    if (f[2] == "ok") {
      CHECK(f[1] == f[3]);
    } else {
      ++rejected;
      CHECK(f[2] == "constant");
    }
  }
  CHECK(n == 31);
  CHECK(rejected == 1);

  // one chip on its own
  REQUIRE(run(dir, "classify " + model + " " + (test / "manta" / "003.png").string()) == 0);
  CHECK_THAT(slurp(dir.file("stdout.txt")),
             Catch::Contains(" manta ") && Catch::Contains("classified 1 chip (0 rejected)"));
  // ... a degenerate one: nothing classified, exit 1 with the reason
  CHECK(run(dir, "classify " + model + " " + (test / "rock" / "flat.png").string()) == 1);
  CHECK_THAT(slurp(dir.file("stderr.txt")), Catch::Contains("constant chip"));

  // an unlabelled folder: predictions, no scores
  fs::create_directories(dir.path() / "flat");
  fs::copy_file(test / "rock" / "001.png", dir.path() / "flat" / "a.png");
  fs::copy_file(test / "cylinder" / "001.png", dir.path() / "flat" / "b.png");
  REQUIRE(run(dir, "classify " + model + " " + (dir.path() / "flat").string()) == 0);
  const std::string flat = slurp(dir.file("stdout.txt"));
  CHECK_THAT(flat, Catch::Contains("a.png") && Catch::Contains(" rock ") &&
                       Catch::Contains(" cylinder ") && !Catch::Contains("accuracy"));

  // multi-aspect training from labels.csv, and group subspaces
  REQUIRE(run(dir, "train " + train.string() + " --out " + dir.file("m2.slpca") +
                       " --aspect-sectors 2 --p 5 --group-subspaces") == 0);
  const atr::Model m2 = atr::load_model(dir.file("m2.slpca"));
  CHECK(m2.aspect_sectors == 2);
  CHECK(m2.classes[0].subspaces.size() == 2);
  CHECK(m2.groups.size() == 2);
  REQUIRE(run(dir, "classify " + model + " " + test.string() + " --quiet") == 0);
  CHECK_THAT(slurp(dir.file("stdout.txt")), !Catch::Contains("001.png"));

  // a pre-processing model: stored in the file, applied by classify to the full-size chips
  REQUIRE(run(dir, "train " + train.string() + " --out " + dir.file("crop.slpca") +
                       " --crop 0.5 --multilook 3 --levels above_seabed --reject-quantile 0.9") ==
          0);
  CHECK_THAT(slurp(dir.file("stdout.txt")),
             Catch::Contains("crop 0.5 + multilook 3 + above_seabed (features 8 x 8)") &&
                 Catch::Contains("unknown beyond distance"));
  const atr::Model m3 = atr::load_model(dir.file("crop.slpca"));
  CHECK(m3.chip_width == 16);
  CHECK(m3.feature_width() == 8);
  CHECK(m3.preprocess.multilook_px == 3);
  CHECK(m3.preprocess.levels == atr::ChipLevels::kAboveSeabed);
  CHECK(std::isfinite(m3.classes[0].reject_distance));
  REQUIRE(run(dir, "classify " + dir.file("crop.slpca") + " " + test.string() + " --json " +
                       dir.file("crop.json")) == 0);
  CHECK_THAT(slurp(dir.file("stdout.txt")), Catch::Contains("classified 30 chips (1 rejected)"));
  CHECK_THAT(slurp(dir.file("crop.json")), Catch::Contains("\"open_set_score\":"));
  // the model without open-set rejection reports no such field
  CHECK_THAT(slurp(json), !Catch::Contains("open_set_score"));
}

TEST_CASE("train/classify cli: usage and input errors") {
  testing::TempDir dir("train-classify-cli-errors");
  const fs::path train = dir.path() / "train";
  write_chip_folder(train, 4, 3);
  CHECK(run(dir, "train " + train.string()) == 2);  // no --out
  CHECK_THAT(slurp(dir.file("stderr.txt")), Catch::Contains("--out"));
  CHECK(run(dir, "train " + train.string() + " --out " + dir.file("m") + " --p 0") == 2);
  CHECK(run(dir, "train " + train.string() + " --out " + dir.file("m") + " --multilook 4") == 2);
  CHECK_THAT(slurp(dir.file("stderr.txt")), Catch::Contains("odd"));
  CHECK(run(dir, "train " + train.string() + " --out " + dir.file("m") + " --levels bright") == 2);
  CHECK_THAT(slurp(dir.file("stderr.txt")), Catch::Contains("above_seabed"));
  CHECK(run(dir, "train " + train.string() + " --out " + dir.file("m") + " --crop 1.5") == 2);
  CHECK(run(dir, "train --out " + dir.file("m")) == 2);
  CHECK(run(dir, "classify " + dir.file("m")) == 2);
  CHECK(run(dir, "train " + dir.file("missing") + " --out " + dir.file("m")) == 1);
  CHECK_THAT(slurp(dir.file("stderr.txt")), Catch::Contains("not a folder"));

  // mixed sizes: the odd chip is named
  image::write_png_gray8((train / "rock" / "big.png").string(), 17, 16,
                         std::vector<std::uint8_t>(17 * 16, 5));
  CHECK(run(dir, "train " + train.string() + " --out " + dir.file("m")) == 1);
  CHECK_THAT(slurp(dir.file("stderr.txt")),
             Catch::Contains("rock/big.png") && Catch::Contains("same size"));
  fs::remove(train / "rock" / "big.png");

  // aspect sectors without aspect angles for every chip
  fs::remove(train / "labels.csv");
  CHECK(run(dir, "train " + train.string() + " --out " + dir.file("m") + " --aspect-sectors 4") ==
        1);
  CHECK_THAT(slurp(dir.file("stderr.txt")),
             Catch::Contains("aspect angle for every chip") && Catch::Contains("no labels.csv"));

  // a file that is not a model
  std::ofstream(dir.file("bad.slpca")) << "hello";
  CHECK(run(dir, "classify " + dir.file("bad.slpca") + " " + train.string()) == 1);
  CHECK_THAT(slurp(dir.file("stderr.txt")), Catch::Contains("bad magic"));
}
