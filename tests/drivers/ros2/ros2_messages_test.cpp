// ROS 2 messages as CDR (drivers/ros2/cdr.h, ros2_messages.h) against bytes laid out by hand from
// the CDR rules (encapsulation header, alignment from its end, strings with their NUL), and the
// ros2msg schema texts (every type they use defined after its separator line).
#include "drivers/ros2/ros2_messages.h"

#include <catch2/catch.hpp>
#include <cstring>
#include <string>
#include <vector>

#include "drivers/ros2/cdr.h"

using namespace sonarloop;

namespace {

using Bytes = std::vector<std::uint8_t>;

double f64_at(const Bytes& b, std::size_t offset) {
  double v;
  std::memcpy(&v, b.data() + offset, 8);
  return v;
}

}  // namespace

TEST_CASE("cdr: std_msgs/String and the alignment rule, byte by byte") {
  Bytes b;
  ros2::encode_string("hi", b);
  CHECK(b == Bytes{0x00, 0x01, 0x00, 0x00, 0x03, 0x00, 0x00, 0x00, 'h', 'i', 0x00});

  ros2::CdrWriter w(b);
  w.put(std::uint8_t{7});
  w.put(std::uint16_t{0x0102});  // aligned to 2 after the byte
  w.put(std::uint32_t{3});
  w.put(1.0);  // aligned to 8: no padding after 1 + 1 + 2 + 4 bytes
  CHECK(b ==
        Bytes{0x00, 0x01, 0x00, 0x00, 7, 0, 0x02, 0x01, 3, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xF0, 0x3F});
  ros2::CdrWriter v(b);
  v.put(std::uint8_t{1});
  v.put(2.0);  // 7 padding bytes
  CHECK(b.size() == 4 + 8 + 8);
  CHECK(f64_at(b, 12) == 2.0);
}

TEST_CASE("cdr: a PoseStamped and a NavSatFix laid out field by field") {
  ros2::PoseStamped p;
  p.header = {1'767'225'600'250'000'000, "map"};
  p.x = 1.5;
  p.y = -2.0;
  p.z = -14.0;
  p.qw = 1.0;
  Bytes b;
  ros2::encode(p, b);
  // header: sec, nanosec, frame_id "map" (length 4 with its NUL): 16 bytes; 7 float64 from 16
  REQUIRE(b.size() == 4 + 16 + 7 * 8);
  std::int32_t sec;
  std::uint32_t nsec, len;
  std::memcpy(&sec, b.data() + 4, 4);
  std::memcpy(&nsec, b.data() + 8, 4);
  std::memcpy(&len, b.data() + 12, 4);
  CHECK(sec == 1767225600);
  CHECK(nsec == 250'000'000u);
  CHECK(len == 4);
  CHECK(std::string(reinterpret_cast<const char*>(b.data() + 16), 3) == "map");
  CHECK(b[19] == 0);
  CHECK(f64_at(b, 20) == 1.5);
  CHECK(f64_at(b, 28) == -2.0);
  CHECK(f64_at(b, 36) == -14.0);
  CHECK(f64_at(b, 68) == 1.0);  // w

  ros2::NavSatFix f;
  f.header = {0, "map"};
  f.latitude_deg = 59.9;
  f.longitude_deg = 10.75;
  f.altitude_m = -14.0;
  ros2::encode(f, b);
  // header 16, status (int8) at 16, service (u16) at 18, latitude aligned to 24, longitude 32,
  // altitude 40, 9 covariances 48..120, covariance type at 120: 121 bytes after the encapsulation
  REQUIRE(b.size() == 4 + 121);
  CHECK(b[4 + 16] == 0);
  CHECK(b[4 + 18] == 1);
  CHECK(f64_at(b, 4 + 24) == 59.9);
  CHECK(f64_at(b, 4 + 32) == 10.75);
  CHECK(f64_at(b, 4 + 40) == -14.0);
}

TEST_CASE("cdr: a one-beam RawSonarImage") {
  const Bytes samples = {1, 0, 2, 0, 3, 0};  // three uint16 samples
  ros2::RawSonarImage m;
  m.header = {0, "sonar"};
  m.frequency_hz = 600e3f;
  m.sound_speed_m_s = 1500.0f;
  m.sample_rate_hz = 15000.0f;
  m.rx_angle_rad = 1.5f;
  m.dtype = ros2::RawSonarImage::kDtypeUint16;
  m.samples = 3;
  m.data = samples;
  Bytes b;
  ros2::encode(m, b);
  // header: 8 + "sonar" (4 + 6) = 18, padded to 20; ping_info: frequency 20, sound_speed 24, two
  // empty sequences 28, 32; sample_rate 36, samples_per_beam 40, sample0 44; tx_delays (1) 48,
  // tx_angles (1) 56, rx_angles (1) 64; image: is_bigendian 72, dtype 76, beam_count 80, data
  // count 84, data 88..94
  REQUIRE(b.size() == 4 + 94);
  const auto u32_at = [&](std::size_t o) {
    std::uint32_t v;
    std::memcpy(&v, b.data() + 4 + o, 4);
    return v;
  };
  const auto f32_at = [&](std::size_t o) {
    float v;
    std::memcpy(&v, b.data() + 4 + o, 4);
    return v;
  };
  CHECK(f32_at(20) == 600e3f);
  CHECK(u32_at(28) == 0);
  CHECK(u32_at(32) == 0);
  CHECK(f32_at(36) == 15000.0f);
  CHECK(u32_at(40) == 3);
  CHECK(u32_at(64) == 1);
  CHECK(f32_at(68) == 1.5f);
  CHECK(b[4 + 72] == 0);
  CHECK(u32_at(76) == 2);
  CHECK(u32_at(80) == 1);
  CHECK(u32_at(84) == 6);
  CHECK(Bytes(b.begin() + 4 + 88, b.end()) == samples);
}

TEST_CASE("ros2msg schemas: named in full, every type used defined once") {
  for (const ros2::MessageSchema* s :
       {&ros2::raw_sonar_image_schema(), &ros2::image_schema(), &ros2::nav_sat_fix_schema(),
        &ros2::pose_stamped_schema(), &ros2::string_schema()}) {
    INFO(s->name);
    CHECK(s->name.find("/msg/") != std::string::npos);
    // each "pkg/Type name" field names a type defined in a "MSG: pkg/Type" section
    std::size_t pos = 0;
    while ((pos = s->definition.find('/', pos)) != std::string::npos) {
      const std::size_t start = s->definition.rfind('\n', pos) + 1;
      const std::size_t space = s->definition.find(' ', pos);
      const std::string type = s->definition.substr(start, space - start);
      if (type.rfind("MSG: ", 0) != 0) {
        CHECK(s->definition.find("MSG: " + type + "\n") != std::string::npos);
      }
      pos = s->definition.find('\n', pos);
    }
  }
  CHECK(ros2::raw_sonar_image_schema().definition.rfind("std_msgs/Header header\n", 0) == 0);
  CHECK(ros2::string_schema().definition == "string data\n");
}
