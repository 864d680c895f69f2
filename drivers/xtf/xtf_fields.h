#pragma once
// The XTF byte layouts, written once and shared by the codec's source files (xtf_codec.cpp: the
// file header and the packet start; xtf_ping_encode.cpp and xtf_ping_decode.cpp: sonar pings).
// Internal to drivers/xtf: users include xtf_codec.h.
//
// It holds the little-endian scalar access (byte by byte, so host endianness and alignment do not
// matter), the two "IO" classes FieldWriter and FieldReader, and the field tables of each header
// (docs/formats.md 1.2-1.6). Each table is one template run with either IO class, so the encoder
// and the decoder cannot disagree about an offset.
#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "drivers/xtf/xtf_types.h"

namespace sonarloop::xtf::wire {

// ---- little-endian scalars, written and read byte by byte ----

template <class T>
void put_le(std::span<std::uint8_t> b, std::size_t off, T v) {
  if constexpr (std::is_same_v<T, float>) {
    put_le(b, off, std::bit_cast<std::uint32_t>(v));
  } else if constexpr (std::is_same_v<T, double>) {
    put_le(b, off, std::bit_cast<std::uint64_t>(v));
  } else {
    static_assert(std::is_integral_v<T>);
    using U = std::make_unsigned_t<T>;
    const auto u = static_cast<U>(v);
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      b[off + i] = static_cast<std::uint8_t>(u >> (8 * i));
    }
  }
}

template <class T>
T get_le(std::span<const std::uint8_t> b, std::size_t off) {
  if constexpr (std::is_same_v<T, float>) {
    return std::bit_cast<float>(get_le<std::uint32_t>(b, off));
  } else if constexpr (std::is_same_v<T, double>) {
    return std::bit_cast<double>(get_le<std::uint64_t>(b, off));
  } else {
    static_assert(std::is_integral_v<T>);
    using U = std::make_unsigned_t<T>;
    U u = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      u = static_cast<U>(u | static_cast<U>(static_cast<U>(b[off + i]) << (8 * i)));
    }
    return static_cast<T>(u);
  }
}

// The field tables below are written once and run with either of these two "IO" classes, so
// the encoder and the decoder cannot disagree about an offset.
class FieldWriter {
 public:
  explicit FieldWriter(std::span<std::uint8_t> b) : b_(b) {}
  template <class T>
  void field(std::size_t off, const T& v) {
    put_le(b_, off, v);
  }
  template <class T, std::size_t N>
  void field(std::size_t off, const std::array<T, N>& a) {
    for (std::size_t i = 0; i < N; ++i)
      put_le(b_, off + i * sizeof(T), a[i]);
  }
  // char[size]: NUL padded; a string of exactly `size` characters has no NUL
  void text(std::size_t off, std::size_t size, const std::string& s, const char* name) {
    if (s.size() > size) {
      throw std::invalid_argument(std::string("XTF field ") + name + " holds at most " +
                                  std::to_string(size) + " characters, got " +
                                  std::to_string(s.size()) + " (\"" + s + "\")");
    }
    std::copy(s.begin(), s.end(), b_.begin() + static_cast<std::ptrdiff_t>(off));
    std::fill_n(b_.begin() + static_cast<std::ptrdiff_t>(off + s.size()), size - s.size(), 0);
  }

 private:
  std::span<std::uint8_t> b_;
};

class FieldReader {
 public:
  explicit FieldReader(std::span<const std::uint8_t> b) : b_(b) {}
  template <class T>
  void field(std::size_t off, T& v) {
    v = get_le<T>(b_, off);
  }
  template <class T, std::size_t N>
  void field(std::size_t off, std::array<T, N>& a) {
    for (std::size_t i = 0; i < N; ++i)
      a[i] = get_le<T>(b_, off + i * sizeof(T));
  }
  // char[size] up to the first NUL
  void text(std::size_t off, std::size_t size, std::string& s, const char* /*name*/) {
    const auto first = b_.begin() + static_cast<std::ptrdiff_t>(off);
    const auto last = first + static_cast<std::ptrdiff_t>(size);
    s.assign(first, std::find(first, last, std::uint8_t{0}));
  }

 private:
  std::span<const std::uint8_t> b_;
};

