// IMC packets (drivers/imc/imc_codec.h) against hand-checked byte strings (laid out field by field
// from IMC.xml, their CRCs computed apart, table-driven, with CRC-16/ARC), a big-endian packet,
// round trips of every message, and the refusals.
#include "drivers/imc/imc_codec.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace sonarloop;

namespace {

using Bytes = std::vector<std::uint8_t>;

imc::Header test_header(double t = 1.5) {
  imc::Header h;
  h.timestamp_s = t;
  h.src = 0x4001;
  h.src_ent = 0x22;
  return h;
}

template <class M>
Bytes encoded(const M& m, const imc::Header& h = test_header()) {
  Bytes out;
  imc::encode(h, m, out);
  return out;
}

template <class M>
M round_trip(const M& m) {
  const Bytes b = encoded(m);
  imc::Packet p;
  REQUIRE(imc::decode(b, p) == imc::DecodeStatus::kOk);
  CHECK(p.mgid == M::kId);
  REQUIRE(std::holds_alternative<M>(p.message));
  return std::get<M>(p.message);
}

float float_at(const Bytes& b, std::size_t offset) {
  float v;
  std::memcpy(&v, b.data() + offset, 4);  // little-endian host (x86, ARM)
  return v;
}

}  // namespace

TEST_CASE("imc: the CRC is CRC-16-IBM as IMC computes it (the catalogue's check value)") {
  const std::string check = "123456789";
  CHECK(imc::crc16({reinterpret_cast<const std::uint8_t*>(check.data()), check.size()}) == 0xBB3D);
  CHECK(imc::crc16({}) == 0);
}

TEST_CASE("imc: a Heartbeat, byte by byte") {
  // sync 54 FE, id 150, size 0, timestamp 1.5 (3FF8...), src 0x4001, src_ent 0x22, dst FFFF,
  // dst_ent FF, CRC 0x8713
  const Bytes expected = {0x54, 0xFE, 0x96, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
                          0x00, 0xF8, 0x3F, 0x01, 0x40, 0x22, 0xFF, 0xFF, 0xFF, 0x13, 0x87};
  CHECK(encoded(imc::Heartbeat{}) == expected);
  imc::Packet p;
  REQUIRE(imc::decode(expected, p) == imc::DecodeStatus::kOk);
  CHECK(p.mgid == 150);
  CHECK(p.header.timestamp_s == 1.5);
  CHECK(p.header.src == 0x4001);
  CHECK(p.header.src_ent == 0x22);
  CHECK(p.header.dst == imc::kAnyAddress);
  CHECK(p.header.dst_ent == imc::kAnyEntity);
  CHECK(std::holds_alternative<imc::Heartbeat>(p.message));
}

TEST_CASE("imc: a big-endian packet (sync FE 54) is read in its own byte order") {
  const Bytes big = {0xFE, 0x54, 0x00, 0x96, 0x00, 0x00, 0x3F, 0xF8, 0x00, 0x00, 0x00,
                     0x00, 0x00, 0x00, 0x40, 0x01, 0x22, 0xFF, 0xFF, 0xFF, 0x04, 0xFA};
  imc::Packet p;
  REQUIRE(imc::decode(big, p) == imc::DecodeStatus::kOk);
  CHECK(p.mgid == 150);
  CHECK(p.header.timestamp_s == 1.5);
  CHECK(p.header.src == 0x4001);
  // re-encoded little-endian: the hand-checked little-endian bytes
  Bytes le;
  imc::encode_message(p.header, p.message, le);
  CHECK(le[0] == 0x54);
  CHECK(le[1] == 0xFE);
  CHECK(le == encoded(imc::Heartbeat{}));
}

