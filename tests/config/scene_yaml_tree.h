#pragma once
// The scene loader's randomized test (scene_loader_random_test.cpp) builds each random scenario
// as a YAML tree, writes it out as text (block or flow style) and mutates the tree to make
// corruptions: the tree, its builders and its writer.
#include <string>
#include <utility>
#include <vector>

#include "config/loader/yaml_fields.h"
#include "tests/config/config_test_text.h"

namespace sonarloop::config::scene_loader_checks {

using sonarloop::testing::real_text;

struct YEntry;

// A YAML tree built by the generator, written out as text, and mutated for corruptions.
struct YNode {
  enum class Kind { kScalar, kMap, kList };
  // what the loader accepts at this node, so that a corruption can be made that it must reject
  enum class Accepts { kNothing, kReal, kUInt, kName, kText, kVector, kSection };
  Kind kind = Kind::kScalar;
  std::string text;
  std::vector<YEntry> map;  // in order
  std::vector<YNode> list;
  bool flow = false;
  Accepts accepts = Accepts::kNothing;
  std::vector<Range> ranges;    // kReal: one; kVector: one per component
  bool map_or_null_ok = false;  // material, texture: a map or no value is valid too
};

struct YEntry {
  std::string key;
  YNode value;
};

inline YNode scalar(std::string text, YNode::Accepts a) {
  YNode n;
  n.text = std::move(text);
  n.accepts = a;
  return n;
}

inline YNode real(double v, const Range& r) {
  YNode n = scalar(real_text(v), YNode::Accepts::kReal);
  n.ranges = {r};
  return n;
}

inline YNode vec(const std::vector<double>& v, const std::vector<Range>& r) {
  YNode n;
  n.kind = YNode::Kind::kList;
  n.flow = true;
  n.accepts = YNode::Accepts::kVector;
  n.ranges = r;
  for (double x : v)
    n.list.push_back(scalar(real_text(x), YNode::Accepts::kNothing));
  return n;
}

inline YNode map_node() {
  YNode n;
  n.kind = YNode::Kind::kMap;
  return n;
}

inline YNode section_list() {
  YNode n;
  n.kind = YNode::Kind::kList;
  n.accepts = YNode::Accepts::kSection;
  return n;
}

inline std::string flow_text(const YNode& n) {
  switch (n.kind) {
    case YNode::Kind::kScalar:
      return n.text.empty() ? "~" : n.text;
    case YNode::Kind::kList: {
      std::string out = "[";
      for (std::size_t i = 0; i < n.list.size(); ++i)
        out += (i ? ", " : "") + flow_text(n.list[i]);
      return out + "]";
    }
    case YNode::Kind::kMap: {
      std::string out = "{";
      for (std::size_t i = 0; i < n.map.size(); ++i) {
        out += (i ? ", " : "") + n.map[i].key + ": " + flow_text(n.map[i].value);
      }
      return out + "}";
    }
  }
  return "";
}

inline bool is_block(const YNode& n) {
  return n.kind != YNode::Kind::kScalar && !n.flow &&
         !(n.kind == YNode::Kind::kMap ? n.map.empty() : n.list.empty());
}

inline void write_block(const YNode& n, int indent, std::string& out) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  if (n.kind == YNode::Kind::kMap) {
    for (const auto& [key, v] : n.map) {
      out += pad + key + ":";
      if (is_block(v)) {
        out += "\n";
        write_block(v, indent + 2, out);
      } else {
        const std::string t = v.kind == YNode::Kind::kScalar ? v.text : flow_text(v);
        out += (t.empty() ? "" : " " + t) + "\n";
      }
    }
    return;
  }
  for (const auto& item : n.list) {
    if (is_block(item)) {
      // the item's first line starts with "- " in place of two spaces of indentation
      std::string sub;
      write_block(item, indent + 2, sub);
      out += pad + "- " + sub.substr(static_cast<std::size_t>(indent) + 2);
    } else {
      out += pad + "- " + flow_text(item) + "\n";
    }
  }
}

inline std::string to_yaml(const YNode& root) {
  std::string out = "# generated\n";
  write_block(root, 0, out);
  return out;
}

}  // namespace sonarloop::config::scene_loader_checks
