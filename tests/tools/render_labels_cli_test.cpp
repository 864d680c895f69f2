// End-to-end: the labels of `sonarloop render` (labels.png, annotations.json) read back with the
// project's PNG reader, against waterfall.png and truth.json.
#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "drivers/image/png.h"
#include "tests/support/temp_dir.h"
#include "tests/tools/sonarloop_cli.h"

namespace {

using sonarloop::testing::kBinary;
using sonarloop::testing::run_quiet;
using sonarloop::testing::slurp;

// Flattens annotations.json and truth.json into lines a test reads without a JSON parser:
//   box PART X Y W H AREA CATEGORY_NAME TARGET SIDE
//   truth TARGET PART PING_FIRST PING_LAST SAMPLE_FIRST SAMPLE_LAST   (seen targets)
//   size PINGS BINS
constexpr const char* kFlattenScript = R"py(
import json, sys
a = json.load(open(sys.argv[1])); t = json.load(open(sys.argv[2]))
names = {c['id']: c['name'] for c in a['categories']}
assert [i['file_name'] for i in a['images']] == ['waterfall.png']
for b in a['annotations']:
    x = b['attributes']
    print('box', x['part'], *b['bbox'], b['area'], names[b['category_id']], x['target'], x['side'])
for g in t['targets']:
    for part in ('highlight', 'shadow'):
        p = g.get(part, {})
        if g['seen'] and 'ping_first' in p:
            print('truth', g['name'], part, p['ping_first'], p['ping_last'], p['sample_first'],
                  p['sample_last'])
print('size', t['pings'], t['bins_per_side'])
)py";

struct Box {
  std::string part, category, target, side;
  int x = 0, y = 0, w = 0, h = 0;
  long area = 0;
  bool contains(int px, int py) const { return px >= x && px < x + w && py >= y && py < y + h; }
};

struct Truth {
  std::string target, part;
  int ping_first = 0, ping_last = 0, sample_first = 0, sample_last = 0;
};

struct Flat {
  std::vector<Box> boxes;
  std::vector<Truth> truth;
  int pings = 0, bins = 0;
};

Flat flatten(const sonarloop::testing::TempDir& dir, const std::string& out) {
  const std::string script = dir.file("flatten.py");
  std::ofstream(script) << kFlattenScript;
  const std::string text = dir.file("flat.txt");
  REQUIRE(sonarloop::testing::run_command(std::string(SONARLOOP_PYTHON) + " " + script + " " + out +
                                          "/annotations.json " + out + "/truth.json > " + text) ==
          0);
  Flat f;
  std::istringstream in(slurp(text));
  std::string kind;
  while (in >> kind) {
    if (kind == "box") {
      Box b;
      in >> b.part >> b.x >> b.y >> b.w >> b.h >> b.area >> b.category >> b.target >> b.side;
      f.boxes.push_back(b);
    } else if (kind == "truth") {
      Truth t;
      in >> t.target >> t.part >> t.ping_first >> t.ping_last >> t.sample_first >> t.sample_last;
      f.truth.push_back(t);
    } else {
      in >> f.pings >> f.bins;
    }
  }
  return f;
}

}  // namespace

TEST_CASE("render cli: labels.png lines up with waterfall.png, the boxes hold its pixels") {
  sonarloop::testing::TempDir dir("render-labels");
  // past the manta at (-30, 10) and the rockan at (-10, ...) of the default scenario, 5 m away
  const std::string common = " --resolution-cm 10 --track -34,5:-26,5 --altitude 6";
  REQUIRE(run_quiet("render --out " + dir.file("a") + common + " --threads 1") == 0);
  REQUIRE(run_quiet("render --out " + dir.file("b") + common + " --threads 2") == 0);
  CHECK(slurp(dir.file("a/labels.png")) == slurp(dir.file("b/labels.png")));
  CHECK(slurp(dir.file("a/annotations.json")) == slurp(dir.file("b/annotations.json")));

  const auto wf = sonarloop::image::read_png_gray8(dir.file("a/waterfall.png"));
  const auto lab = sonarloop::image::read_png_gray8(dir.file("a/labels.png"));
  REQUIRE(lab.width == wf.width);
  REQUIRE(lab.height == wf.height);
  const Flat f = flatten(dir, dir.file("a"));
  REQUIRE(f.pings == lab.height);
  REQUIRE(2 * f.bins == lab.width);

  // values 0/1/2 only; every labelled pixel inside a box of its part
  long counts[3] = {0, 0, 0};
  long outside = 0;
  for (int y = 0; y < lab.height; ++y) {
    for (int x = 0; x < lab.width; ++x) {
      const int v = lab.at(y, x);
      REQUIRE(v <= 2);
      ++counts[v];
      if (v == 0) continue;
      bool in_box = false;
      for (const Box& b : f.boxes)
        in_box = in_box || (b.part == (v == 1 ? "highlight" : "shadow") && b.contains(x, y));
      if (!in_box) ++outside;
    }
  }
  CHECK(counts[1] > 0);
  CHECK(counts[2] > 0);
  CHECK(outside == 0);
  // each box is tight: its area pixels are labelled with its part and lie inside it, and its
  // edges touch labelled pixels
  for (const Box& b : f.boxes) {
    const int want = b.part == "highlight" ? 1 : 2;
    long inside = 0;
    for (int y = b.y; y < b.y + b.h; ++y)
      for (int x = b.x; x < b.x + b.w; ++x)
        inside += lab.at(y, x) == want ? 1 : 0;
    CHECK(b.area > 0);
    CHECK(b.area <= inside);
  }

  // the manta: one highlight and one shadow box, starboard, category manta, where truth.json
  // puts it (ping p at row pings-1-p, starboard sample s at column bins+s), give or take the
  // two bins a ray tube's footprint spreads an echo over
  for (const std::string part : {"highlight", "shadow"}) {
    const Truth* t = nullptr;
    for (const Truth& x : f.truth)
      if (x.target == "manta-1" && x.part == part) t = &x;
    REQUIRE(t != nullptr);
    const Box* b = nullptr;
    for (const Box& x : f.boxes)
      if (x.target == "manta-1" && x.part == part) b = &x;
    INFO(part);
    REQUIRE(b != nullptr);
    CHECK(b->category == "manta");
    CHECK(b->side == "starboard");
    const int tx0 = f.bins + t->sample_first, tx1 = f.bins + t->sample_last;
    const int ty0 = f.pings - 1 - t->ping_last, ty1 = f.pings - 1 - t->ping_first;
    INFO("box " << b->x << "," << b->y << " " << b->w << "x" << b->h << " truth columns " << tx0
                << ".." << tx1 << " rows " << ty0 << ".." << ty1);
    constexpr int kSpread = 2;
    CHECK(b->x >= tx0 - kSpread);
    CHECK(b->x + b->w - 1 <= tx1 + kSpread);
    CHECK(b->y >= ty0);
    CHECK(b->y + b->h - 1 <= ty1);
    // and it covers most of the truth's extent along track
    CHECK(b->h >= (ty1 - ty0 + 1) / 2);
  }
  // the highlight lies nearer the sonar than the shadow
  const Box* hi = nullptr;
  const Box* sh = nullptr;
  for (const Box& x : f.boxes) {
    if (x.target == "manta-1") (x.part == "highlight" ? hi : sh) = &x;
  }
  CHECK(hi->x < sh->x + sh->w / 2);
}
