// The model file: save -> load gives the same model and the same scores, bit for bit; the byte
// layout is as documented; bad magic, versions, truncation, trailing bytes, corruption and
// inconsistent contents are clear errors.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "atr/contact_gate.h"
#include "atr/model_file.h"
#include "tests/atr/synthetic_chips.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop;
using namespace sonarloop::atr;

namespace {

std::vector<LabelledChip> chips(int per_class, std::uint64_t seed, bool aspects) {
  const auto lc = testing::make_linear_classes(3, 8, 6, 3, 77);
  const std::vector<std::string> names = {"manta", "rock", "cuboid"};
  Rng rng(seed, RngStream::kTraining, 4);
  std::vector<LabelledChip> out;
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < per_class; ++i) {
      LabelledChip l;
      l.chip = testing::sample_linear(lc, c, rng, 0.2, 3.0, 100.0);
      l.label = names[static_cast<std::size_t>(c)];
      if (aspects) l.aspect_deg = rng.uniform(0.0, 360.0);
      out.push_back(std::move(l));
    }
  }
  return out;
}

Model trained(bool multi) {
  TrainOptions opt;
  opt.p = 5;
  opt.class_metadata["cuboid"] = {true, 0.4};
  opt.class_metadata["manta"] = {true, 0.47};  // rock: not mine-like, height unknown
  if (multi) {
    opt.aspect_sectors = 3;
    opt.group_subspaces = true;
  }
  return train_model(chips(15, 1, multi), opt);
}

void expect_same(const Model& a, const Model& b) {
  CHECK(a.chip_width == b.chip_width);
  CHECK(a.chip_height == b.chip_height);
  CHECK(a.p == b.p);
  CHECK(a.aspect_sectors == b.aspect_sectors);
  REQUIRE(a.classes.size() == b.classes.size());
  REQUIRE(a.groups.size() == b.groups.size());
  auto same_class = [](const ClassModel& x, const ClassModel& y) {
    CHECK(x.name == y.name);
    CHECK(x.mine_like == y.mine_like);
    REQUIRE(x.subspaces.size() == y.subspaces.size());
    for (std::size_t s = 0; s < x.subspaces.size(); ++s) {
      const Subspace& u = x.subspaces[s];
      const Subspace& v = y.subspaces[s];
      CHECK(u.aspect_min_deg == v.aspect_min_deg);
      CHECK(u.aspect_max_deg == v.aspect_max_deg);
      CHECK(u.train_count == v.train_count);
      CHECK(u.mean == v.mean);
      CHECK(u.basis == v.basis);
      CHECK(u.eigenvalues == v.eigenvalues);
    }
  };
  for (std::size_t c = 0; c < a.classes.size(); ++c)
    same_class(a.classes[c], b.classes[c]);
  for (std::size_t g = 0; g < a.groups.size(); ++g)
    same_class(a.groups[g], b.groups[g]);
}

std::uint32_t le32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return b[at] | b[at + 1] << 8 | b[at + 2] << 16 | static_cast<std::uint32_t>(b[at + 3]) << 24;
}

void put_le32(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i)
    b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

// Rewrites the CRC trailer after an edit, so that the parser sees the edited content.
void fix_crc(std::vector<std::uint8_t>& b) {
  put_le32(b, b.size() - 4, crc32(std::span(b).first(b.size() - 4)));
}

