// The simulator ping -> XTF mapping: file header fields, ping fields, sample order and values
// through the real codec (encode_ping/decode_ping) and through a real file (XtfWriter/XtfReader),
// for each sample type; and no allocation once the output ping is sized.
#include "emulator/xtf_ping.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <new>
#include <numbers>
#include <span>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "drivers/xtf/xtf_codec.h"
#include "drivers/xtf/xtf_file.h"
#include "drivers/xtf/xtf_types.h"
#include "sim/render/quantise.h"
#include "sim/render/sonar.h"
#include "tests/support/allocation_counter.h"
#include "tests/support/temp_dir.h"
#include "units/angles.h"

// Heap allocations are counted (tests/support/allocation_counter.h, also under ASan), to show
// that make_xtf_ping reuses the buffers of its output.
using sonarloop::testing::allocations_in;

namespace {

using namespace sonarloop;
using emulator::make_xtf_file_header;
using emulator::make_xtf_ping;
using emulator::PingNav;
using render::SampleType;

// 2026-03-14T15:09:26.535897123Z
constexpr std::int64_t kPingTimeNs = 1773500966LL * 1'000'000'000LL + 535'897'123LL;

struct TypeCase {
  SampleType type;
  std::uint16_t bytes_per_sample;
  std::uint8_t sample_format;
  const char* name;
};
constexpr TypeCase kTypeCases[] = {
    {SampleType::kUint8, 1, xtf::kSampleFormatInt8, "uint8"},
    {SampleType::kUint16, 2, xtf::kSampleFormatInt16, "uint16"},
    {SampleType::kInt16, 2, xtf::kSampleFormatInt16, "int16"},
    {SampleType::kFloat32, 4, xtf::kSampleFormatIeeeFloat32, "float32"},
};

render::SonarSetup test_setup(SampleType type,
                              render::AlongTrackModel model = render::AlongTrackModel::kBeam) {
  render::SonarDesc d;
  d.name = "test sidescan";
  d.frequency_hz = 600e3;
  d.max_range_m = 30.0;
  d.bin_size_m = 0.05;  // 600 bins
  d.depression_deg = 12.5;
  d.array_length_m = 0.5;
  d.array_height_m = 0.02;
  d.along_track = model;
  d.along_track_resolution_m = 0.1;
  d.sample_type = type;
  return render::make_sonar_setup(d, scene::WaterDesc{});
}

// Intensity that quantise.h maps to amplitude `a` re full scale at the centre of bin k.
float intensity_for(const render::SonarSetup& s, std::size_t k, double a) {
  const double r = (static_cast<double>(k) + 0.5) * s.desc.bin_size_m;
  const double unit = render::relative_amplitude(s, 1.0, r);  // amplitude ∝ √intensity
  return static_cast<float>((a / unit) * (a / unit));
}

// A ramp: port rises from -60 dB to -0.2 dB re full scale, starboard falls from -6 dB to -66 dB;
// port bin 0 is empty (sample 0) and port's last bin is 10 dB over full scale (clipped).
render::PingLines ramp_lines(const render::SonarSetup& s, double scale = 1.0) {
  render::PingLines l;
  const auto n = static_cast<std::size_t>(s.bins);
  l.port.resize(n);
  l.stbd.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double x = static_cast<double>(k) / static_cast<double>(n - 1);
    l.port[k] = intensity_for(s, k, scale * std::pow(10.0, (-60.0 + 59.8 * x) / 20.0));
    l.stbd[k] = intensity_for(s, k, scale * std::pow(10.0, (-6.0 - 60.0 * x) / 20.0));
  }
  l.port[0] = 0.0f;
  l.port[n - 1] = intensity_for(s, n - 1, std::pow(10.0, 10.0 / 20.0));
  l.altitude_m = 4.5;
  return l;
}

PingNav test_nav() {
  PingNav nav;
  nav.time_utc_ns = kPingTimeNs;
  nav.sensor = GeoPoint{55.912345678912, -3.198765432198};
  nav.heading_deg = 271.25;
  nav.pitch_deg = -1.5;
  nav.roll_deg = 2.25;
  nav.depth_m = 25.5;
  nav.altitude_m = 4.5;
  nav.speed_m_s = 2.0;
  nav.ping_number = 123456;
  return nav;
}

