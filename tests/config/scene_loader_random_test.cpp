// Seeded randomized tests of the scene loader (config/loader/scene_loader.h, docs/style.md habit
// 22): random valid scenarios round-trip, single-key corruptions are always rejected with a
// ConfigError, random byte edits never crash.
#include "config/loader/scene_loader.h"

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/rng.h"
#include "config/default_scenario.h"
#include "config/loader/scenario_loader.h"
#include "sim/seabed/sediment.h"
#include "sim/targets/material.h"
#include "sim/targets/target_type.h"
#include "tests/config/config_test_text.h"
#include "tests/config/scene_loader_checks.h"
#include "tests/config/scene_yaml_tree.h"
#include "tests/support/temp_dir.h"

using sonarloop::Rng;
using sonarloop::RngStream;
using sonarloop::Vec2;
using sonarloop::Vec3;
using namespace sonarloop::config;
namespace scene = sonarloop::scene;
namespace seabed = sonarloop::seabed;
namespace targets = sonarloop::targets;
using namespace sonarloop::config::scene_loader_checks;
using sonarloop::testing::feed_byte_edits;
using sonarloop::testing::real_text;

// ---------------------------------------------------------------------------------------------
// seeded randomized test (docs/style.md habit 22)

namespace {

class ScenarioGenerator {
 public:
  explicit ScenarioGenerator(std::uint64_t sample) : rng_(20240611, RngStream::kDataset, sample) {}

  Rng& rng() { return rng_; }

  // Fills `expect` with a random valid scene and `root` with the YAML that describes it.
  void generate(scene::SceneDesc& expect, YNode& root, const std::string& stem) {
    root = map_node();
    if (chance(0.75)) {
      expect.seed = chance(0.5) ? rng_.next_u64() : rng_.below(1000);
      root.map.push_back({"seed", scalar(std::to_string(expect.seed), YNode::Accepts::kUInt)});
    }
    expect.name = stem;
    if (chance(0.5)) {
      expect.name = "survey " + std::to_string(rng_.below(100000));
      root.map.push_back({"name", scalar(chance(0.5) ? "\"" + expect.name + "\"" : expect.name,
                                         YNode::Accepts::kText)});
    }
    section(root, "origin", [&](YNode& m) {
      auto& o = expect.origin;
      o.latitude_deg = num(m, "latitude_deg", o.latitude_deg, Range::closed(-89, 89));
      o.longitude_deg = num(m, "longitude_deg", o.longitude_deg, Range::closed(-180, 180));
    });
    section(root, "water", [&](YNode& m) {
      auto& w = expect.water;
      w.temperature_c = num(m, "temperature_c", w.temperature_c, Range::closed(-2, 35));
      w.salinity_ppt = num(m, "salinity_ppt", w.salinity_ppt, Range::closed(0, 45));
      w.ph = num(m, "ph", w.ph, Range::closed(7, 9));
      w.depth_m = num(m, "depth_m", w.depth_m, Range::closed(2, 1000));
    });
    section(root, "seabed", [&](YNode& m) { seabed_section(m, expect.seabed); });
    targets_section(root, expect);
    shuffle(root);
  }

 private:
  bool chance(double p) { return rng_.uniform() < p; }

  // a value in r: often an end point, log-uniform over wide positive ranges
  double draw(const Range& r) {
    for (;;) {
      double v = 0;
      const double u = rng_.uniform();
      if (u < 0.1) {
        v = r.lo;
      } else if (u < 0.2) {
        v = r.hi;
      } else if (r.lo > 0 && r.hi / r.lo > 1000) {
        v = std::exp(rng_.uniform(std::log(r.lo), std::log(r.hi)));
        v = std::min(std::max(v, r.lo), r.hi);
      } else {
        v = rng_.uniform(r.lo, r.hi);
      }
      if (r.contains(v)) return v;
    }
  }

