#pragma once
// Plain data for XTF (eXtended Triton Format, Triton Imaging spec X41/X42): the file header with
// its channel descriptions, and sonar ping packets (ping header + one block per channel).
//
// Byte layouts: docs/formats.md §1 (XTFFILEHEADER 1.2, CHANINFO 1.3, XTFPINGHEADER
// 1.5, XTFPINGCHANHEADER 1.6). The structs below mirror those tables field by field. Values are
// kept in the units the file stores (the field name says which: _kn knots, _dm decimetres, _deg
// degrees, _ms milliseconds ...), so that decode -> encode reproduces a file byte for byte.
// Reserved fields are kept for the same reason; writers should leave them zero.
//
// Sample order (docs/formats.md 1.7): an XtfPingChannel holds its samples exactly in FILE order.
// For a port sidescan channel (ChanInfo TypeOfChannel = kChannelPort) the file stores the FAR range
// first and nadir last; starboard and sub-bottom store nadir first. Use
// store_samples_near_to_far() / samples_near_to_far() to hand or get samples nearest-first
// whatever the side.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace sonarloop::xtf {

// ---- sizes and magic numbers (docs/formats.md 1.1-1.6) ----
inline constexpr std::size_t kFileHeaderSize = 1024;       // XTFFILEHEADER with 6 CHANINFO
inline constexpr std::size_t kChanInfoOffset = 256;        // ChanInfo[0] in the file header
inline constexpr std::size_t kChanInfoSize = 128;          // one CHANINFO
inline constexpr std::size_t kChanInfosInBaseHeader = 6;   // CHANINFO slots in the first 1024 B
inline constexpr std::size_t kChanInfosPerExtraBlock = 8;  // each further 1024 B block (xtf.h)
inline constexpr std::size_t kPacketStartSize = 14;        // common packet start (1.4)
inline constexpr std::size_t kPingHeaderSize = 256;        // XTFPINGHEADER (1.5)
inline constexpr std::size_t kPingChanHeaderSize = 64;     // XTFPINGCHANHEADER (1.6)
inline constexpr std::size_t kPacketAlignment = 64;        // Isis pads packets to 64 B (1.1)
inline constexpr std::uint8_t kFileFormat = 0x7B;          // FileFormat byte, mandatory
inline constexpr std::uint8_t kSystemType = 1;             // SystemType byte, mandatory
inline constexpr std::uint16_t kMagicNumber = 0xFACE;      // packet magic, on disk CE FA

// HeaderType values of the packet start (1.4) used here; others exist and are passed raw.
inline constexpr std::uint8_t kHeaderTypeSonar = 0;
inline constexpr std::uint8_t kHeaderTypeNotes = 1;
inline constexpr std::uint8_t kHeaderTypeBathy = 2;
inline constexpr std::uint8_t kHeaderTypeAttitude = 3;
inline constexpr std::uint8_t kHeaderTypeNavigation = 42;
inline constexpr std::uint8_t kHeaderTypePosRawNavigation = 107;

// CHANINFO.TypeOfChannel (1.3).
inline constexpr std::uint8_t kChannelSubbottom = 0;
inline constexpr std::uint8_t kChannelPort = 1;
inline constexpr std::uint8_t kChannelStbd = 2;
inline constexpr std::uint8_t kChannelBathymetry = 3;

// CHANINFO.SampleFormat (1.3, X41). 0 = legacy: type follows from BytesPerSample.
inline constexpr std::uint8_t kSampleFormatLegacy = 0;
inline constexpr std::uint8_t kSampleFormatIbmFloat32 = 1;
inline constexpr std::uint8_t kSampleFormatInt32 = 2;
inline constexpr std::uint8_t kSampleFormatInt16 = 3;
inline constexpr std::uint8_t kSampleFormatIeeeFloat32 = 5;
inline constexpr std::uint8_t kSampleFormatInt8 = 8;

