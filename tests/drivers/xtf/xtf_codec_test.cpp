// XTF codec: byte offsets against docs/formats.md §1, encode -> decode round trips,
// padding, errors.
#include "drivers/xtf/xtf_codec.h"

#include <catch2/catch.hpp>

#include "drivers/xtf/xtf_types.h"
#include "tests/drivers/xtf/xtf_codec_fixtures.h"
#include "tests/support/allocation_counter.h"

// Heap allocations are counted (tests/support/allocation_counter.h, also under ASan), to show
// that encoding into a span and decoding into a reused ping do not allocate.
using sonarloop::testing::allocations_in;

using namespace sonarloop::xtf;
using namespace sonarloop::xtf::codec_test;

namespace {

// Encodes pings of every size class and checks the bytes (padding, sync, sizes, little-endian
// samples) and the round trip.
template <class T>
void check_round_trip(std::size_t channels, std::uint16_t bytes, std::uint8_t format,
                      std::uint64_t seed) {
  TestRng r(seed);
  const XtfFileHeader h = sidescan_header(channels, bytes, format);
  for (const std::size_t n : {0u, 1u, 7u, 31u, 32u, 500u, 1000u, 1024u, 4001u}) {
    const XtfPing ping = random_ping<T>(channels, n, r);
    const std::vector<std::uint8_t> b = encode_ping(ping, h);
    const std::size_t unpadded = kPingHeaderSize + channels * (kPingChanHeaderSize + n * bytes);
    INFO("channels " << channels << ", samples " << n << ", bytes/sample " << bytes);
    REQUIRE(b.size() == encoded_ping_size(ping));
    CHECK(b.size() % 64 == 0);
    CHECK(b.size() >= unpadded);
    CHECK(b.size() < unpadded + 64);
    CHECK(le<std::uint32_t>(b, 10) == b.size());  // NumBytesThisRecord = padded size
    CHECK(b[0] == 0xCE);
    CHECK(b[1] == 0xFA);
    CHECK(b[2] == kHeaderTypeSonar);
    CHECK(le<std::uint16_t>(b, 4) == channels);
    for (std::size_t i = unpadded; i < b.size(); ++i)
      REQUIRE(b[i] == 0);
    // samples little-endian right after each channel header
    for (std::size_t k = 0; k < channels; ++k) {
      const std::size_t ch = kPingHeaderSize + k * (kPingChanHeaderSize + n * bytes);
      CHECK(le<std::uint32_t>(b, ch + 42) == n);
      const auto& v = std::get<std::vector<T>>(ping.channels[k].samples);
      for (std::size_t i = 0; i < n; i += 97) {
        REQUIRE(le<T>(b, ch + kPingChanHeaderSize + i * bytes) == v[i]);
      }
    }
    const XtfPing back = decode_ping(b, h);
    REQUIRE(back == ping);
    REQUIRE(encode_ping(back, h) == b);
  }
}

}  // namespace