  // adds `key` with a drawn value, or leaves it out (when the default is valid here)
  double num(YNode& m, const char* key, double def, const Range& valid) {
    return num(m, key, def, valid, valid);
  }
  double num(YNode& m, const char* key, double def, const Range& valid, const Range& gen) {
    if (valid.contains(def) && chance(0.25)) return def;
    const double v = draw(gen);
    m.map.push_back({key, real(v, valid)});
    return v;
  }
  Vec2 vec2(YNode& m, const char* key, const Vec2& def, const std::array<Range, 2>& valid,
            const Range& gen, bool required = false) {
    if (!required && valid[0].contains(def.x()) && valid[1].contains(def.y()) && chance(0.25))
      return def;
    // bounded components are drawn from their valid range, unbounded ones from `gen`
    const Vec2 v(draw(std::isfinite(valid[0].lo) ? valid[0] : gen),
                 draw(std::isfinite(valid[1].lo) ? valid[1] : gen));
    YNode n = vec({v.x(), v.y()}, {valid[0], valid[1]});
    if (chance(0.3)) n.flow = false;  // block list
    m.map.push_back({key, n});
    return v;
  }

  // a map section: filled by `fill`, written in block or flow style, or left out / empty
  template <class Fn>
  void section(YNode& parent, const char* key, Fn&& fill) {
    YNode m = map_node();
    fill(m);
    if (m.map.empty()) {
      const double u = rng_.uniform();
      if (u < 0.4) return;                                    // left out
      if (u < 0.7) m = scalar("", YNode::Accepts::kNothing);  // "key:" (null)
    }
    if (m.kind == YNode::Kind::kMap) {
      bool leaves = true;
      for (const auto& kv : m.map)
        leaves = leaves && !is_block(kv.value);
      m.flow = leaves && chance(0.3);
    }
    parent.map.push_back({key, m});
  }

  void seabed_section(YNode& m, scene::SeabedDesc& s) {
    s.origin_m =
        vec2(m, "origin_m", s.origin_m, {Range::any(), Range::any()}, Range::closed(-5000, 5000));
    const Range ext = Range::closed(1, 100000);
    s.extent_m = vec2(m, "extent_m", s.extent_m, {ext, ext}, ext);
    // at most 1e12 cells; a hair above the exact bound so that rounding cannot cross it
    const double cells_lo = std::sqrt(s.extent_m.x() * s.extent_m.y() / 1e12) * (1 + 1e-9);
    const Range grid =
        Range::closed(std::max(0.005, cells_lo), std::min(1.0, s.extent_m.minCoeff()));
    s.grid_spacing_m = num(m, "grid_spacing_m", s.grid_spacing_m, grid);
    section(m, "elevation", [&](YNode& e) {
      auto& el = s.elevation;
      el.slope = vec2(e, "slope", el.slope, {Range::closed(-0.5, 0.5), Range::closed(-0.5, 0.5)},
                      Range::closed(-0.5, 0.5));
      el.rms_m = num(e, "rms_m", el.rms_m, Range::closed(0, 50));
      el.beta = num(e, "beta", el.beta, Range::closed(0.5, 3.5));
      el.spacing_m = num(e, "spacing_m", el.spacing_m,
                         Range::closed(s.grid_spacing_m, std::min(10.0, s.extent_m.minCoeff())));
      const Range inner{el.spacing_m, 10000, false, true, {}};
      el.inner_scale_m = num(e, "inner_scale_m", el.inner_scale_m, inner,
                             Range::closed(el.spacing_m, std::min(el.spacing_m * 100, 9999.0)));
      el.outer_scale_m = num(e, "outer_scale_m", el.outer_scale_m,
                             Range{el.inner_scale_m, 10000, true, false, {}});
      shuffle(e);
    });
    section(m, "partition", [&](YNode& p) {
      auto& pa = s.partition;
      pa.border_warp_m = num(p, "border_warp_m", pa.border_warp_m, Range::closed(0, 1000));
      pa.border_beta = num(p, "border_beta", pa.border_beta, Range::closed(1, 3.5));
      pa.border_scale_m = num(p, "border_scale_m", pa.border_scale_m, Range::closed(0.1, 10000));
      pa.blend_width_m = num(p, "blend_width_m", pa.blend_width_m, Range::closed(0, 100));
    });
    regions(m, s);
  }

