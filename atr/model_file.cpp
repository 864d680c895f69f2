#include "atr/model_file.h"

#include <array>
#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "atr/contact_gate.h"
#include "drivers/io/input_file.h"

namespace sonarloop::atr {
namespace {

constexpr std::size_t kHeaderBytes = 36;
// Sanity limits on load: beyond these a file is corrupt, not a model.
constexpr std::uint32_t kMaxChipSide = 8192;
constexpr std::uint32_t kMaxP = 4096;
constexpr std::uint32_t kMaxAspectSectors = 360;
constexpr std::uint32_t kMaxClasses = 65535;
constexpr std::size_t kMaxNameBytes = 255;
// class flags (version 3; bit 1 from version 4)
constexpr std::uint8_t kHeightKnown = 1;
constexpr std::uint8_t kClutterClass = 2;

class Writer {
 public:
  void u8(std::uint8_t v) { out_.push_back(v); }
  void u16(std::uint16_t v) {
    for (int i = 0; i < 2; ++i)
      out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i)
      out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i)
      out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  void bytes(const void* p, std::size_t n) {
    const auto* b = static_cast<const std::uint8_t*>(p);
    out_.insert(out_.end(), b, b + n);
  }
  std::vector<std::uint8_t>& data() { return out_; }

 private:
  std::vector<std::uint8_t> out_;
};

class Reader {
 public:
  Reader(std::span<const std::uint8_t> b, const std::string& name) : b_(b), name_(name) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("model file '" + name_ + "', offset " + std::to_string(pos_) + ": " +
                             what);
  }
  void need(std::size_t n, const char* what) {
    if (b_.size() - pos_ < n) {
      truncated_ = true;
      fail(std::string("truncated: ") + what + " needs " + std::to_string(n) + " bytes, " +
           std::to_string(b_.size() - pos_) + " left (the file is " + std::to_string(b_.size()) +
           " bytes, incomplete or cut short)");
    }
  }
  std::uint64_t uint(int bytes, const char* what) {
    need(static_cast<std::size_t>(bytes), what);
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i)
      v |= static_cast<std::uint64_t>(b_[pos_ + i]) << (8 * i);
    pos_ += static_cast<std::size_t>(bytes);
    return v;
  }
  std::uint8_t u8(const char* what) { return static_cast<std::uint8_t>(uint(1, what)); }
  std::uint16_t u16(const char* what) { return static_cast<std::uint16_t>(uint(2, what)); }
  std::uint32_t u32(const char* what) { return static_cast<std::uint32_t>(uint(4, what)); }
  double f64(const char* what) { return std::bit_cast<double>(uint(8, what)); }
  float f32(const char* what) { return std::bit_cast<float>(u32(what)); }
  // n float32 values into dst
  void f32s(float* dst, std::size_t n, const char* what) {
    need(n * 4, what);
    for (std::size_t i = 0; i < n; ++i) {
      std::uint32_t v = 0;
      for (int k = 0; k < 4; ++k)
        v |= static_cast<std::uint32_t>(b_[pos_ + 4 * i + k]) << (8 * k);
      dst[i] = std::bit_cast<float>(v);
    }
    pos_ += n * 4;
  }
  std::string str(std::size_t n, const char* what) {
    need(n, what);
    std::string s(reinterpret_cast<const char*>(b_.data() + pos_), n);
    pos_ += n;
    return s;
  }
  std::size_t pos() const { return pos_; }
  std::size_t left() const { return b_.size() - pos_; }
  bool truncated() const { return truncated_; }

 private:
  std::span<const std::uint8_t> b_;
  std::string name_;
  std::size_t pos_ = 0;
  bool truncated_ = false;
};

void write_subspaces(Writer& w, const ClassModel& c, std::size_t n) {
  for (const Subspace& s : c.subspaces) {
    w.f64(s.aspect_min_deg);
    w.f64(s.aspect_max_deg);
    w.u32(static_cast<std::uint32_t>(s.train_count));
    w.u32(static_cast<std::uint32_t>(s.rank()));
    for (Eigen::Index j = 0; j < s.eigenvalues.size(); ++j)
      w.f64(s.eigenvalues[j]);
    for (std::size_t i = 0; i < n; ++i)
      w.f32(s.mean[static_cast<Eigen::Index>(i)]);
    // Eigen matrices are column-major: the data is already eigenvector by eigenvector
    const float* u = s.basis.data();
    for (std::size_t i = 0; i < n * static_cast<std::size_t>(s.rank()); ++i)
      w.f32(u[i]);
  }
}