// The bytes an older version (1 to 3) would have written for a model without groups, clutter
// classes or gates: version 3 has no gate count; version 2 no class height either (and a 0
// flags byte); version 1 neither the pre-processing record nor the reject and typical distances.
std::vector<std::uint8_t> downgrade(const Model& m, int version) {
  REQUIRE_FALSE(m.detector_rules);
  REQUIRE(m.views.empty());
  const auto v6 = encode_model(m);
  // version 5: without the view count (0) before the CRC
  std::vector<std::uint8_t> v5(v6.begin(), v6.end() - 8);
  v5[6] = 5;
  v5.insert(v5.end(), 4, 0);
  fix_crc(v5);
  if (version == 5) return v5;
  // version 4: without the detector rules record (4 bytes for none) before the CRC
  std::vector<std::uint8_t> v4(v5.begin(), v5.end() - 8);
  v4[6] = 4;
  v4.insert(v4.end(), 4, 0);
  fix_crc(v4);
  if (version == 4) return v4;
  const auto& v3 = v4;
  if (version == 3) {
    std::vector<std::uint8_t> out(v3.begin(), v3.end() - 8);  // without the gate count and CRC
    out[6] = 3;
    out.insert(out.end(), 4, 0);
    fix_crc(out);
    return out;
  }
  std::vector<std::uint8_t> out(v3.begin(), v3.begin() + (version >= 2 ? 60 : 36));
  out[6] = static_cast<std::uint8_t>(version);
  std::size_t at = 60;
  const auto copy = [&](std::size_t n) {
    out.insert(out.end(), v3.begin() + static_cast<long>(at),
               v3.begin() + static_cast<long>(at + n));
    at += n;
  };
  for (const ClassModel& c : m.classes) {
    copy(2 + c.name.size() + 1);  // name and mine_like
    out.push_back(0);             // the reserved byte
    ++at;
    copy(4);  // subspace count
    if (version >= 2)
      copy(8);  // reject and typical distances
    else
      at += 8;
    at += 8;  // no height before version 3
    std::size_t body = 0;
    for (const auto& sub : c.subspaces)
      body += 16 + 8 + 8 * sub.rank() + 4 * m.feature_count() * (1 + sub.rank());
    copy(body);
  }
  REQUIRE(at + 8 == v3.size());  // the gate count (0) and the CRC remain
  out.insert(out.end(), 4, 0);
  fix_crc(out);
  return out;
}

}  // namespace

TEST_CASE("model file: save -> load gives the same model and identical scores") {
  testing::TempDir dir("atr-model-file");
  for (const bool multi : {false, true}) {
    CAPTURE(multi);
    const Model m = trained(multi);
    const std::string path = dir.file(multi ? "multi.slpca" : "single.slpca");
    save_model(m, path);
    const Model back = load_model(path);
    expect_same(m, back);
    // re-encoding the loaded model gives the same bytes
    CHECK(encode_model(back) == encode_model(m));
    // the same answers, bit for bit
    Classifier a(m), b(back);
    for (const auto& t : chips(10, 2, multi)) {
      REQUIRE(a.classify(t.chip.view()).ok());
      REQUIRE(b.classify(t.chip.view()).ok());
      CHECK(a.result().class_index == b.result().class_index);
      CHECK(a.result().class_distance == b.result().class_distance);
      CHECK(a.result().class_subspace == b.result().class_subspace);
      CHECK(a.result().mine_distance == b.result().mine_distance);
      CHECK(a.result().non_mine_distance == b.result().non_mine_distance);
      CHECK(a.result().mine_like == b.result().mine_like);
    }
  }
}

TEST_CASE("model file: the byte layout is the documented one") {
  const Model m = trained(false);
  const auto b = encode_model(m);
  REQUIRE(b.size() > 40);
  CHECK(std::memcmp(b.data(), "SLPCA", 5) == 0);
  CHECK(b[5] == 0);
  CHECK((b[6] | b[7] << 8) == kModelFileVersion);
  CHECK(le32(b, 8) == 8);   // width
  CHECK(le32(b, 12) == 6);  // height
  CHECK(le32(b, 16) == 5);  // p
  CHECK(le32(b, 20) == 1);  // aspect sectors
  CHECK(le32(b, 24) == 3);  // classes
  CHECK(le32(b, 28) == 0);  // groups
  CHECK(le32(b, 32) == 0);  // reserved
  // pre-processing record: none (crop 1, multilook 1, levels db, threshold 6 dB)
  CHECK(le32(b, 36) == 0);
  CHECK(le32(b, 40) == 0x3FF00000u);  // 1.0 as f64, high word
  CHECK(le32(b, 44) == 1);
  CHECK(b[48] == 0);
  CHECK(le32(b, 56) == 0x40180000u);  // 6.0 as f64, high word
  // first class record: "cuboid" (classes are sorted by name)
  CHECK((b[60] | b[61] << 8) == 6);
  CHECK(std::string(b.begin() + 62, b.begin() + 68) == "cuboid");
  CHECK(b[68] == 1);                  // cuboid is mine-like
  CHECK(b[69] == 1);                  // flags: its height is known
  CHECK(le32(b, 70) == 1);            // one subspace
  CHECK(le32(b, 74) == 0x7F800000u);  // reject distance +infinity: no open-set rejection
  CHECK(le32(b, 78) == 0);            // typical distance 0: not calibrated
  double h = 0.0;
  std::memcpy(&h, b.data() + 82, 8);  // height_m (little-endian host)
  CHECK(h == 0.4);
  // size: header + pre-processing + per class (name record + subspaces) + gate count + detector
  // rules (none: the flag and 3 reserved bytes) + view count + crc
  CHECK(le32(b, b.size() - 16) == 0);  // no gates
  CHECK(le32(b, b.size() - 12) == 0);  // no detector rules
  CHECK(le32(b, b.size() - 8) == 0);   // no views
  std::size_t expect = 36 + 24 + 4 + 4 + 4 + 4;
  for (const auto& c : m.classes) {
    expect += 2 + c.name.size() + 2 + 4 + 8 + 8;
    for (const auto& s : c.subspaces) {
      expect += 16 + 8 + 8 * s.rank() + 4 * 48 * (1 + s.rank());
    }
  }
  CHECK(b.size() == expect);
  CHECK(le32(b, b.size() - 4) == crc32(std::span(b).first(b.size() - 4)));
  // CRC-32 check value of the standard ("123456789" -> 0xCBF43926)
  const std::string check = "123456789";
  CHECK(crc32(std::span(reinterpret_cast<const std::uint8_t*>(check.data()), check.size())) ==
        0xCBF43926u);
}