// XTFFILEHEADER.NavUnits (1.2).
inline constexpr std::uint16_t kNavUnitsMetres = 0;   // X/Y are easting/northing (m)
inline constexpr std::uint16_t kNavUnitsLatLong = 3;  // X/Y are longitude/latitude (deg)

// CHANINFO: one channel's static description (128 bytes, docs/formats.md 1.3).
struct XtfChanInfo {
  std::uint8_t type_of_channel = kChannelPort;     // kChannelPort, kChannelStbd, ...
  std::uint8_t sub_channel_number = 0;             // index of this CHANINFO
  std::uint16_t correction_flags = 1;              // 1 slant-range, 2 ground-range imagery
  std::uint16_t uni_polar = 1;                     // 0 bipolar, 1 unipolar (envelope) samples
  std::uint16_t bytes_per_sample = 2;              // 1, 2 or 4
  std::uint32_t reserved_samples_per_channel = 0;  // legacy "Reserved": nominal sample count
  std::string channel_name;                        // at most 16 characters
  float volt_scale_v = 5.0f;                       // volts of a full-scale sample
  float frequency = 0.0f;  // centre frequency as stored; unit not fixed by the spec (Sea Scan: kHz)
  float horiz_beam_angle_deg = 0.0f;
  float tilt_angle_deg = 0.0f;
  float beam_width_deg = 0.0f;  // 3 dB vertical beam width
  float offset_x_m = 0.0f;      // + starboard
  float offset_y_m = 0.0f;      // + forward
  float offset_z_m = 0.0f;      // + down
  float offset_yaw_deg = 0.0f;
  float offset_pitch_deg = 0.0f;
  float offset_roll_deg = 0.0f;
  std::uint16_t beams_per_array = 0;                 // forward-look only
  std::uint8_t sample_format = kSampleFormatLegacy;  // kSampleFormat*
  std::array<std::uint8_t, 53> reserved_area2{};

  bool operator==(const XtfChanInfo&) const = default;
};

// XTFFILEHEADER (1024 bytes; more when the file has > 6 channels, docs/formats.md 1.2).
struct XtfFileHeader {
  std::uint8_t file_format = kFileFormat;
  std::uint8_t system_type = kSystemType;
  std::string recording_program_name;     // at most 8 characters
  std::string recording_program_version;  // at most 8 characters
  std::string sonar_name;                 // at most 16 characters
  std::uint16_t sonar_type = 0;           // 0 = none (see docs/formats.md 1.2 about types that
                                          // make readers apply Weight)
  std::string note_string;                // at most 64 characters
  std::string this_file_name;             // at most 64 characters
  std::uint16_t nav_units = kNavUnitsLatLong;
  std::uint16_t number_of_sonar_channels = 0;
  std::uint16_t number_of_bathymetry_channels = 0;
  std::uint8_t number_of_snippet_channels = 0;
  std::uint8_t number_of_forward_look_arrays = 0;
  std::uint16_t number_of_echo_strength_channels = 0;
  std::uint8_t number_of_interferometry_channels = 0;
  std::uint8_t reserved1 = 0;
  std::uint16_t reserved2 = 0;
  float reference_point_height_m = 0.0f;  // above the waterline
  std::array<std::uint8_t, 12> projection_type{};
  std::array<std::uint8_t, 10> spheroid_type{};
  std::int32_t navigation_latency_ms = 0;
  float origin_y = 0.0f;
  float origin_x = 0.0f;
  float nav_offset_y_m = 0.0f;  // + forward
  float nav_offset_x_m = 0.0f;  // + starboard
  float nav_offset_z_m = 0.0f;  // + down
  float nav_offset_yaw_deg = 0.0f;
  float mru_offset_y_m = 0.0f;
  float mru_offset_x_m = 0.0f;
  float mru_offset_z_m = 0.0f;
  float mru_offset_yaw_deg = 0.0f;
  float mru_offset_pitch_deg = 0.0f;  // + nose up
  float mru_offset_roll_deg = 0.0f;   // + lean to starboard
  // ChanInfo[i] at byte 256 + 128 i. Decoding keeps every declared channel plus any non-empty
  // slot of the 6 in the base block; encoding writes these and zero-fills the rest.
  std::vector<XtfChanInfo> chan_info;