void write_class(Writer& w, const ClassModel& c, std::size_t n) {
  if (c.name.size() > kMaxNameBytes) {
    throw std::runtime_error("class name '" + c.name + "' is longer than 255 bytes");
  }
  w.u16(static_cast<std::uint16_t>(c.name.size()));
  w.bytes(c.name.data(), c.name.size());
  w.u8(c.mine_like ? 1 : 0);
  w.u8(static_cast<std::uint8_t>((c.height_m ? kHeightKnown : 0) |
                                 (c.clutter ? kClutterClass : 0)));  // version 3 flags
  w.u32(static_cast<std::uint32_t>(c.subspaces.size()));
  w.f32(c.reject_distance);  // version 2
  w.f32(c.typical_distance);
  w.f64(c.height_m.value_or(0.0));  // version 3
  write_subspaces(w, c, n);
}

// `count` subspace records of class `c` (labelled `label` in errors).
void read_subspaces(Reader& r, const Model& m, ClassModel& c, const std::string& label,
                    std::uint32_t count) {
  const std::size_t n = m.feature_count();
  for (std::uint32_t s = 0; s < count; ++s) {
    Subspace sub;
    sub.aspect_min_deg = r.f64("aspect_min_deg");
    sub.aspect_max_deg = r.f64("aspect_max_deg");
    sub.train_count = static_cast<int>(std::min<std::uint32_t>(r.u32("train_count"), 1u << 30));
    const std::uint32_t rank = r.u32("rank");
    if (rank > static_cast<std::uint32_t>(m.p)) {
      r.fail(label + " '" + c.name + "' subspace " + std::to_string(s) + ": rank " +
             std::to_string(rank) + " exceeds p = " + std::to_string(m.p));
    }
    // check the bytes are there before allocating
    r.need(8 * static_cast<std::size_t>(rank) + 4 * n * (1 + static_cast<std::size_t>(rank)),
           "subspace eigenvalues, mean and basis");
    sub.eigenvalues.resize(rank);
    for (std::uint32_t j = 0; j < rank; ++j)
      sub.eigenvalues[j] = r.f64("eigenvalue");
    sub.mean.resize(static_cast<Eigen::Index>(n));
    r.f32s(sub.mean.data(), n, "mean image");
    sub.basis.resize(static_cast<Eigen::Index>(n), rank);
    r.f32s(sub.basis.data(), n * rank, "basis");
    c.subspaces.push_back(std::move(sub));
  }
}

std::uint32_t read_subspace_count(Reader& r, const Model& m, const ClassModel& c,
                                  const std::string& label) {
  const std::uint32_t count = r.u32("subspace count");
  if (count == 0 || count > static_cast<std::uint32_t>(m.aspect_sectors)) {
    r.fail(label + " '" + c.name + "': subspace count " + std::to_string(count) +
           " (allowed 1 to the aspect sector count " + std::to_string(m.aspect_sectors) + ")");
  }
  return count;
}

void write_preprocess(Writer& w, const ChipPreprocess& p) {
  w.f64(p.crop_fraction);
  w.u32(static_cast<std::uint32_t>(p.multilook_px));
  w.u8(static_cast<std::uint8_t>(p.levels));
  w.u8(0);
  w.u8(0);
  w.u8(0);
  w.f64(p.threshold_db);
}

ChipPreprocess read_preprocess(Reader& r) {
  ChipPreprocess p;
  p.crop_fraction = r.f64("crop fraction");
  const std::uint32_t looks = r.u32("multilook window");
  const std::uint8_t levels = r.u8("levels mode");
  r.u8("reserved byte");
  r.u8("reserved byte");
  r.u8("reserved byte");
  p.threshold_db = r.f64("three-level threshold");
  p.multilook_px = static_cast<int>(std::min<std::uint32_t>(looks, 1u << 20));
  p.levels = static_cast<ChipLevels>(levels);
  try {
    validate_preprocess(p);
  } catch (const std::invalid_argument& e) {
    r.fail(e.what());
  }
  return p;
}