TEST_CASE("model file: bad magic, version, truncation, trailing bytes and corruption") {
  const auto good = encode_model(trained(true));
  REQUIRE_NOTHROW(decode_model(good, "m.slpca"));

  auto b = good;
  b[0] = 'X';
  CHECK_THROWS_WITH(decode_model(b, "m.slpca"),
                    Catch::Contains("m.slpca") && Catch::Contains("bad magic"));
  CHECK_THROWS_WITH(decode_model(std::vector<std::uint8_t>{'S', 'L'}, "m"),
                    Catch::Contains("bad magic"));

  b = good;
  b[6] = 7;
  CHECK_THROWS_WITH(decode_model(b, "m"), Catch::Contains("unsupported format version 7") &&
                                              Catch::Contains("reads versions 1 to 6"));
  // class metadata: an unknown flag, a height out of range, a height said unknown but not 0
  const auto single = encode_model(trained(false));  // first class cuboid, height at 82
  b = single;
  b[69] = 4;
  fix_crc(b);
  CHECK_THROWS_WITH(decode_model(b, "m"), Catch::Contains("flags byte 4"));
  b = single;
  const double bad_h = -1.0;
  std::memcpy(b.data() + 82, &bad_h, 8);
  fix_crc(b);
  CHECK_THROWS_WITH(decode_model(b, "m"), Catch::Contains("cuboid") && Catch::Contains("height"));
  b = single;
  b[69] = 0;
  fix_crc(b);
  CHECK_THROWS_WITH(decode_model(b, "m"), Catch::Contains("flags say unknown"));
  // a bad pre-processing record: an even multilook window
  b = good;
  put_le32(b, 44, 4);
  fix_crc(b);
  CHECK_THROWS_WITH(decode_model(b, "m"), Catch::Contains("multilook window 4"));

  // every truncation is an error, none crashes
  for (std::size_t len = 0; len < good.size(); ++len) {
    const std::vector<std::uint8_t> cut(good.begin(), good.begin() + static_cast<long>(len));
    CHECK_THROWS(decode_model(cut, "m"));
  }
  const std::vector<std::uint8_t> half(good.begin(),
                                       good.begin() + static_cast<long>(good.size() / 2));
  CHECK_THROWS_WITH(decode_model(half, "m"), Catch::Contains("truncated"));

  b = good;
  b.insert(b.end() - 4, {1, 2, 3});
  fix_crc(b);
  CHECK_THROWS_WITH(decode_model(b, "m"), Catch::Contains("3 unexpected bytes"));

  // a flipped bit in the data is caught by the checksum
  b = good;
  b[b.size() / 2] ^= 0x10;
  CHECK_THROWS_WITH(decode_model(b, "m"), Catch::Contains("checksum"));
}