template <class T>
std::vector<T> quantised(const render::SonarSetup& s, const std::vector<float>& line) {
  std::vector<T> out(line.size());
  render::quantise_line(s, line, std::span<T>(out));
  return out;
}

// Little-endian sample of type T at `p` (independent of the codec's reading code).
template <class T>
T read_le(const std::uint8_t* p) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i)
    v |= static_cast<std::uint32_t>(p[i]) << (8 * i);
  if constexpr (std::is_same_v<T, float>) {
    return std::bit_cast<float>(v);
  } else {
    return static_cast<T>(v);
  }
}

std::uint32_t read_u32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return read_le<std::uint32_t>(b.data() + at);
}

const void* sample_data(const xtf::XtfPingChannel& ch) {
  return std::visit([](const auto& v) -> const void* { return v.data(); }, ch.samples);
}

// The sample checks of one type: file order in the bytes and in the decoded struct, values equal
// to quantise_line near -> far.
template <class T>
void check_samples(const render::SonarSetup& s, const render::PingLines& lines,
                   const xtf::XtfFileHeader& h, const std::vector<std::uint8_t>& bytes,
                   const xtf::XtfPing& decoded) {
  const std::vector<T> port = quantised<T>(s, lines.port);
  const std::vector<T> stbd = quantised<T>(s, lines.stbd);
  const std::size_t n = port.size();
  // the ramp exercises the range of the type: many distinct values, 0 and clipping included
  std::vector<T> sorted = port;
  std::sort(sorted.begin(), sorted.end());
  CHECK(std::unique(sorted.begin(), sorted.end()) - sorted.begin() > 50);
  CHECK(port.front() == T(0));
  if constexpr (!std::is_same_v<T, float>) {
    // clipping at full scale: the type's maximum, or 32767 for int16 samples
    const T full_scale =
        s.desc.sample_type == SampleType::kInt16 ? T(32767) : std::numeric_limits<T>::max();
    CHECK(port.back() == full_scale);
  }

  // in the file: port samples far range first, starboard nadir first
  REQUIRE(decoded.channels.size() == 2);
  const auto& port_file = std::get<std::vector<T>>(decoded.channels[0].samples);
  const auto& stbd_file = std::get<std::vector<T>>(decoded.channels[1].samples);
  REQUIRE(port_file.size() == n);
  REQUIRE(stbd_file.size() == n);
  CHECK(std::equal(port_file.begin(), port_file.end(), port.rbegin()));
  CHECK(std::equal(stbd_file.begin(), stbd_file.end(), stbd.begin()));
  // the same read through the driver's near -> far helper
  CHECK(xtf::samples_near_to_far<T>(decoded.channels[0], h.chan_info[0]) == port);
  CHECK(xtf::samples_near_to_far<T>(decoded.channels[1], h.chan_info[1]) == stbd);

  // and in the raw bytes (docs/formats.md 1.7): [256) ping header, [64) port channel header, port
  // samples, [64) starboard channel header, starboard samples
  const std::size_t port_at = 256 + 64;
  const std::size_t stbd_hdr = port_at + n * sizeof(T);
  const std::size_t stbd_at = stbd_hdr + 64;
  REQUIRE(bytes.size() >= stbd_at + n * sizeof(T));
  CHECK(read_u32(bytes, 256 + 42) == n);                        // NumSamples
  CHECK(read_u32(bytes, stbd_hdr + 42) == n);                   // NumSamples
  CHECK(read_le<std::uint16_t>(bytes.data() + 256) == 0);       // ChannelNumber port
  CHECK(read_le<std::uint16_t>(bytes.data() + stbd_hdr) == 1);  // ChannelNumber stbd
  CHECK(read_le<T>(bytes.data() + port_at) == port[n - 1]);     // far range first
  CHECK(read_le<T>(bytes.data() + port_at + (n - 1) * sizeof(T)) == port[0]);
  CHECK(read_le<T>(bytes.data() + stbd_at) == stbd[0]);  // nadir first
  CHECK(read_le<T>(bytes.data() + stbd_at + (n - 1) * sizeof(T)) == stbd[n - 1]);
}

