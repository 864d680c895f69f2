#pragma once
// The onboard waterfall: a ring of the most recent pings of a two-channel sidescan, each side as
// levels in dB re full scale from near to far range, with the navigation of each ping.
//
// Levels. A sample s of an integer channel is an amplitude re full scale A = s / s_max (s_max =
// 255 for 1-byte and 65535 for 2-byte samples, the uint8 / uint16 coding of
// sim/render/quantise.h); IEEE float samples are A itself. The level is L = 20 log10(A) dB re
// full scale (0 dB = full scale; TVG was applied by the sonar, XTF ProcessingFlags 4), the
// quantity `sonarloop dataset` chips are made of. A zero sample (no echo) is kNoEchoDb. Integer
// samples go through a lookup table built once per sample type, so adding a ping costs a table
// lookup per sample and no logarithm.
//
// Geometry. Sample k of a channel covers slant range [r0 + k·b, r0 + (k + 1)·b) with r0 = the
// channel's TimeDelay × the ping's SoundVelocity (XTF's one-way speed, docs/formats.md 1.5) and
// b = (SlantRange − r0) / NumSamples. Channels come from ChanInfo TypeOfChannel (port = 1,
// starboard = 2) whatever their order; both must have the same sample count and type. A change
// of sample count, bin size, r0 or sample type clears the ring (reset() counts them).
//
// Navigation per ping (XTF ping header, docs/formats.md 1.5): SensorY/X (latitude/longitude when
// NavUnits = 3, else northing/easting in metres), SensorHeading, SensorPitch (+ nose up),
// SensorRoll, SensorPrimaryAltitude (0 = unknown -> NaN), SensorDepth, SensorSpeed (knots).
// Positions are kept as north/east metres in a local tangent plane (common/geodesy.h) whose
// origin is the frame origin given at construction (the scenario's origin: then positions are
// those of its scene.json and truth.json), else the first ping's position; converted back to
// latitude/longitude for reports.
//
// Along-track coordinate. Each ping gets along_m, the distance the sonar has travelled, by dead
// reckoning: along_k = along_(k-1) + speed_k · Δt_k, with Δt_k = (PingNumber difference) ×
// SecondsPerPing (else the difference of ping times); without a speed, the ping-to-ping
// displacement projected on the heading. Navigation positions carry white noise (a good INS:
// 0.1 m rms per fix), as large as the ping spacing; speed integrates smoothly, so along_m is
// what chips are resampled on (atr/chip_cutter.h), while absolute positions are averaged over
// many pings for reports.
//
// Allocation: the ring (capacity x 2 x samples floats) and the lookup table are sized when the
// first ping (or a geometry change) arrives; add() allocates nothing afterwards.
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "common/geodesy.h"
#include "drivers/xtf/xtf_types.h"

namespace sonarloop::atr {

// The level of a zero sample (no echo at all), dB re full scale: below every display or chip
// span (chips map -60..0 dB), and above what a float could underflow to.
inline constexpr float kNoEchoDb = -120.0f;
// Default ring capacity: 1024 pings, 68 s of the default sonar, 137 m of track at 2 m/s.
inline constexpr int kDefaultWaterfallPings = 1024;

// Navigation and bookkeeping of one ping in the ring.
struct PingRecord {
  std::uint64_t seq = 0;          // index of the ping in the waterfall (0, 1, ...)
  std::uint32_t ping_number = 0;  // XTF PingNumber
  std::optional<std::int64_t> time_utc_ns;
  double north_m = 0.0;  // sonar position in the local plane (origin: the frame origin)
  double east_m = 0.0;
  double along_m = 0.0;  // dead-reckoned distance travelled (see the header comment)
  double heading_deg = 0.0;
  double pitch_deg = 0.0;  // + nose up
  double roll_deg = 0.0;   // + starboard down
  double altitude_m = std::numeric_limits<double>::quiet_NaN();
  double depth_m = 0.0;
  double speed_m_s = 0.0;
};

// The along-track position of a ping's strip of seabed ("footprint"): along_m + altitude ·
// tan(pitch). The beam plane (perpendicular to the body's x axis) tilts with the vehicle's pitch,
// so a seabed point at depth d below the sonar lies d·tan(pitch) ahead of it (pitch + nose up:
// R_y(pitch) maps the body's down axis to (sin θ, 0, cos θ)). Without an altitude, along_m.
double footprint_along_m(const PingRecord& r);

enum class AddResult {
  kAdded,
  kReset,     // added, after clearing the ring for a new geometry
  kUnusable,  // not a two-channel sidescan ping this waterfall can hold; not added
};

class Waterfall {
 public:
  // `frame_origin`: the origin of the local plane for latitude/longitude streams (a scenario's
  // origin, so that positions agree with its scene.json and truth.json); without it, the
  // stream's first ping with a position fix (latitude and longitude 0, 0, or out of range, is
  // none: such a ping keeps the last position). Throws std::invalid_argument if capacity < 2 or the
  // origin is invalid.
  explicit Waterfall(int capacity = kDefaultWaterfallPings,
                     std::optional<GeoPoint> frame_origin = std::nullopt);

