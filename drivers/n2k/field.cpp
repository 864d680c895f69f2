#include "drivers/n2k/field.h"

#include <algorithm>

namespace sonarloop::n2k {

std::int64_t scale_to_raw(std::optional<double> value, const ScaledField& field) {
  const std::int64_t top = raw_top(field.bits, field.is_signed);
  if (!value || std::isnan(*value)) return top;
  const std::int64_t lo_raw = raw_min_data(field.bits, field.is_signed);
  const std::int64_t hi_raw = raw_max_data(field.bits, field.is_signed);

  double x = *value;
  if (field.out_of_range == OutOfRange::kWrap && std::isfinite(x)) {
    const double period = field.max - field.min;
    x = field.min + (x - field.min) - period * std::floor((x - field.min) / period);
  }
  // saturate in value space first so the division below cannot overflow an int64
  x = std::clamp(x, field.min, field.max);
  const double steps = std::round(x / field.resolution);
  const double clamped =
      std::clamp(steps, static_cast<double>(lo_raw), static_cast<double>(hi_raw));
  return static_cast<std::int64_t>(clamped);
}

std::optional<double> raw_to_value(std::int64_t raw, const ScaledField& field) {
  if (raw > raw_max_data(field.bits, field.is_signed)) return std::nullopt;
  return static_cast<double>(raw) * field.resolution;
}

namespace {

// The 8 data bytes as one little-endian 64-bit word: bit k of the word is bit k of the frame.
std::uint64_t load_word(const FrameBytes& bytes) {
  std::uint64_t w = 0;
  for (int i = 7; i >= 0; --i)
    w = (w << 8) | bytes[static_cast<std::size_t>(i)];
  return w;
}

void store_word(FrameBytes& bytes, std::uint64_t w) {
  for (std::size_t i = 0; i < 8; ++i, w >>= 8)
    bytes[i] = static_cast<std::uint8_t>(w & 0xFF);
}

std::uint64_t low_mask(int bits) {
  return bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1;
}

}  // namespace

void put_bits(FrameBytes& bytes, int offset, int bits, std::uint64_t raw) {
  const std::uint64_t mask = low_mask(bits) << offset;
  const std::uint64_t w = load_word(bytes);
  store_word(bytes, (w & ~mask) | ((raw << offset) & mask));
}

std::uint64_t get_bits(const FrameBytes& bytes, int offset, int bits) {
  return (load_word(bytes) >> offset) & low_mask(bits);
}

std::int64_t get_bits_signed(const FrameBytes& bytes, int offset, int bits) {
  const std::uint64_t u = get_bits(bytes, offset, bits);
  const std::uint64_t sign = std::uint64_t{1} << (bits - 1);
  // sign-extend: (u ^ sign) - sign maps the two's complement pattern onto its value
  return static_cast<std::int64_t>(u ^ sign) - static_cast<std::int64_t>(sign);
}

void put_field(FrameBytes& bytes, int offset, const ScaledField& field,
               std::optional<double> value) {
  const std::int64_t raw = scale_to_raw(value, field);
  put_bits(bytes, offset, field.bits, static_cast<std::uint64_t>(raw));
}

std::optional<double> get_field(const FrameBytes& bytes, int offset, const ScaledField& field) {
  const std::int64_t raw = field.is_signed
                               ? get_bits_signed(bytes, offset, field.bits)
                               : static_cast<std::int64_t>(get_bits(bytes, offset, field.bits));
  return raw_to_value(raw, field);
}

}  // namespace sonarloop::n2k