void check_samples_of_type(SampleType type, const render::SonarSetup& s,
                           const render::PingLines& lines, const xtf::XtfFileHeader& h,
                           const std::vector<std::uint8_t>& bytes, const xtf::XtfPing& decoded) {
  switch (type) {
    case SampleType::kUint8:
      check_samples<std::uint8_t>(s, lines, h, bytes, decoded);
      break;
    case SampleType::kUint16:
    case SampleType::kInt16:
      check_samples<std::uint16_t>(s, lines, h, bytes, decoded);
      break;
    case SampleType::kFloat32:
      check_samples<float>(s, lines, h, bytes, decoded);
      break;
  }
}

}  // namespace

TEST_CASE("the file header describes the sonar, for each sample type", "[xtf_ping]") {
  for (const TypeCase& tc : kTypeCases) {
    INFO("sample type " << tc.name);
    const render::SonarSetup s = test_setup(tc.type);
    REQUIRE(s.bins == 600);
    const xtf::XtfFileHeader h = make_xtf_file_header(s, "Test SSS", "a note");
    CHECK(h.file_format == 0x7B);
    CHECK(h.system_type == 1);
    CHECK(h.recording_program_name == "SONARLP");
    CHECK(h.recording_program_version == emulator::kXtfRecordingProgramVersion);
    CHECK(h.sonar_name == "Test SSS");
    CHECK(h.note_string == "a note");
    CHECK(h.sonar_type == 0);
    CHECK(h.nav_units == 3);
    CHECK(h.number_of_sonar_channels == 2);
    CHECK(h.number_of_bathymetry_channels == 0);
    REQUIRE(h.chan_info.size() == 2);
    for (std::size_t i = 0; i < 2; ++i) {
      const xtf::XtfChanInfo& c = h.chan_info[i];
      INFO("ChanInfo[" << i << "]");
      CHECK(c.type_of_channel == (i == 0 ? xtf::kChannelPort : xtf::kChannelStbd));
      CHECK(c.channel_name == (i == 0 ? "PORT" : "STARBOARD"));
      CHECK(c.sub_channel_number == i);
      CHECK(c.bytes_per_sample == tc.bytes_per_sample);
      CHECK(c.sample_format == tc.sample_format);
      CHECK(c.reserved_samples_per_channel == 600);
      CHECK(c.frequency == 600.0f);  // kHz, as the Iver file
      CHECK(c.horiz_beam_angle_deg ==
            Approx(s.horizontal_beamwidth_rad * kDegPerRad).epsilon(1e-6));
      // two-way -3 dB of a 0.5 m array at 600 kHz: 0.6378 λ/L rad ≈ 0.18°
      CHECK(c.horiz_beam_angle_deg ==
            Approx(0.6378 * s.wavelength_m / 0.5 * kDegPerRad).epsilon(2e-3));
      CHECK(c.tilt_angle_deg == 12.5f);
      CHECK(c.beam_width_deg == Approx(s.vertical_beamwidth_rad * kDegPerRad).epsilon(1e-6));
      CHECK(c.volt_scale_v == 5.0f);
      CHECK(c.correction_flags == 1);
      CHECK(c.uni_polar == 1);
      CHECK(c.offset_x_m == 0.0f);
      CHECK(c.beams_per_array == 0);
    }
    // encode -> decode gives it back; the bytes sit where docs/formats.md 1.2/1.3 says
    const std::vector<std::uint8_t> bytes = xtf::encode_file_header(h);
    REQUIRE(bytes.size() == 1024);
    CHECK(xtf::decode_file_header(bytes) == h);
    CHECK(std::string(reinterpret_cast<const char*>(bytes.data()) + 2, 7) == "SONARLP");
    CHECK(read_le<std::uint16_t>(bytes.data() + 164) == 3);  // NavUnits
    CHECK(read_le<std::uint16_t>(bytes.data() + 166) == 2);  // NumberOfSonarChannels
    CHECK(bytes[256] == 1);                                  // ChanInfo[0] PORT
    CHECK(bytes[384] == 2);                                  // ChanInfo[1] STBD
    CHECK(read_le<std::uint16_t>(bytes.data() + 256 + 6) == tc.bytes_per_sample);
    CHECK(bytes[256 + 74] == tc.sample_format);
    CHECK(read_le<float>(bytes.data() + 256 + 32) == 600.0f);  // Frequency
  }
}