TEST_CASE("file header fields sit at the docs/formats.md 1.2/1.3 offsets", "[xtf]") {
  XtfFileHeader h = sidescan_header(2, 2, kSampleFormatInt16);
  h.sonar_type = 44;
  h.note_string = "note";
  h.this_file_name = "pings.xtf";
  h.nav_units = kNavUnitsLatLong;
  h.reference_point_height_m = 1.5f;
  h.navigation_latency_ms = -12;
  h.nav_offset_y_m = 0.25f;
  h.mru_offset_roll_deg = -2.5f;
  h.chan_info[1].reserved_samples_per_channel = 1024;
  h.chan_info[1].channel_name = "Stbd 600";
  h.chan_info[1].volt_scale_v = 2.5f;
  h.chan_info[1].frequency = 600.0f;
  h.chan_info[1].offset_roll_deg = 3.0f;

  const std::vector<std::uint8_t> b = encode_file_header(h);
  REQUIRE(b.size() == 1024);
  CHECK(b[0] == 0x7B);
  CHECK(b[1] == 1);
  CHECK(text_at(b, 2, 8) == "SSSEMU");
  CHECK(text_at(b, 10, 8) == "223");
  CHECK(text_at(b, 18, 16) == "sonarloop");
  CHECK(le<std::uint16_t>(b, 34) == 44);
  CHECK(text_at(b, 36, 64) == "note");
  CHECK(text_at(b, 100, 64) == "pings.xtf");
  CHECK(le<std::uint16_t>(b, 164) == 3);  // NavUnits
  CHECK(le<std::uint16_t>(b, 166) == 2);  // NumberOfSonarChannels
  CHECK(le<std::uint16_t>(b, 168) == 0);
  CHECK(le<float>(b, 178) == 1.5f);
  CHECK(le<std::int32_t>(b, 204) == -12);
  CHECK(le<float>(b, 216) == 0.25f);
  CHECK(le<float>(b, 252) == -2.5f);
  // ChanInfo[i] at 256 + 128 i
  CHECK(b[256] == kChannelPort);
  CHECK(b[384] == kChannelStbd);                  // ChanInfo[1].TypeOfChannel
  CHECK(b[385] == 1);                             // SubChannelNumber
  CHECK(le<std::uint16_t>(b, 384 + 6) == 2);      // BytesPerSample
  CHECK(le<std::uint32_t>(b, 384 + 8) == 1024);   // Reserved (legacy samples per channel)
  CHECK(text_at(b, 384 + 12, 16) == "Stbd 600");  // ChannelName
  CHECK(le<float>(b, 384 + 28) == 2.5f);          // VoltScale
  CHECK(le<float>(b, 384 + 32) == 600.0f);        // Frequency
  CHECK(le<float>(b, 384 + 68) == 3.0f);          // OffsetRoll
  CHECK(b[384 + 74] == kSampleFormatInt16);       // SampleFormat
  for (std::size_t i = 512; i < 1024; ++i)
    REQUIRE(b[i] == 0);  // unused ChanInfo zero-filled

  const XtfFileHeader back = decode_file_header(b);
  CHECK(back == h);
  CHECK(encode_file_header(back) == b);
  CHECK(declared_file_header_size(b) == 1024);
}

TEST_CASE("file header strings fill their fields exactly; bad headers are refused", "[xtf]") {
  XtfFileHeader h = sidescan_header(2, 2, 0);
  h.note_string = std::string(64, 'n');  // no room for a NUL: kept whole
  h.sonar_name = std::string(16, 's');
  auto b = encode_file_header(h);
  CHECK(decode_file_header(b).note_string == h.note_string);
  CHECK(decode_file_header(b).sonar_name == h.sonar_name);

  h.sonar_name = std::string(17, 's');
  CHECK_THROWS_WITH(encode_file_header(h), Catch::Contains("SonarName holds at most 16"));
  h.sonar_name = "ok";
  h.number_of_sonar_channels = 3;  // only 2 CHANINFO
  CHECK_THROWS_WITH(encode_file_header(h), Catch::Contains("declares 3 channels"));
  h.number_of_sonar_channels = 2;
  h.file_format = 0x7A;
  CHECK_THROWS_AS(encode_file_header(h), std::invalid_argument);

  // decoding: too short, wrong FileFormat
  h.file_format = kFileFormat;
  b = encode_file_header(h);
  try {
    decode_file_header(std::span(b).first(1000));
    FAIL("no error");
  } catch (const XtfFormatError& e) {
    CHECK(std::string(e.what()).find("1000 bytes") != std::string::npos);
  }
  b[0] = 0x00;
  CHECK_THROWS_AS(decode_file_header(b), XtfFormatError);
}

TEST_CASE("more than 6 channels grow the file header by 1024 bytes per 8 channels", "[xtf]") {
  CHECK(file_header_size_for(0) == 1024);
  CHECK(file_header_size_for(6) == 1024);
  CHECK(file_header_size_for(7) == 2048);
  CHECK(file_header_size_for(14) == 2048);
  CHECK(file_header_size_for(15) == 3072);

  XtfFileHeader h = sidescan_header(8, 1, kSampleFormatInt8);
  h.chan_info[7].channel_name = "eighth";
  const auto b = encode_file_header(h);
  REQUIRE(b.size() == 2048);
  CHECK(declared_file_header_size(std::span(b).first(1024)) == 2048);
  CHECK(b[256 + 128 * 7] == kChannelStbd);  // ChanInfo[7] in the extension block
  CHECK(text_at(b, 256 + 128 * 7 + 12, 16) == "eighth");
  const XtfFileHeader back = decode_file_header(b);
  REQUIRE(back.chan_info.size() == 8);
  CHECK(back == h);
  CHECK_THROWS_AS(decode_file_header(std::span(b).first(1024)), XtfFormatError);
}

