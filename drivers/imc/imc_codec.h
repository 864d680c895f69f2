#pragma once
// IMC, the LSTS Inter-Module Communication protocol (the message set of the DUNE onboard software
// and the Neptus console), as its specification IMC.xml defines it (github.com/LSTS/imc, version
// 5.4.x; docs/formats.md §7). Pure: bytes <-> plain structs, no sockets.
//
// A packet is a 20-byte header, the message's fields, and a 2-byte CRC:
//
//   off size type  field
//     0    2 u16   sync = 0xFE54 (0xFE, major 5, minor 4; read as 0x54FE: the other byte order)
//     2    2 u16   mgid: the message's id
//     4    2 u16   size: bytes of the fields (the payload)
//     6    8 fp64  timestamp: s since 1970-01-01 UTC
//    14    2 u16   src: the sending system's IMC address
//    16    1 u8    src_ent: the entity within it
//    17    2 u16   dst (0xFFFF: any)
//    19    1 u8    dst_ent (0xFF: any)
//    20 size ...   the fields, in the specification's order, no padding
//     +    2 u16   CRC-16-IBM (polynomial 0x8005, reflected, initial value 0: CRC-16/ARC) of
//                  every byte before it
//
// Every multi-byte value is in the sender's byte order, which the sync number tells; this encoder
// writes little-endian, the decoder reads either. Variable-length fields carry a u16 prefix:
// plaintext and rawdata their byte count, message-list its message count, an inline message its
// id (65535: none) before its fields (IMC.xml, "serialization").
//
// Messages this project speaks (IMC.xml ids; fields in order, units as the specification gives):
//   150 Heartbeat       (no fields)
//   151 Announce        sys_name (plaintext), sys_type (u8: 2 UUV), owner (u16), lat, lon
//                       (fp64 rad), height (fp32 m), services (plaintext, ';'-separated URLs)
//   276 SonarData       type (u8: 0 sidescan), frequency (u32 Hz), min_range, max_range (u16 m),
//                       bits_per_point (u8), scale_factor (fp32), beam_config (message-list of
//                       BeamConfig), data (rawdata; sidescan: one line across, port from far to
//                       near then starboard from near to far, little-endian units of
//                       bits_per_point, value = unit × scale_factor)
//   283 BeamConfig      beam_width, beam_height (fp32 rad)
//   350 EstimatedState  lat, lon (fp64 rad), height (fp32 m), x, y, z (fp32 m: NED offsets from
//                       lat/lon/height), phi, theta, psi (fp32 rad: roll, pitch, yaw), u, v, w
//                       (fp32 m/s, body), vx, vy, vz (fp32 m/s, NED), p, q, r (fp32 rad/s, body),
//                       depth, alt (fp32 m; negative: invalid)
//   603 MapFeature      id (plaintext), feature_type (u8: 0 point of interest), rgb_red,
//                       rgb_green, rgb_blue (u8), feature (message-list of MapPoint)
//   604 MapPoint        lat, lon (fp64 rad), alt (fp32 m)
//   606 CcuEvent        type (u8: 5 map feature added), id (plaintext), arg (message: here a
//                       MapFeature or none)
//
// Decoding is strict and never throws: a wrong sync, size, CRC or field layout, or a message this
// project does not speak, is a status (DecodeStatus) and the packet is dropped by the caller.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