TEST_CASE("strip sonars give the angle of the strip at maximum range", "[xtf_ping]") {
  const render::SonarSetup s = test_setup(SampleType::kUint16, render::AlongTrackModel::kStrip);
  const xtf::XtfFileHeader h = make_xtf_file_header(s, "sas", "");
  // 0.1 m strip at 30 m: 2·atan(0.05/30) = 0.19099°
  CHECK(h.chan_info[0].horiz_beam_angle_deg == Approx(0.190986).epsilon(1e-5));
  CHECK(h.chan_info[1].horiz_beam_angle_deg == h.chan_info[0].horiz_beam_angle_deg);
}

TEST_CASE("long names are cut to their fields at a character boundary", "[xtf_ping]") {
  const render::SonarSetup s = test_setup(SampleType::kUint16);
  // 15 ASCII bytes then 'é' (2 bytes) would end at byte 17: cut before it
  const xtf::XtfFileHeader h =
      make_xtf_file_header(s, "ABCDEFGHIJKLMNO\xC3\xA9XYZ", std::string(100, 'n'));
  CHECK(h.sonar_name == "ABCDEFGHIJKLMNO");
  CHECK(h.note_string == std::string(64, 'n'));
  CHECK_NOTHROW(xtf::encode_file_header(h));
  const xtf::XtfFileHeader h2 = make_xtf_file_header(s, "ABCDEFGHIJKLMN\xC3\xA9XYZ", "");
  CHECK(h2.sonar_name == "ABCDEFGHIJKLMN\xC3\xA9");
}