  void regions(YNode& m, scene::SeabedDesc& s) {
    s.regions.clear();
    if (chance(0.2)) {
      scene::RegionDesc r;
      r.sediment = sediment("medium_sand");
      s.regions.push_back(r);
      return;
    }
    YNode list = section_list();
    const auto n = 1 + rng_.below(3);
    std::vector<std::string> names;
    for (const auto& info : seabed::sediment_table())
      names.emplace_back(info.key);
    names.insert(names.end(), {"sand", "gravel", "pebble", "silty_sand", "clayey_silt"});
    for (std::uint64_t i = 0; i < n; ++i) {
      YNode r = map_node();
      scene::RegionDesc d;
      d.sediment = sediment("medium_sand");
      if (chance(0.8)) {
        const std::string name = names[rng_.below(names.size())];
        d.sediment = sediment(name.c_str());
        r.map.push_back({"sediment", scalar(name, YNode::Accepts::kName)});
      }
      if (i > 0 || chance(0.8)) {
        d.centre_m = Vec2(rng_.uniform(-500, 500), rng_.uniform(-500, 500));
        r.map.push_back(
            {"centre_m", vec({d.centre_m.x(), d.centre_m.y()}, {Range::any(), Range::any()})});
      }
      texture(r, d.texture);
      shuffle(r);
      if (chance(0.3)) r.flow = true;
      list.list.push_back(r);
      s.regions.push_back(d);
    }
    m.map.push_back({"regions", list});
  }

  void texture(YNode& region, scene::TextureDesc& t) {
    const double u = rng_.uniform();
    if (u < 0.2) return;  // left out
    if (u < 0.35) {
      YNode flat = scalar("flat", YNode::Accepts::kName);
      flat.map_or_null_ok = true;
      region.map.push_back({"texture", flat});
      return;
    }
    YNode tex = map_node();
    if (chance(0.5)) {
      t.ripples = scene::RipplesDesc{};
      kind(tex, "ripples", [&](YNode& m) {
        auto& r = *t.ripples;
        r.wavelength_m = num(m, "wavelength_m", r.wavelength_m, Range::closed(0.05, 20));
        r.direction_deg = num(m, "direction_deg", r.direction_deg, Range::closed(0, 360));
        r.beta1 = num(m, "beta1", r.beta1, Range::closed(0.5, 6));
        r.beta = num(m, "beta", r.beta, Range::closed(0.5, 6));
        r.height_m = num(m, "height_m", r.height_m, Range::closed(0, 2));
      });
    }
    if (chance(0.5)) {
      t.rocky = scene::RockyDesc{};
      kind(tex, "rocky", [&](YNode& m) {
        auto& r = *t.rocky;
        r.rms_m = num(m, "rms_m", r.rms_m, Range::closed(0, 5));
        r.beta = num(m, "beta", r.beta, Range::closed(2, 5));
        r.anisotropy = num(m, "anisotropy", r.anisotropy, Range::closed(1, 20));
        r.direction_deg = num(m, "direction_deg", r.direction_deg, Range::closed(0, 360));
        r.outer_scale_m = num(m, "outer_scale_m", r.outer_scale_m, Range::closed(0.1, 100));
      });
    }
    if (chance(0.5)) {
      t.clutter = scene::ClutterDesc{};
      kind(tex, "clutter", [&](YNode& m) {
        auto& c = *t.clutter;
        c.density_per_m2 = num(m, "density_per_m2", c.density_per_m2, Range::closed(0, 10));
        c.median_diameter_m =
            num(m, "median_diameter_m", c.median_diameter_m, Range::closed(0.02, 5));
        c.sigma_ln = num(m, "sigma_ln", c.sigma_ln, Range::closed(0, 2));
        c.height_ratio = num(m, "height_ratio", c.height_ratio, Range::closed(0.05, 2));
        c.max_diameter_m =
            num(m, "max_diameter_m", c.max_diameter_m, Range::at_least(c.median_diameter_m),
                Range::closed(c.median_diameter_m, c.median_diameter_m * 10));
      });
    }
    tex.map_or_null_ok = true;
    region.map.push_back({"texture", tex});
  }