TEST_CASE("model file: inconsistent contents are rejected even with a valid checksum") {
  const auto good = encode_model(trained(false));
  // chip size 0
  auto b = good;
  put_le32(b, 8, 0);
  fix_crc(b);
  CHECK_THROWS_WITH(decode_model(b, "m"), Catch::Contains("chip size 0 x 6"));
  // a width that does not match the stored vectors: the data no longer parses to the end
  b = good;
  put_le32(b, 8, 9);
  fix_crc(b);
  CHECK_THROWS(decode_model(b, "m"));
  // three groups
  b = good;
  put_le32(b, 28, 3);
  fix_crc(b);
  CHECK_THROWS_WITH(decode_model(b, "m"), Catch::Contains("group count 3"));
  // p smaller than a stored rank
  b = good;
  put_le32(b, 16, 2);
  fix_crc(b);
  CHECK_THROWS_WITH(decode_model(b, "m"), Catch::Contains("exceeds p = 2"));
  // a NaN in the first mean image (the first class: name "cuboid", 1 subspace, rank 5)
  b = good;
  const std::size_t mean_at = 36 + 24 + 2 + 6 + 2 + 4 + 8 + 8 + 16 + 8 + 8 * 5;
  put_le32(b, mean_at, 0x7FC00000u);
  fix_crc(b);
  CHECK_THROWS_WITH(decode_model(b, "m"), Catch::Contains("non-finite"));
  // a basis that is not orthonormal: scale the first basis vector
  b = good;
  const std::size_t basis_at = mean_at + 4 * 48;
  for (std::size_t i = 0; i < 48; ++i) {
    float v;
    std::uint32_t u = le32(b, basis_at + 4 * i);
    std::memcpy(&v, &u, 4);
    v *= 1.1f;
    std::memcpy(&u, &v, 4);
    put_le32(b, basis_at + 4 * i, u);
  }
  fix_crc(b);
  CHECK_THROWS_WITH(decode_model(b, "m"), Catch::Contains("not orthonormal"));
}

TEST_CASE("model file: file errors name the path") {
  testing::TempDir dir("atr-model-file-errors");
  CHECK_THROWS_WITH(load_model(dir.file("missing.slpca")), Catch::Contains("missing.slpca"));
  {
    std::ofstream out(dir.file("text.slpca"));
    out << "not a model\n";
  }
  CHECK_THROWS_WITH(load_model(dir.file("text.slpca")),
                    Catch::Contains("text.slpca") && Catch::Contains("bad magic"));
  CHECK_THROWS_WITH(save_model(trained(false), dir.file("no/such/dir/m.slpca")),
                    Catch::Contains("cannot create"));
  // not files: refused by what they are, before a byte is read (/dev/zero would be read until
  // memory runs out, a FIFO would block for ever)
  CHECK_THROWS_WITH(load_model("/dev/zero"),
                    Catch::Contains("'/dev/zero'") && Catch::Contains("a character device"));
  CHECK_THROWS_WITH(load_model(dir.path().string()),
                    Catch::Contains(dir.path().string()) && Catch::Contains("a directory"));
  REQUIRE(::mkfifo(dir.file("fifo.slpca").c_str(), 0600) == 0);
  CHECK_THROWS_WITH(load_model(dir.file("fifo.slpca")), Catch::Contains("a FIFO"));
}

TEST_CASE("model file: a pre-processing model round-trips; version 1 reads as none") {
  TrainOptions opt;
  opt.p = 4;
  opt.preprocess = ChipPreprocess{0.5, 3, ChipLevels::kAboveSeabed, 4.5};
  opt.reject_quantile = 0.9;
  const Model m = train_model(chips(12, 5, false), opt);
  REQUIRE(m.feature_width() == 4);
  REQUIRE(m.feature_height() == 3);
  REQUIRE(std::isfinite(m.classes[0].reject_distance));
  const Model back = decode_model(encode_model(m), "pre");
  CHECK(back.preprocess.crop_fraction == 0.5);
  CHECK(back.preprocess.multilook_px == 3);
  CHECK(back.preprocess.levels == ChipLevels::kAboveSeabed);
  CHECK(back.preprocess.threshold_db == 4.5);
  CHECK(back.classes[0].subspaces[0].mean.size() == 12);
  CHECK(back.classes[0].reject_distance == m.classes[0].reject_distance);
  CHECK(back.classes[0].typical_distance == m.classes[0].typical_distance);
  CHECK(m.classes[0].typical_distance > 0.0f);
  CHECK(m.classes[0].typical_distance <= m.classes[0].reject_distance);
  CHECK(encode_model(back) == encode_model(m));

  // a version 1 file: no pre-processing record, no distances, no heights
  const Model plain = trained(false);
  const auto v1 = downgrade(plain, 1);
  const Model old = decode_model(v1, "v1");
  CHECK(old.preprocess.is_identity());
  CHECK(std::isinf(old.classes[0].reject_distance));
  expect_same(plain, old);
  CHECK_FALSE(old.classes[0].height_m);
}

