#include "drivers/n2k/messages.h"

#include <algorithm>
#include <numbers>

#include "drivers/n2k/field.h"

namespace sonarloop::n2k {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kSecondsPerDay = 86400.0;
constexpr std::int64_t kNsPerSecond = 1'000'000'000;
constexpr std::int64_t kNsPerDay = 86400 * kNsPerSecond;
constexpr std::int64_t kNsPerTimeStep = 100'000;  // TIME resolution 0.0001 s

// Field layouts of docs/formats.md §2.3 (canboat canboat.json): bits, signed, resolution, range.
constexpr ScaledField kLatitude{32, true, 1e-7, -90.0, 90.0, OutOfRange::kClamp};
constexpr ScaledField kLongitude{32, true, 1e-7, -180.0, 180.0, OutOfRange::kWrap};
// unsigned angles 0..2pi, signed angles -pi..pi, both 1e-4 rad
constexpr ScaledField kAngleU16{16, false, 1e-4, 0.0, 2.0 * kPi, OutOfRange::kWrap};
constexpr ScaledField kAngleS16{16, true, 1e-4, -kPi, kPi, OutOfRange::kWrap};
// speeds 0.01 m/s in 16 bits: 0 .. 65532 steps
constexpr ScaledField kSpeedU16{16, false, 0.01, 0.0, 655.32, OutOfRange::kClamp};
// rate of turn: 1/32 * 1e-6 rad/s per step in a signed 32-bit field
constexpr ScaledField kRateOfTurn{
    32, true, 3.125e-8, -2147483647 * 3.125e-8, 2147483644 * 3.125e-8, OutOfRange::kClamp};
constexpr ScaledField kDepth{32, false, 0.01, 0.0, 4294967292 * 0.01, OutOfRange::kClamp};
constexpr ScaledField kDepthOffset{16, true, 0.001, -32.767, 32.764, OutOfRange::kClamp};
constexpr ScaledField kDepthRange{8, false, 10.0, 0.0, 2520.0, OutOfRange::kClamp};
constexpr ScaledField kDate{16, false, 1.0, 0.0, 65532.0, OutOfRange::kClamp};
// a time of day may hold a leap second: allow up to 86400.9999 s
constexpr ScaledField kTimeOfDay{32, false, 1e-4, 0.0, kSecondsPerDay + 0.9999, OutOfRange::kClamp};

constexpr std::uint64_t kAllOnes = ~std::uint64_t{0};

// A raw lookup value saturated to the field width (all ones = not available).
std::uint64_t lookup_raw(std::uint8_t value, int bits) {
  const std::uint64_t top = (std::uint64_t{1} << bits) - 1;
  return std::min<std::uint64_t>(value, top);
}

template <class T>
CanFrame start_frame(std::uint8_t source, std::uint8_t priority) {
  CanFrame f;
  f.id = encode_can_id(N2kId{priority, T::kPgn, source, kAddressGlobal});
  f.extended = true;
  f.len = 8;
  return f;
}

// Checks what every decode needs: an extended, 8-byte frame carrying T's PGN.
template <class T>
std::optional<DecodeError> check_frame(const CanFrame& frame) {
  if (!frame.extended) return DecodeError::kNotExtended;
  if (decode_can_id(frame.id).pgn != T::kPgn) return DecodeError::kWrongPgn;
  if (frame.len != 8) return DecodeError::kWrongLength;
  return std::nullopt;
}

std::uint8_t get_u8(const FrameBytes& b, int offset, int bits) {
  return static_cast<std::uint8_t>(get_bits(b, offset, bits));
}

}  // namespace

SystemTime system_time_from_unix_ns(std::int64_t unix_ns, std::uint8_t sid,
                                    SystemTimeSource source) {
  SystemTime t;
  t.sid = sid;
  t.source = source;
  if (unix_ns < 0) unix_ns = 0;
  const std::int64_t days = unix_ns / kNsPerDay;
  const std::int64_t in_day_steps = (unix_ns % kNsPerDay) / kNsPerTimeStep;
  t.date_days = static_cast<double>(days);
  t.time_of_day_s = static_cast<double>(in_day_steps) * 1e-4;
  return t;
}

