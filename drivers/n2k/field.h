#pragma once
// NMEA 2000 field encoding (docs/formats.md §2.2, canboat FieldTypes): little-endian bit fields
// counted from bit 0 of byte 0, scaled integers with a resolution, reserved bits all ones, and
// "top of range" sentinels.
//
// Sentinels of an n-bit NUMBER field whose largest raw value is M (2^n - 1 unsigned,
// 2^(n-1) - 1 signed): M = not available, M - 1 = error (out of range), M - 2 = reserved.
// Data values therefore use raw 0 .. M - 3 (unsigned) or -M .. M - 3 (signed); canboat's analyzer
// treats raw >= M - 2 as "no value". A decoded sentinel becomes std::nullopt.
//
// Encoding rounds to the nearest resolution step and saturates to the field's valid range, so a
// real value never turns into a sentinel. Periodic quantities (angles, longitude) are wrapped
// into their range instead of clamped. NaN (and nullopt) encode as "not available".
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>

namespace sonarloop::n2k {

using FrameBytes = std::array<std::uint8_t, 8>;

// How a real value outside [min, max] is brought into range.
enum class OutOfRange : std::uint8_t {
  kClamp,  // saturate to min or max
  kWrap,   // periodic: map into [min, max) with period max - min (angles, longitude)
};

// One scaled NUMBER field: raw = round(value / resolution), stored in `bits` bits.
struct ScaledField {
  int bits = 8;             // field width, 2..32
  bool is_signed = false;   // two's complement
  double resolution = 1.0;  // value of one raw step, in the field's SI unit
  double min = 0.0;         // valid value range (SI); clamped further to the raw data range
  double max = 0.0;
  OutOfRange out_of_range = OutOfRange::kClamp;
};

// Largest raw value M of a field (the "not available" sentinel).
constexpr std::int64_t raw_top(int bits, bool is_signed) {
  return is_signed ? (std::int64_t{1} << (bits - 1)) - 1 : (std::int64_t{1} << bits) - 1;
}
// Largest raw value that carries data (M - 3).
constexpr std::int64_t raw_max_data(int bits, bool is_signed) {
  return raw_top(bits, is_signed) - 3;
}
// Smallest raw value that carries data (0 unsigned, -M signed).
constexpr std::int64_t raw_min_data(int bits, bool is_signed) {
  return is_signed ? -raw_top(bits, is_signed) : 0;
}
// The n-bit pattern of "not available" (as stored on the wire).
constexpr std::uint32_t raw_not_available(int bits, bool is_signed) {
  return static_cast<std::uint32_t>(raw_top(bits, is_signed));
}

// Raw integer (in raw_min_data..raw_max_data, or the n/a sentinel) for a value. Allocation-free.
std::int64_t scale_to_raw(std::optional<double> value, const ScaledField& field);

// Value for a raw integer, nullopt for the three top-of-range sentinels.
std::optional<double> raw_to_value(std::int64_t raw, const ScaledField& field);

// Writes the low `bits` bits of `raw` at bit `offset` (little-endian, LSB first);
// 0 <= offset, 1 <= bits, offset + bits <= 64.
void put_bits(FrameBytes& bytes, int offset, int bits, std::uint64_t raw);
// Reads `bits` bits at bit `offset` as an unsigned value.
std::uint64_t get_bits(const FrameBytes& bytes, int offset, int bits);
// Reads `bits` bits at bit `offset` as a two's complement signed value.
std::int64_t get_bits_signed(const FrameBytes& bytes, int offset, int bits);

// Encodes value into the field at `offset` (scale, saturate, store).
void put_field(FrameBytes& bytes, int offset, const ScaledField& field,
               std::optional<double> value);
// Decodes the field at `offset`; nullopt for n/a, error and reserved.
std::optional<double> get_field(const FrameBytes& bytes, int offset, const ScaledField& field);

}  // namespace sonarloop::n2k