TEST_CASE("model file: class metadata round-trips; version 2 files still load") {
  const Model m = trained(false);
  REQUIRE(m.classes[0].name == "cuboid");
  REQUIRE(m.classes[2].name == "rock");
  std::uint16_t version = 0;
  const Model back = decode_model(encode_model(m), "meta", &version);
  CHECK(version == kModelFileVersion);
  for (std::size_t c = 0; c < m.classes.size(); ++c) {
    CHECK(back.classes[c].mine_like == m.classes[c].mine_like);
    CHECK(back.classes[c].height_m == m.classes[c].height_m);
  }
  CHECK(back.classes[0].height_m == 0.4);
  CHECK(back.classes[1].height_m == 0.47);
  CHECK_FALSE(back.classes[2].height_m);
  CHECK_FALSE(back.classes[2].mine_like);

  // version 2: mine_like was stored, heights were not (unknown on load)
  const Model old = decode_model(downgrade(m, 2), "v2", &version);
  CHECK(version == 2);
  expect_same(m, old);
  CHECK(old.classes[0].mine_like);
  CHECK_FALSE(old.classes[2].mine_like);
  for (const auto& c : old.classes)
    CHECK_FALSE(c.height_m);
  CHECK(old.classes[0].reject_distance == m.classes[0].reject_distance);
}

TEST_CASE("model file: version 4 keeps clutter classes and contact gates; version 3 loads") {
  Model m = trained(false);
  m.classes[2].clutter = true;  // "rock": not mine-like
  LogisticGate d;
  d.stage = GateStage::kDetection;
  const std::size_t nd = gate_feature_count(GateStage::kDetection);
  for (std::size_t i = 0; i < nd; ++i) {
    d.mean.push_back(0.5 * static_cast<double>(i));
    d.scale.push_back(1.0 + static_cast<double>(i));
    d.weights.push_back(-0.25 * static_cast<double>(i));
  }
  d.bias = 0.75;
  d.threshold = 0.01;
  LogisticGate c = d;
  c.stage = GateStage::kClassification;
  c.form = GateForm::kQuadratic;
  const std::size_t nc = gate_feature_count(GateStage::kClassification);
  c.mean.resize(nc, 2.0);
  c.scale.resize(nc, 3.0);
  c.weights.resize(gate_term_count(nc, GateForm::kQuadratic), 0.125);
  c.threshold = 0.2;
  m.detection_gate = d;
  m.classification_gate = c;
  const auto bytes = encode_model(m);
  const Model back = decode_model(bytes, "v4");
  CHECK(back.classes[2].clutter);
  CHECK_FALSE(back.classes[0].clutter);
  REQUIRE(back.detection_gate);
  REQUIRE(back.classification_gate);
  CHECK(back.detection_gate->weights == d.weights);
  CHECK(back.detection_gate->mean == d.mean);
  CHECK(back.detection_gate->scale == d.scale);
  CHECK(back.detection_gate->bias == d.bias);
  CHECK(back.detection_gate->threshold == d.threshold);
  CHECK(back.classification_gate->weights == c.weights);
  CHECK(back.classification_gate->form == GateForm::kQuadratic);
  CHECK(back.detection_gate->form == GateForm::kLinear);
  CHECK(back.classification_gate->threshold == c.threshold);
  // a gate of the wrong size, or a clutter class that is mine-like, is refused
  Model bad = m;
  bad.classification_gate->weights.pop_back();
  CHECK_THROWS_AS(encode_model(bad), std::runtime_error);
  bad = m;
  bad.classes[2].mine_like = true;
  CHECK_THROWS_AS(encode_model(bad), std::runtime_error);
  // version 3: no gates, no clutter flag (its flags byte allows the height bit only)
  const Model plain = trained(false);
  std::uint16_t version = 0;
  const Model v3 = decode_model(downgrade(plain, 3), "v3", &version);
  CHECK(version == 3);
  expect_same(plain, v3);
  CHECK_FALSE(v3.detection_gate);
  CHECK_FALSE(v3.classification_gate);
  auto flagged = downgrade(plain, 3);
  flagged[69] |= 2;  // the clutter bit in a version 3 file
  fix_crc(flagged);
  CHECK_THROWS_WITH(decode_model(flagged, "v3"), Catch::Contains("flags byte"));
}

