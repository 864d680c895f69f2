#include "drivers/xtf/xtf_codec.h"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <limits>
#include <type_traits>

namespace sonarloop::xtf {

namespace {

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

constexpr std::size_t kNumSamplesOffset = 42;  // within XTFPINGCHANHEADER

std::string hex(unsigned v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%0*X", digits, v);
  return buf;
}

// Index into XtfSamples that CHANINFO asks for: BytesPerSample 1 -> uint8, 2 -> uint16,
// 4 -> float for IEEE float32, else uint32; npos for any other BytesPerSample.
constexpr std::size_t kBadSampleType = std::numeric_limits<std::size_t>::max();
std::size_t sample_type_index(const XtfChanInfo& info) {
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

const char* sample_type_name(std::size_t index) {
  constexpr const char* kNames[] = {"uint8", "uint16", "uint32", "float32"};
  return index < 4 ? kNames[index] : "?";
}

std::size_t padded(std::size_t n) {
  return (n + kPacketAlignment - 1) / kPacketAlignment * kPacketAlignment;
}

bool all_zero(std::span<const std::uint8_t> b) {
  return std::all_of(b.begin(), b.end(), [](std::uint8_t x) { return x == 0; });
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// file header

std::size_t encoded_file_header_size(const XtfFileHeader& header) {
  return file_header_size_for(declared_channel_count(header));
}

std::vector<std::uint8_t> encode_file_header(const XtfFileHeader& header) {
  if (header.file_format != kFileFormat) {
    throw std::invalid_argument("XTF file header: FileFormat must be 0x7B, got " +
                                hex(header.file_format, 2));
  }
  const std::size_t declared = declared_channel_count(header);
  const std::size_t slots = std::max(declared, kChanInfosInBaseHeader);
  if (header.chan_info.size() < declared) {
    throw std::invalid_argument("XTF file header declares " + std::to_string(declared) +
                                " channels but chan_info has only " +
                                std::to_string(header.chan_info.size()) + " entries");
  }
  if (header.chan_info.size() > slots) {
    throw std::invalid_argument("XTF file header: chan_info has " +
                                std::to_string(header.chan_info.size()) +
                                " entries but a header declaring " + std::to_string(declared) +
                                " channels holds at most " + std::to_string(slots));
  }
  std::vector<std::uint8_t> bytes(file_header_size_for(declared), 0);
  FieldWriter w(bytes);
  file_header_fields(w, header);
  for (std::size_t i = 0; i < header.chan_info.size(); ++i) {
    FieldWriter cw{std::span(bytes).subspan(kChanInfoOffset + kChanInfoSize * i, kChanInfoSize)};
    chan_info_fields(cw, header.chan_info[i]);
  }
  return bytes;
}

std::size_t declared_file_header_size(std::span<const std::uint8_t> first_bytes) {
  if (first_bytes.size() < kFileHeaderSize) {
    throw XtfFormatError("XTF file header truncated: " + std::to_string(first_bytes.size()) +
                             " bytes, it needs " + std::to_string(kFileHeaderSize),
                         first_bytes.size());
  }
  if (first_bytes[0] != kFileFormat) {
    throw XtfFormatError(
        "not an XTF file header: FileFormat byte is " + hex(first_bytes[0], 2) + " (expected 0x7B)",
        0);
  }
  XtfFileHeader counts;
  FieldReader r(first_bytes);
  file_header_fields(r, counts);
  return file_header_size_for(declared_channel_count(counts));
}

XtfFileHeader decode_file_header(std::span<const std::uint8_t> bytes) {
  const std::size_t size = declared_file_header_size(bytes);
  XtfFileHeader h;
  FieldReader r(bytes);
  file_header_fields(r, h);
  const std::size_t declared = declared_channel_count(h);
  if (bytes.size() < size) {
    throw XtfFormatError("XTF file header declares " + std::to_string(declared) +
                             " channels and so is " + std::to_string(size) + " bytes long, only " +
                             std::to_string(bytes.size()) + " bytes given",
                         bytes.size());
  }
  // keep every declared channel, plus non-empty slots of the base block (byte-exact re-encoding)
  std::size_t count = declared;
  for (std::size_t i = kChanInfosInBaseHeader; i > declared; --i) {
    if (!all_zero(bytes.subspan(kChanInfoOffset + kChanInfoSize * (i - 1), kChanInfoSize))) {
      count = i;
      break;
    }
  }
  h.chan_info.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    FieldReader cr(bytes.subspan(kChanInfoOffset + kChanInfoSize * i, kChanInfoSize));
    chan_info_fields(cr, h.chan_info[i]);
  }
  return h;
}

// ---------------------------------------------------------------------------------------------
// packets

std::optional<PacketInfo> peek_packet(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < kPacketStartSize) return std::nullopt;
  PacketInfo info;
  info.magic_ok = get_le<std::uint16_t>(bytes, 0) == kMagicNumber;
  info.header_type = bytes[2];
  info.sub_channel_number = bytes[3];
  info.num_chans_to_follow = get_le<std::uint16_t>(bytes, 4);
  info.num_bytes_this_record = get_le<std::uint32_t>(bytes, 10);
  return info;
}

DatagramKind classify_datagram(std::span<const std::uint8_t> datagram) {
  if (datagram.size() >= kFileHeaderSize && datagram[0] == kFileFormat &&
      declared_file_header_size(datagram) == datagram.size()) {
    return DatagramKind::kFileHeader;
  }
  const auto info = peek_packet(datagram);
  if (info && info->valid() && info->num_bytes_this_record == datagram.size()) {
    return DatagramKind::kPacket;
  }
  return DatagramKind::kInvalid;
}

// ---------------------------------------------------------------------------------------------
// sonar pings

std::size_t encoded_ping_size(const XtfPing& ping) {
  std::size_t n = kPingHeaderSize;
  for (const auto& c : ping.channels)
    n += kPingChanHeaderSize + c.num_samples() * c.bytes_per_sample();
  return padded(n);
}

std::size_t encode_ping(const XtfPing& ping, const XtfFileHeader& header,
                        std::span<std::uint8_t> out) {
  const std::size_t declared = declared_channel_count(header);
  if (ping.channels.size() > declared) {
    throw std::invalid_argument("XTF ping has " + std::to_string(ping.channels.size()) +
                                " channels but the file header declares " +
                                std::to_string(declared));
  }
  for (std::size_t k = 0; k < ping.channels.size(); ++k) {
    const auto& c = ping.channels[k];
    // built only on error: the happy path must not allocate
    const auto which = [&] {
      return "XTF ping channel " + std::to_string(k) + " (ChannelNumber " +
             std::to_string(c.channel_number) + ")";
    };
    if (c.channel_number >= header.chan_info.size()) {
      throw std::invalid_argument(which() + " has no CHANINFO: the file header has " +
                                  std::to_string(header.chan_info.size()));
    }
    const XtfChanInfo& info = header.chan_info[c.channel_number];
    const std::size_t want = sample_type_index(info);
    if (want != c.samples.index()) {
      throw std::invalid_argument(which() + " holds " + sample_type_name(c.samples.index()) +
                                  " samples but its CHANINFO has BytesPerSample " +
                                  std::to_string(info.bytes_per_sample) + ", SampleFormat " +
                                  std::to_string(info.sample_format) + " (" +
                                  sample_type_name(want) + ")");
    }
    if (c.num_samples() > std::numeric_limits<std::uint32_t>::max()) {
      throw std::invalid_argument(which() + " has too many samples for the DWORD NumSamples");
    }
    if (c.num_samples_from_chan_info && c.num_samples() != info.reserved_samples_per_channel) {
      throw std::invalid_argument(which() + " is marked num_samples_from_chan_info but holds " +
                                  std::to_string(c.num_samples()) + " samples, CHANINFO says " +
                                  std::to_string(info.reserved_samples_per_channel));
    }
  }
  const std::size_t total = encoded_ping_size(ping);
  if (total > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("XTF ping of " + std::to_string(total) +
                                " bytes does not fit the DWORD NumBytesThisRecord");
  }
  if (out.size() < total) {
    throw std::invalid_argument("XTF ping needs " + std::to_string(total) +
                                " bytes, the output buffer holds " + std::to_string(out.size()));
  }
  auto b = out.first(total);
  std::fill(b.begin(), b.end(), std::uint8_t{0});

  // packet start + ping header
  put_le(b, 0, kMagicNumber);
  put_le(b, 2, kHeaderTypeSonar);
  put_le(b, 4, static_cast<std::uint16_t>(ping.channels.size()));
  put_le(b, 10, static_cast<std::uint32_t>(total));
  FieldWriter hw(b.first(kPingHeaderSize));
  ping_header_fields(hw, ping.header);

  // channel blocks: header then samples, little-endian
  std::size_t pos = kPingHeaderSize;
  for (const auto& c : ping.channels) {
    auto ch = b.subspan(pos, kPingChanHeaderSize);
    FieldWriter cw(ch);
    ping_chan_fields(cw, c);
    const auto n = static_cast<std::uint32_t>(c.num_samples_from_chan_info ? 0 : c.num_samples());
    put_le(ch, kNumSamplesOffset, n);
    pos += kPingChanHeaderSize;
    std::visit(
        [&](const auto& v) {
          using T = typename std::decay_t<decltype(v)>::value_type;
          for (const T s : v) {
            put_le(b, pos, s);
            pos += sizeof(T);
          }
        },
        c.samples);
  }
  // bytes [pos, total) stay zero: padding to a multiple of 64
  return total;
}

std::vector<std::uint8_t> encode_ping(const XtfPing& ping, const XtfFileHeader& header) {
  std::vector<std::uint8_t> bytes(encoded_ping_size(ping));
  encode_ping(ping, header, bytes);
  return bytes;
}

XtfPing decode_ping(std::span<const std::uint8_t> packet, const XtfFileHeader& header) {
  XtfPing ping;
  decode_ping(packet, header, ping);
  return ping;
}

namespace {

template <class T>
void read_samples(std::span<const std::uint8_t> b, std::size_t pos, std::size_t n,
                  XtfSamples& samples) {
  if (!std::holds_alternative<std::vector<T>>(samples)) samples = std::vector<T>{};
  auto& v = std::get<std::vector<T>>(samples);
  v.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    v[i] = get_le<T>(b, pos + i * sizeof(T));
}

}  // namespace

void decode_ping(std::span<const std::uint8_t> packet, const XtfFileHeader& header, XtfPing& out) {
  if (packet.size() < kPingHeaderSize) {
    throw XtfFormatError("XTF sonar packet truncated: " + std::to_string(packet.size()) +
                             " bytes, the ping header alone needs 256",
                         packet.size());
  }
  const PacketInfo info = *peek_packet(packet);
  if (!info.magic_ok) {
    throw XtfFormatError(
        "bad magic " + hex(get_le<std::uint16_t>(packet, 0), 4) + " (expected 0xFACE, bytes CE FA)",
        0);
  }
  if (info.header_type != kHeaderTypeSonar) {
    throw XtfFormatError(
        "HeaderType " + std::to_string(info.header_type) + " is not a sonar ping (0)", 2);
  }
  const std::size_t record = info.num_bytes_this_record;
  if (record < kPingHeaderSize) {
    throw XtfFormatError("NumBytesThisRecord " + std::to_string(record) +
                             " is smaller than the 256-byte ping header",
                         10);
  }
  if (record > packet.size()) {
    throw XtfFormatError("NumBytesThisRecord " + std::to_string(record) + " exceeds the " +
                             std::to_string(packet.size()) + " bytes available",
                         10);
  }
  const std::size_t declared = declared_channel_count(header);
  if (info.num_chans_to_follow > declared) {
    throw XtfFormatError("NumChansToFollow " + std::to_string(info.num_chans_to_follow) +
                             " exceeds the " + std::to_string(declared) +
                             " channels the file header declares",
                         4);
  }
  const auto b = packet.first(record);
  FieldReader hr(b.first(kPingHeaderSize));
  ping_header_fields(hr, out.header);

  out.channels.resize(info.num_chans_to_follow);
  std::size_t pos = kPingHeaderSize;
  for (std::size_t k = 0; k < out.channels.size(); ++k) {
    if (pos + kPingChanHeaderSize > record) {
      throw XtfFormatError("channel " + std::to_string(k) + " header at packet offset " +
                               std::to_string(pos) + " runs past NumBytesThisRecord " +
                               std::to_string(record),
                           pos);
    }
    XtfPingChannel& c = out.channels[k];
    const auto ch = b.subspan(pos, kPingChanHeaderSize);
    FieldReader cr(ch);
    ping_chan_fields(cr, c);
    if (c.channel_number >= header.chan_info.size()) {
      throw XtfFormatError("channel " + std::to_string(k) + " has ChannelNumber " +
                               std::to_string(c.channel_number) + " but the file header has only " +
                               std::to_string(header.chan_info.size()) + " CHANINFO entries",
                           pos);
    }
    const XtfChanInfo& ci = header.chan_info[c.channel_number];
    const std::size_t type = sample_type_index(ci);
    if (type == kBadSampleType) {
      throw XtfFormatError("CHANINFO " + std::to_string(c.channel_number) +
                               " gives BytesPerSample " + std::to_string(ci.bytes_per_sample) +
                               " (1, 2 or 4 allowed)",
                           pos);
    }
    std::uint64_t n = get_le<std::uint32_t>(ch, kNumSamplesOffset);
    c.num_samples_from_chan_info = n == 0 && ci.reserved_samples_per_channel > 0;
    if (c.num_samples_from_chan_info) n = ci.reserved_samples_per_channel;
    pos += kPingChanHeaderSize;
    const std::uint64_t data_bytes = n * ci.bytes_per_sample;
    if (pos + data_bytes > record) {
      throw XtfFormatError("channel " + std::to_string(k) + " (ChannelNumber " +
                               std::to_string(c.channel_number) + "): " + std::to_string(n) +
                               " samples x " + std::to_string(ci.bytes_per_sample) +
                               " bytes at packet offset " + std::to_string(pos) +
                               " run past NumBytesThisRecord " + std::to_string(record),
                           pos);
    }
    const auto count = static_cast<std::size_t>(n);
    switch (type) {
      case 0:
        read_samples<std::uint8_t>(b, pos, count, c.samples);
        break;
      case 1:
        read_samples<std::uint16_t>(b, pos, count, c.samples);
        break;
      case 2:
        read_samples<std::uint32_t>(b, pos, count, c.samples);
        break;
      default:
        read_samples<float>(b, pos, count, c.samples);
        break;
    }
    pos += static_cast<std::size_t>(data_bytes);
  }
}

}  // namespace sonarloop::xtf