  bool operator==(const XtfFileHeader&) const = default;
};

// XTFPINGHEADER (256 bytes, docs/formats.md 1.5) without the derived fields of the packet start
// (MagicNumber, HeaderType = 0, NumChansToFollow and NumBytesThisRecord come from the encoder).
struct XtfPingHeader {
  std::uint8_t sub_channel_number = 0;
  std::array<std::uint16_t, 2> reserved1{};
  // ping time: UTC recommended; resolution 1/100 s. See time_utc_ns() / set_time_utc_ns().
  std::uint16_t year = 0;
  std::uint8_t month = 0;        // 1-12
  std::uint8_t day = 0;          // 1-31
  std::uint8_t hour = 0;         // 0-23
  std::uint8_t minute = 0;       // 0-59
  std::uint8_t second = 0;       // 0-59
  std::uint8_t hseconds = 0;     // hundredths of a second, 0-99
  std::uint16_t julian_day = 0;  // day of the year (writers differ on 0- or 1-based)
  std::uint32_t event_number = 0;
  std::uint32_t ping_number = 0;      // mandatory, counts consecutively
  float sound_velocity_mps = 750.0f;  // Isis stores HALF the sound speed (one way), 750
  float ocean_tide_m = 0.0f;
  std::uint32_t reserved2 = 0;
  float conductivity_freq_hz = 0.0f;
  float temperature_freq_hz = 0.0f;
  float pressure_freq_hz = 0.0f;
  float pressure_temp_degc = 0.0f;
  float conductivity_s_per_m = 0.0f;
  float water_temperature_degc = 0.0f;
  float pressure_psia = 0.0f;
  float computed_sound_velocity_mps = 0.0f;  // full speed, e.g. 1500
  float mag_x_mgauss = 0.0f;
  float mag_y_mgauss = 0.0f;
  float mag_z_mgauss = 0.0f;
  std::array<float, 6> aux_val{};
  float speed_log_kn = 0.0f;
  float turbidity = 0.0f;  // 0-5 V x 10000
  float ship_speed_kn = 0.0f;
  float ship_gyro_deg = 0.0f;
  double ship_y = 0.0;  // ship latitude (deg) when NavUnits = 3, else northing (m)
  double ship_x = 0.0;  // ship longitude (deg) when NavUnits = 3, else easting (m)
  std::uint16_t ship_altitude_dm = 0;
  std::uint16_t ship_depth_dm = 0;
  std::uint8_t fix_time_hour = 0;  // time of the most recent nav fix
  std::uint8_t fix_time_minute = 0;
  std::uint8_t fix_time_second = 0;
  std::uint8_t fix_time_hsecond = 0;
  float sensor_speed_kn = 0.0f;  // towfish / vehicle speed
  float kp_km = 0.0f;
  double sensor_y = 0.0;  // sensor latitude (deg) when NavUnits = 3, else northing (m)
  double sensor_x = 0.0;  // sensor longitude (deg) when NavUnits = 3, else easting (m)
  std::uint16_t sonar_status = 0;
  std::uint16_t range_to_fish_dm = 0;
  std::uint16_t bearing_to_fish_cdeg = 0;  // degrees x 100
  std::uint16_t cable_out_m = 0;
  float layback_m = 0.0f;
  float cable_tension = 0.0f;
  float sensor_depth_m = 0.0f;             // below the surface, + down
  float sensor_primary_altitude_m = 0.0f;  // above the seafloor
  float sensor_aux_altitude_m = 0.0f;
  float sensor_pitch_deg = 0.0f;  // + nose up
  float sensor_roll_deg = 0.0f;   // + roll to starboard
  float sensor_heading_deg = 0.0f;
  float heave_m = 0.0f;  // + up
  float yaw_deg = 0.0f;  // + turn right
  std::uint32_t attitude_time_tag_ms = 0;
  float dot_m = 0.0f;  // distance off track
  std::uint32_t nav_fix_ms = 0;
  std::uint8_t computer_clock_hour = 0;
  std::uint8_t computer_clock_minute = 0;
  std::uint8_t computer_clock_second = 0;
  std::uint8_t computer_clock_hsec = 0;
  std::int16_t fish_position_delta_x_third_m = 0;  // metres x 3
  std::int16_t fish_position_delta_y_third_m = 0;  // metres x 3
  std::uint8_t fish_position_error_code = 0;
  std::uint32_t optional_offset = 0;  // Triton 7125 only
  std::uint8_t cable_out_hundredths = 0;
  std::array<std::uint8_t, 6> reserved_space2{};