  // a texture kind: a map of values, or "{}" / no value for all defaults
  template <class Fn>
  void kind(YNode& tex, const char* key, Fn&& fill) {
    YNode m = map_node();
    if (chance(0.7)) {
      fill(m);
      shuffle(m);
    }
    if (m.map.empty() && chance(0.5)) m = scalar("", YNode::Accepts::kNothing);
    tex.map.push_back({key, m});
  }

  void targets_section(YNode& root, scene::SceneDesc& s) {
    const double u = rng_.uniform();
    if (u < 0.25) return;
    YNode list = section_list();
    const auto n = u < 0.35 ? 0 : 1 + rng_.below(4);
    std::map<targets::TargetType, int> per_type;
    const auto types = targets::target_type_table();
    const auto materials = targets::material_table();
    const Vec2 lo = s.seabed.origin_m;
    const Vec2 hi = s.seabed.origin_m + s.seabed.extent_m;
    const std::array<Range, 2> inside{Range::closed(lo.x(), hi.x()), Range::closed(lo.y(), hi.y())};
    for (std::uint64_t i = 0; i < n; ++i) {
      YNode m = map_node();
      scene::TargetDesc t;
      if (chance(0.8)) {
        t.type = types[rng_.below(types.size())].type;
        m.map.push_back({"type", scalar(std::string(targets::target_type_info(t.type).key),
                                        YNode::Accepts::kName)});
      }
      const int ordinal = ++per_type[t.type];
      t.name = std::string(targets::target_type_info(t.type).key) + "-" + std::to_string(ordinal);
      if (chance(0.5)) {
        // formatted, then moved in: GCC 12 -O3 warns falsely (-Wrestrict) on string appends here
        char buf[48];
        std::snprintf(buf, sizeof buf, "t%d_%d", static_cast<int>(i),
                      static_cast<int>(rng_.below(1000)));
        t.name = std::string(buf);
        m.map.push_back({"name", scalar(t.name, YNode::Accepts::kText)});
      }
      t.position_m = vec2(m, "position_m", t.position_m, inside, Range::any(), true);
      t.heading_deg = num(m, "heading_deg", t.heading_deg, Range::closed(0, 360));
      const Vec3 nominal = targets::target_type_info(t.type).size_m;
      const double mode = rng_.uniform();
      if (mode < 0.33) {
        const Range each = Range::closed(0.05, 20);
        t.size_m = Vec3(draw(each), draw(each), draw(each));
        m.map.push_back(
            {"size_m", vec({t.size_m.x(), t.size_m.y(), t.size_m.z()}, {each, each, each})});
      } else if (mode < 0.66) {
        const double scale = draw(Range::closed(0.1, 10));
        t.size_m = nominal * scale;
        m.map.push_back({"scale", real(scale, Range::closed(0.1, 10))});
      } else {
        t.size_m = nominal;
      }
      material(m, t.material, materials);
      t.burial_m = num(m, "burial_m", t.burial_m, Range::closed(0, t.size_m.z()));
      shuffle(m);
      if (chance(0.3)) {
        bool leaves = true;
        for (const auto& kv : m.map)
          leaves = leaves && !is_block(kv.value);
        m.flow = leaves;
      }
      list.list.push_back(m);
      s.targets.push_back(t);
    }
    if (list.list.empty()) list.flow = true;
    root.map.push_back({"targets", list});
  }

  void material(YNode& m, scene::MaterialDesc& mat,
                std::span<const targets::NamedMaterial> materials) {
    const double u = rng_.uniform();
    if (u < 0.3) return;
    if (u < 0.7) {
      const auto& named = materials[rng_.below(materials.size())];
      mat.density_kg_m3 = named.density_kg_m3;
      mat.sound_speed_m_s = named.sound_speed_m_s;
      YNode n = scalar(std::string(named.key), YNode::Accepts::kName);
      n.map_or_null_ok = true;
      m.map.push_back({"material", n});
      return;
    }
    YNode n = map_node();
    mat.density_kg_m3 = num(n, "density_kg_m3", mat.density_kg_m3, Range::closed(500, 25000));
    mat.sound_speed_m_s = num(n, "sound_speed_m_s", mat.sound_speed_m_s, Range::closed(300, 15000));
    n.flow = chance(0.5);
    n.map_or_null_ok = true;
    m.map.push_back({"material", n});
  }

