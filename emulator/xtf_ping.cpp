#include "emulator/xtf_ping.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <stdexcept>
#include <utility>
#include <variant>
#include <vector>

#include "sim/render/quantise.h"
#include "units/angles.h"

namespace sonarloop::emulator {
namespace {

constexpr double kHzPerKhz = 1000.0;
// String fields of XTFFILEHEADER (docs/formats.md 1.2).
constexpr std::size_t kSonarNameBytes = 16;
constexpr std::size_t kNoteBytes = 64;

// `text` cut to at most `bytes` bytes without splitting a UTF-8 character.
std::string cut_utf8(const std::string& text, std::size_t bytes) {
  if (text.size() <= bytes) return text;
  std::size_t n = bytes;
  // back up over continuation bytes (10xxxxxx) to the start of the character that was cut
  while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80)
    --n;
  return text.substr(0, n);
}

struct SampleCoding {
  std::uint16_t bytes_per_sample;
  std::uint8_t sample_format;
};

SampleCoding sample_coding(render::SampleType type) {
  switch (type) {
    case render::SampleType::kUint8:
      return {1, xtf::kSampleFormatInt8};
    case render::SampleType::kUint16:
    case render::SampleType::kInt16:
      return {2, xtf::kSampleFormatInt16};
    case render::SampleType::kFloat32:
      return {4, xtf::kSampleFormatIeeeFloat32};
  }
  throw std::invalid_argument("make_xtf_file_header: unknown sonar sample type");
}

// Horizontal (along-track) beam angle for CHANINFO.HorizBeamAngle, degrees: the two-way -3 dB
// beamwidth of a line array (kBeam), or for a strip of constant width w the angle it subtends at
// maximum range R, 2·atan(w / 2R) (kStrip).
double horizontal_beam_angle_deg(const render::SonarSetup& s) {
  if (s.desc.along_track == render::AlongTrackModel::kStrip) {
    return 2.0 * std::atan(s.along_track_resolution_m / (2.0 * s.desc.max_range_m)) * kDegPerRad;
  }
  return s.horizontal_beamwidth_rad * kDegPerRad;
}

xtf::XtfChanInfo make_chan_info(const render::SonarSetup& s, std::uint8_t type, std::uint8_t index,
                                const char* name) {
  const SampleCoding coding = sample_coding(s.desc.sample_type);
  xtf::XtfChanInfo c;
  c.type_of_channel = type;
  c.sub_channel_number = index;
  c.correction_flags = kXtfSlantRangeImagery;
  c.uni_polar = 1;
  c.bytes_per_sample = coding.bytes_per_sample;
  c.reserved_samples_per_channel = static_cast<std::uint32_t>(s.bins);
  c.channel_name = name;
  c.volt_scale_v = kXtfVoltScaleV;
  c.frequency = static_cast<float>(s.desc.frequency_hz / kHzPerKhz);
  c.horiz_beam_angle_deg = static_cast<float>(horizontal_beam_angle_deg(s));
  c.tilt_angle_deg = static_cast<float>(s.desc.depression_deg);
  c.beam_width_deg = static_cast<float>(s.vertical_beamwidth_rad * kDegPerRad);
  c.sample_format = coding.sample_format;
  return c;
}

// Quantises `line` (near to far) into the channel's own buffer of T and puts it in file order.
// The buffer is reused: no allocation once it holds vector<T> with enough capacity. (Not
// xtf::store_samples_near_to_far: that copies from a separate near-to-far buffer, which would
// need a scratch; reversing in place gives the same order by the same rule.)
template <class T>
void store_line(const render::SonarSetup& s, std::span<const float> line,
                const xtf::XtfChanInfo& info, xtf::XtfPingChannel& ch) {
  if (!std::holds_alternative<std::vector<T>>(ch.samples)) ch.samples = std::vector<T>{};
  auto& v = std::get<std::vector<T>>(ch.samples);
  v.resize(line.size());
  render::quantise_line(s, line, std::span<T>(v));
  if (xtf::stored_far_to_near(info)) std::reverse(v.begin(), v.end());
}

void fill_channel(const render::SonarSetup& s, const xtf::XtfChanInfo& info,
                  std::uint16_t channel_number, std::span<const float> line, double altitude_m,
                  xtf::XtfPingChannel& ch) {
  // zero every header field but keep the sample buffer
  xtf::XtfSamples samples = std::move(ch.samples);
  ch = xtf::XtfPingChannel{};
  ch.samples = std::move(samples);

  const double slant_range_m = static_cast<double>(s.bins) * s.desc.bin_size_m;
  ch.channel_number = channel_number;
  ch.slant_range_m = static_cast<float>(slant_range_m);
  if (std::isfinite(altitude_m)) {
    ch.ground_range_m = static_cast<float>(
        std::sqrt(std::max(0.0, slant_range_m * slant_range_m - altitude_m * altitude_m)));
  }
  ch.time_delay_s = 0.0f;
  ch.time_duration_s = static_cast<float>(slant_range_m / kXtfSoundVelocityMps);
  ch.seconds_per_ping_s = static_cast<float>(s.ping_period_s);
  ch.processing_flags = kXtfProcessingTvg;
  // how the recorder made each sample of several raw ones (none: one raw sample per bin)
  if (s.desc.raw_samples_per_bin > 1)
    ch.downsample_method = acoustics::xtf_downsample_method(s.desc.downsample);
  ch.frequency_khz = static_cast<std::uint16_t>(
      std::clamp<long>(std::lround(s.desc.frequency_hz / kHzPerKhz), 0L, 65535L));

  switch (s.desc.sample_type) {
    case render::SampleType::kUint8:
      store_line<std::uint8_t>(s, line, info, ch);
      break;
    case render::SampleType::kUint16:
    case render::SampleType::kInt16:  // 0 .. 32767: the same bytes as a signed 16-bit sample
      store_line<std::uint16_t>(s, line, info, ch);
      break;
    case render::SampleType::kFloat32:
      store_line<float>(s, line, info, ch);
      break;
  }
}

// Checks that ChanInfo[index] is a sidescan channel of `type` coded as the sonar's samples.
void check_chan_info(const render::SonarSetup& s, const xtf::XtfFileHeader& header,
                     std::size_t index, std::uint8_t type) {
  if (header.chan_info.size() <= index) {
    throw std::invalid_argument("make_xtf_ping: the file header has " +
                                std::to_string(header.chan_info.size()) +
                                " CHANINFO entries, need 2 (port, starboard)");
  }
  const xtf::XtfChanInfo& c = header.chan_info[index];
  const SampleCoding coding = sample_coding(s.desc.sample_type);
  if (c.type_of_channel != type || c.bytes_per_sample != coding.bytes_per_sample ||
      c.sample_format != coding.sample_format) {
    throw std::invalid_argument(
        "make_xtf_ping: ChanInfo[" + std::to_string(index) + "] has TypeOfChannel " +
        std::to_string(c.type_of_channel) + ", BytesPerSample " +
        std::to_string(c.bytes_per_sample) + ", SampleFormat " + std::to_string(c.sample_format) +
        "; the sonar needs TypeOfChannel " + std::to_string(type) + ", BytesPerSample " +
        std::to_string(coding.bytes_per_sample) + ", SampleFormat " +
        std::to_string(coding.sample_format) + " (use make_xtf_file_header)");
  }
}

}  // namespace

