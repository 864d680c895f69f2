#pragma once
// The onboard detector: finds mine-like objects in the waterfall as a bright highlight followed
// (in range) by an acoustic shadow, and reports each object once.
//
// A proud object on the seabed returns a strong echo from the faces that look at the sonar and
// hides the seabed behind it (Pailhas, Petillot & Capus 2010, Sec. 2.3 and 4.2: "highlight and
// shadow"). Seabed texture does one of the two at a time: ripple crests and rough patches are
// bright without a deep shadow behind them; troughs and relief cast shadows without a strong echo
// before them; small rocks do both but over a short shadow. The detector therefore asks for both,
// and for a shadow long enough for an object at least min_height_m tall.
//
// Per ping and side (levels in dB re full scale, atr/waterfall.h):
//   1. Background B: the seabed's local level, robust to objects and speckle. The swath beyond
//      min_ground_m is cut into blocks of background_block_m; B of a bin is the median of the
//      medians of the background_blocks blocks around its own (a 7 m window by default).
//   2. Shadow runs: consecutive bins with L <= B - shadow_below_db (single-bin gaps bridged) over
//      at least shadow_min_m of slant range. A real shadow holds no echo at all, only noise
//      (-75 dB re full scale for the default sonar, 40-60 dB under the seabed); speckle alone
//      (exponential intensity) falls 20 dB under its median with probability 1 - exp(-0.0069)
//      = 0.7 % per bin, three bins in a row 3e-7.
//   3. Ping detection: a shadow run with a highlight bin, L >= B + highlight_above_db and
//      L >= highlight_min_db, at most highlight_before_m before its start (the echo of the
//      object's near faces; an end-on cuboid shows its top face between the two).
// Over pings:
//   4. Objects: ping detections of one side are linked when their pings lie at most
//      link_along_m apart along track (footprint positions, see below) and their slant extents
//      (highlight to shadow end) overlap.
//   5. Gates, when an object is complete (the sonar has moved link_along_m past its last ping):
//      at least min_pings pings; along-track extent in [min_along_m, max_along_m] (ripple and
//      relief shadows run for metres); slant extent at most max_range_extent_m; height from the
//      shadow at least min_height_m. Height: a shadow from ground range g0 to g1 behind an object
//      seen from altitude a means an object of height h = (g1 - g0) · a / g1 (similar
//      triangles, flat seabed); the object's height is the second largest over its pings (one
//      ping running into a trough does not make an object).
//   6. Non-maximum suppression: an object is decided once the sonar is settle_m past it; it is
//      dropped if an object already reported, or a stronger one still undecided, lies within
//      min_separation_m (ground distance). Score = shadow area (m²), so one object is one
//      contact even when its highlight and shadow break into pieces.
//
// Along-track positions. A ping's strip does not lie under the sonar when the vehicle pitches:
// the beam plane (perpendicular to the body's x axis) tilts with it, and a seabed point at depth
// d below the sonar is displaced forward by d·tan(pitch) (pitch + nose up; rotation
// R_y(pitch) maps the body down axis to (sin θ, 0, cos θ)). With the default scenario's terrain
// following (pitch up to 6 deg at 7.5 m altitude) that is up to 0.8 m, more than the objects. Each
// ping's footprint is therefore at along_m + altitude · tan(pitch) (footprint_along_m,
// atr/waterfall.h), and objects, chips and reports use footprint positions.
//
// Measured on the default scenario (config/default.yaml, 45 s, 669 pings; `sonarloop run
// --classify`): 281 ping detections, 123 objects, 116 rejected by the gates, 7 reported: the four
// targets and three rocks of the cluttered gravel (0.19-0.26 m shadow heights over 2 pings).
//
// Streaming and cost: process() is called once per ping added to the waterfall and returns the
// objects decided at that ping (at most a few). No allocation per ping once sized (the first ping,
// or a geometry change); the pools of open objects (kMaxOpenObjects per side) and pending
// decisions are fixed; an overflow is counted and the oldest object is closed early.
#include <cstdint>
#include <span>
#include <vector>

#include "atr/waterfall.h"