namespace sonarloop::imc {

inline constexpr std::uint16_t kSync = 0xFE54;
inline constexpr std::size_t kHeaderBytes = 20;
inline constexpr std::size_t kFooterBytes = 2;
inline constexpr std::uint16_t kNoMessage = 65535;  // an empty inline message
inline constexpr std::uint16_t kAnyAddress = 0xFFFF;
inline constexpr std::uint8_t kAnyEntity = 0xFF;

// The emulated vehicle's address (an "other vehicles, AUV" address of the IMC addressing scheme,
// 0x2000-0x23FF; `--imc-system` changes it) and the entities its packets come from.
inline constexpr std::uint16_t kDefaultImcSystem = 0x2050;
inline constexpr std::uint8_t kImcEntitySonar = 1;       // SonarData
inline constexpr std::uint8_t kImcEntityNavigation = 2;  // EstimatedState, Announce, Heartbeat
inline constexpr std::uint8_t kImcEntityAtr = 3;         // contacts (the onboard consumer)

// The header's addressing and time (mgid and size follow from the message).
struct Header {
  double timestamp_s = 0.0;  // s since 1970-01-01 UTC
  std::uint16_t src = 0;
  std::uint8_t src_ent = 0;
  std::uint16_t dst = kAnyAddress;
  std::uint8_t dst_ent = kAnyEntity;
};

struct Heartbeat {
  static constexpr std::uint16_t kId = 150;
  bool operator==(const Heartbeat&) const = default;
};

struct Announce {
  static constexpr std::uint16_t kId = 151;
  static constexpr std::uint8_t kSystemUuv = 2;  // SystemType UUV
  std::string sys_name;
  std::uint8_t sys_type = kSystemUuv;
  std::uint16_t owner = kAnyAddress;  // no owner
  double lat_rad = 0.0;               // 0, 0: unknown
  double lon_rad = 0.0;
  float height_m = 0.0f;
  std::string services;
  bool operator==(const Announce&) const = default;
};

struct BeamConfig {
  static constexpr std::uint16_t kId = 283;
  float beam_width_rad = 0.0f;
  float beam_height_rad = 0.0f;
  bool operator==(const BeamConfig&) const = default;
};

struct SonarData {
  static constexpr std::uint16_t kId = 276;
  static constexpr std::uint8_t kSidescan = 0;
  std::uint8_t type = kSidescan;
  std::uint32_t frequency_hz = 0;
  std::uint16_t min_range_m = 0;
  std::uint16_t max_range_m = 0;
  std::uint8_t bits_per_point = 8;
  float scale_factor = 1.0f;
  std::vector<BeamConfig> beam_config;
  std::vector<std::uint8_t> data;
  bool operator==(const SonarData&) const = default;
};

struct EstimatedState {
  static constexpr std::uint16_t kId = 350;
  double lat_rad = 0.0, lon_rad = 0.0;
  float height_m = 0.0f;
  float x_m = 0.0f, y_m = 0.0f, z_m = 0.0f;
  float phi_rad = 0.0f, theta_rad = 0.0f, psi_rad = 0.0f;
  float u_m_s = 0.0f, v_m_s = 0.0f, w_m_s = 0.0f;
  float vx_m_s = 0.0f, vy_m_s = 0.0f, vz_m_s = 0.0f;
  float p_rad_s = 0.0f, q_rad_s = 0.0f, r_rad_s = 0.0f;
  float depth_m = -1.0f;  // negative: invalid
  float alt_m = -1.0f;    // negative: invalid
  bool operator==(const EstimatedState&) const = default;
};

struct MapPoint {
  static constexpr std::uint16_t kId = 604;
  double lat_rad = 0.0, lon_rad = 0.0;
  float alt_m = 0.0f;
  bool operator==(const MapPoint&) const = default;
};

struct MapFeature {
  static constexpr std::uint16_t kId = 603;
  static constexpr std::uint8_t kPointOfInterest = 0;  // FTYPE_POI
  std::string id;
  std::uint8_t feature_type = kPointOfInterest;
  std::uint8_t rgb_red = 0, rgb_green = 0, rgb_blue = 0;
  std::vector<MapPoint> feature;
  bool operator==(const MapFeature&) const = default;
};

struct CcuEvent {
  static constexpr std::uint16_t kId = 606;
  static constexpr std::uint8_t kMapFeatureAdded = 5;  // EVT_MAP_FEATURE_ADDED
  std::uint8_t type = kMapFeatureAdded;
  std::string id;
  std::optional<MapFeature> arg;  // the inline message (none, or a MapFeature)
  bool operator==(const CcuEvent&) const = default;
};

// The messages a packet may carry (BeamConfig and MapPoint only travel inside others).
using Message = std::variant<Heartbeat, Announce, SonarData, EstimatedState, MapFeature, CcuEvent>;

// CRC-16-IBM as IMC computes it (reflected polynomial 0x8005, initial 0, no final xor: the
// check value of "123456789" is 0xBB3D).
std::uint16_t crc16(std::span<const std::uint8_t> bytes);

// Encodes one packet into `out` (replaced; its capacity is reused: no allocation once it is
// large enough). Throws std::length_error when the fields exceed the header's 65,535 bytes or a
// variable field its u16 prefix.
template <class M>
void encode(const Header& header, const M& message, std::vector<std::uint8_t>& out);
void encode_message(const Header& header, const Message& message, std::vector<std::uint8_t>& out);

enum class DecodeStatus {
  kOk,
  kTooShort,        // fewer bytes than a header and a footer
  kBadSync,         // neither 0xFE54 nor 0x54FE
  kSizeMismatch,    // the header's size does not match the bytes given
  kBadCrc,          // the footer does not match
  kUnknownMessage,  // a valid packet of a message this project does not speak
  kBadFields,       // the fields do not fit the message's layout
};
const char* decode_status_name(DecodeStatus s);

struct Packet {
  Header header;
  std::uint16_t mgid = 0;
  Message message;
};

// Decodes one packet (exactly `bytes`: one UDP datagram). On kUnknownMessage `out.header` and
// `out.mgid` are set, the message is not.
DecodeStatus decode(std::span<const std::uint8_t> bytes, Packet& out);

}  // namespace sonarloop::imc