  AddResult add(const xtf::XtfFileHeader& header, const xtf::XtfPing& ping);

  int capacity() const { return capacity_; }
  bool empty() const { return count_ == 0; }
  int size() const { return count_; }
  // Sequence numbers of the pings held: [oldest_seq(), newest_seq()].
  std::uint64_t newest_seq() const { return next_seq_ - 1; }
  std::uint64_t oldest_seq() const { return next_seq_ - static_cast<std::uint64_t>(count_); }
  bool contains(std::uint64_t seq) const {
    return count_ > 0 && seq >= oldest_seq() && seq <= newest_seq();
  }

  const PingRecord& record(std::uint64_t seq) const;
  // Levels (dB re full scale) of side 0 (port) or 1 (starboard), near to far.
  std::span<const float> levels(std::uint64_t seq, int side) const;

  int bins() const { return bins_; }
  double bin_size_m() const { return bin_size_m_; }
  double range_start_m() const { return range_start_m_; }
  // Slant range of the centre of bin k.
  double bin_centre_m(double k) const { return range_start_m_ + (k + 0.5) * bin_size_m_; }

  // Positions: geodetic when the stream gives latitude/longitude (NavUnits 3).
  bool geodetic() const { return geodetic_stream_; }
  // Latitude/longitude of a local point (geodetic() only).
  GeoPoint to_geodetic(double north_m, double east_m) const;
  // A local point in the stream's own metres: the local plane itself for latitude/longitude
  // streams, the stream's northing/easting for metre streams.
  Vec2 stream_metres(double north_m, double east_m) const {
    return {north_m + origin_north_m_, east_m + origin_east_m_};
  }

  std::uint64_t unusable() const { return unusable_; }
  std::uint64_t resets() const { return resets_; }

 private:
  enum class SampleKind { kUint8, kUint16, kFloat };
  struct Layout {
    int port = -1, stbd = -1;  // channel indices in the ping
    int bins = 0;
    SampleKind kind = SampleKind::kUint16;
    double bin_size_m = 0.0;
    double range_start_m = 0.0;
  };
  std::optional<Layout> layout_of(const xtf::XtfFileHeader& header, const xtf::XtfPing& ping) const;
  void configure(const Layout& layout);
  void fill_levels(const xtf::XtfPingChannel& ch, bool reversed, float* out) const;
  PingRecord make_record(const xtf::XtfFileHeader& header, const xtf::XtfPing& ping);
  std::size_t slot_of(std::uint64_t seq) const {
    return static_cast<std::size_t>(seq % static_cast<std::uint64_t>(capacity_));
  }

  int capacity_;
  int count_ = 0;
  std::uint64_t next_seq_ = 0;
  bool configured_ = false;
  Layout layout_;
  int bins_ = 0;
  double bin_size_m_ = 0.0;
  double range_start_m_ = 0.0;
  std::vector<float> levels_;        // capacity x 2 x bins
  std::vector<PingRecord> records_;  // capacity
  std::vector<float> table_;         // level of every integer sample value
  std::unique_ptr<LocalTangentPlane> plane_;
  bool geodetic_stream_ = false;  // a latitude/longitude ping has come
  bool have_origin_ = false;      // metres navigation: origin of the local frame set
  double origin_north_m_ = 0.0, origin_east_m_ = 0.0;
  bool have_last_ = false;
  PingRecord last_;  // the previous ping (dead reckoning)
  std::uint64_t unusable_ = 0;
  std::uint64_t resets_ = 0;
};

}  // namespace sonarloop::atr
