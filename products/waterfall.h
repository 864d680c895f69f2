#pragma once
// Waterfall images of rendered pings for `sonarloop render`: slant-range (port far range on the
// left, starboard far range on the right, one row per ping, the last ping at the top so that a
// north-going track reads north-up) and ground-range corrected. 8-bit, log-compressed: the grey
// level spans the seabed's amplitude range in dB, from its 1st to its 99.5th percentile (at most
// 40 dB), measured on the samples beyond each ping's altitude.
#include <cstdint>
#include <string>
#include <vector>

namespace sonarloop::products {

struct WaterfallData {
  int bins = 0;  // per side
  double bin_size_m = 0.0;
  std::vector<float> amplitude;    // pings x (2 * bins): [port near..far | stbd near..far]
  std::vector<double> altitude_m;  // per ping, for the ground-range correction
  // pings x (2 * bins), laid out as amplitude: the ping renderer's per-bin labels (kLabelSeabed,
  // kLabelHighlight, kLabelShadow of sim/render/ping_renderer.h); empty when not rendered
  std::vector<std::uint8_t> label;
  int pings() const { return bins > 0 ? static_cast<int>(amplitude.size() / (2 * bins)) : 0; }
};

// Column of sample `bin` of side 0 (port) or 1 (starboard) in the slant-range image.
inline int waterfall_column(int bins, int side, int bin) {
  return side == 0 ? bins - 1 - bin : bins + bin;
}

void write_waterfall_png(const std::string& path, const WaterfallData& w);
// The labels as an 8-bit PNG aligned pixel for pixel with write_waterfall_png's image; pixel
// values are the labels themselves (0, 1, 2), not visible grey levels.
void write_label_png(const std::string& path, const WaterfallData& w);
// Ground range 0 .. max on each side at the bin size; samples nearer than the altitude (the
// water column) are left black.
void write_ground_waterfall_png(const std::string& path, const WaterfallData& w);

}  // namespace sonarloop::products