ClassModel read_class(Reader& r, const Model& m, int version, const char* kind, std::size_t index) {
  ClassModel c;
  const std::string label = std::string(kind) + " " + std::to_string(index);
  const std::uint16_t len = r.u16("class name length");
  if (len == 0 || len > kMaxNameBytes) {
    r.fail(label + ": name length " + std::to_string(len) + " (allowed 1 to 255)");
  }
  c.name = r.str(len, "class name");
  const std::uint8_t mine = r.u8("mine_like flag");
  if (mine > 1)
    r.fail(label + " '" + c.name + "': mine_like flag " + std::to_string(mine) + " (0 or 1)");
  c.mine_like = mine == 1;
  // a reserved byte before version 3 (ignored, as those versions did)
  const std::uint8_t flags = r.u8(version >= 3 ? "class flags" : "reserved byte");
  const std::uint8_t allowed = version >= 4 ? kHeightKnown | kClutterClass : kHeightKnown;
  if (version >= 3 && (flags & ~allowed) != 0) {
    r.fail(label + " '" + c.name + "': flags byte " + std::to_string(flags) + " (allowed bits " +
           std::to_string(allowed) + ")");
  }
  c.clutter = version >= 4 && (flags & kClutterClass) != 0;
  const std::uint32_t count = read_subspace_count(r, m, c, label);
  if (version >= 2) {
    c.reject_distance = r.f32("reject distance");
    c.typical_distance = r.f32("typical distance");
  }
  if (version >= 3) {
    const double h = r.f64("height_m");
    if (flags & kHeightKnown) {
      if (!valid_class_height(h)) {
        r.fail(label + " '" + c.name + "': height " + std::to_string(h) +
               " m (allowed 0 to 100 m)");
      }
      c.height_m = h;
    } else if (h != 0.0) {
      r.fail(label + " '" + c.name + "': height " + std::to_string(h) +
             " m, but the flags say unknown (then 0)");
    }
  }
  read_subspaces(r, m, c, label, count);
  return c;
}

// version 6: the views, after the detector rules
void write_views(Writer& w, const Model& m) {
  w.u32(static_cast<std::uint32_t>(m.views.size()));
  for (const ModelView& v : m.views) {
    write_preprocess(w, v.preprocess);
    for (const ClassModel& c : v.classes) {
      w.u32(static_cast<std::uint32_t>(c.subspaces.size()));
      write_subspaces(w, c, m.feature_count());
    }
  }
}

void read_views(Reader& r, Model& m) {
  const std::uint32_t views = r.u32("view count");
  if (views > kMaxModelViews) {
    r.fail("view count " + std::to_string(views) + " (0 to " + std::to_string(kMaxModelViews) +
           ")");
  }
  for (std::uint32_t v = 0; v < views; ++v) {
    ModelView view;
    view.preprocess = read_preprocess(r);
    if (view.preprocess.crop_fraction != m.preprocess.crop_fraction) {
      r.fail("view " + std::to_string(v) + ": crop fraction " +
             std::to_string(view.preprocess.crop_fraction) + ", the model's " +
             std::to_string(m.preprocess.crop_fraction) + " (they must be the same)");
    }
    for (const ClassModel& primary : m.classes) {
      ClassModel c;
      c.name = primary.name;
      c.mine_like = primary.mine_like;
      c.clutter = primary.clutter;
      c.height_m = primary.height_m;
      const std::string label = "view " + std::to_string(v) + " class";
      read_subspaces(r, m, c, label, read_subspace_count(r, m, c, label));
      view.classes.push_back(std::move(c));
    }
    m.views.push_back(std::move(view));
  }
}

// version 4: the gates, after the groups
void write_gate(Writer& w, const LogisticGate& g) {
  w.u8(static_cast<std::uint8_t>(g.stage));
  w.u8(static_cast<std::uint8_t>(g.form));
  w.u8(0);
  w.u8(0);
  w.u32(static_cast<std::uint32_t>(g.mean.size()));
  w.f64(g.threshold);
  w.f64(g.bias);
  for (const double v : g.mean)
    w.f64(v);
  for (const double v : g.scale)
    w.f64(v);
  for (const double v : g.weights)
    w.f64(v);
}