TEST_CASE("imc: a sidescan SonarData, byte by byte") {
  imc::SonarData s;
  s.frequency_hz = 600000;
  s.max_range_m = 50;
  s.bits_per_point = 8;
  s.scale_factor = 1.0f;
  s.data = {1, 2, 3, 4};
  // payload: type 00, frequency C0 27 09 00, min 00 00, max 32 00, bits 08, scale 00 00 80 3F,
  // beam_config count 00 00, data length 04 00, data 01 02 03 04 (22 bytes)
  const Bytes expected = {0x54, 0xFE, 0x14, 0x01, 0x16, 0x00, 0x00, 0x00, 0x10, 0x40, 0x6E,
                          0x55, 0xDA, 0x41, 0x01, 0x40, 0x22, 0xFF, 0xFF, 0xFF, 0x00, 0xC0,
                          0x27, 0x09, 0x00, 0x00, 0x00, 0x32, 0x00, 0x08, 0x00, 0x00, 0x80,
                          0x3F, 0x00, 0x00, 0x04, 0x00, 0x01, 0x02, 0x03, 0x04, 0xC1, 0x60};
  CHECK(encoded(s, test_header(1767225600.25)) == expected);
  CHECK(round_trip(s) == s);
}

TEST_CASE("imc: EstimatedState's fields in the specification's order (88 bytes)") {
  imc::EstimatedState e;
  e.lat_rad = 0.7;
  e.lon_rad = -0.15;
  e.x_m = 1.0f;
  e.y_m = 2.0f;
  e.z_m = 3.0f;
  e.phi_rad = 0.01f;
  e.theta_rad = -0.02f;
  e.psi_rad = 1.25f;
  e.u_m_s = 1.5f;
  e.vx_m_s = 0.5f;
  e.vy_m_s = 1.4f;
  e.r_rad_s = 0.03f;
  e.depth_m = 17.5f;
  e.alt_m = 7.5f;
  const Bytes b = encoded(e);
  REQUIRE(b.size() == imc::kHeaderBytes + 88 + imc::kFooterBytes);
  CHECK(b[4] == 88);
  CHECK(b[5] == 0);
  const std::size_t f = imc::kHeaderBytes;
  double lat;
  std::memcpy(&lat, b.data() + f, 8);
  CHECK(lat == 0.7);
  CHECK(float_at(b, f + 20) == 1.0f);   // x
  CHECK(float_at(b, f + 40) == 1.25f);  // psi
  CHECK(float_at(b, f + 44) == 1.5f);   // u
  CHECK(float_at(b, f + 60) == 1.4f);   // vy
  CHECK(float_at(b, f + 76) == 0.03f);  // r
  CHECK(float_at(b, f + 80) == 17.5f);  // depth
  CHECK(float_at(b, f + 84) == 7.5f);   // alt
  CHECK(round_trip(e) == e);
}

TEST_CASE("imc: Announce, BeamConfig lists and a contact as a map feature round-trip") {
  imc::Announce a;
  a.sys_name = "sonarloop-auv";
  a.lat_rad = 0.7;
  a.lon_rad = -0.15;
  a.services = "imc+udp://127.0.0.1:6002/";
  CHECK(round_trip(a) == a);
  const Bytes ab = encoded(a);
  // sys_name: a u16 length then the characters
  CHECK(ab[imc::kHeaderBytes] == 13);
  CHECK(ab[imc::kHeaderBytes + 1] == 0);
  CHECK(std::string(ab.begin() + imc::kHeaderBytes + 2, ab.begin() + imc::kHeaderBytes + 15) ==
        "sonarloop-auv");

  imc::SonarData s;
  s.beam_config = {{0.01f, 0.9f}, {0.02f, 0.8f}};
  s.data.assign(300, 7);
  s.bits_per_point = 16;
  CHECK(round_trip(s) == s);

  imc::MapFeature mf;
  mf.id = "contact 7: manta (mine-like)";
  mf.rgb_red = 255;
  mf.feature = {{0.7, -0.15, -20.0f}};
  imc::CcuEvent ev;
  ev.id = mf.id;
  ev.arg = mf;
  CHECK(round_trip(ev) == ev);
  CHECK(round_trip(mf) == mf);
  imc::CcuEvent empty;
  empty.id = "x";
  CHECK(round_trip(empty) == empty);
  // the inline message's id comes before its fields
  const Bytes eb = encoded(ev);
  const std::size_t arg = imc::kHeaderBytes + 1 + 2 + ev.id.size();
  CHECK(eb[arg] == (imc::MapFeature::kId & 0xFF));
  CHECK(eb[arg + 1] == (imc::MapFeature::kId >> 8));
}