  // key order must not matter
  void shuffle(YNode& m) {
    for (std::size_t i = m.map.size(); i > 1; --i) {
      std::swap(m.map[i - 1], m.map[rng_.below(i)]);
    }
  }

  Rng rng_;
};

// Every place in the tree a corruption can be made.
struct Site {
  YNode* node;
  YNode* parent_map;  // the map holding `node` under a key, if any
  std::string path;
};

void collect_sites(YNode& n, YNode* parent_map, const std::string& path, std::vector<Site>& out) {
  out.push_back({&n, parent_map, path});
  if (n.kind == YNode::Kind::kMap) {
    for (auto& [key, v] : n.map)
      collect_sites(v, &n, path.empty() ? key : path + "." + key, out);
  } else if (n.kind == YNode::Kind::kList && n.accepts == YNode::Accepts::kSection) {
    for (std::size_t i = 0; i < n.list.size(); ++i) {
      collect_sites(n.list[i], nullptr, path + "[" + std::to_string(i) + "]", out);
    }
  }
}

// A value outside `r` (below or above), if r has a finite end.
std::optional<double> outside(const Range& r, Rng& rng) {
  std::vector<double> bad;
  if (std::isfinite(r.lo))
    bad.push_back(r.lo_open ? r.lo : r.lo - 0.5 * std::max(std::fabs(r.lo), 1.0));
  if (std::isfinite(r.hi))
    bad.push_back(r.hi_open ? r.hi : r.hi + 0.5 * std::max(std::fabs(r.hi), 1.0));
  if (bad.empty()) return std::nullopt;
  return bad[rng.below(bad.size())];
}

template <class T>
T one_of(const std::vector<T>& v, Rng& rng) {
  return v[rng.below(v.size())];
}

// Mutates one site so that the scene becomes invalid. Returns a description and sets
// `expect_path` to the path the error must name ("" = any path).
std::string corrupt(const Site& site, Rng& rng, std::string& expect_path) {
  YNode& n = *site.node;
  expect_path = site.path;
  using A = YNode::Accepts;
  const auto set_scalar = [&](const std::string& text) {
    n = scalar(text, A::kNothing);
    return "set " + site.path + " to '" + text + "'";
  };
  if (n.kind == YNode::Kind::kMap) {
    if (site.path.empty() || rng.uniform() < 0.5) {
      n.map.push_back({"zz_unknown_key", scalar("1", A::kNothing)});
      expect_path = site.path.empty() ? "zz_unknown_key" : site.path + ".zz_unknown_key";
      return "added " + expect_path;
    }
    if (!n.map.empty() && rng.uniform() < 0.5) {
      auto& entry = n.map[rng.below(n.map.size())];
      entry.key += "_x";
      expect_path.clear();  // the default of the renamed key may be what fails first
      return "renamed a key of " + site.path + " to " + entry.key;
    }
    return set_scalar(one_of<std::string>({"[1, 2]", "[]"}, rng));
  }
  switch (n.accepts) {
    case A::kReal: {
      std::vector<std::string> bad{"abc",    ".nan", ".inf",  "-.inf", "'5'",  "[1, 2]",
                                   "{a: 1}", "~",    "1e999", "0x1F",  "true", "1.2.3"};
      if (auto v = outside(n.ranges.front(), rng)) {
        for (int k = 0; k < 6; ++k)
          bad.push_back(real_text(*v));
      }
      return set_scalar(one_of(bad, rng));
    }
    case A::kUInt:
      return set_scalar(
          one_of<std::string>({"-1", "1.5", "abc", "99999999999999999999999", "[1]", "~"}, rng));
    case A::kName: {
      std::vector<std::string> bad{"zz_no_such_name", "[1, 2]"};
      if (!n.map_or_null_ok) bad.insert(bad.end(), {"{a: 1}", "~"});
      return set_scalar(one_of(bad, rng));
    }
    case A::kText:
      return set_scalar(one_of<std::string>({"[1, 2]", "{a: 1}", "~"}, rng));
    case A::kVector: {
      const double u = rng.uniform();
      if (u < 0.5) {
        const std::size_t k = rng.below(n.list.size());
        std::vector<std::string> bad{"abc", ".nan", "[1]", "'3'"};
        if (auto v = outside(n.ranges[k], rng)) {
          for (int j = 0; j < 4; ++j)
            bad.push_back(real_text(*v));
        }
        n.list[k].text = one_of(bad, rng);
        return "set " + site.path + "[" + std::to_string(k) + "] to '" + n.list[k].text + "'";
      }
      if (u < 0.7) {
        n.list.pop_back();
        return "shortened " + site.path;
      }
      if (u < 0.8) {
        n.list.push_back(scalar("1", A::kNothing));
        return "lengthened " + site.path;
      }
      return set_scalar(one_of<std::string>({"5", "{a: 1}", "~", "abc"}, rng));
    }
    case A::kSection:
      return set_scalar(one_of<std::string>({"5", "{a: 1}", "abc"}, rng));
    case A::kNothing:
      break;
  }
  return "";
}

}  // namespace