LogisticGate read_gate(Reader& r, std::uint32_t index) {
  LogisticGate g;
  const std::uint8_t stage = r.u8("gate stage");
  if (stage > 1)
    r.fail("gate " + std::to_string(index) + ": stage " + std::to_string(stage) +
           " (0 detection or 1 classification)");
  g.stage = static_cast<GateStage>(stage);
  const std::uint8_t form = r.u8("gate form");
  if (form > 1) {
    r.fail("gate " + std::to_string(index) + ": form " + std::to_string(form) +
           " (0 linear or 1 quadratic)");
  }
  g.form = static_cast<GateForm>(form);
  r.u8("reserved byte");
  r.u8("reserved byte");
  const std::uint32_t n = r.u32("gate feature count");
  if (n != gate_feature_count(g.stage)) {
    r.fail("gate " + std::to_string(index) + " (" + gate_stage_name(g.stage) +
           "): " + std::to_string(n) + " features (this build's stage has " +
           std::to_string(gate_feature_count(g.stage)) + ")");
  }
  g.threshold = r.f64("gate threshold");
  g.bias = r.f64("gate bias");
  for (auto* v : {&g.mean, &g.scale, &g.weights}) {
    v->resize(v == &g.weights ? gate_term_count(n, g.form) : n);
    for (double& x : *v)
      x = r.f64("gate parameter");
  }
  return g;
}

}  // namespace

std::vector<std::uint8_t> encode_model(const Model& m) {
  validate_model(m);
  Writer w;
  w.bytes(kModelFileMagic, sizeof kModelFileMagic);
  w.u8(0);
  w.u16(kModelFileVersion);
  w.u32(static_cast<std::uint32_t>(m.chip_width));
  w.u32(static_cast<std::uint32_t>(m.chip_height));
  w.u32(static_cast<std::uint32_t>(m.p));
  w.u32(static_cast<std::uint32_t>(m.aspect_sectors));
  w.u32(static_cast<std::uint32_t>(m.classes.size()));
  w.u32(static_cast<std::uint32_t>(m.groups.size()));
  w.u32(0);
  // version 2: the pre-processing record
  write_preprocess(w, m.preprocess);
  for (const auto& c : m.classes)
    write_class(w, c, m.feature_count());
  for (const auto& g : m.groups)
    write_class(w, g, m.feature_count());
  // version 4: the gates
  w.u32(static_cast<std::uint32_t>(m.detection_gate.has_value()) +
        static_cast<std::uint32_t>(m.classification_gate.has_value()));
  if (m.detection_gate) write_gate(w, *m.detection_gate);
  if (m.classification_gate) write_gate(w, *m.classification_gate);
  // version 5: the detector rules
  w.u8(m.detector_rules ? 1 : 0);
  w.u8(0);
  w.u8(0);
  w.u8(0);
  if (m.detector_rules) {
    w.u32(static_cast<std::uint32_t>(m.detector_rules->min_pings));
    w.f64(m.detector_rules->min_along_m);
  }
  write_views(w, m);  // version 6
  w.u32(crc32(w.data()));
  return std::move(w.data());
}

