#pragma once
// Detection annotations of a rendered waterfall for `sonarloop render`: one box per target, per
// side and per part (highlight, shadow) around the pixels labelled so in labels.png
// (WaterfallData::label), written as a COCO-style annotations.json for detection learners.
//
// Attribution: a labelled pixel (ping p, side, sample b) belongs to the target whose truth trace
// in ping p on that side (render::TargetTrace: the bins of its echoes, or of the seabed it hides)
// is nearest to b in bins (0 inside it; ties to the lower target index); failing that, the
// nearest trace of the other part. A pixel with no trace at all in its ping and side (which the
// renderers do not produce: a label comes from the same rays as the traces) is left out and
// counted. So every box holds every labelled pixel attributed to it, and a target whose echoes
// never dominate a bin (or whose shadow never hides most of one) has no box of that part.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "products/waterfall.h"
#include "sim/render/ping_renderer.h"
#include "sim/targets/target_type.h"

namespace sonarloop::products {

// A labelled part of one target on one side, in waterfall.png pixels (column x, row y; the
// box's corners are pixel indices, inclusive).
struct LabelBox {
  int target = -1;  // PlacedTarget::index
  int side = 0;     // 0 port, 1 starboard
  std::uint8_t part = render::kLabelHighlight;
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  std::int64_t pixels = 0;  // labelled pixels attributed to it
};

struct LabelBoxes {
  std::vector<LabelBox> boxes;  // sorted by target, side, part
  std::int64_t unattributed = 0;
};

// traces_by_ping[p]: the truth traces of ping p (PingScratch::traces with RenderOptions::truth).
LabelBoxes label_boxes(const WaterfallData& w,
                       std::span<const std::vector<render::TargetTrace>> traces_by_ping);

// A target of the scene, for the annotations.
struct AnnotatedTarget {
  std::string name;
  targets::TargetType type = targets::TargetType::kManta;
};

// Writes annotations.json: images (the waterfall), categories (every target type, id = its
// position in the type table + 1, so that ids agree across renders), annotations (one per box,
// bbox [x, y, width, height] in pixels from the top-left corner of the top-left pixel, area =
// labelled pixels, attributes: part, target name, side).
void write_coco_annotations(const std::string& path, const WaterfallData& w,
                            const LabelBoxes& boxes, std::span<const AnnotatedTarget> targets,
                            const std::string& image_file, const std::string& label_file);

}  // namespace sonarloop::products