  bool operator==(const XtfPingHeader&) const = default;
};

// Samples of one channel in file order. The alternative follows CHANINFO: BytesPerSample 1 ->
// uint8, 2 -> uint16, 4 -> float when SampleFormat is IEEE float32, else uint32 (the raw bits;
// for IBM float or signed formats reinterpret them yourself).
using XtfSamples = std::variant<std::vector<std::uint8_t>, std::vector<std::uint16_t>,
                                std::vector<std::uint32_t>, std::vector<float>>;

// XTFPINGCHANHEADER (64 bytes, docs/formats.md 1.6) plus the samples that follow it.
struct XtfPingChannel {
  std::uint16_t channel_number = 0;     // index into XtfFileHeader::chan_info
  std::uint16_t downsample_method = 0;  // 2 MAX, 4 RMS
  float slant_range_m = 0.0f;           // range of the last sample (mandatory)
  float ground_range_m = 0.0f;
  float time_delay_s = 0.0f;     // time to the first sample
  float time_duration_s = 0.0f;  // time recorded (typically slant range / 750)
  float seconds_per_ping_s = 0.0f;
  std::uint16_t processing_flags = 0;  // 4 TVG, 8 BAC&GAC, 16 filter
  std::uint16_t frequency_khz = 0;     // WORD; kHz in practice (docs/formats.md 1.9)
  std::uint16_t initial_gain_code = 0;
  std::uint16_t gain_code = 0;
  std::uint16_t band_width = 0;
  std::uint32_t contact_number = 0;
  std::uint16_t contact_classification = 0;
  std::uint8_t contact_sub_number = 0;
  std::uint8_t contact_type = 0;
  std::uint16_t millivolt_scale_mv = 0;  // 0 = use CHANINFO VoltScale
  float contact_time_off_track = 0.0f;
  std::uint8_t contact_close_number = 0;
  std::uint8_t reserved2 = 0;
  float fixed_vsop_cm = 0.0f;  // along-track ping size
  std::int16_t weight = 0;     // 2^-N scale, EdgeTech/Kongsberg sonar types only
  std::array<std::uint8_t, 4> reserved_space{};
  // Legacy files write NumSamples = 0 and give the count in CHANINFO.Reserved (pyxtf reads them
  // so). Set by the decoder in that case so that re-encoding writes 0 again.
  bool num_samples_from_chan_info = false;
  XtfSamples samples = std::vector<std::uint16_t>{};  // FILE order (port: far range first)

  std::size_t num_samples() const {
    return std::visit([](const auto& v) { return v.size(); }, samples);
  }
  std::size_t bytes_per_sample() const {
    return std::visit([](const auto& v) { return sizeof(v[0]); }, samples);
  }
  bool operator==(const XtfPingChannel&) const = default;
};