TEST_CASE("model file: version 5 keeps the detector rules; version 4 loads without them") {
  Model m = trained(false);
  m.detector_rules = DetectorRules{1, 0.0};
  std::uint16_t version = 0;
  const Model back = decode_model(encode_model(m), "v5", &version);
  CHECK(version == kModelFileVersion);
  REQUIRE(back.detector_rules);
  CHECK(*back.detector_rules == DetectorRules{1, 0.0});
  m.detector_rules = DetectorRules{3, 0.25};
  CHECK(*decode_model(encode_model(m), "v5").detector_rules == DetectorRules{3, 0.25});
  // none recorded: none read
  const Model plain = trained(false);
  CHECK_FALSE(decode_model(encode_model(plain), "v5").detector_rules);
  // version 4 files have no record: none
  const Model v4 = decode_model(downgrade(plain, 4), "v4", &version);
  CHECK(version == 4);
  CHECK_FALSE(v4.detector_rules);
  expect_same(plain, v4);
  // out of range: refused when written and when read
  Model bad = m;
  bad.detector_rules->min_pings = 0;
  CHECK_THROWS_WITH(encode_model(bad), Catch::Contains("min_pings"));
  bad.detector_rules = DetectorRules{2, -1.0};
  CHECK_THROWS_WITH(encode_model(bad), Catch::Contains("min_along_m"));
  // rules {3, 0.25}: the u32 starts 20 bytes before the end (f64, the view count, the CRC)
  auto bytes = encode_model(m);
  bytes[bytes.size() - 20] = 0;
  fix_crc(bytes);
  CHECK_THROWS_WITH(decode_model(bytes, "zero"), Catch::Contains("min_pings 0"));
  bytes = encode_model(m);
  bytes[bytes.size() - 24] = 2;  // the flag byte
  fix_crc(bytes);
  CHECK_THROWS_WITH(decode_model(bytes, "flag"), Catch::Contains("detector rules flag 2"));
}

TEST_CASE("model file: version 6 keeps the fused readings; version 5 loads without them") {
  TrainOptions opt;
  opt.p = 5;
  opt.preprocess.levels = ChipLevels::kAboveSeabed;
  ChipPreprocess shadow = opt.preprocess;
  shadow.levels = ChipLevels::kBelowSeabed;
  opt.views = {shadow};
  const Model m = train_model(chips(15, 1, false), opt);
  REQUIRE(m.views.size() == 1);
  std::uint16_t version = 0;
  const Model back = decode_model(encode_model(m), "v6", &version);
  CHECK(version == 6);
  REQUIRE(back.views.size() == 1);
  CHECK(back.views[0].preprocess == shadow);
  expect_same(m, back);
  Model primary = m, view = m;
  primary.views.clear();
  view.views.clear();
  view.preprocess = shadow;
  view.classes = m.views[0].classes;
  Model back_view = back;
  back_view.views.clear();
  back_view.preprocess = shadow;
  back_view.classes = back.views[0].classes;
  expect_same(view, back_view);
  // the same fused distances, bit for bit
  Classifier a(m), b(back);
  for (const LabelledChip& c : chips(3, 9, false)) {
    REQUIRE(a.classify(c.chip.view()).ok());
    REQUIRE(b.classify(c.chip.view()).ok());
    CHECK(a.result().class_distance == b.result().class_distance);
  }
  // a model without views writes a view count of 0, which version 5 lacks
  const Model v5 = decode_model(downgrade(primary, 5), "v5", &version);
  CHECK(version == 5);
  CHECK(v5.views.empty());
  expect_same(primary, v5);
  // refused: a view's crop other than the model's, a view of another class count, a view count
  // beyond the limit
  Model bad = m;
  bad.views[0].preprocess.crop_fraction = 0.5;
  CHECK_THROWS_WITH(encode_model(bad), Catch::Contains("crop fraction"));
  bad = m;
  bad.views[0].classes.pop_back();
  CHECK_THROWS_WITH(encode_model(bad), Catch::Contains("classes"));
  bad = m;
  bad.views[0].classes[0].typical_distance = 3.0f;
  CHECK_THROWS_WITH(encode_model(bad), Catch::Contains("typical distance"));
  auto bytes = encode_model(m);
  // the view count follows the detector rules record (4 bytes for none), after the gate count
  std::size_t at = 36 + 24;
  for (const auto& c : m.classes) {
    at += 2 + c.name.size() + 2 + 4 + 8 + 8;
    for (const auto& s : c.subspaces)
      at += 16 + 8 + 8 * s.rank() + 4 * m.feature_count() * (1 + s.rank());
  }
  at += 4 + 4;
  REQUIRE(le32(bytes, at) == 1);
  put_le32(bytes, at, 4);
  fix_crc(bytes);
  CHECK_THROWS_WITH(decode_model(bytes, "views"), Catch::Contains("view count 4"));
}
