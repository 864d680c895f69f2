#pragma once
// The ROS 2 messages sonarloop records (drivers/mcap/mcap_writer.h, docs/formats.md §8), as CDR
// (cdr.h) and as the "ros2msg" schema text MCAP carries: the message's definition, then one
// section per type it uses ("====...====" line, "MSG: package/Type", the definition), every type
// named in full. Definitions are the messages' fields as their packages define them
// (marine_acoustic_msgs 2.0, sensor_msgs, geometry_msgs, std_msgs, builtin_interfaces of ROS 2
// Humble and later); constants and comments are left out, which changes no byte on the wire.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sonarloop::ros2 {

// A message type as an MCAP Schema record holds it.
struct MessageSchema {
  std::string name;        // e.g. "sensor_msgs/msg/NavSatFix"
  std::string definition;  // ros2msg text with its dependencies
};

const MessageSchema& raw_sonar_image_schema();  // marine_acoustic_msgs/msg/RawSonarImage
const MessageSchema& image_schema();            // sensor_msgs/msg/Image
const MessageSchema& nav_sat_fix_schema();      // sensor_msgs/msg/NavSatFix
const MessageSchema& pose_stamped_schema();     // geometry_msgs/msg/PoseStamped
const MessageSchema& string_schema();           // std_msgs/msg/String

// std_msgs/Header.
struct Header {
  std::int64_t stamp_ns = 0;  // ns since 1970-01-01 UTC
  std::string_view frame_id;
};

// marine_acoustic_msgs/RawSonarImage of one beam (a sidescan side): samples near to far.
struct RawSonarImage {
  static constexpr std::uint32_t kDtypeUint8 = 0;
  static constexpr std::uint32_t kDtypeUint16 = 2;
  static constexpr std::uint32_t kDtypeFloat32 = 8;
  Header header;
  float frequency_hz = 0.0f;
  float sound_speed_m_s = 0.0f;
  float sample_rate_hz = 0.0f;  // samples per second of two-way travel time
  std::uint32_t sample0 = 0;    // the first sample's index (samples before it not recorded)
  float rx_angle_rad = 0.0f;    // the beam's across-track angle from nadir, + to starboard
  std::uint32_t dtype = kDtypeUint16;
  std::uint32_t samples = 0;
  std::span<const std::uint8_t> data;  // samples × the dtype's size, little-endian
};

// sensor_msgs/Image.
struct Image {
  Header header;
  std::uint32_t height = 0, width = 0;
  std::string_view encoding;  // e.g. "mono8"
  std::uint32_t step = 0;     // bytes per row
  std::span<const std::uint8_t> data;
};

// sensor_msgs/NavSatFix (status: a fix; covariance unknown).
struct NavSatFix {
  Header header;
  double latitude_deg = 0.0, longitude_deg = 0.0, altitude_m = 0.0;
};

// geometry_msgs/PoseStamped.
struct PoseStamped {
  Header header;
  double x = 0.0, y = 0.0, z = 0.0;
  double qx = 0.0, qy = 0.0, qz = 0.0, qw = 1.0;
};

// Each encodes one message as CDR into `out` (replaced; its capacity reused).
void encode(const RawSonarImage& m, std::vector<std::uint8_t>& out);
void encode(const Image& m, std::vector<std::uint8_t>& out);
void encode(const NavSatFix& m, std::vector<std::uint8_t>& out);
void encode(const PoseStamped& m, std::vector<std::uint8_t>& out);
void encode_string(std::string_view data, std::vector<std::uint8_t>& out);  // std_msgs/String

}  // namespace sonarloop::ros2