// One sonar packet: the ping header and its channel blocks in file order (port, stbd, ...).
struct XtfPing {
  XtfPingHeader header;
  std::vector<XtfPingChannel> channels;

  bool operator==(const XtfPing&) const = default;
};

// ---- helpers ----

// Sum of the six channel counts of the file header (what pyxtf calls channel_count).
std::size_t declared_channel_count(const XtfFileHeader& header);
// Bytes of a file header describing `channels` channels: 1024, plus 1024 for every further 8
// channels beyond 6 (Triton xtf.h: "header record grows 1K in size for each additional 8
// channels"), so ChanInfo[i] stays at byte 256 + 128 i for every i.
std::size_t file_header_size_for(std::size_t channels);

// Ping time (Year..HSeconds, read as UTC) as nanoseconds since 1970-01-01T00:00:00Z; nullopt when
// the fields are not a valid date and time (e.g. all zero).
std::optional<std::int64_t> time_utc_ns(const XtfPingHeader& header);
// Sets Year..HSeconds from t_ns (UTC, ns since the Unix epoch, truncated to 1/100 s towards
// minus infinity) and JulianDay to the 1-based day of the year (1 January = 1). Throws
// std::invalid_argument for times before year 0 or after 9999.
void set_time_utc_ns(XtfPingHeader& header, std::int64_t t_ns);

// True when this channel's samples are stored far range first: port sidescan (docs/formats.md 1.7).
inline bool stored_far_to_near(const XtfChanInfo& info) {
  return info.type_of_channel == kChannelPort;
}

// The CHANINFO of a ping channel (by ChannelNumber); throws std::out_of_range naming both.
const XtfChanInfo& chan_info_for(const XtfFileHeader& header, const XtfPingChannel& channel);

// Stores samples given nearest first into channel.samples in file order (reversed for port).
// Reuses the channel's buffer: no allocation once it is large enough and holds vector<T>.
template <class T>
void store_samples_near_to_far(XtfPingChannel& channel, const XtfChanInfo& info,
                               std::span<const T> near_to_far) {
  static_assert(std::is_same_v<T, std::uint8_t> || std::is_same_v<T, std::uint16_t> ||
                    std::is_same_v<T, std::uint32_t> || std::is_same_v<T, float>,
                "XTF samples are uint8, uint16, uint32 or float");
  if (!std::holds_alternative<std::vector<T>>(channel.samples)) {
    channel.samples = std::vector<T>{};
  }
  auto& out = std::get<std::vector<T>>(channel.samples);
  if (stored_far_to_near(info)) {
    out.assign(near_to_far.rbegin(), near_to_far.rend());
  } else {
    out.assign(near_to_far.begin(), near_to_far.end());
  }
}

// Copies the channel's samples nearest first into `out` (out.size() must equal num_samples()),
// converting to T. Does not allocate.
template <class T>
void copy_samples_near_to_far(const XtfPingChannel& channel, const XtfChanInfo& info,
                              std::span<T> out) {
  std::visit(
      [&](const auto& v) {
        if (v.size() != out.size()) {
          throw std::invalid_argument("copy_samples_near_to_far: output holds " +
                                      std::to_string(out.size()) + " samples, channel has " +
                                      std::to_string(v.size()));
        }
        if (stored_far_to_near(info)) {
          std::transform(v.rbegin(), v.rend(), out.begin(),
                         [](auto s) { return static_cast<T>(s); });
        } else {
          std::transform(v.begin(), v.end(), out.begin(), [](auto s) { return static_cast<T>(s); });
        }
      },
      channel.samples);
}

// The channel's samples nearest first, converted to T (e.g. float for image work).
template <class T>
std::vector<T> samples_near_to_far(const XtfPingChannel& channel, const XtfChanInfo& info) {
  std::vector<T> out(channel.num_samples());
  copy_samples_near_to_far<T>(channel, info, std::span<T>(out));
  return out;
}

}  // namespace sonarloop::xtf