TEST_CASE("ping header and channel header fields sit at the docs/formats.md 1.5/1.6 offsets",
          "[xtf]") {
  const XtfFileHeader h = sidescan_header(2, 2, kSampleFormatInt16);
  XtfPing p;
  p.header.year = 2024;
  p.header.month = 5;
  p.header.day = 17;
  p.header.hour = 13;
  p.header.minute = 45;
  p.header.second = 59;
  p.header.hseconds = 99;
  p.header.julian_day = 138;
  p.header.event_number = 0x01020304;
  p.header.ping_number = 123456;
  p.header.sound_velocity_mps = 750.0f;
  p.header.computed_sound_velocity_mps = 1500.0f;
  p.header.ship_speed_kn = 4.5f;
  p.header.ship_y = 48.445;
  p.header.ship_x = -68.83;
  p.header.sensor_speed_kn = 3.5f;
  p.header.sensor_y = 48.44545166666666;
  p.header.sensor_x = -68.82793666666667;
  p.header.sensor_depth_m = 14.07f;
  p.header.sensor_primary_altitude_m = 11.45f;
  p.header.sensor_pitch_deg = -2.0f;
  p.header.sensor_roll_deg = 1.5f;
  p.header.sensor_heading_deg = 354.4f;
  p.header.nav_fix_ms = 987654;
  p.header.optional_offset = 0xA1B2C3D4;
  p.header.cable_out_hundredths = 77;
  p.channels.resize(2);
  for (std::uint16_t i = 0; i < 2; ++i) {
    auto& c = p.channels[i];
    c.channel_number = i;
    c.downsample_method = 2;
    c.slant_range_m = 29.98f;
    c.time_duration_s = 29.98f / 750.0f;
    c.seconds_per_ping_s = 0.13f;
    c.processing_flags = 4;
    c.frequency_khz = 600;
    c.millivolt_scale_mv = 5000;
    c.weight = -3;
    std::vector<std::uint16_t> s(1000);
    for (std::size_t k = 0; k < s.size(); ++k)
      s[k] = static_cast<std::uint16_t>(k * 7 + i);
    c.samples = s;
  }
  const auto b = encode_ping(p, h);
  CHECK(b.size() == 4416);  // docs/formats.md 1.7: 256 + 2 (64 + 2000) = 4384 -> padded 4416
  CHECK(le<std::uint32_t>(b, 10) == 4416);
  CHECK(le<std::uint16_t>(b, 14) == 2024);
  CHECK(b[16] == 5);
  CHECK(b[17] == 17);
  CHECK(b[18] == 13);
  CHECK(b[19] == 45);
  CHECK(b[20] == 59);
  CHECK(b[21] == 99);
  CHECK(le<std::uint16_t>(b, 22) == 138);
  CHECK(le<std::uint32_t>(b, 24) == 0x01020304u);
  CHECK(le<std::uint32_t>(b, 28) == 123456);        // PingNumber
  CHECK(le<float>(b, 32) == 750.0f);                // SoundVelocity
  CHECK(le<float>(b, 72) == 1500.0f);               // ComputedSoundVelocity
  CHECK(le<float>(b, 120) == 4.5f);                 // ShipSpeed
  CHECK(le<double>(b, 128) == 48.445);              // ShipYcoordinate
  CHECK(le<double>(b, 136) == -68.83);              // ShipXcoordinate
  CHECK(le<float>(b, 152) == 3.5f);                 // SensorSpeed
  CHECK(le<double>(b, 160) == 48.44545166666666);   // SensorYcoordinate
  CHECK(le<double>(b, 168) == -68.82793666666667);  // SensorXcoordinate
  CHECK(le<float>(b, 192) == 14.07f);               // SensorDepth
  CHECK(le<float>(b, 196) == 11.45f);               // SensorPrimaryAltitude
  CHECK(le<float>(b, 204) == -2.0f);                // SensorPitch
  CHECK(le<float>(b, 208) == 1.5f);                 // SensorRoll
  CHECK(le<float>(b, 212) == 354.4f);               // SensorHeading
  CHECK(le<std::uint32_t>(b, 232) == 987654u);      // NavFixMilliseconds
  CHECK(le<std::uint32_t>(b, 245) == 0xA1B2C3D4u);  // OptionalOffset (unaligned)
  CHECK(b[249] == 77);                              // CableOutHundredths
  // channel 1 header follows channel 0's 1000 samples
  for (const std::size_t ch : {std::size_t{256}, std::size_t{256 + 64 + 2000}}) {
    const std::uint16_t index = ch == 256 ? 0 : 1;
    CHECK(le<std::uint16_t>(b, ch + 0) == index);     // ChannelNumber
    CHECK(le<std::uint16_t>(b, ch + 2) == 2);         // DownsampleMethod
    CHECK(le<float>(b, ch + 4) == 29.98f);            // SlantRange
    CHECK(le<float>(b, ch + 16) == 29.98f / 750.0f);  // TimeDuration
    CHECK(le<float>(b, ch + 20) == 0.13f);            // SecondsPerPing
    CHECK(le<std::uint16_t>(b, ch + 24) == 4);        // ProcessingFlags
    CHECK(le<std::uint16_t>(b, ch + 26) == 600);      // Frequency
    CHECK(le<std::uint32_t>(b, ch + 42) == 1000);     // NumSamples
    CHECK(le<std::uint16_t>(b, ch + 46) == 5000);     // MillivoltScale
    CHECK(le<std::int16_t>(b, ch + 58) == -3);        // Weight
    CHECK(le<std::uint16_t>(b, ch + 64) == index);    // sample 0
    CHECK(le<std::uint16_t>(b, ch + 64 + 2 * 999) == 999 * 7 + index);
  }
}