std::optional<std::int64_t> unix_ns_from_system_time(const SystemTime& t) {
  if (!t.date_days || !t.time_of_day_s) return std::nullopt;
  const auto days = static_cast<std::int64_t>(std::llround(*t.date_days));
  const auto steps = static_cast<std::int64_t>(std::llround(*t.time_of_day_s * 1e4));
  return days * kNsPerDay + steps * kNsPerTimeStep;
}

// 129025: lat s32 @0, lon s32 @32.  09F80123#00E6B523B1AC6A06 = 59.9123456 N, 10.7654321 E
CanFrame encode(const PositionRapidUpdate& m, std::uint8_t source, std::uint8_t priority) {
  CanFrame f = start_frame<PositionRapidUpdate>(source, priority);
  put_field(f.data, 0, kLatitude, m.latitude_deg);
  put_field(f.data, 32, kLongitude, m.longitude_deg);
  return f;
}

// 129026: SID @0, ref 2 bits @8, reserved 6 @10, COG u16 @16, SOG u16 @32, reserved 16 @48.
// 09F80223#07FCAE1EFA00FFFF = SID 7, true, COG 45 deg, SOG 2.50 m/s
CanFrame encode(const CogSogRapidUpdate& m, std::uint8_t source, std::uint8_t priority) {
  CanFrame f = start_frame<CogSogRapidUpdate>(source, priority);
  put_bits(f.data, 0, 8, m.sid);
  put_bits(f.data, 8, 2, lookup_raw(static_cast<std::uint8_t>(m.cog_reference), 2));
  put_bits(f.data, 10, 6, kAllOnes);
  put_field(f.data, 16, kAngleU16, m.cog_rad);
  put_field(f.data, 32, kSpeedU16, m.sog_mps);
  put_bits(f.data, 48, 16, kAllOnes);
  return f;
}

// 127250: SID @0, heading u16 @8, deviation s16 @24, variation s16 @40, ref 2 @56, reserved 6.
// 09F11223#072154FF7FA3FEFC = SID 7, 123.4 deg, deviation n/a, variation -2.0 deg, true
CanFrame encode(const VesselHeading& m, std::uint8_t source, std::uint8_t priority) {
  CanFrame f = start_frame<VesselHeading>(source, priority);
  put_bits(f.data, 0, 8, m.sid);
  put_field(f.data, 8, kAngleU16, m.heading_rad);
  put_field(f.data, 24, kAngleS16, m.deviation_rad);
  put_field(f.data, 40, kAngleS16, m.variation_rad);
  put_bits(f.data, 56, 2, lookup_raw(static_cast<std::uint8_t>(m.reference), 2));
  put_bits(f.data, 58, 6, kAllOnes);
  return f;
}

// 127251: SID @0, rate s32 @8 (3.125e-8 rad/s), reserved 24 @40.
// 09F11323#07A9850800FFFFFF = SID 7, 1.0 deg/s
CanFrame encode(const RateOfTurn& m, std::uint8_t source, std::uint8_t priority) {
  CanFrame f = start_frame<RateOfTurn>(source, priority);
  put_bits(f.data, 0, 8, m.sid);
  put_field(f.data, 8, kRateOfTurn, m.rate_rad_per_s);
  put_bits(f.data, 40, 24, kAllOnes);
  return f;
}

// 127257: SID @0, yaw s16 @8, pitch s16 @24, roll s16 @40, reserved 8 @56.
// 0DF11923#070C02FAFE8901FF = SID 7, yaw 3.0, pitch -1.5, roll 2.25 deg
CanFrame encode(const Attitude& m, std::uint8_t source, std::uint8_t priority) {
  CanFrame f = start_frame<Attitude>(source, priority);
  put_bits(f.data, 0, 8, m.sid);
  put_field(f.data, 8, kAngleS16, m.yaw_rad);
  put_field(f.data, 24, kAngleS16, m.pitch_rad);
  put_field(f.data, 40, kAngleS16, m.roll_rad);
  put_bits(f.data, 56, 8, kAllOnes);
  return f;
}