TEST_CASE("imc: what the decoder refuses") {
  const Bytes good = encoded(imc::Heartbeat{});
  imc::Packet p;
  CHECK(imc::decode(Bytes(good.begin(), good.begin() + 21), p) == imc::DecodeStatus::kTooShort);
  Bytes b = good;
  b[0] = 0x55;
  CHECK(imc::decode(b, p) == imc::DecodeStatus::kBadSync);
  b = good;
  b.push_back(0);
  CHECK(imc::decode(b, p) == imc::DecodeStatus::kSizeMismatch);
  b = good;
  b[8] ^= 1;  // a timestamp bit
  CHECK(imc::decode(b, p) == imc::DecodeStatus::kBadCrc);
  b = good;
  b[20] ^= 1;  // the CRC itself
  CHECK(imc::decode(b, p) == imc::DecodeStatus::kBadCrc);

  // a valid packet of another message (id 151 with a Heartbeat's empty fields: Announce needs
  // fields) and an id not spoken here
  auto with_id = [](std::uint16_t id, Bytes payload) {
    Bytes out(imc::kHeaderBytes, 0);
    out[0] = 0x54;
    out[1] = 0xFE;
    out[2] = static_cast<std::uint8_t>(id & 0xFF);
    out[3] = static_cast<std::uint8_t>(id >> 8);
    out[4] = static_cast<std::uint8_t>(payload.size());
    for (std::uint8_t byte : payload)
      out.push_back(byte);
    const std::uint16_t c = imc::crc16(out);
    out.push_back(static_cast<std::uint8_t>(c & 0xFF));
    out.push_back(static_cast<std::uint8_t>(c >> 8));
    return out;
  };
  CHECK(imc::decode(with_id(151, {}), p) == imc::DecodeStatus::kBadFields);
  CHECK(imc::decode(with_id(999, {1, 2, 3}), p) == imc::DecodeStatus::kUnknownMessage);
  CHECK(p.mgid == 999);
  CHECK(imc::decode(with_id(150, {0}), p) == imc::DecodeStatus::kBadFields);  // a byte too many
  // a length prefix beyond the fields
  CHECK(imc::decode(with_id(603, {0xFF, 0x00}), p) == imc::DecodeStatus::kBadFields);
  // a CcuEvent whose inline message is not a MapFeature
  CHECK(imc::decode(with_id(606, {5, 0, 0, 150, 0}), p) == imc::DecodeStatus::kBadFields);
  CHECK(std::string(imc::decode_status_name(imc::DecodeStatus::kBadCrc)) == "CRC mismatch");
}

TEST_CASE("imc: the fuzz harness's seeds (made apart, in Python, from IMC.xml) decode") {
  const std::filesystem::path dir =
      std::filesystem::path(SONARLOOP_SOURCE_DIR) / "tests/fuzz/corpus/imc_decode";
  std::size_t n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::ifstream in(entry.path(), std::ios::binary);
    const Bytes b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    imc::Packet p;
    INFO(entry.path().filename().string());
    CHECK(imc::decode(b, p) == imc::DecodeStatus::kOk);
    ++n;
  }
  CHECK(n == 6);
}

TEST_CASE("imc: fields beyond the header's 65535 bytes are refused when encoding") {
  imc::SonarData s;
  s.data.assign(65536, 0);
  Bytes out;
  CHECK_THROWS_AS(imc::encode(test_header(), s, out), std::length_error);
  // the data fits its u16 prefix, the fields (18 bytes besides the data) do not fit the header
  s.data.assign(65535 - 10, 0);
  CHECK_THROWS_AS(imc::encode(test_header(), s, out), std::length_error);
}