Model decode_model(std::span<const std::uint8_t> bytes, const std::string& name,
                   std::uint16_t* version_out) {
  Reader r(bytes, name);
  if (bytes.size() < sizeof kModelFileMagic ||
      std::memcmp(bytes.data(), kModelFileMagic, sizeof kModelFileMagic) != 0) {
    r.fail("bad magic: not a sonarloop PCA model (expected the file to start with \"SLPCA\")");
  }
  r.str(sizeof kModelFileMagic, "magic");
  r.u8("reserved byte");
  const std::uint16_t version = r.u16("format version");
  if (version < 1 || version > kModelFileVersion) {
    r.fail("unsupported format version " + std::to_string(version) +
           " (this build reads versions 1 to " + std::to_string(kModelFileVersion) + ")");
  }
  if (version_out) *version_out = version;
  // the checksum over everything but the trailer; judged after parsing, so that a truncated
  // file is reported where it ends, and a parse error can say whether the bytes are corrupt
  const bool crc_ok = bytes.size() >= kHeaderBytes + 4 && [&] {
    const std::size_t body = bytes.size() - 4;
    std::uint32_t stored = 0;
    for (int i = 0; i < 4; ++i)
      stored |= static_cast<std::uint32_t>(bytes[body + i]) << (8 * i);
    return stored == crc32(bytes.first(body));
  }();
  Model m;
  try {
    const std::uint32_t w = r.u32("chip width"), h = r.u32("chip height");
    const std::uint32_t p = r.u32("p"), sectors = r.u32("aspect sectors");
    const std::uint32_t classes = r.u32("class count"), groups = r.u32("group count");
    r.u32("reserved");
    if (w == 0 || h == 0 || w > kMaxChipSide || h > kMaxChipSide) {
      r.fail("chip size " + std::to_string(w) + " x " + std::to_string(h) + " (allowed 1 to " +
             std::to_string(kMaxChipSide) + " a side)");
    }
    if (p == 0 || p > kMaxP) r.fail("p = " + std::to_string(p) + " (allowed 1 to 4096)");
    if (sectors == 0 || sectors > kMaxAspectSectors) {
      r.fail("aspect sectors = " + std::to_string(sectors) + " (allowed 1 to 360)");
    }
    if (classes == 0 || classes > kMaxClasses) {
      r.fail("class count " + std::to_string(classes) + " (allowed 1 to 65535)");
    }
    if (groups != 0 && groups != 2) r.fail("group count " + std::to_string(groups) + " (0 or 2)");
    m.chip_width = static_cast<int>(w);
    m.chip_height = static_cast<int>(h);
    m.p = static_cast<int>(p);
    m.aspect_sectors = static_cast<int>(sectors);
    // version 1 models have no pre-processing (the identity)
    if (version >= 2) m.preprocess = read_preprocess(r);
    for (std::uint32_t c = 0; c < classes; ++c)
      m.classes.push_back(read_class(r, m, version, "class", c));
    for (std::uint32_t g = 0; g < groups; ++g)
      m.groups.push_back(read_class(r, m, version, "group", g));
    if (version >= 4) {
      const std::uint32_t gates = r.u32("gate count");
      if (gates > 2) r.fail("gate count " + std::to_string(gates) + " (0 to 2)");
      for (std::uint32_t i = 0; i < gates; ++i) {
        LogisticGate g = read_gate(r, i);
        auto& slot = g.stage == GateStage::kDetection ? m.detection_gate : m.classification_gate;
        if (slot) r.fail("two gates of the " + std::string(gate_stage_name(g.stage)) + " stage");
        slot = std::move(g);
      }
    }
    if (version >= 5) {
      const std::uint8_t recorded = r.u8("detector rules flag");
      if (recorded > 1) r.fail("detector rules flag " + std::to_string(recorded) + " (0 or 1)");
      r.u8("reserved byte");
      r.u8("reserved byte");
      r.u8("reserved byte");
      if (recorded == 1) {
        DetectorRules d;
        const std::uint32_t pings = r.u32("detector min_pings");
        if (pings < 1 || pings > static_cast<std::uint32_t>(kMaxDetectorRulePings)) {
          r.fail("detector min_pings " + std::to_string(pings) + " (1 to " +
                 std::to_string(kMaxDetectorRulePings) + ")");
        }
        d.min_pings = static_cast<int>(pings);
        d.min_along_m = r.f64("detector min_along_m");
        m.detector_rules = d;
      }
    }
    if (version >= 6) read_views(r, m);
    r.need(4, "the checksum trailer");
    if (r.left() > 4) {
      r.fail(std::to_string(r.left() - 4) + " unexpected bytes after the last record");
    }
  } catch (const std::runtime_error& e) {
    if (crc_ok || r.truncated()) throw;
    throw std::runtime_error(std::string(e.what()) +
                             " (the checksum does not match either: the file is corrupt)");
  }
  if (!crc_ok) {
    throw std::runtime_error("model file '" + name +
                             "': checksum mismatch: the file is corrupt (its CRC-32 trailer "
                             "does not match its contents)");
  }
  try {
    validate_model(m);
  } catch (const std::exception& e) {
    throw std::runtime_error("model file '" + name + "': " + e.what());
  }
  return m;
}

void save_model(const Model& m, const std::string& path) {
  const std::vector<std::uint8_t> bytes = encode_model(m);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error("cannot create model file '" + path + "'");
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw std::runtime_error("cannot write model file '" + path + "'");
}

Model load_model(const std::string& path, std::uint16_t* version) {
  io::check_input_file(path, "model file", kMaxModelFileBytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open model file '" + path + "'");
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                        std::istreambuf_iterator<char>());
  if (in.bad()) throw std::runtime_error("cannot read model file '" + path + "'");
  return decode_model(bytes, path, version);
}

}  // namespace sonarloop::atr