TEST_CASE("ping round trip is byte-exact for 8/16/32-bit and float samples, 2 and 4 channels",
          "[xtf]") {
  check_round_trip<std::uint8_t>(2, 1, kSampleFormatInt8, 1);
  check_round_trip<std::uint8_t>(4, 1, kSampleFormatLegacy, 2);
  check_round_trip<std::uint16_t>(2, 2, kSampleFormatInt16, 3);
  check_round_trip<std::uint16_t>(4, 2, kSampleFormatLegacy, 4);
  check_round_trip<std::uint32_t>(2, 4, kSampleFormatInt32, 5);
  check_round_trip<float>(2, 4, kSampleFormatIeeeFloat32, 6);
  check_round_trip<float>(4, 4, kSampleFormatIeeeFloat32, 7);
}

TEST_CASE("mixed sample types per channel follow each channel's CHANINFO", "[xtf]") {
  XtfFileHeader h = sidescan_header(4, 2, 0);
  h.chan_info[2].bytes_per_sample = 1;
  h.chan_info[3].bytes_per_sample = 4;
  h.chan_info[3].sample_format = kSampleFormatIeeeFloat32;
  TestRng r(11);
  XtfPing p = random_ping<std::uint16_t>(4, 333, r);
  p.channels[2].samples = random_samples<std::uint8_t>(100, r);
  p.channels[3].samples = random_samples<float>(17, r);
  const auto b = encode_ping(p, h);
  CHECK(b.size() == (256 + 2 * (64 + 666) + 64 + 100 + 64 + 68 + 63) / 64 * 64);
  CHECK(decode_ping(b, h) == p);
}

TEST_CASE("encode_ping into a span and decode_ping into a reused ping do not allocate", "[xtf]") {
  const XtfFileHeader h = sidescan_header(2, 2, kSampleFormatInt16);
  TestRng r(21);
  const XtfPing p = random_ping<std::uint16_t>(2, 1024, r);
  std::vector<std::uint8_t> buffer(encoded_ping_size(p));
  XtfPing decoded = decode_ping(encode_ping(p, h), h);  // sizes the buffers once

  std::size_t n = 0;
  CHECK(allocations_in([&] {
          n = encode_ping(p, h, buffer);
          decode_ping(buffer, h, decoded);
        }) == 0);
  // the counter does count: a fresh decode allocates its samples
  CHECK(allocations_in([&] { decoded = decode_ping(buffer, h); }) > 0);
  CHECK(n == 4480);
  CHECK(decoded == p);

  std::vector<std::uint8_t> small(n - 1);
  CHECK_THROWS_WITH(encode_ping(p, h, small), Catch::Contains("needs 4480 bytes"));
}

