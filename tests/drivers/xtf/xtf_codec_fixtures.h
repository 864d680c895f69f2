#pragma once
// Fixtures of the XTF codec's tests (xtf_codec_test.cpp): deterministic random values
// (splitmix64, no std distributions), sidescan file headers and random pings of any channel
// count, sample size and format, and little-endian field readers independent of the codec.
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "drivers/xtf/xtf_codec.h"
#include "drivers/xtf/xtf_types.h"

namespace sonarloop::xtf::codec_test {

// Deterministic test values (splitmix64); no std distributions.
class TestRng {
 public:
  explicit TestRng(std::uint64_t seed) : s_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  template <class T>
  T uint() {
    return static_cast<T>(next());
  }
  float real(float lo, float hi) {
    return lo + (hi - lo) * static_cast<float>(next() >> 40) / static_cast<float>(1ull << 24);
  }
  double real64(double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(next() >> 11) / static_cast<double>(1ull << 53);
  }

 private:
  std::uint64_t s_;
};

template <class T>
inline T le(const std::vector<std::uint8_t>& b, std::size_t off) {
  // independent of the codec: memcpy on this little-endian test host
  static_assert(std::endian::native == std::endian::little);
  T v;
  std::memcpy(&v, b.data() + off, sizeof(T));
  return v;
}

inline std::string text_at(const std::vector<std::uint8_t>& b, std::size_t off, std::size_t n) {
  std::string s(reinterpret_cast<const char*>(b.data() + off), n);
  return s.substr(0, s.find('\0'));
}

inline XtfChanInfo chan(std::uint8_t type, std::uint8_t index, std::uint16_t bytes,
                        std::uint8_t format) {
  XtfChanInfo c;
  c.type_of_channel = type;
  c.sub_channel_number = index;
  c.bytes_per_sample = bytes;
  c.sample_format = format;
  c.reserved_samples_per_channel = 0;
  c.channel_name = type == kChannelPort ? "Port" : "Stbd";
  c.frequency = 600.0f;
  c.beam_width_deg = 50.0f;
  c.tilt_angle_deg = 30.0f;
  return c;
}

// A 2- or 4-channel sidescan header whose channels all hold one sample type.
inline XtfFileHeader sidescan_header(std::size_t channels, std::uint16_t bytes,
                                     std::uint8_t format) {
  XtfFileHeader h;
  h.recording_program_name = "SSSEMU";
  h.recording_program_version = "223";
  h.sonar_name = "sonarloop";
  h.number_of_sonar_channels = static_cast<std::uint16_t>(channels);
  for (std::size_t i = 0; i < channels; ++i) {
    h.chan_info.push_back(chan(i % 2 == 0 ? kChannelPort : kChannelStbd,
                               static_cast<std::uint8_t>(i), bytes, format));
  }
  return h;
}

inline void randomize(XtfPingHeader& h, TestRng& r) {
  h.sub_channel_number = r.uint<std::uint8_t>();
  h.reserved1 = {r.uint<std::uint16_t>(), r.uint<std::uint16_t>()};
  h.year = r.uint<std::uint16_t>();
  h.month = r.uint<std::uint8_t>();
  h.day = r.uint<std::uint8_t>();
  h.hour = r.uint<std::uint8_t>();
  h.minute = r.uint<std::uint8_t>();
  h.second = r.uint<std::uint8_t>();
  h.hseconds = r.uint<std::uint8_t>();
  h.julian_day = r.uint<std::uint16_t>();
  h.event_number = r.uint<std::uint32_t>();
  h.ping_number = r.uint<std::uint32_t>();
  float* floats[] = {&h.sound_velocity_mps,
                     &h.ocean_tide_m,
                     &h.conductivity_freq_hz,
                     &h.temperature_freq_hz,
                     &h.pressure_freq_hz,
                     &h.pressure_temp_degc,
                     &h.conductivity_s_per_m,
                     &h.water_temperature_degc,
                     &h.pressure_psia,
                     &h.computed_sound_velocity_mps,
                     &h.mag_x_mgauss,
                     &h.mag_y_mgauss,
                     &h.mag_z_mgauss,
                     &h.speed_log_kn,
                     &h.turbidity,
                     &h.ship_speed_kn,
                     &h.ship_gyro_deg,
                     &h.sensor_speed_kn,
                     &h.kp_km,
                     &h.layback_m,
                     &h.cable_tension,
                     &h.sensor_depth_m,
                     &h.sensor_primary_altitude_m,
                     &h.sensor_aux_altitude_m,
                     &h.sensor_pitch_deg,
                     &h.sensor_roll_deg,
                     &h.sensor_heading_deg,
                     &h.heave_m,
                     &h.yaw_deg,
                     &h.dot_m};
  for (float* f : floats)
    *f = r.real(-1000.0f, 1000.0f);
  for (float& a : h.aux_val)
    a = r.real(-1.0f, 1.0f);
  h.reserved2 = r.uint<std::uint32_t>();
  h.ship_y = r.real64(-90, 90);
  h.ship_x = r.real64(-180, 180);
  h.sensor_y = r.real64(-90, 90);
  h.sensor_x = r.real64(-180, 180);
  h.ship_altitude_dm = r.uint<std::uint16_t>();
  h.ship_depth_dm = r.uint<std::uint16_t>();
  h.fix_time_hour = r.uint<std::uint8_t>();
  h.fix_time_minute = r.uint<std::uint8_t>();
  h.fix_time_second = r.uint<std::uint8_t>();
  h.fix_time_hsecond = r.uint<std::uint8_t>();
  h.sonar_status = r.uint<std::uint16_t>();
  h.range_to_fish_dm = r.uint<std::uint16_t>();
  h.bearing_to_fish_cdeg = r.uint<std::uint16_t>();
  h.cable_out_m = r.uint<std::uint16_t>();
  h.attitude_time_tag_ms = r.uint<std::uint32_t>();
  h.nav_fix_ms = r.uint<std::uint32_t>();
  h.computer_clock_hour = r.uint<std::uint8_t>();
  h.computer_clock_minute = r.uint<std::uint8_t>();
  h.computer_clock_second = r.uint<std::uint8_t>();
  h.computer_clock_hsec = r.uint<std::uint8_t>();
  h.fish_position_delta_x_third_m = r.uint<std::int16_t>();
  h.fish_position_delta_y_third_m = r.uint<std::int16_t>();
  h.fish_position_error_code = r.uint<std::uint8_t>();
  h.optional_offset = r.uint<std::uint32_t>();
  h.cable_out_hundredths = r.uint<std::uint8_t>();
  for (auto& b : h.reserved_space2)
    b = r.uint<std::uint8_t>();
}

inline void randomize(XtfPingChannel& c, TestRng& r) {
  c.downsample_method = r.uint<std::uint16_t>();
  c.slant_range_m = r.real(1, 300);
  c.ground_range_m = r.real(1, 300);
  c.time_delay_s = r.real(0, 1);
  c.time_duration_s = r.real(0, 1);
  c.seconds_per_ping_s = r.real(0, 1);
  c.processing_flags = r.uint<std::uint16_t>();
  c.frequency_khz = r.uint<std::uint16_t>();
  c.initial_gain_code = r.uint<std::uint16_t>();
  c.gain_code = r.uint<std::uint16_t>();
  c.band_width = r.uint<std::uint16_t>();
  c.contact_number = r.uint<std::uint32_t>();
  c.contact_classification = r.uint<std::uint16_t>();
  c.contact_sub_number = r.uint<std::uint8_t>();
  c.contact_type = r.uint<std::uint8_t>();
  c.millivolt_scale_mv = r.uint<std::uint16_t>();
  c.contact_time_off_track = r.real(-5, 5);
  c.contact_close_number = r.uint<std::uint8_t>();
  c.reserved2 = r.uint<std::uint8_t>();
  c.fixed_vsop_cm = r.real(0, 100);
  c.weight = r.uint<std::int16_t>();
  for (auto& b : c.reserved_space)
    b = r.uint<std::uint8_t>();
}

template <class T>
inline std::vector<T> random_samples(std::size_t n, TestRng& r) {
  std::vector<T> v(n);
  for (auto& s : v) {
    if constexpr (std::is_same_v<T, float>) {
      s = r.real(-1e6f, 1e6f);
    } else {
      s = r.uint<T>();
    }
  }
  return v;
}

template <class T>
inline XtfPing random_ping(std::size_t channels, std::size_t samples, TestRng& r) {
  XtfPing p;
  randomize(p.header, r);
  p.channels.resize(channels);
  for (std::size_t i = 0; i < channels; ++i) {
    randomize(p.channels[i], r);
    p.channels[i].channel_number = static_cast<std::uint16_t>(i);
    p.channels[i].samples = random_samples<T>(samples, r);
  }
  return p;
}

}  // namespace sonarloop::xtf::codec_test