TEST_CASE("a ping maps to XTF and survives encode/decode, for each sample type", "[xtf_ping]") {
  for (const TypeCase& tc : kTypeCases) {
    INFO("sample type " << tc.name);
    const render::SonarSetup s = test_setup(tc.type);
    const xtf::XtfFileHeader h = make_xtf_file_header(s, "Test SSS", "");
    const render::PingLines lines = ramp_lines(s);
    const PingNav nav = test_nav();
    xtf::XtfPing ping;
    make_xtf_ping(s, h, lines, nav, ping);

    const std::vector<std::uint8_t> bytes = xtf::encode_ping(ping, h);
    CHECK(bytes.size() == (256u + 2u * (64u + 600u * tc.bytes_per_sample) + 63u) / 64u * 64u);
    const xtf::XtfPing decoded = xtf::decode_ping(bytes, h);
    CHECK(decoded == ping);

    // ping header
    const xtf::XtfPingHeader& p = decoded.header;
    CHECK(p.year == 2026);
    CHECK(p.month == 3);
    CHECK(p.day == 14);
    CHECK(p.hour == 15);
    CHECK(p.minute == 9);
    CHECK(p.second == 26);
    CHECK(p.hseconds == 53);
    CHECK(p.julian_day == 73);  // 31 + 28 + 14, 1-based
    REQUIRE(xtf::time_utc_ns(p).has_value());
    CHECK(*xtf::time_utc_ns(p) == kPingTimeNs - kPingTimeNs % 10'000'000);  // to the 1/100 s
    CHECK(p.fix_time_hour == 15);
    CHECK(p.fix_time_minute == 9);
    CHECK(p.fix_time_second == 26);
    CHECK(p.fix_time_hsecond == 53);
    CHECK(p.computer_clock_hour == 15);
    CHECK(p.computer_clock_hsec == 53);
    CHECK(p.ping_number == 123456);
    CHECK(p.event_number == 0);
    CHECK(p.sound_velocity_mps == 750.0f);
    CHECK(p.computed_sound_velocity_mps == static_cast<float>(s.sound_speed_m_s));
    CHECK(p.computed_sound_velocity_mps > 1400.0f);
    CHECK(p.computed_sound_velocity_mps < 1600.0f);
    CHECK(p.sensor_y == Approx(55.912345678912).margin(1e-9));
    CHECK(p.sensor_x == Approx(-3.198765432198).margin(1e-9));
    CHECK(p.ship_y == Approx(55.912345678912).margin(1e-9));
    CHECK(p.ship_x == Approx(-3.198765432198).margin(1e-9));
    CHECK(p.sensor_speed_kn == Approx(3.8876889849).epsilon(1e-6));  // 2 m/s
    CHECK(p.ship_speed_kn == p.sensor_speed_kn);
    CHECK(p.ship_gyro_deg == 271.25f);
    CHECK(p.sensor_heading_deg == 271.25f);
    CHECK(p.sensor_pitch_deg == -1.5f);
    CHECK(p.sensor_roll_deg == 2.25f);
    CHECK(p.sensor_depth_m == 25.5f);
    CHECK(p.sensor_primary_altitude_m == 4.5f);
    CHECK(p.layback_m == 0.0f);
    CHECK(p.ship_altitude_dm == 0);
    // the same fields at their byte offsets (docs/formats.md 1.5)
    CHECK(read_le<std::uint16_t>(bytes.data() + 0) == 0xFACE);
    CHECK(bytes[2] == 0);                                  // HeaderType sonar
    CHECK(read_le<std::uint16_t>(bytes.data() + 4) == 2);  // NumChansToFollow
    CHECK(read_u32(bytes, 10) == bytes.size());            // NumBytesThisRecord
    CHECK(read_le<std::uint16_t>(bytes.data() + 14) == 2026);
    CHECK(bytes[21] == 53);  // HSeconds
    CHECK(read_u32(bytes, 28) == 123456);
    CHECK(read_le<float>(bytes.data() + 32) == 750.0f);
    CHECK(std::bit_cast<double>(static_cast<std::uint64_t>(read_u32(bytes, 160)) |
                                static_cast<std::uint64_t>(read_u32(bytes, 164)) << 32) ==
          Approx(55.912345678912).margin(1e-9));  // SensorYcoordinate

    // channel headers
    const double slant = 600 * 0.05;
    for (std::size_t i = 0; i < 2; ++i) {
      const xtf::XtfPingChannel& c = decoded.channels[i];
      INFO("channel " << i);
      CHECK(c.channel_number == i);
      CHECK(c.slant_range_m == Approx(30.0).epsilon(1e-7));
      CHECK(c.ground_range_m == Approx(std::sqrt(slant * slant - 4.5 * 4.5)).epsilon(1e-6));
      CHECK(c.time_delay_s == 0.0f);
      CHECK(c.time_duration_s == Approx(30.0 / 750.0).epsilon(1e-7));
      CHECK(c.seconds_per_ping_s == Approx(s.ping_period_s).epsilon(1e-7));
      CHECK(c.seconds_per_ping_s == Approx(2.0 * 30.0 / s.sound_speed_m_s).epsilon(1e-6));
      CHECK(c.processing_flags == 4);
      CHECK(c.frequency_khz == 600);
      CHECK(c.num_samples() == 600);
      CHECK(c.bytes_per_sample() == tc.bytes_per_sample);
      CHECK(c.downsample_method == 0);
      CHECK(c.millivolt_scale_mv == 0);
      CHECK(c.weight == 0);
      CHECK_FALSE(c.num_samples_from_chan_info);
    }
    check_samples_of_type(tc.type, s, lines, h, bytes, decoded);
  }
}

TEST_CASE("an unknown altitude is written as zero, not NaN", "[xtf_ping]") {
  const render::SonarSetup s = test_setup(SampleType::kUint16);
  const xtf::XtfFileHeader h = make_xtf_file_header(s, "x", "");
  PingNav nav = test_nav();
  nav.altitude_m = std::nan("");
  xtf::XtfPing ping;
  make_xtf_ping(s, h, ramp_lines(s), nav, ping);
  CHECK(ping.header.sensor_primary_altitude_m == 0.0f);
  CHECK(ping.channels[0].ground_range_m == 0.0f);
  CHECK(ping.channels[1].ground_range_m == 0.0f);
  // altitude above the slant range: no ground range
  nav.altitude_m = 40.0;
  make_xtf_ping(s, h, ramp_lines(s), nav, ping);
  CHECK(ping.channels[0].ground_range_m == 0.0f);
}

