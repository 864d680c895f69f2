#include "products/waterfall_annotations.h"

#include <algorithm>
#include <climits>
#include <fstream>
#include <map>
#include <stdexcept>
#include <tuple>

#include "drivers/json/json_writer.h"

namespace sonarloop::products {
namespace {

using render::kLabelHighlight;
using render::kLabelShadow;

// Distance in bins from `bin` to [first, last]; INT_MAX when the range is empty (-1).
int bins_away(int bin, int first, int last) {
  if (first < 0) return INT_MAX;
  if (bin < first) return first - bin;
  if (bin > last) return bin - last;
  return 0;
}

// The target a labelled bin of `part` belongs to (see the header), or -1.
int attribute(std::span<const render::TargetTrace> traces, int side, int bin, std::uint8_t part) {
  for (const bool same_part : {true, false}) {
    int best = -1, best_d = INT_MAX;
    for (const render::TargetTrace& tr : traces) {
      if (tr.side != side) continue;
      const bool highlight = (part == kLabelHighlight) == same_part;
      const int d = highlight ? bins_away(bin, tr.highlight_first, tr.highlight_last)
                              : bins_away(bin, tr.shadow_first, tr.shadow_last);
      if (d < best_d || (d == best_d && d < INT_MAX && tr.target < best)) {
        best_d = d;
        best = tr.target;
      }
    }
    if (best >= 0) return best;
  }
  return -1;
}

}  // namespace

LabelBoxes label_boxes(const WaterfallData& w,
                       std::span<const std::vector<render::TargetTrace>> traces_by_ping) {
  const int n = w.pings();
  if (w.label.size() != w.amplitude.size() ||
      traces_by_ping.size() != static_cast<std::size_t>(n)) {
    throw std::logic_error("label_boxes: labels and traces must cover every ping");
  }
  std::map<std::tuple<int, int, int>, LabelBox> by_key;  // (target, side, part)
  LabelBoxes out;
  const auto row_len = static_cast<std::size_t>(2 * w.bins);
  for (int p = 0; p < n; ++p) {
    const std::uint8_t* row = w.label.data() + static_cast<std::size_t>(p) * row_len;
    const auto& traces = traces_by_ping[static_cast<std::size_t>(p)];
    for (int side = 0; side < 2; ++side) {
      for (int b = 0; b < w.bins; ++b) {
        const std::uint8_t part = row[side * w.bins + b];
        if (part != kLabelHighlight && part != kLabelShadow) continue;
        const int target = attribute(traces, side, b, part);
        if (target < 0) {
          ++out.unattributed;
          continue;
        }
        // waterfall.png: ping p at row pings-1-p, the sample at waterfall_column()
        const int x = waterfall_column(w.bins, side, b);
        const int y = n - 1 - p;
        LabelBox& box = by_key[{target, side, part}];
        if (box.pixels == 0) box = LabelBox{target, side, part, x, y, x, y, 0};
        box.x0 = std::min(box.x0, x);
        box.x1 = std::max(box.x1, x);
        box.y0 = std::min(box.y0, y);
        box.y1 = std::max(box.y1, y);
        ++box.pixels;
      }
    }
  }
  for (const auto& kv : by_key)
    out.boxes.push_back(kv.second);
  return out;
}

void write_coco_annotations(const std::string& path, const WaterfallData& w,
                            const LabelBoxes& boxes, std::span<const AnnotatedTarget> targets,
                            const std::string& image_file, const std::string& label_file) {
  json::Writer j(true);
  j.begin_object();
  j.key("info").begin_object();
  j.field("description", "sonarloop render: target highlights and shadows on " + image_file);
  j.field("labels", label_file +
                        ": per pixel 0 seabed, 1 target highlight, 2 target shadow (values, not "
                        "grey levels), aligned with " +
                        image_file);
  j.field("bbox",
          "[x, y, width, height] in pixels, x right and y down from the top-left corner of the "
          "top-left pixel; area = the labelled pixels in the box's part");
  j.field("unattributed_pixels", static_cast<std::int64_t>(boxes.unattributed));
  j.end_object();
  j.key("images").begin_array();
  j.begin_object()
      .field("id", 1)
      .field("file_name", image_file)
      .field("label_file", label_file)
      .field("width", 2 * w.bins)
      .field("height", std::max(w.pings(), 1))
      .end_object();
  j.end_array();
  j.key("categories").begin_array();
  const auto table = targets::target_type_table();
  for (std::size_t i = 0; i < table.size(); ++i) {
    j.begin_object()
        .field("id", static_cast<int>(i) + 1)
        .field("name", table[i].key)
        .field("supercategory", table[i].mine_like ? "mine_like" : "non_mine_like")
        .end_object();
  }
  j.end_array();
  j.key("annotations").begin_array();
  int id = 0;
  for (const LabelBox& b : boxes.boxes) {
    const AnnotatedTarget& t = targets[static_cast<std::size_t>(b.target)];
    const auto type = std::find_if(table.begin(), table.end(),
                                   [&](const auto& info) { return info.type == t.type; });
    j.begin_object()
        .field("id", ++id)
        .field("image_id", 1)
        .field("category_id", static_cast<int>(type - table.begin()) + 1);
    j.key("bbox")
        .begin_array()
        .value(b.x0)
        .value(b.y0)
        .value(b.x1 - b.x0 + 1)
        .value(b.y1 - b.y0 + 1)
        .end_array();
    j.field("area", static_cast<std::int64_t>(b.pixels)).field("iscrowd", 0);
    j.key("attributes")
        .begin_object()
        .field("part", b.part == kLabelHighlight ? "highlight" : "shadow")
        .field("target", t.name)
        .field("side", b.side == 0 ? "port" : "starboard")
        .end_object();
    j.end_object();
  }
  j.end_array();
  j.end_object();
  std::ofstream out(path);
  out << j.str() << '\n';
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
}

}  // namespace sonarloop::products
