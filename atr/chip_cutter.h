#pragma once
// Cuts classifier chips out of the live waterfall, in exactly the convention of the chips that
// `sonarloop dataset` renders and `sonarloop train` learns from (sim/render/chip_renderer.h):
//
//   size      highlight chips: 3 m along track x 3 m slant range (kHighlightChipAlong_m,
//             kHighlightChipRange_m), so a model of W x H pixels has pixels of 3/H m along
//             track and 3/W m in range (60 x 60 = 5 cm);
//   centre    the object's centre: its slant range at the middle column (the chip's range
//             window starts half a chip before it), its along-track position at the middle row;
//   columns   slant range, near to far;
//   rows      pings along track, one per pixel: starboard chips put the LAST ping in row 0, port
//             chips the FIRST, so that a chip is the seabed seen from above, not mirrored, with
//             the sonar looking to the right;
//   pixels    round(255 · (L + 60) / 60) clipped to 0..255 for the level L in dB re full scale
//             (chips::chip_pixel with the default ChipLevels), as floats 0..255 like a PNG chip
//             read by study/chip_folder.h.
//
// Along-track resampling. The dataset's chips have one ping per pixel (ping spacing = pixel
// size); a live sonar pings at its own rate (the default scenario: every 0.067 s at 2 m/s, one
// ping per 13 cm for 5 cm pixels) and its strip of seabed moves with pitch (atr/detector.h).
// Row k of a chip takes the ping whose FOOTPRINT along-track position (waterfall along_m +
// altitude · tan(pitch)) is nearest to the row's position, centre + (k - (rows - 1)/2) · pixel:
// nearest neighbour, not interpolation, because a row of the dataset is one ping's speckle, and
// interpolating two pings' speckle makes rows the classifier never saw (measured on 400 held-out
// dataset chips decimated to the live ping spacing: 76.8 % correct with nearest-ping rows,
// 71.0 % with rows interpolated in amplitude, 77.5 % undecimated).
//
// Range resampling. When the stream's bin size equals the chip's range pixel (the default: both
// 5 cm), columns are stream bins, the window snapped to the stream's bin grid. Otherwise each
// pixel is the mean intensity (power) of the stream bins it overlaps, weighted by the overlap.
//
// Context. The cutter cuts a larger chip, margin_rows and margin_cols pixels wider on every
// side, so that the classifier can slide the chip window over it (atr/aligned_classifier.h);
// window(dr, dc) moves the window dr rows down and dc columns right.
//
// Allocation: none per cut once the buffers are sized (at construction).
#include <cstdint>
#include <vector>

#include "atr/chip.h"
#include "atr/waterfall.h"
#include "common/chip_convention.h"

namespace sonarloop::atr {

// A row whose nearest ping is farther than this from its position makes the cut fail (pings
// missing from the stream): 1 m is more than 7 pings of the default sonar.
inline constexpr double kMaxRowGap_m = 1.0;

struct ChipSpec {
  int rows = 60;                // pixels along track (model chip_height)
  int cols = 60;                // pixels in range (model chip_width)
  double pixel_along_m = 0.05;  // kHighlightChipAlong_m / rows
  double pixel_range_m = 0.05;  // kHighlightChipRange_m / cols
  chips::ChipLevels levels;     // -60..0 dB
};

// The highlight-chip spec for a model's chip size. Throws std::invalid_argument for a size
// below 4 pixels.
ChipSpec highlight_chip_spec(int width, int height);

// Where to cut: an object's centre.
struct ChipCentre {
  int side = 1;          // 0 port, 1 starboard
  double along_m = 0.0;  // footprint along-track position
  double slant_m = 0.0;  // slant range
};

enum class CutStatus {
  kOk,
  kNotYet,   // the chip reaches beyond the newest ping
  kGone,     // the chip reaches before the oldest ping held
  kGap,      // a row's nearest ping is more than kMaxRowGap_m away
  kOutside,  // the range window leaves the swath
};
const char* cut_status_name(CutStatus s);

// The window of a context chip with the given margins, shifted by (dr, dc) from its centre
// (|dr| <= margin_rows, |dc| <= margin_cols; std::out_of_range otherwise), into `out`
// ((height - 2 margin_rows) x (width - 2 margin_cols); resized only if its size differs).
void copy_window(const Chip& context, int margin_rows, int margin_cols, int dr, int dc, Chip& out);

class ChipCutter {
 public:
  ChipCutter(const ChipSpec& spec, int margin_rows, int margin_cols);

  const ChipSpec& spec() const { return spec_; }
  int margin_rows() const { return margin_rows_; }
  int margin_cols() const { return margin_cols_; }

  // Cuts the context chip ((rows + 2 margin_rows) x (cols + 2 margin_cols)) centred on `c`.
  CutStatus cut(const Waterfall& w, const ChipCentre& c);
  const Chip& context() const { return context_; }
  // Rows whose nearest ping lay more than a ping spacing and a half away (lost pings) in the
  // last cut, and the largest row-to-ping distance (m).
  int gap_rows() const { return gap_rows_; }
  double max_row_distance_m() const { return max_row_distance_m_; }
  // The ping used for each context row in the last cut.
  const std::vector<std::uint64_t>& row_pings() const { return row_seq_; }

  // Copies the rows x cols window shifted by (dr, dc) from the centre (|dr| <= margin_rows,
  // |dc| <= margin_cols) into `out` (resized only if its size differs).
  void window(int dr, int dc, Chip& out) const {
    copy_window(context_, margin_rows_, margin_cols_, dr, dc, out);
  }

  // The centre of the window shifted by (dr, dc) from `c`: rows run against the along-track
  // direction on starboard (last ping on top) and with it on port.
  ChipCentre shifted(const ChipCentre& c, int dr, int dc) const;

 private:
  void fill_row(const Waterfall& w, std::uint64_t seq, int side, double first_edge_m, float* row);

  ChipSpec spec_;
  int margin_rows_;
  int margin_cols_;
  Chip context_;
  std::vector<std::uint64_t> candidates_seq_;
  std::vector<double> candidates_along_;
  std::vector<std::uint64_t> row_seq_;
  int gap_rows_ = 0;
  double max_row_distance_m_ = 0.0;
};

}  // namespace sonarloop::atr