// XTFFILEHEADER bytes 0-255 (docs/formats.md 1.2).
template <class IO, class H>
void file_header_fields(IO& io, H& h) {
  io.field(0, h.file_format);
  io.field(1, h.system_type);
  io.text(2, 8, h.recording_program_name, "RecordingProgramName");
  io.text(10, 8, h.recording_program_version, "RecordingProgramVersion");
  io.text(18, 16, h.sonar_name, "SonarName");
  io.field(34, h.sonar_type);
  io.text(36, 64, h.note_string, "NoteString");
  io.text(100, 64, h.this_file_name, "ThisFileName");
  io.field(164, h.nav_units);
  io.field(166, h.number_of_sonar_channels);
  io.field(168, h.number_of_bathymetry_channels);
  io.field(170, h.number_of_snippet_channels);
  io.field(171, h.number_of_forward_look_arrays);
  io.field(172, h.number_of_echo_strength_channels);
  io.field(174, h.number_of_interferometry_channels);
  io.field(175, h.reserved1);
  io.field(176, h.reserved2);
  io.field(178, h.reference_point_height_m);
  io.field(182, h.projection_type);
  io.field(194, h.spheroid_type);
  io.field(204, h.navigation_latency_ms);
  io.field(208, h.origin_y);
  io.field(212, h.origin_x);
  io.field(216, h.nav_offset_y_m);
  io.field(220, h.nav_offset_x_m);
  io.field(224, h.nav_offset_z_m);
  io.field(228, h.nav_offset_yaw_deg);
  io.field(232, h.mru_offset_y_m);
  io.field(236, h.mru_offset_x_m);
  io.field(240, h.mru_offset_z_m);
  io.field(244, h.mru_offset_yaw_deg);
  io.field(248, h.mru_offset_pitch_deg);
  io.field(252, h.mru_offset_roll_deg);
}

// CHANINFO, offsets relative to its start (docs/formats.md 1.3).
template <class IO, class C>
void chan_info_fields(IO& io, C& c) {
  io.field(0, c.type_of_channel);
  io.field(1, c.sub_channel_number);
  io.field(2, c.correction_flags);
  io.field(4, c.uni_polar);
  io.field(6, c.bytes_per_sample);
  io.field(8, c.reserved_samples_per_channel);
  io.text(12, 16, c.channel_name, "ChannelName");
  io.field(28, c.volt_scale_v);
  io.field(32, c.frequency);
  io.field(36, c.horiz_beam_angle_deg);
  io.field(40, c.tilt_angle_deg);
  io.field(44, c.beam_width_deg);
  io.field(48, c.offset_x_m);
  io.field(52, c.offset_y_m);
  io.field(56, c.offset_z_m);
  io.field(60, c.offset_yaw_deg);
  io.field(64, c.offset_pitch_deg);
  io.field(68, c.offset_roll_deg);
  io.field(72, c.beams_per_array);
  io.field(74, c.sample_format);
  io.field(75, c.reserved_area2);
}