// 128259: SID @0, STW u16 @8, SOG u16 @24, type u8 @40, direction 4 @48, reserved 12 @52.
// 09F50323#07F000FFFF02F0FF = SID 7, STW 2.40 m/s, ground n/a, Doppler, forward
CanFrame encode(const SpeedWaterReferenced& m, std::uint8_t source, std::uint8_t priority) {
  CanFrame f = start_frame<SpeedWaterReferenced>(source, priority);
  put_bits(f.data, 0, 8, m.sid);
  put_field(f.data, 8, kSpeedU16, m.speed_water_mps);
  put_field(f.data, 24, kSpeedU16, m.speed_ground_mps);
  put_bits(f.data, 40, 8, static_cast<std::uint8_t>(m.speed_water_type));
  put_bits(f.data, 48, 4, lookup_raw(m.speed_direction, 4));
  put_bits(f.data, 52, 12, kAllOnes);
  return f;
}

// 128267: SID @0, depth u32 @8 (0.01 m), offset s16 @40 (0.001 m), range u8 @56 (10 m).
// 0DF50B23#078D1000000CFEFF = SID 7, 42.37 m, offset -0.500 m, range n/a
CanFrame encode(const WaterDepth& m, std::uint8_t source, std::uint8_t priority) {
  CanFrame f = start_frame<WaterDepth>(source, priority);
  put_bits(f.data, 0, 8, m.sid);
  put_field(f.data, 8, kDepth, m.depth_m);
  put_field(f.data, 40, kDepthOffset, m.offset_m);
  put_field(f.data, 56, kDepthRange, m.range_m);
  return f;
}

// 126992: SID @0, source 4 @8, reserved 4 @12, date u16 @16, time u32 @32 (1e-4 s).
// 0DF01023#07F0DB4CC2E5AE2F = SID 7, GPS, 2023-11-14 (19675) 22:13:19.1234
CanFrame encode(const SystemTime& m, std::uint8_t source, std::uint8_t priority) {
  CanFrame f = start_frame<SystemTime>(source, priority);
  put_bits(f.data, 0, 8, m.sid);
  put_bits(f.data, 8, 4, lookup_raw(static_cast<std::uint8_t>(m.source), 4));
  put_bits(f.data, 12, 4, kAllOnes);
  put_field(f.data, 16, kDate, m.date_days);
  put_field(f.data, 32, kTimeOfDay, m.time_of_day_s);
  return f;
}

CanFrame encode(const N2kMessage& m, std::uint8_t source) {
  return std::visit([source](const auto& msg) { return encode(msg, source); }, m);
}

const char* to_string(DecodeError e) {
  switch (e) {
    case DecodeError::kNotExtended:
      return "not an extended (29-bit) frame";
    case DecodeError::kWrongPgn:
      return "frame carries a different PGN";
    case DecodeError::kWrongLength:
      return "frame length is not 8 bytes";
    case DecodeError::kUnsupportedPgn:
      return "PGN not supported by this codec";
  }
  return "unknown decode error";
}

template <>
Decoded<PositionRapidUpdate> decode(const CanFrame& frame) {
  if (auto e = check_frame<PositionRapidUpdate>(frame)) return *e;
  PositionRapidUpdate m;
  m.latitude_deg = get_field(frame.data, 0, kLatitude);
  m.longitude_deg = get_field(frame.data, 32, kLongitude);
  return m;
}

template <>
Decoded<CogSogRapidUpdate> decode(const CanFrame& frame) {
  if (auto e = check_frame<CogSogRapidUpdate>(frame)) return *e;
  CogSogRapidUpdate m;
  m.sid = get_u8(frame.data, 0, 8);
  m.cog_reference = static_cast<DirectionReference>(get_u8(frame.data, 8, 2));
  m.cog_rad = get_field(frame.data, 16, kAngleU16);
  m.sog_mps = get_field(frame.data, 32, kSpeedU16);
  return m;
}