TEST_CASE("encode_ping refuses pings that do not match the file header", "[xtf]") {
  const XtfFileHeader h = sidescan_header(2, 2, kSampleFormatInt16);
  TestRng r(31);
  XtfPing p = random_ping<std::uint8_t>(2, 10, r);  // 1-byte samples, header says 2
  CHECK_THROWS_WITH(encode_ping(p, h),
                    Catch::Contains("holds uint8 samples") && Catch::Contains("BytesPerSample 2"));
  p = random_ping<std::uint16_t>(3, 10, r);
  CHECK_THROWS_WITH(encode_ping(p, h),
                    Catch::Contains("3 channels but the file header declares 2"));
  p = random_ping<std::uint16_t>(2, 10, r);
  p.channels[1].channel_number = 5;
  CHECK_THROWS_WITH(encode_ping(p, h), Catch::Contains("ChannelNumber 5"));
}

TEST_CASE("decode_ping reports malformed packets with the byte offset", "[xtf]") {
  const XtfFileHeader h = sidescan_header(2, 2, kSampleFormatInt16);
  TestRng r(41);
  const XtfPing p = random_ping<std::uint16_t>(2, 100, r);
  const std::vector<std::uint8_t> good = encode_ping(p, h);  // 256 + 2 x 264 = 784 -> 832
  REQUIRE(good.size() == 832);

  auto expect_error = [&](std::vector<std::uint8_t> b, std::uint64_t offset, const char* text) {
    try {
      decode_ping(b, h);
      FAIL("no error for: " << text);
    } catch (const XtfFormatError& e) {
      INFO(e.what());
      CHECK(e.offset() == offset);
      CHECK(std::string(e.what()).find(text) != std::string::npos);
    }
  };
  auto b = good;
  b[0] = 0xCF;
  expect_error(b, 0, "bad magic 0xFACF");
  b = good;
  b[10] = 10;
  b[11] = 0;
  expect_error(b, 10, "NumBytesThisRecord 10 is smaller than the 256-byte ping header");
  b = good;
  b.resize(800);  // cut before the end of the record
  expect_error(b, 10, "NumBytesThisRecord 832 exceeds the 800 bytes");
  b = good;
  b[4] = 3;  // NumChansToFollow
  expect_error(b, 4, "NumChansToFollow 3 exceeds the 2 channels");
  b = good;
  b[256 + 264 + 42] = 0xFF;  // channel 1 NumSamples = 255 -> 510 bytes: past the record
  expect_error(b, 256 + 264 + 64, "channel 1 (ChannelNumber 1): 255 samples x 2 bytes");
  b = good;
  b[256 + 264] = 7;  // channel 1 ChannelNumber = 7
  expect_error(b, 256 + 264, "ChannelNumber 7");
  b = good;
  b[2] = kHeaderTypeAttitude;
  expect_error(b, 2, "HeaderType 3 is not a sonar ping");
  expect_error(std::vector<std::uint8_t>(good.begin(), good.begin() + 100), 100, "truncated");

  // a record with fewer channel bytes than NumChansToFollow promises
  b = good;
  b[10] = 0x40;  // NumBytesThisRecord = 320: ping header + one channel header only
  b[11] = 0x01;
  expect_error(b, 256 + 64, "channel 0 (ChannelNumber 0): 100 samples x 2 bytes");
}

TEST_CASE("legacy NumSamples = 0 takes the count from CHANINFO Reserved and re-encodes as 0",
          "[xtf]") {
  XtfFileHeader h = sidescan_header(2, 2, kSampleFormatInt16);
  h.chan_info[0].reserved_samples_per_channel = 16;
  h.chan_info[1].reserved_samples_per_channel = 16;
  TestRng r(51);
  XtfPing p = random_ping<std::uint16_t>(2, 16, r);
  auto b = encode_ping(p, h);
  for (std::size_t ch : {256u, 256u + 64u + 32u})
    std::fill_n(b.begin() + ch + 42, 4, 0);
  const XtfPing back = decode_ping(b, h);
  CHECK(back.channels[0].num_samples_from_chan_info);
  CHECK(back.channels[1].num_samples() == 16);
  CHECK(encode_ping(back, h) == b);
}

