// End-to-end: the `sonarloop dataset` command as a user runs it, its files read back by Python's
// csv module and by `sonarloop train`.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "drivers/image/png.h"
#include "tests/support/temp_dir.h"
#include "tests/tools/sonarloop_cli.h"

namespace {

namespace fs = std::filesystem;

using sonarloop::testing::file_tree;
using sonarloop::testing::kBinary;
using sonarloop::testing::run_quiet;
using sonarloop::testing::slurp;

// Checks a dataset root with Python's csv module: labels.csv parses; every row names an
// existing PNG in its class folder, of the stated size, with its label image; every chip PNG has
// exactly one row; the classes are the expected ones, balanced; aspect_deg in [0, 360); no
// temporary files.
// Arguments: root, expected rows (-1: any), width, height, classes (comma list).
constexpr const char* kCheckScript = R"py(
import collections, csv, os, struct, sys
root, n, w, h, classes = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5].split(',')
def png_size(path):
    with open(path, 'rb') as f:
        head = f.read(24)
    assert head[:8] == b'\x89PNG\r\n\x1a\n', path
    return struct.unpack('>II', head[16:24])
with open(os.path.join(root, 'labels.csv'), newline='') as f:
    rows = list(csv.DictReader(f))
need = ['file', 'class', 'aspect_deg', 'mine_like', 'kind', 'seabed', 'altitude_m', 'range_m',
        'heading_deg', 'side', 'resolution_cm', 'seed', 'index']
for k in need:
    assert k in rows[0] if rows else True, 'missing column ' + k
if n >= 0:
    assert len(rows) == n, (len(rows), n)
files = set()
for r in rows:
    assert r['file'] not in files, 'duplicate ' + r['file']
    files.add(r['file'])
    assert r['file'].split('/')[0] == r['class'], r['file']
    assert os.path.isfile(os.path.join(root, r['file'])), r['file']
    label = os.path.join(root, os.path.dirname(r['file']), r['label_file'])
    assert png_size(label) == (w, h), label
    assert png_size(os.path.join(root, r['file'])) == (w, h) == (int(r['width']), int(r['height']))
    assert 0.0 <= float(r['aspect_deg']) < 360.0
    assert 2.0 <= float(r['altitude_m']) <= 10.0
    assert r['side'] in ('port', 'starboard')
    assert r['mine_like'] in ('0', '1')
    assert r['class'] in classes, r['class']
on_disk = set()
for d, _, names in os.walk(root):
    for name in names:
        assert not name.endswith('.tmp'), name
        if name.endswith('.png') and not name.endswith('_label.png'):
            on_disk.add(os.path.relpath(os.path.join(d, name), root).replace(os.sep, '/'))
assert on_disk == files, (sorted(on_disk ^ files))[:5]
if n >= 0:
    counts = collections.Counter(r['class'] for r in rows)
    assert sorted(counts) == sorted(classes), counts
    assert len(set(counts.values())) == 1, counts
print('ok', len(rows))
)py";

int check_dataset(const sonarloop::testing::TempDir& dir, const fs::path& root, int rows, int width,
                  int height, const std::string& classes) {
  const std::string script = dir.file("check_dataset.py");
  std::ofstream(script) << kCheckScript;
  return sonarloop::testing::run_command(std::string(SONARLOOP_PYTHON) + " " + script + " " +
                                         root.string() + " " + std::to_string(rows) + " " +
                                         std::to_string(width) + " " + std::to_string(height) +
                                         " " + classes);
}

std::size_t line_count(const fs::path& path) {
  const std::string s = slurp(path);
  return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n'));
}

}  // namespace

TEST_CASE("dataset cli: a tiny set, byte-identical on 1 or 2 threads, read back by Python") {
  sonarloop::testing::TempDir dir("dataset-cli");
  const std::string common = " --count 3 --resolution-cm 20 --seed 11";
  REQUIRE(run_quiet("dataset --out " + dir.file("a") + common + " --threads 1") == 0);
  REQUIRE(run_quiet("dataset --out " + dir.file("b") + common + " --threads 2") == 0);
  const auto a = file_tree(dir.path() / "a");
  const auto b = file_tree(dir.path() / "b");
  REQUIRE(a.size() == 4 * 3 * 2 + 2);  // 12 chips, their label images, labels.csv, dataset.json
  CHECK(a == b);
  CHECK(a.count("manta/000000.png") == 1);
  CHECK(a.count("rockan/000001.png") == 1);
  CHECK(a.count("cylinder/000011.png") == 1);
  // 3 m x 3 m at 20 cm: 15 x 15 pixels
  const auto png = sonarloop::image::read_png_gray8((dir.path() / "a/manta/000004.png").string());
  CHECK(png.width == 15);
  CHECK(png.height == 15);
  CHECK(check_dataset(dir, dir.path() / "a", 12, 15, 15, "manta,rockan,cuboid,cylinder") == 0);
  // another seed: other chips; the same seed with more chips: the same first ones
  REQUIRE(run_quiet("dataset --out " + dir.file("c") + " --count 3 --resolution-cm 20 --seed 12") ==
          0);
  CHECK(slurp(dir.path() / "c/manta/000004.png") != a.at("manta/000004.png"));
  REQUIRE(run_quiet("dataset --out " + dir.file("d") + " --count 4 --resolution-cm 20 --seed 11") ==
          0);
  CHECK(slurp(dir.path() / "d/manta/000004.png") == a.at("manta/000004.png"));
  CHECK(slurp(dir.path() / "d/cuboid/000010.png") == a.at("cuboid/000010.png"));
  // the classifier's trainer reads the folder as it is
  CHECK(run_quiet("train " + dir.file("d") + " --out " + dir.file("model.slpca")) == 0);
}