template <>
Decoded<VesselHeading> decode(const CanFrame& frame) {
  if (auto e = check_frame<VesselHeading>(frame)) return *e;
  VesselHeading m;
  m.sid = get_u8(frame.data, 0, 8);
  m.heading_rad = get_field(frame.data, 8, kAngleU16);
  m.deviation_rad = get_field(frame.data, 24, kAngleS16);
  m.variation_rad = get_field(frame.data, 40, kAngleS16);
  m.reference = static_cast<DirectionReference>(get_u8(frame.data, 56, 2));
  return m;
}

template <>
Decoded<RateOfTurn> decode(const CanFrame& frame) {
  if (auto e = check_frame<RateOfTurn>(frame)) return *e;
  RateOfTurn m;
  m.sid = get_u8(frame.data, 0, 8);
  m.rate_rad_per_s = get_field(frame.data, 8, kRateOfTurn);
  return m;
}

template <>
Decoded<Attitude> decode(const CanFrame& frame) {
  if (auto e = check_frame<Attitude>(frame)) return *e;
  Attitude m;
  m.sid = get_u8(frame.data, 0, 8);
  m.yaw_rad = get_field(frame.data, 8, kAngleS16);
  m.pitch_rad = get_field(frame.data, 24, kAngleS16);
  m.roll_rad = get_field(frame.data, 40, kAngleS16);
  return m;
}

template <>
Decoded<SpeedWaterReferenced> decode(const CanFrame& frame) {
  if (auto e = check_frame<SpeedWaterReferenced>(frame)) return *e;
  SpeedWaterReferenced m;
  m.sid = get_u8(frame.data, 0, 8);
  m.speed_water_mps = get_field(frame.data, 8, kSpeedU16);
  m.speed_ground_mps = get_field(frame.data, 24, kSpeedU16);
  m.speed_water_type = static_cast<WaterReference>(get_u8(frame.data, 40, 8));
  m.speed_direction = get_u8(frame.data, 48, 4);
  return m;
}

template <>
Decoded<WaterDepth> decode(const CanFrame& frame) {
  if (auto e = check_frame<WaterDepth>(frame)) return *e;
  WaterDepth m;
  m.sid = get_u8(frame.data, 0, 8);
  m.depth_m = get_field(frame.data, 8, kDepth);
  m.offset_m = get_field(frame.data, 40, kDepthOffset);
  m.range_m = get_field(frame.data, 56, kDepthRange);
  return m;
}

template <>
Decoded<SystemTime> decode(const CanFrame& frame) {
  if (auto e = check_frame<SystemTime>(frame)) return *e;
  SystemTime m;
  m.sid = get_u8(frame.data, 0, 8);
  m.source = static_cast<SystemTimeSource>(get_u8(frame.data, 8, 4));
  m.date_days = get_field(frame.data, 16, kDate);
  m.time_of_day_s = get_field(frame.data, 32, kTimeOfDay);
  return m;
}

namespace {
template <class T>
Decoded<N2kMessage> decode_as_any(const CanFrame& frame) {
  Decoded<T> d = decode<T>(frame);
  if (!d) return d.error();
  return N2kMessage{*d};
}
}  // namespace

Decoded<N2kMessage> decode_any(const CanFrame& frame) {
  if (!frame.extended) return DecodeError::kNotExtended;
  switch (decode_can_id(frame.id).pgn) {
    case PositionRapidUpdate::kPgn:
      return decode_as_any<PositionRapidUpdate>(frame);
    case CogSogRapidUpdate::kPgn:
      return decode_as_any<CogSogRapidUpdate>(frame);
    case VesselHeading::kPgn:
      return decode_as_any<VesselHeading>(frame);
    case RateOfTurn::kPgn:
      return decode_as_any<RateOfTurn>(frame);
    case Attitude::kPgn:
      return decode_as_any<Attitude>(frame);
    case SpeedWaterReferenced::kPgn:
      return decode_as_any<SpeedWaterReferenced>(frame);
    case WaterDepth::kPgn:
      return decode_as_any<WaterDepth>(frame);
    case SystemTime::kPgn:
      return decode_as_any<SystemTime>(frame);
    default:
      return DecodeError::kUnsupportedPgn;
  }
}

}  // namespace sonarloop::n2k