namespace sonarloop::atr {

struct DetectorOptions {
  double min_ground_m = 2.0;         // ground range where the search starts (nadir returns before)
  double background_block_m = 1.0;   // block length of the background medians (slant)
  int background_blocks = 7;         // blocks in a background window (odd)
  double highlight_above_db = 10.0;  // highlight: L >= B + this ...
  double highlight_min_db = -10.0;   // ... and L >= this (dB re full scale)
  double shadow_below_db = 20.0;     // shadow: L <= B - this
  double shadow_min_m = 0.15;        // shortest shadow run (slant)
  double highlight_before_m = 1.2;   // longest highlight-to-shadow distance (slant)
  double link_along_m = 0.45;        // largest along-track gap inside one object
  int min_pings = 2;
  double min_along_m = 0.1;
  double max_along_m = 2.5;
  double max_range_extent_m = 3.0;
  double min_height_m = 0.18;     // mine-like targets are 0.3-0.5 m tall
  double min_separation_m = 1.5;  // between two contacts (ground)
  double settle_m = 2.5;          // decide an object once the sonar is this far past it

  // Throws std::invalid_argument naming the first value out of range.
  void validate() const;
};

inline constexpr int kMaxOpenObjects = 64;      // per side
inline constexpr int kMaxPendingObjects = 64;   // gated, waiting for their decision
inline constexpr int kMaxRecentContacts = 256;  // reported, remembered for suppression

// One object, as reported.
struct Detection {
  int side = 0;                               // 0 port, 1 starboard
  std::uint64_t first_seq = 0, last_seq = 0;  // its pings in the waterfall
  std::uint64_t centre_seq = 0;               // the ping nearest its along-track centre
  int pings = 0;
  double along_m = 0.0;              // footprint along-track position of its centre
  double along_extent_m = 0.0;       // first to last ping
  double slant_m = 0.0;              // slant range of its centre (highlight to shadow start, mean)
  double ground_m = 0.0;             // ground range of that point from the centre ping's altitude
  double near_m = 0.0, far_m = 0.0;  // slant extent: first highlight bin to last shadow bin
  double height_m = 0.0;             // from the shadow
  double shadow_area_m2 = 0.0;       // slant length x ping spacing, summed: the score
  double highlight_db = -300.0;      // strongest highlight bin
};

struct DetectorStats {
  std::uint64_t pings = 0;              // processed
  std::uint64_t pings_no_altitude = 0;  // skipped: no altitude
  std::uint64_t ping_detections = 0;
  std::uint64_t objects = 0;     // complete objects
  std::uint64_t rejected = 0;    // by the gates
  std::uint64_t suppressed = 0;  // by non-maximum suppression
  std::uint64_t reported = 0;
  std::uint64_t overflows = 0;  // pool full: an object closed early
};

class Detector {
 public:
  explicit Detector(const DetectorOptions& options = {});

  // Processes the newest ping of `w` (w.newest_seq()). Returns the objects decided at this ping,
  // valid until the next call.
  std::span<const Detection> process(const Waterfall& w);
  // Decides every object still open or pending (end of stream).
  std::span<const Detection> finish(const Waterfall& w);
  // Forgets everything (the waterfall was reset).
  void reset();

  const DetectorOptions& options() const { return options_; }
  const DetectorStats& stats() const { return stats_; }

  // The background of one line (for tests and displays): out[k] = B of bin k (bins before the
  // search start get the first block's value). Allocation-free once sized.
  void background(std::span<const float> levels, double bin_size_m, int start_bin,
                  std::span<float> out);

 private:
  struct Object {
    int side = 0;
    std::uint64_t first_seq = 0, last_seq = 0;
    double first_along = 0.0, last_along = 0.0;
    int near_bin = 0, far_bin = 0;
    int pings = 0;
    double centre_sum = 0.0;  // sum of (highlight + shadow start) / 2 over ping detections
    int centre_count = 0;
    double along_sum = 0.0;
    double area_m2 = 0.0;
    double height1 = 0.0, height2 = 0.0;  // largest and second largest
    double highlight_db = -300.0;
  };

  void configure(const Waterfall& w);
  void detect_side(const Waterfall& w, std::uint64_t seq, int side, double footprint_along);
  void add_ping_detection(const Waterfall& w, std::uint64_t seq, int side, double along,
                          int highlight_bin, int shadow_begin, int shadow_end, float peak_db);
  void close_objects(const Waterfall& w, double along_now, int side, bool all);
  void retire(const Waterfall& w, int side, std::size_t index);  // gates, then removes
  void decide(double along_now, bool all);
  Detection to_detection(const Waterfall& w, const Object& o) const;

  DetectorOptions options_;
  DetectorStats stats_;
  int bins_ = 0;
  double bin_size_m_ = 0.0;
  std::vector<float> block_median_;
  std::vector<float> block_background_;
  std::vector<float> scratch_;
  std::vector<float> background_;
  std::vector<Object> open_[2];
  std::vector<Detection> pending_;
  std::vector<Detection> recent_;  // ring of reported contacts
  std::size_t recent_next_ = 0;
  std::vector<Detection> out_;
};

}  // namespace sonarloop::atr