TEST_CASE("DownsampleMethod says how the recorder made each sample of its raw ones", "[xtf_ping]") {
  // one raw sample per bin: nothing to say (0); several: 2 MAX, 4 RMS, 0 for decimation
  const std::pair<acoustics::Downsample, int> cases[] = {{acoustics::Downsample::kMax, 2},
                                                         {acoustics::Downsample::kRms, 4},
                                                         {acoustics::Downsample::kDecimate, 0}};
  for (const auto& [how, code] : cases) {
    render::SonarSetup s = test_setup(SampleType::kUint16);
    s.desc.speckle_model = render::SpeckleModel::kPulse;
    s.desc.downsample = how;
    const xtf::XtfFileHeader h = make_xtf_file_header(s, "x", "");
    xtf::XtfPing ping;
    make_xtf_ping(s, h, ramp_lines(s), test_nav(), ping);
    CHECK(ping.channels[0].downsample_method == 0);
    s.desc.raw_samples_per_bin = 3;
    make_xtf_ping(s, h, ramp_lines(s), test_nav(), ping);
    CHECK(ping.channels[0].downsample_method == code);
    CHECK(ping.channels[1].downsample_method == code);
    CHECK(xtf::decode_ping(xtf::encode_ping(ping, h), h).channels[1].downsample_method == code);
  }
}

TEST_CASE("pings written with XtfWriter read back with XtfReader", "[xtf_ping]") {
  testing::TempDir dir("xtf_ping");
  for (const TypeCase& tc : kTypeCases) {
    INFO("sample type " << tc.name);
    const render::SonarSetup s = test_setup(tc.type);
    const xtf::XtfFileHeader h = make_xtf_file_header(s, "Test SSS", "emulator test");
    const std::string path = dir.file(std::string("pings_") + tc.name + ".xtf");
    const LocalTangentPlane ltp(GeoPoint{55.9, -3.2});
    constexpr int kPings = 5;
    std::vector<xtf::XtfPing> written;
    {
      xtf::XtfWriter writer(path, h);
      xtf::XtfPing ping;
      for (int k = 0; k < kPings; ++k) {
        PingNav nav = test_nav();
        nav.ping_number = static_cast<std::uint32_t>(k);
        nav.time_utc_ns = kPingTimeNs + k * 40'000'000LL;
        nav.sensor = ltp.to_geodetic(2.0 * 0.04 * k, 10.0);
        make_xtf_ping(s, h, ramp_lines(s, 1.0 / (k + 1)), nav, ping);
        writer.write_ping(ping);
        written.push_back(ping);
      }
      writer.close();
    }
    const std::size_t packet = (256u + 2u * (64u + 600u * tc.bytes_per_sample) + 63u) / 64u * 64u;
    CHECK(std::filesystem::file_size(path) == 1024 + kPings * packet);

    xtf::XtfReader reader(path);
    CHECK(reader.file_header() == h);
    xtf::XtfRecord rec;
    int k = 0;
    while (reader.next(rec)) {
      REQUIRE(k < kPings);
      CHECK(rec.is_ping);
      CHECK(rec.ping == written[static_cast<std::size_t>(k)]);
      CHECK(rec.ping.header.ping_number == static_cast<std::uint32_t>(k));
      CHECK(*xtf::time_utc_ns(rec.ping.header) ==
            (kPingTimeNs + k * 40'000'000LL) / 10'000'000 * 10'000'000);
      const Vec2 local = ltp.to_local(GeoPoint{rec.ping.header.sensor_y, rec.ping.header.sensor_x});
      CHECK(local.x() == Approx(0.08 * k).margin(1e-6));
      CHECK(local.y() == Approx(10.0).margin(1e-6));
      ++k;
    }
    CHECK(k == kPings);
    CHECK(reader.stats().sonar_pings == kPings);
    CHECK(reader.stats().other_packets == 0);
  }
}