PingNav ping_nav_of(const vehicle::NavSolution& nav, const LocalTangentPlane& ltp,
                    std::int64_t time_utc_ns, double rendered_altitude_m,
                    std::uint32_t ping_number) {
  PingNav pn;
  pn.time_utc_ns = time_utc_ns;
  pn.sensor = ltp.to_geodetic(nav.north_m, nav.east_m);
  pn.heading_deg = nav.heading * kDegPerRad;
  pn.pitch_deg = nav.pitch * kDegPerRad;
  pn.roll_deg = nav.roll * kDegPerRad;
  pn.depth_m = nav.depth_m;
  pn.altitude_m = std::isfinite(nav.altitude_m) ? nav.altitude_m : rendered_altitude_m;
  pn.speed_m_s = nav.speed_over_ground_m_s;
  pn.ping_number = ping_number;
  return pn;
}

xtf::XtfFileHeader make_xtf_file_header(const render::SonarSetup& sonar,
                                        const std::string& sonar_name, const std::string& note) {
  xtf::XtfFileHeader h;
  h.recording_program_name = kXtfRecordingProgramName;
  h.recording_program_version = kXtfRecordingProgramVersion;
  h.sonar_name = cut_utf8(sonar_name, kSonarNameBytes);
  h.sonar_type = 0;  // none: readers apply no vendor-specific Weight (docs/formats.md 1.2)
  h.note_string = cut_utf8(note, kNoteBytes);
  h.nav_units = xtf::kNavUnitsLatLong;
  h.number_of_sonar_channels = 2;
  h.chan_info.push_back(make_chan_info(sonar, xtf::kChannelPort, kXtfPortChannel, "PORT"));
  h.chan_info.push_back(make_chan_info(sonar, xtf::kChannelStbd, kXtfStbdChannel, "STARBOARD"));
  return h;
}

