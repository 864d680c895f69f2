#pragma once
// The chip convention: what a target chip is, shared by the side that renders chips (the
// simulator, sim/render/chip_renderer.h) and the side that cuts them out of a live sonar stream
// and classifies them (atr/), so that a chip means the same on both without either depending on
// the other. After Pailhas, Petillot & Capus (2010), Section 4: isotropic pixels of size R
// (range bin = along-track resolution = ping spacing = R).
//
// Geometry (a fixed physical size per kind, so round(size / R) pixels a side):
//   highlight   3 m along track x 3 m slant range, centred on the slant range of the target's
//               centre (the middle of its bounding box) at closest approach;
//   shadow      3 m along track x 10 m slant range, from 1 m before the target's centre, with
//               the target at a fixed 25 m ground range (Section 4.2).
// Rows are pings along track, columns range bins from near to far. Starboard chips put the last
// ping in row 0 (the direction of travel points up, as on a waterfall display), port chips the
// first: either way a chip is the seabed seen from above (not mirrored), turned so that the sonar
// looks to the right, and a target at a given aspect looks the same on either side.
//
// Pixel values: the level L = 20·log10(A) in dB re full scale (A the relative amplitude after
// TVG) mapped as round(255·(L - min_db) / (max_db - min_db)), clipped to 0..255, over a FIXED
// span (ChipLevels, default -60..0 dB), never per-chip auto levels, so that chips compare across
// a dataset and with chips cut from a live stream.
#include <cstdint>

namespace sonarloop::chips {

enum class ChipKind { kHighlight, kShadow };

const char* chip_kind_name(ChipKind kind);  // "highlight", "shadow"

// Physical chip sizes (see the header comment).
inline constexpr double kHighlightChipAlong_m = 3.0;
inline constexpr double kHighlightChipRange_m = 3.0;
inline constexpr double kShadowChipAlong_m = 3.0;
inline constexpr double kShadowChipRange_m = 10.0;
inline constexpr double kShadowChipNear_m = 1.0;  // the window starts this far before the centre
// Section 4.2: shadow chips are taken at a fixed 25 m ground range.
inline constexpr double kShadowGroundRange_m = 25.0;

// Pixel mapping (see the header comment).
struct ChipLevels {
  double min_db = -60.0;  // pixel 0 (and below)
  double max_db = 0.0;    // pixel 255 (and above): full scale
};

// 8-bit pixel of a level (dB re full scale) over a span (see ChipLevels).
std::uint8_t chip_pixel(double level_db, const ChipLevels& levels);

}  // namespace sonarloop::chips
