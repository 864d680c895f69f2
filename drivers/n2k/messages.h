#pragma once
// The NMEA 2000 navigation PGNs sonarloop publishes (docs/formats.md §2.3), as plain structs with
// pure, allocation-free encode/decode to single 8-byte CAN frames.
//
// Units are SI (angles in radians, speeds in m/s, depths in m, time of day in s); latitude and
// longitude stay in degrees and say so. Every NUMBER field is std::optional: nullopt <-> the
// field's "not available" sentinel (docs/formats.md §2.2). Encoding rounds to the nearest
// resolution step and saturates out-of-range values (angles and longitude wrap), so a real value
// never becomes a sentinel; reserved bits are written as ones. SIDs are passed through raw (0..252,
// kSidNotAvailable = 255).
//
// Example (docs/formats.md §2.4): PositionRapidUpdate{59.9123456, 10.7654321} from source 0x23
// encodes to 09F80123#00E6B523B1AC6A06.
//
// Decoding checks that the frame is extended, carries the expected PGN and has 8 data bytes;
// anything else is a DecodeError (never an exception). Reserved bits are not checked.
#include <cstdint>
#include <optional>
#include <utility>
#include <variant>

#include "drivers/can/can_frame.h"
#include "drivers/n2k/can_id.h"

namespace sonarloop::n2k {

using can::CanFrame;

inline constexpr std::uint8_t kSidNotAvailable = 255;

// DIRECTION_REFERENCE lookup (2 bits).
enum class DirectionReference : std::uint8_t { kTrue = 0, kMagnetic = 1, kError = 2, kNull = 3 };

// WATER_REFERENCE lookup (8 bits).
enum class WaterReference : std::uint8_t {
  kPaddleWheel = 0,
  kPitotTube = 1,
  kDoppler = 2,
  kCorrelation = 3,  // correlation (ultrasound)
  kElectroMagnetic = 4,
  kNotAvailable = 255,
};

// SYSTEM_TIME lookup (4 bits).
enum class SystemTimeSource : std::uint8_t {
  kGps = 0,
  kGlonass = 1,
  kRadioStation = 2,
  kLocalCesiumClock = 3,
  kLocalRubidiumClock = 4,
  kLocalCrystalClock = 5,
  kNotAvailable = 15,
};

// PGN 129025 Position, Rapid Update (no SID).
struct PositionRapidUpdate {
  static constexpr std::uint32_t kPgn = 129025;
  static constexpr std::uint8_t kDefaultPriority = 2;
  static constexpr std::int64_t kDefaultPeriodNs = 100'000'000;
  std::optional<double> latitude_deg;   // -90..90, resolution 1e-7 deg (clamped)
  std::optional<double> longitude_deg;  // -180..180, resolution 1e-7 deg (wrapped)
  friend bool operator==(const PositionRapidUpdate&, const PositionRapidUpdate&) = default;
};

// PGN 129026 COG & SOG, Rapid Update.
struct CogSogRapidUpdate {
  static constexpr std::uint32_t kPgn = 129026;
  static constexpr std::uint8_t kDefaultPriority = 2;
  static constexpr std::int64_t kDefaultPeriodNs = 250'000'000;
  std::uint8_t sid = kSidNotAvailable;
  DirectionReference cog_reference = DirectionReference::kTrue;
  std::optional<double> cog_rad;  // course over ground 0..2pi, resolution 1e-4 rad (wrapped)
  std::optional<double> sog_mps;  // speed over ground 0..655.32 m/s, resolution 0.01 m/s
  friend bool operator==(const CogSogRapidUpdate&, const CogSogRapidUpdate&) = default;
};

// PGN 127250 Vessel Heading.
struct VesselHeading {
  static constexpr std::uint32_t kPgn = 127250;
  static constexpr std::uint8_t kDefaultPriority = 2;
  static constexpr std::int64_t kDefaultPeriodNs = 100'000'000;
  std::uint8_t sid = kSidNotAvailable;
  std::optional<double> heading_rad;    // 0..2pi, resolution 1e-4 rad (wrapped)
  std::optional<double> deviation_rad;  // -pi..pi, resolution 1e-4 rad (wrapped)
  std::optional<double> variation_rad;  // -pi..pi, resolution 1e-4 rad (wrapped)
  DirectionReference reference = DirectionReference::kTrue;
  friend bool operator==(const VesselHeading&, const VesselHeading&) = default;
};

// PGN 127251 Rate of Turn.
struct RateOfTurn {
  static constexpr std::uint32_t kPgn = 127251;
  static constexpr std::uint8_t kDefaultPriority = 2;
  static constexpr std::int64_t kDefaultPeriodNs = 100'000'000;
  std::uint8_t sid = kSidNotAvailable;
  std::optional<double> rate_rad_per_s;  // +-67.1 rad/s, resolution 3.125e-8 rad/s (clamped)
  friend bool operator==(const RateOfTurn&, const RateOfTurn&) = default;
};

// PGN 127257 Attitude.
struct Attitude {
  static constexpr std::uint32_t kPgn = 127257;
  static constexpr std::uint8_t kDefaultPriority = 3;
  static constexpr std::int64_t kDefaultPeriodNs = 1'000'000'000;
  std::uint8_t sid = kSidNotAvailable;
  std::optional<double> yaw_rad;    // -pi..pi, resolution 1e-4 rad (wrapped)
  std::optional<double> pitch_rad;  // -pi..pi, resolution 1e-4 rad (wrapped)
  std::optional<double> roll_rad;   // -pi..pi, resolution 1e-4 rad (wrapped)
  friend bool operator==(const Attitude&, const Attitude&) = default;
};

// PGN 128259 Speed (water referenced).
struct SpeedWaterReferenced {
  static constexpr std::uint32_t kPgn = 128259;
  static constexpr std::uint8_t kDefaultPriority = 2;
  static constexpr std::int64_t kDefaultPeriodNs = 1'000'000'000;
  std::uint8_t sid = kSidNotAvailable;
  std::optional<double> speed_water_mps;   // 0..655.32 m/s, resolution 0.01 m/s
  std::optional<double> speed_ground_mps;  // 0..655.32 m/s, resolution 0.01 m/s
  WaterReference speed_water_type = WaterReference::kNotAvailable;
  std::uint8_t speed_direction = 0;  // raw 4-bit value (0 = forward in practice, 15 = n/a)
  friend bool operator==(const SpeedWaterReferenced&, const SpeedWaterReferenced&) = default;
};

// PGN 128267 Water Depth.
struct WaterDepth {
  static constexpr std::uint32_t kPgn = 128267;
  static constexpr std::uint8_t kDefaultPriority = 3;
  static constexpr std::int64_t kDefaultPeriodNs = 1'000'000'000;
  std::uint8_t sid = kSidNotAvailable;
  std::optional<double> depth_m;   // below the transducer, 0..42949672.92 m, resolution 0.01 m
  std::optional<double> offset_m;  // + transducer-to-surface, - transducer-to-keel; +-32.764 m,
                                   // resolution 0.001 m
  std::optional<double> range_m;   // maximum measurement range 0..2520 m, resolution 10 m
  friend bool operator==(const WaterDepth&, const WaterDepth&) = default;
};

// PGN 126992 System Time.
struct SystemTime {
  static constexpr std::uint32_t kPgn = 126992;
  static constexpr std::uint8_t kDefaultPriority = 3;
  static constexpr std::int64_t kDefaultPeriodNs = 1'000'000'000;
  std::uint8_t sid = kSidNotAvailable;
  SystemTimeSource source = SystemTimeSource::kGps;
  std::optional<double> date_days;      // days since 1970-01-01, 0..65532, resolution 1 day
  std::optional<double> time_of_day_s;  // seconds since midnight UTC, 0..86400.9999, 1e-4 s
  friend bool operator==(const SystemTime&, const SystemTime&) = default;
};

// Any of the above.
using N2kMessage = std::variant<PositionRapidUpdate, CogSogRapidUpdate, VesselHeading, RateOfTurn,
                                Attitude, SpeedWaterReferenced, WaterDepth, SystemTime>;

// System Time for a UNIX time in ns (floored to the field's 100 us step; dates before 1970 clamp
// to day 0).
SystemTime system_time_from_unix_ns(std::int64_t unix_ns, std::uint8_t sid,
                                    SystemTimeSource source = SystemTimeSource::kGps);
// UNIX time in ns of a System Time; nullopt if date or time is not available.
std::optional<std::int64_t> unix_ns_from_system_time(const SystemTime& t);

// --- encode: one 8-byte extended frame; destination is global (all eight PGNs are PDU2) ---
CanFrame encode(const PositionRapidUpdate& m, std::uint8_t source,
                std::uint8_t priority = PositionRapidUpdate::kDefaultPriority);
CanFrame encode(const CogSogRapidUpdate& m, std::uint8_t source,
                std::uint8_t priority = CogSogRapidUpdate::kDefaultPriority);
CanFrame encode(const VesselHeading& m, std::uint8_t source,
                std::uint8_t priority = VesselHeading::kDefaultPriority);
CanFrame encode(const RateOfTurn& m, std::uint8_t source,
                std::uint8_t priority = RateOfTurn::kDefaultPriority);
CanFrame encode(const Attitude& m, std::uint8_t source,
                std::uint8_t priority = Attitude::kDefaultPriority);
CanFrame encode(const SpeedWaterReferenced& m, std::uint8_t source,
                std::uint8_t priority = SpeedWaterReferenced::kDefaultPriority);
CanFrame encode(const WaterDepth& m, std::uint8_t source,
                std::uint8_t priority = WaterDepth::kDefaultPriority);
CanFrame encode(const SystemTime& m, std::uint8_t source,
                std::uint8_t priority = SystemTime::kDefaultPriority);
// Encodes whichever message the variant holds, with that message's default priority.
CanFrame encode(const N2kMessage& m, std::uint8_t source);

// --- decode ---
enum class DecodeError : std::uint8_t {
  kNotExtended,     // an 11-bit frame: NMEA 2000 uses 29-bit identifiers
  kWrongPgn,        // the identifier carries another PGN than the one asked for
  kWrongLength,     // not the 8 data bytes of a single-frame PGN
  kUnsupportedPgn,  // decode_any: a PGN this codec does not know
};
// A short English description, e.g. "frame length is not 8 bytes".
const char* to_string(DecodeError e);

// A decoded value or the reason there is none (an expected-like type; C++20 has no
// std::expected).
template <class T>
class Decoded {
 public:
  Decoded(T value) : value_(std::move(value)) {}  // NOLINT: implicit by design
  Decoded(DecodeError error) : error_(error) {}   // NOLINT: implicit by design
  bool has_value() const { return value_.has_value(); }
  explicit operator bool() const { return has_value(); }
  const T& value() const { return value_.value(); }
  const T& operator*() const { return *value_; }
  const T* operator->() const { return &*value_; }
  // Only meaningful when !has_value().
  DecodeError error() const { return error_; }

 private:
  std::optional<T> value_;
  DecodeError error_ = DecodeError::kUnsupportedPgn;
};

// decode<T>(frame) for each message type above (e.g. decode<VesselHeading>(frame)).
template <class T>
Decoded<T> decode(const CanFrame& frame);
template <>
Decoded<PositionRapidUpdate> decode<PositionRapidUpdate>(const CanFrame& frame);
template <>
Decoded<CogSogRapidUpdate> decode<CogSogRapidUpdate>(const CanFrame& frame);
template <>
Decoded<VesselHeading> decode<VesselHeading>(const CanFrame& frame);
template <>
Decoded<RateOfTurn> decode<RateOfTurn>(const CanFrame& frame);
template <>
Decoded<Attitude> decode<Attitude>(const CanFrame& frame);
template <>
Decoded<SpeedWaterReferenced> decode<SpeedWaterReferenced>(const CanFrame& frame);
template <>
Decoded<WaterDepth> decode<WaterDepth>(const CanFrame& frame);
template <>
Decoded<SystemTime> decode<SystemTime>(const CanFrame& frame);
// Decodes any of the eight PGNs, chosen by the frame's PGN.
Decoded<N2kMessage> decode_any(const CanFrame& frame);

}  // namespace sonarloop::n2k
