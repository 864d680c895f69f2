#include "drivers/ros2/ros2_messages.h"

#include <array>

#include "drivers/ros2/cdr.h"

namespace sonarloop::ros2 {
namespace {

constexpr std::string_view kSeparator =
    "================================================================================\n";

// The definitions (fields only), each type named in full.
constexpr std::string_view kTime = "int32 sec\nuint32 nanosec\n";
constexpr std::string_view kHeader = "builtin_interfaces/Time stamp\nstring frame_id\n";
constexpr std::string_view kPingInfo =
    "float32 frequency\nfloat32 sound_speed\nfloat32[] tx_beamwidths\nfloat32[] rx_beamwidths\n";
constexpr std::string_view kSonarImageData =
    "bool is_bigendian\nuint32 dtype\nuint32 beam_count\nuint8[] data\n";
constexpr std::string_view kRawSonarImage =
    "std_msgs/Header header\nmarine_acoustic_msgs/PingInfo ping_info\nfloat32 sample_rate\n"
    "uint32 samples_per_beam\nuint32 sample0\nfloat32[] tx_delays\nfloat32[] tx_angles\n"
    "float32[] rx_angles\nmarine_acoustic_msgs/SonarImageData image\n";
constexpr std::string_view kImage =
    "std_msgs/Header header\nuint32 height\nuint32 width\nstring encoding\nuint8 is_bigendian\n"
    "uint32 step\nuint8[] data\n";
constexpr std::string_view kNavSatStatus = "int8 status\nuint16 service\n";
constexpr std::string_view kNavSatFix =
    "std_msgs/Header header\nsensor_msgs/NavSatStatus status\nfloat64 latitude\n"
    "float64 longitude\nfloat64 altitude\nfloat64[9] position_covariance\n"
    "uint8 position_covariance_type\n";
constexpr std::string_view kPoint = "float64 x\nfloat64 y\nfloat64 z\n";
constexpr std::string_view kQuaternion = "float64 x\nfloat64 y\nfloat64 z\nfloat64 w\n";
constexpr std::string_view kPose =
    "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n";
constexpr std::string_view kPoseStamped = "std_msgs/Header header\ngeometry_msgs/Pose pose\n";

struct Dependency {
  std::string_view name;  // package/Type
  std::string_view definition;
};

MessageSchema schema(std::string name, std::string_view main,
                     std::initializer_list<Dependency> deps) {
  MessageSchema s{std::move(name), std::string(main)};
  for (const Dependency& d : deps) {
    s.definition += kSeparator;
    s.definition += "MSG: ";
    s.definition += d.name;
    s.definition += "\n";
    s.definition += d.definition;
  }
  return s;
}

void put_header(CdrWriter& w, const Header& h) {
  w.put_time(h.stamp_ns);
  w.put_string(h.frame_id);
}

}  // namespace

const MessageSchema& raw_sonar_image_schema() {
  static const MessageSchema s = schema("marine_acoustic_msgs/msg/RawSonarImage", kRawSonarImage,
                                        {{"std_msgs/Header", kHeader},
                                         {"builtin_interfaces/Time", kTime},
                                         {"marine_acoustic_msgs/PingInfo", kPingInfo},
                                         {"marine_acoustic_msgs/SonarImageData", kSonarImageData}});
  return s;
}

const MessageSchema& image_schema() {
  static const MessageSchema s =
      schema("sensor_msgs/msg/Image", kImage,
             {{"std_msgs/Header", kHeader}, {"builtin_interfaces/Time", kTime}});
  return s;
}

const MessageSchema& nav_sat_fix_schema() {
  static const MessageSchema s = schema("sensor_msgs/msg/NavSatFix", kNavSatFix,
                                        {{"std_msgs/Header", kHeader},
                                         {"builtin_interfaces/Time", kTime},
                                         {"sensor_msgs/NavSatStatus", kNavSatStatus}});
  return s;
}

const MessageSchema& pose_stamped_schema() {
  static const MessageSchema s = schema("geometry_msgs/msg/PoseStamped", kPoseStamped,
                                        {{"std_msgs/Header", kHeader},
                                         {"builtin_interfaces/Time", kTime},
                                         {"geometry_msgs/Pose", kPose},
                                         {"geometry_msgs/Point", kPoint},
                                         {"geometry_msgs/Quaternion", kQuaternion}});
  return s;
}

const MessageSchema& string_schema() {
  static const MessageSchema s = schema("std_msgs/msg/String", "string data\n", {});
  return s;
}

void encode(const RawSonarImage& m, std::vector<std::uint8_t>& out) {
  CdrWriter w(out);
  put_header(w, m.header);
  // ping_info
  w.put(m.frequency_hz);
  w.put(m.sound_speed_m_s);
  w.put_sequence<float>({});  // tx_beamwidths: not reported
  w.put_sequence<float>({});  // rx_beamwidths
  w.put(m.sample_rate_hz);
  w.put(m.samples);  // samples_per_beam
  w.put(m.sample0);
  const std::array<float, 1> zero = {0.0f};
  const std::array<float, 1> rx = {m.rx_angle_rad};
  w.put_sequence<float>(zero);  // tx_delays
  w.put_sequence<float>(zero);  // tx_angles
  w.put_sequence<float>(rx);    // rx_angles
  // image: one beam
  w.put_bool(false);
  w.put(m.dtype);
  w.put(std::uint32_t{1});
  w.put_sequence<std::uint8_t>(m.data);
}

void encode(const Image& m, std::vector<std::uint8_t>& out) {
  CdrWriter w(out);
  put_header(w, m.header);
  w.put(m.height);
  w.put(m.width);
  w.put_string(m.encoding);
  w.put(std::uint8_t{0});  // is_bigendian
  w.put(m.step);
  w.put_sequence<std::uint8_t>(m.data);
}

void encode(const NavSatFix& m, std::vector<std::uint8_t>& out) {
  CdrWriter w(out);
  put_header(w, m.header);
  w.put(std::int8_t{0});    // status: STATUS_FIX
  w.put(std::uint16_t{1});  // service: SERVICE_GPS
  w.put(m.latitude_deg);
  w.put(m.longitude_deg);
  w.put(m.altitude_m);
  for (int i = 0; i < 9; ++i)
    w.put(0.0);            // position_covariance: unknown
  w.put(std::uint8_t{0});  // COVARIANCE_TYPE_UNKNOWN
}

void encode(const PoseStamped& m, std::vector<std::uint8_t>& out) {
  CdrWriter w(out);
  put_header(w, m.header);
  for (double v : {m.x, m.y, m.z, m.qx, m.qy, m.qz, m.qw})
    w.put(v);
}

void encode_string(std::string_view data, std::vector<std::uint8_t>& out) {
  CdrWriter w(out);
  w.put_string(data);
}

}  // namespace sonarloop::ros2