TEST_CASE("scene_loader: random valid scenarios round-trip, corruptions are rejected") {
  constexpr int kSamples = 300;
  constexpr int kCorruptionsPerSample = 6;
  int corruptions = 0;
  for (int sample = 0; sample < kSamples; ++sample) {
    ScenarioGenerator gen(static_cast<std::uint64_t>(sample));
    scene::SceneDesc expect;
    YNode root;
    const std::string file = "random-" + std::to_string(sample) + ".yaml";
    gen.generate(expect, root, "random-" + std::to_string(sample));
    const std::string yaml = to_yaml(root);
    INFO("sample " << sample << ":\n" << yaml);
    scene::SceneDesc got;
    try {
      got = parse_scene(yaml, file);
    } catch (const ConfigError& e) {
      FAIL("valid scenario rejected: " << e.what());
    }
    check_same(got, expect);

    for (int c = 0; c < kCorruptionsPerSample; ++c) {
      YNode bad = root;
      std::vector<Site> sites;
      collect_sites(bad, nullptr, "", sites);
      // only sites where a corruption can be made
      std::vector<Site> usable;
      for (const auto& s : sites) {
        if (s.node->kind == YNode::Kind::kMap || s.node->accepts != YNode::Accepts::kNothing) {
          usable.push_back(s);
        }
      }
      REQUIRE_FALSE(usable.empty());
      std::string expect_path;
      const std::string what = corrupt(one_of(usable, gen.rng()), gen.rng(), expect_path);
      const std::string bad_yaml = to_yaml(bad);
      INFO("corruption: " << what << "\n" << bad_yaml);
      ++corruptions;
      try {
        parse_scene(bad_yaml, file);
        FAIL("corrupted scenario accepted");
      } catch (const ConfigError& e) {
        const std::string msg = e.what();
        INFO("message: " << msg);
        CHECK(msg.rfind(file + ": ", 0) == 0);
        CHECK(contains(msg, "; allowed: "));
        if (!expect_path.empty()) {
          const std::string& p = e.first().path;
          CHECK((p == expect_path || p.rfind(expect_path + "[", 0) == 0));
        }
      } catch (const std::exception& e) {
        FAIL("not a ConfigError: " << e.what());
      }
    }
  }
  CHECK(corruptions == kSamples * kCorruptionsPerSample);
}

TEST_CASE("scene_loader: random byte edits give a scene or a ConfigError, never a crash") {
  // yaml-cpp itself is exercised here too: this found the stray-',' endless loop of
  // yaml-cpp 0.7 that parse_document works around
  Rng rng(7, RngStream::kDataset, 99);
  const auto n =
      feed_byte_edits(kFullScenario, rng, 5000,
                      [](const std::string& text, const char* name) { parse_scene(text, name); });
  CHECK(n.accepted > 0);
  CHECK(n.rejected > n.accepted);
}