// XTFPINGHEADER without MagicNumber (0), HeaderType (2), NumChansToFollow (4) and
// NumBytesThisRecord (10), which the codec derives (docs/formats.md 1.4, 1.5).
template <class IO, class H>
void ping_header_fields(IO& io, H& h) {
  io.field(3, h.sub_channel_number);
  io.field(6, h.reserved1);
  io.field(14, h.year);
  io.field(16, h.month);
  io.field(17, h.day);
  io.field(18, h.hour);
  io.field(19, h.minute);
  io.field(20, h.second);
  io.field(21, h.hseconds);
  io.field(22, h.julian_day);
  io.field(24, h.event_number);
  io.field(28, h.ping_number);
  io.field(32, h.sound_velocity_mps);
  io.field(36, h.ocean_tide_m);
  io.field(40, h.reserved2);
  io.field(44, h.conductivity_freq_hz);
  io.field(48, h.temperature_freq_hz);
  io.field(52, h.pressure_freq_hz);
  io.field(56, h.pressure_temp_degc);
  io.field(60, h.conductivity_s_per_m);
  io.field(64, h.water_temperature_degc);
  io.field(68, h.pressure_psia);
  io.field(72, h.computed_sound_velocity_mps);
  io.field(76, h.mag_x_mgauss);
  io.field(80, h.mag_y_mgauss);
  io.field(84, h.mag_z_mgauss);
  io.field(88, h.aux_val);
  io.field(112, h.speed_log_kn);
  io.field(116, h.turbidity);
  io.field(120, h.ship_speed_kn);
  io.field(124, h.ship_gyro_deg);
  io.field(128, h.ship_y);
  io.field(136, h.ship_x);
  io.field(144, h.ship_altitude_dm);
  io.field(146, h.ship_depth_dm);
  io.field(148, h.fix_time_hour);
  io.field(149, h.fix_time_minute);
  io.field(150, h.fix_time_second);
  io.field(151, h.fix_time_hsecond);
  io.field(152, h.sensor_speed_kn);
  io.field(156, h.kp_km);
  io.field(160, h.sensor_y);
  io.field(168, h.sensor_x);
  io.field(176, h.sonar_status);
  io.field(178, h.range_to_fish_dm);
  io.field(180, h.bearing_to_fish_cdeg);
  io.field(182, h.cable_out_m);
  io.field(184, h.layback_m);
  io.field(188, h.cable_tension);
  io.field(192, h.sensor_depth_m);
  io.field(196, h.sensor_primary_altitude_m);
  io.field(200, h.sensor_aux_altitude_m);
  io.field(204, h.sensor_pitch_deg);
  io.field(208, h.sensor_roll_deg);
  io.field(212, h.sensor_heading_deg);
  io.field(216, h.heave_m);
  io.field(220, h.yaw_deg);
  io.field(224, h.attitude_time_tag_ms);
  io.field(228, h.dot_m);
  io.field(232, h.nav_fix_ms);
  io.field(236, h.computer_clock_hour);
  io.field(237, h.computer_clock_minute);
  io.field(238, h.computer_clock_second);
  io.field(239, h.computer_clock_hsec);
  io.field(240, h.fish_position_delta_x_third_m);
  io.field(242, h.fish_position_delta_y_third_m);
  io.field(244, h.fish_position_error_code);
  io.field(245, h.optional_offset);  // unaligned in the spec too
  io.field(249, h.cable_out_hundredths);
  io.field(250, h.reserved_space2);
}

// XTFPINGCHANHEADER without NumSamples (42), which follows from the samples (docs/formats.md 1.6).
template <class IO, class C>
void ping_chan_fields(IO& io, C& c) {
  io.field(0, c.channel_number);
  io.field(2, c.downsample_method);
  io.field(4, c.slant_range_m);
  io.field(8, c.ground_range_m);
  io.field(12, c.time_delay_s);
  io.field(16, c.time_duration_s);
  io.field(20, c.seconds_per_ping_s);
  io.field(24, c.processing_flags);
  io.field(26, c.frequency_khz);
  io.field(28, c.initial_gain_code);
  io.field(30, c.gain_code);
  io.field(32, c.band_width);
  io.field(34, c.contact_number);
  io.field(38, c.contact_classification);
  io.field(40, c.contact_sub_number);
  io.field(41, c.contact_type);
  io.field(46, c.millivolt_scale_mv);
  io.field(48, c.contact_time_off_track);
  io.field(52, c.contact_close_number);
  io.field(53, c.reserved2);
  io.field(54, c.fixed_vsop_cm);
  io.field(58, c.weight);
  io.field(60, c.reserved_space);
}

inline constexpr std::size_t kNumSamplesOffset = 42;  // within XTFPINGCHANHEADER

inline std::string hex(unsigned v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%0*X", digits, v);
  return buf;
}

// Index into XtfSamples that CHANINFO asks for: BytesPerSample 1 -> uint8, 2 -> uint16,
// 4 -> float for IEEE float32, else uint32; npos for any other BytesPerSample.
inline constexpr std::size_t kBadSampleType = std::numeric_limits<std::size_t>::max();
inline std::size_t sample_type_index(const XtfChanInfo& info) {
  switch (info.bytes_per_sample) {
    case 1:
      return 0;
    case 2:
      return 1;
    case 4:
      return info.sample_format == kSampleFormatIeeeFloat32 ? 3 : 2;
    default:
      return kBadSampleType;
  }
}

inline const char* sample_type_name(std::size_t index) {
  constexpr const char* kNames[] = {"uint8", "uint16", "uint32", "float32"};
  return index < 4 ? kNames[index] : "?";
}

inline std::size_t padded(std::size_t n) {
  return (n + kPacketAlignment - 1) / kPacketAlignment * kPacketAlignment;
}

inline bool all_zero(std::span<const std::uint8_t> b) {
  return std::all_of(b.begin(), b.end(), [](std::uint8_t x) { return x == 0; });
}

}  // namespace sonarloop::xtf::wire