void make_xtf_ping(const render::SonarSetup& sonar, const xtf::XtfFileHeader& header,
                   const render::PingLines& lines, const PingNav& nav, xtf::XtfPing& out) {
  check_chan_info(sonar, header, kXtfPortChannel, xtf::kChannelPort);
  check_chan_info(sonar, header, kXtfStbdChannel, xtf::kChannelStbd);
  const auto bins = static_cast<std::size_t>(sonar.bins);
  if (lines.port.size() != bins || lines.stbd.size() != bins) {
    throw std::invalid_argument("make_xtf_ping: lines have " + std::to_string(lines.port.size()) +
                                " port and " + std::to_string(lines.stbd.size()) +
                                " starboard bins, the sonar has " + std::to_string(bins));
  }

  // ping header: start from zero (a plain struct, no allocation), then the fields we know
  xtf::XtfPingHeader& p = out.header;
  p = xtf::XtfPingHeader{};
  xtf::set_time_utc_ns(p, nav.time_utc_ns);
  p.ping_number = nav.ping_number;
  p.sound_velocity_mps = static_cast<float>(kXtfSoundVelocityMps);
  p.computed_sound_velocity_mps = static_cast<float>(sonar.sound_speed_m_s);
  const auto speed_kn = static_cast<float>(nav.speed_m_s * kKnotsPerMps);
  p.ship_speed_kn = speed_kn;
  p.ship_gyro_deg = static_cast<float>(nav.heading_deg);
  p.ship_y = nav.sensor.latitude_deg;
  p.ship_x = nav.sensor.longitude_deg;
  p.fix_time_hour = p.hour;
  p.fix_time_minute = p.minute;
  p.fix_time_second = p.second;
  p.fix_time_hsecond = p.hseconds;
  p.sensor_speed_kn = speed_kn;
  p.sensor_y = nav.sensor.latitude_deg;
  p.sensor_x = nav.sensor.longitude_deg;
  p.sensor_depth_m = static_cast<float>(nav.depth_m);
  p.sensor_primary_altitude_m =
      std::isfinite(nav.altitude_m) ? static_cast<float>(nav.altitude_m) : 0.0f;
  p.sensor_pitch_deg = static_cast<float>(nav.pitch_deg);
  p.sensor_roll_deg = static_cast<float>(nav.roll_deg);
  p.sensor_heading_deg = static_cast<float>(nav.heading_deg);
  p.computer_clock_hour = p.hour;
  p.computer_clock_minute = p.minute;
  p.computer_clock_second = p.second;
  p.computer_clock_hsec = p.hseconds;

  // channels: port then starboard, ChannelNumber = ChanInfo index
  out.channels.resize(2);
  fill_channel(sonar, header.chan_info[kXtfPortChannel], kXtfPortChannel, lines.port,
               nav.altitude_m, out.channels[0]);
  fill_channel(sonar, header.chan_info[kXtfStbdChannel], kXtfStbdChannel, lines.stbd,
               nav.altitude_m, out.channels[1]);
}

}  // namespace sonarloop::emulator
