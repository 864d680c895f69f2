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
//      relief shadows run for metres); height from the shadow at least min_height_m and at most
//      max_height_m (a longer shadow is relief, not an object: the tallest target is 0.5 m; the
//      shadow of a 0.5 m object 45 m out from 7.5 m altitude is 3.2 m long, so the height, not
//      the slant extent, is what bounds an object in range). Height: a shadow from ground range g0
//      to g1 behind an object seen from altitude a means an object of height h = (g1 - g0) · a / g1
//      (similar triangles, flat seabed); the object's height is the second largest over its pings
//      (one ping running into a trough does not make an object).
//   6. Non-maximum suppression: an object is decided once the sonar is settle_m past it; it is
//      dropped if a candidate of higher score (decided before it, or still undecided) lies
//      within min_separation_m (ground distance), so one object is one contact even when its
//      highlight and shadow break into pieces.
//
// Score and operating threshold. A candidate's score is its height from the shadow (step 5):
// what the detector looks for is an object proud of the seabed, and the height gate is its
// operating threshold. Every object that passes the shape gates (pings, extents) with a height
// of at least candidate_min_height_m (the floor, below min_height_m) goes through the
// suppression, ranked by score; it is reported when it survives and its score reaches
// min_height_m. Since a candidate is suppressed only by candidates of higher score, the
// contacts at any threshold h >= the floor are exactly the survivors with score >= h: the curve
// of detection against false alarms over the threshold (FROC) comes from one pass over the
// candidates (candidates(), with their fate), not one run per threshold.
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
  double link_along_m = 0.7;         // largest along-track gap inside one object
  int min_pings = 2;
  double min_along_m = 0.1;
  double max_along_m = 2.5;
  double max_height_m = 1.5;  // taller shadows are relief
  // the operating threshold; the targets are 0.25-0.5 m tall, but a shadow broken by speckle or
  // cut by the relief measures less: 0.14 m detects 101 of the 105 targets of the five survey
  // scenarios, 0.18 m 99 (docs/autonomy.md, the detector's FROC)
  double min_height_m = 0.14;
  double candidate_min_height_m = 0.10;  // the floor of the candidates kept (<= min_height_m)
  double min_separation_m = 1.5;         // between two contacts (ground)
  double settle_m = 2.5;                 // decide an object once the sonar is this far past it

  // Throws std::invalid_argument naming the first value out of range.
  void validate() const;
};

inline constexpr int kMaxOpenObjects = 64;      // per side
inline constexpr int kMaxPendingObjects = 64;   // gated, waiting for their decision
inline constexpr int kMaxRecentContacts = 256;  // reported, remembered for suppression
// ping detections remembered for the local clutter density (a rocky seabed gives about 20 per
// ping and side: 20 m of track)
inline constexpr int kMaxRecentHits = 8192;
// the clutter density counts the ping detections within this along-track distance of an object
inline constexpr double kClutterWindow_m = 10.0;

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
  double shadow_area_m2 = 0.0;       // slant length x ping spacing, summed
  double highlight_db = -300.0;      // strongest highlight bin
  // contrasts with the local background B (step 1): the strongest highlight bin's level above
  // its B, and the shadow bins' mean depth below theirs (dB), over the object's pings
  double highlight_above_db = 0.0;
  double shadow_below_db = 0.0;
  // the highlight's extent: its bins (L >= B + highlight_above_db) over the object's pings,
  // slant length x ping spacing summed (m²), and their mean level above B (dB)
  double highlight_area_m2 = 0.0;
  double highlight_mean_above_db = 0.0;
  // the seabed around it: ping detections (of any object) per metre of track on its side within
  // kClutterWindow_m along track (a flat seabed gives few, a rocky or cluttered one many): the
  // object-level counterpart of a CFAR detector's local statistics
  double clutter_hits_per_m = 0.0;
  double score = 0.0;  // the detection statistic: height_m
};

// What became of a complete object (Candidate::fate).
enum class CandidateFate : std::uint8_t {
  kReported,        // a contact
  kSuppressed,      // a candidate of higher score within min_separation_m
  kBelowThreshold,  // survived the suppression, score under min_height_m
  kRejected,        // failed a gate (Candidate::failed_gates)
};
const char* candidate_fate_name(CandidateFate f);

// The gates an object failed (bits of Candidate::failed_gates).
inline constexpr std::uint8_t kGatePings = 1;       // fewer than min_pings
inline constexpr std::uint8_t kGateAlongShort = 2;  // along-track extent under min_along_m
inline constexpr std::uint8_t kGateAlongLong = 4;   // over max_along_m
inline constexpr std::uint8_t kGateTall = 8;        // height over max_height_m
inline constexpr std::uint8_t kGateFloor = 16;      // height under candidate_min_height_m
inline constexpr std::uint8_t kGateOverflow = 32;   // the pending pool was full

// One complete object and its fate.
struct Candidate {
  Detection detection;
  CandidateFate fate = CandidateFate::kRejected;
  std::uint8_t failed_gates = 0;
};

struct DetectorStats {
  std::uint64_t pings = 0;              // processed
  std::uint64_t pings_no_altitude = 0;  // skipped: no altitude
  std::uint64_t ping_detections = 0;
  std::uint64_t objects = 0;     // complete objects
  std::uint64_t rejected = 0;    // by the gates
  std::uint64_t suppressed = 0;  // by non-maximum suppression
  std::uint64_t below_threshold = 0;
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
  // Every object whose fate was decided in the last process() or finish() call (the reported
  // ones among them), valid until the next call.
  std::span<const Candidate> candidates() const { return decided_; }

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
    double highlight_above_db = 0.0;
    double shadow_depth_sum_db = 0.0;  // sum over shadow bins of B - L
    int shadow_bins = 0;
    double highlight_area_m2 = 0.0;
    double highlight_above_sum_db = 0.0;  // sum over highlight bins of L - B
    int highlight_bins = 0;
  };

  void configure(const Waterfall& w);
  void detect_side(const Waterfall& w, std::uint64_t seq, int side, double footprint_along);
  // One ping's highlight and shadow: its bins, the highlight's peak level and its height above
  // the background, the shadow's summed depth below it.
  struct PingHit {
    int highlight_bin = 0, shadow_begin = 0, shadow_end = 0;
    float peak_db = 0.0f, peak_above_db = 0.0f;
    double shadow_depth_sum_db = 0.0;
    int highlight_bins = 0;
    double highlight_above_sum_db = 0.0;
  };
  void add_ping_detection(const Waterfall& w, std::uint64_t seq, int side, double along,
                          const PingHit& hit);
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
  std::vector<Detection> recent_;  // ring of candidates that survived the suppression
  std::size_t recent_next_ = 0;
  std::vector<Detection> out_;
  std::vector<Candidate> decided_;
  struct Hit {
    double along = 0.0;
    int side = 0;
  };
  std::vector<Hit> hits_;  // ring of recent ping detections (clutter density)
  std::size_t hits_next_ = 0;
};

}  // namespace sonarloop::atr