TEST_CASE("dataset cli: several resolutions, shadow chips, all classes") {
  sonarloop::testing::TempDir dir("dataset-cli-res");
  REQUIRE(run_quiet("dataset --out " + dir.file("s") +
                    " --count 2 --resolution-cm 30 --resolution-cm 50 --kind shadow --classes all "
                    "--seabed flat,clutter --threads 2") == 0);
  const std::string all =
      "manta,rockan,cylinder,standing_cylinder,cuboid,large_cuboid,hemisphere,small_hemisphere,"
      "box";
  // each resolution is a dataset of its own: 3 m x 10 m at 30 cm is 10 x 33, at 50 cm 6 x 20
  CHECK(check_dataset(dir, dir.path() / "s/res_30cm", 18, 33, 10, all) == 0);
  CHECK(check_dataset(dir, dir.path() / "s/res_50cm", 18, 20, 6, all) == 0);
  // the root's labels.csv lists both, paths relative to the root; chips 0-8 lie on the first
  // seabed, 9-17 on the second
  const std::string script =
      "import csv,sys; r=list(csv.DictReader(open(sys.argv[1]+'/labels.csv'))); "
      "import os; assert len(r)==36 and all(os.path.isfile(sys.argv[1]+'/'+x['file']) for x in r); "
      "assert {x['resolution_cm'] for x in r}=={'30','50'}; "
      "assert {x['kind'] for x in r}=={'shadow'}; assert {x['range_m'] for x in r}=={'25.0000'}; "
      "assert {x['seabed'] for x in r}=={'flat','clutter'}";
  CHECK(sonarloop::testing::run_command(std::string(SONARLOOP_PYTHON) + " -c \"" + script + "\" " +
                                        dir.file("s")) == 0);
}

TEST_CASE("dataset cli: Ctrl-C leaves a consistent folder") {
  sonarloop::testing::TempDir dir("dataset-cli-int");
  const fs::path out = dir.path() / "x";
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    execl(kBinary.c_str(), kBinary.c_str(), "dataset", "--out", out.c_str(), "--count", "2000",
          "--resolution-cm", "30", "--threads", "2", static_cast<char*>(nullptr));
    _exit(127);
  }
  // interrupt once a few chips are written (or let it end, on a very fast machine)
  int status = 0;
  bool exited = false;
  for (int k = 0; k < 12000 && !exited; ++k) {
    if (waitpid(pid, &status, WNOHANG) == pid) {
      exited = true;
      break;
    }
    if (fs::exists(out / "labels.csv") && line_count(out / "labels.csv") >= 6) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (!exited) {
    kill(pid, SIGINT);
    REQUIRE(waitpid(pid, &status, 0) == pid);
  }
  REQUIRE(WIFEXITED(status));
  const int code = WEXITSTATUS(status);
  CHECK((code == 130 || (exited && code == 0)));
  CHECK(line_count(out / "labels.csv") >= 6);
  // every PNG has its row and every row its PNG, no partial files
  CHECK(check_dataset(dir, out, -1, 10, 10, "manta,rockan,cuboid,cylinder") == 0);
  // dataset.json says how many were written (labels.csv: a header and a row per chip), not only
  // the 2000 per class asked for
  const std::string json = slurp((out / "dataset.json").string());
  if (code == 130) {
    CHECK_THAT(json, Catch::Contains("\"interrupted\": true") &&
                         Catch::Contains("\"chips_written\": " +
                                         std::to_string(line_count(out / "labels.csv") - 1)));
  }
  CHECK(run_quiet("train " + out.string() + " --out " + dir.file("m.slpca")) == 0);
}

TEST_CASE("dataset cli: bad options are usage errors; an existing dataset is never overwritten") {
  sonarloop::testing::TempDir dir("dataset-cli-bad");
  const std::string out = " --out " + dir.file("x");
  CHECK(run_quiet("dataset") == 2);
  CHECK(run_quiet("dataset" + out + " --resolution-cm 0") == 2);
  CHECK(run_quiet("dataset" + out + " --resolution-cm 5 --resolution-cm 5") == 2);
  CHECK(run_quiet("dataset" + out + " --kind sideways") == 2);
  CHECK(run_quiet("dataset" + out + " --classes manta,submarine") == 2);
  CHECK(run_quiet("dataset" + out + " --classes manta,manta") == 2);
  CHECK(run_quiet("dataset" + out + " --seabed flat,moon") == 2);
  CHECK(run_quiet("dataset" + out + " --count 0") == 2);
  CHECK(run_quiet("dataset" + out + " --levels-db 0,-60") == 2);
  CHECK(run_quiet("dataset" + out + " --seabed " + dir.file("missing.yaml")) == 1);
  CHECK(run_quiet("dataset" + out + " --sonar nosuchsonar") == 1);
  CHECK_FALSE(fs::exists(dir.path() / "x" / "labels.csv"));
  REQUIRE(run_quiet("dataset" + out + " --count 1 --resolution-cm 50") == 0);
  CHECK(run_quiet("dataset" + out + " --count 1 --resolution-cm 50") == 1);
}