TEST_CASE("make_xtf_ping reuses the output's buffers and rewrites every field", "[xtf_ping]") {
  for (const TypeCase& tc : kTypeCases) {
    INFO("sample type " << tc.name);
    const render::SonarSetup s = test_setup(tc.type);
    const xtf::XtfFileHeader h = make_xtf_file_header(s, "Test SSS", "");
    const render::PingLines first = ramp_lines(s);
    const render::PingLines second = ramp_lines(s, 0.5);
    PingNav nav = test_nav();

    xtf::XtfPing out;
    // sizes the buffers (and shows that the counter does count)
    CHECK(allocations_in([&] { make_xtf_ping(s, h, first, nav, out); }) > 0);
    // leftovers a previous user of `out` might have set must not survive
    out.header.event_number = 99;
    out.header.ocean_tide_m = 1.5f;
    out.channels[0].gain_code = 7;
    out.channels[1].contact_number = 3;
    const void* port_data = sample_data(out.channels[0]);
    const void* stbd_data = sample_data(out.channels[1]);
    const void* channels_data = out.channels.data();
    nav.ping_number += 1;
    nav.time_utc_ns += 40'000'000;

    CHECK(allocations_in([&] { make_xtf_ping(s, h, second, nav, out); }) == 0);
    CHECK(sample_data(out.channels[0]) == port_data);
    CHECK(sample_data(out.channels[1]) == stbd_data);
    CHECK(out.channels.data() == channels_data);

    // the result equals a fresh mapping: nothing left over
    xtf::XtfPing fresh;
    make_xtf_ping(s, h, second, nav, fresh);
    CHECK(out == fresh);
    CHECK(out.header.event_number == 0);
    CHECK(out.channels[0].gain_code == 0);
  }
  // a ping of another sample type is converted (allocating once) and then reused
  const render::SonarSetup s8 = test_setup(SampleType::kUint8);
  const render::SonarSetup s16 = test_setup(SampleType::kUint16);
  xtf::XtfPing out;
  make_xtf_ping(s16, make_xtf_file_header(s16, "", ""), ramp_lines(s16), test_nav(), out);
  const xtf::XtfFileHeader h8 = make_xtf_file_header(s8, "", "");
  make_xtf_ping(s8, h8, ramp_lines(s8), test_nav(), out);
  CHECK(std::holds_alternative<std::vector<std::uint8_t>>(out.channels[0].samples));
  CHECK(out.channels[0].num_samples() == 600);
  CHECK_NOTHROW(xtf::encode_ping(out, h8));
}

TEST_CASE("make_xtf_ping refuses a header or lines that do not fit the sonar", "[xtf_ping]") {
  const render::SonarSetup s8 = test_setup(SampleType::kUint8);
  const render::SonarSetup s16 = test_setup(SampleType::kUint16);
  const xtf::XtfFileHeader h16 = make_xtf_file_header(s16, "", "");
  xtf::XtfPing out;
  CHECK_THROWS_WITH(make_xtf_ping(s8, h16, ramp_lines(s8), test_nav(), out),
                    Catch::Contains("BytesPerSample 2") && Catch::Contains("BytesPerSample 1"));
  xtf::XtfFileHeader one = h16;
  one.chan_info.resize(1);
  CHECK_THROWS_WITH(make_xtf_ping(s16, one, ramp_lines(s16), test_nav(), out),
                    Catch::Contains("1 CHANINFO"));
  xtf::XtfFileHeader swapped = h16;
  std::swap(swapped.chan_info[0], swapped.chan_info[1]);
  CHECK_THROWS_WITH(make_xtf_ping(s16, swapped, ramp_lines(s16), test_nav(), out),
                    Catch::Contains("TypeOfChannel"));
  render::PingLines short_lines = ramp_lines(s16);
  short_lines.stbd.pop_back();
  CHECK_THROWS_WITH(make_xtf_ping(s16, h16, short_lines, test_nav(), out),
                    Catch::Contains("599 starboard bins, the sonar has 600"));
}