TEST_CASE("peek_packet and classify_datagram tell file headers from packets", "[xtf]") {
  const XtfFileHeader h = sidescan_header(2, 2, kSampleFormatInt16);
  TestRng r(61);
  const XtfPing p = random_ping<std::uint16_t>(2, 1024, r);
  const auto header = encode_file_header(h);
  const auto ping = encode_ping(p, h);

  CHECK_FALSE(peek_packet(std::span(ping).first(13)).has_value());
  const auto info = peek_packet(ping);
  REQUIRE(info.has_value());
  CHECK(info->valid());
  CHECK(info->header_type == kHeaderTypeSonar);
  CHECK(info->num_chans_to_follow == 2);
  CHECK(info->num_bytes_this_record == 4480);
  CHECK_FALSE(peek_packet(header)->magic_ok);

  CHECK(classify_datagram(header) == DatagramKind::kFileHeader);
  CHECK(classify_datagram(ping) == DatagramKind::kPacket);
  auto longer = ping;
  longer.push_back(0);
  CHECK(classify_datagram(longer) == DatagramKind::kInvalid);  // size != NumBytesThisRecord
  CHECK(classify_datagram(std::span(header).first(1023)) == DatagramKind::kInvalid);
  CHECK(classify_datagram(std::vector<std::uint8_t>(1024, 0x55)) == DatagramKind::kInvalid);
  CHECK(classify_datagram(std::vector<std::uint8_t>{}) == DatagramKind::kInvalid);
  auto bad = ping;
  bad[1] = 0xFB;
  CHECK(classify_datagram(bad) == DatagramKind::kInvalid);
}

TEST_CASE("port samples are stored far range first; helpers take and give nearest first", "[xtf]") {
  const XtfFileHeader h = sidescan_header(2, 2, kSampleFormatInt16);
  const std::vector<std::uint16_t> near_to_far = {10, 20, 30, 40, 50};
  XtfPingChannel port;
  XtfPingChannel stbd;
  stbd.channel_number = 1;
  store_samples_near_to_far<std::uint16_t>(port, h.chan_info[0], near_to_far);
  store_samples_near_to_far<std::uint16_t>(stbd, h.chan_info[1], near_to_far);
  CHECK(std::get<std::vector<std::uint16_t>>(port.samples) ==
        std::vector<std::uint16_t>{50, 40, 30, 20, 10});
  CHECK(std::get<std::vector<std::uint16_t>>(stbd.samples) == near_to_far);
  CHECK(samples_near_to_far<std::uint16_t>(port, chan_info_for(h, port)) == near_to_far);
  CHECK(samples_near_to_far<float>(stbd, chan_info_for(h, stbd)) ==
        std::vector<float>{10, 20, 30, 40, 50});
  std::vector<float> wrong(4);
  CHECK_THROWS_AS(copy_samples_near_to_far<float>(port, h.chan_info[0], std::span(wrong)),
                  std::invalid_argument);
  XtfPingChannel other;
  other.channel_number = 9;
  CHECK_THROWS_AS(chan_info_for(h, other), std::out_of_range);

  // the file order is what goes on the wire: port far sample first
  XtfPing p;
  p.channels = {port, stbd};
  const auto b = encode_ping(p, h);
  CHECK(le<std::uint16_t>(b, 256 + 64) == 50);
  CHECK(le<std::uint16_t>(b, 256 + 64 + 10 + 64) == 10);
}

TEST_CASE("ping time converts to and from UTC nanoseconds", "[xtf]") {
  XtfPingHeader h;
  CHECK_FALSE(time_utc_ns(h).has_value());  // all zero: no date

  // 2013-09-10T21:13:08.13Z = 1378847588.13 s (first timestamps of the Iver recording)
  const std::int64_t t_ns = 1'378'847'588'130'000'000;
  set_time_utc_ns(h, t_ns + 9'999'999);  // truncated to the hundredth
  CHECK(h.year == 2013);
  CHECK(h.month == 9);
  CHECK(h.day == 10);
  CHECK(h.hour == 21);
  CHECK(h.minute == 13);
  CHECK(h.second == 8);
  CHECK(h.hseconds == 13);
  CHECK(h.julian_day == 253);  // 1-based day of the year
  CHECK(time_utc_ns(h) == t_ns);

  set_time_utc_ns(h, -10'000'001);  // 1969-12-31T23:59:59.98
  CHECK(h.year == 1969);
  CHECK(h.month == 12);
  CHECK(h.day == 31);
  CHECK(h.hour == 23);
  CHECK(h.minute == 59);
  CHECK(h.second == 59);
  CHECK(h.hseconds == 98);
  CHECK(h.julian_day == 365);
  CHECK(time_utc_ns(h) == -20'000'000);

  set_time_utc_ns(h, 951'782'400'000'000'000);  // 2000-02-29 (leap day)
  CHECK(h.month == 2);
  CHECK(h.day == 29);
  CHECK(h.julian_day == 60);
  h.month = 13;
  CHECK_FALSE(time_utc_ns(h).has_value());
}
