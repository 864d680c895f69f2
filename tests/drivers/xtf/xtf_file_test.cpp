// XTF files: reading the real Iver/Sea Scan recording, byte-exact re-encoding, writer/reader round
// trips, extended (> 6 channel) headers and corrupt files.
#include "drivers/xtf/xtf_file.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "tests/support/temp_dir.h"

namespace {

using namespace sonarloop::xtf;
using sonarloop::testing::TempDir;

const std::string kRealFile = SONARLOOP_SOURCE_DIR "/tests/data/xtf/scotsman-iver2.xtf";
constexpr std::size_t kRealPings = 461;
constexpr std::size_t kRealPacketSize = 4480;  // 256 + 2 x (64 + 2048)

std::vector<std::uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const std::string& path, std::span<const std::uint8_t> b) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
  REQUIRE(out);
}

void put_u32(std::vector<std::uint8_t>& b, std::size_t off, std::uint32_t v) {
  for (int i = 0; i < 4; ++i)
    b[off + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

// Reads the whole file; returns the error (message, offset) or nullopt if it read cleanly.
struct ReadError {
  std::string message;
  std::uint64_t offset;
  std::size_t pings_before;
};
std::optional<ReadError> read_error(const std::string& path) {
  std::size_t pings = 0;
  try {
    XtfReader reader(path);
    XtfRecord record;
    while (reader.next(record))
      pings += record.is_ping ? 1 : 0;
  } catch (const XtfFormatError& e) {
    return ReadError{e.what(), e.offset(), pings};
  }
  return std::nullopt;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = static_cast<double>(a.size());
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ma += a[i] / n;
    mb += b[i] / n;
  }
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

XtfFileHeader header_with(std::size_t channels, std::uint16_t bytes) {
  XtfFileHeader h;
  h.recording_program_name = "SSSEMU";
  h.number_of_sonar_channels = static_cast<std::uint16_t>(channels);
  for (std::size_t i = 0; i < channels; ++i) {
    XtfChanInfo c;
    c.type_of_channel = i % 2 == 0 ? kChannelPort : kChannelStbd;
    c.sub_channel_number = static_cast<std::uint8_t>(i);
    c.bytes_per_sample = bytes;
    h.chan_info.push_back(c);
  }
  return h;
}

XtfPing ping_with(std::size_t channels, std::size_t samples, std::uint32_t number) {
  XtfPing p;
  p.header.ping_number = number;
  p.header.sensor_y = 48.4 + number * 1e-5;
  p.header.sensor_x = -68.8;
  for (std::size_t i = 0; i < channels; ++i) {
    XtfPingChannel c;
    c.channel_number = static_cast<std::uint16_t>(i);
    c.slant_range_m = 30.0f;
    std::vector<std::uint8_t> s(samples);
    for (std::size_t k = 0; k < samples; ++k)
      s[k] = static_cast<std::uint8_t>(k + i + number);
    c.samples = s;
    p.channels.push_back(c);
  }
  return p;
}

}  // namespace

TEST_CASE("the real Iver recording: file header", "[xtf][real]") {
  XtfReader reader(kRealFile);
  const XtfFileHeader& h = reader.file_header();
  CHECK(reader.file_header_bytes().size() == 1024);
  CHECK(h.file_format == 0x7B);
  CHECK(h.system_type == 1);
  CHECK(h.recording_program_name == "SEASCAN");
  CHECK(h.recording_program_version == "3100");
  CHECK(h.sonar_name == "HDS");
  CHECK(h.sonar_type == 0);
  CHECK(h.note_string.size() == 64);  // fills the field, no NUL
  CHECK(h.note_string.rfind("Created by Sea Scan Survey", 0) == 0);
  CHECK(h.this_file_name == "20130910_171023_inconnue_iver2-148_wp4.xtf");
  CHECK(h.nav_units == kNavUnitsLatLong);
  CHECK(h.number_of_sonar_channels == 2);
  CHECK(declared_channel_count(h) == 2);
  REQUIRE(h.chan_info.size() == 2);
  CHECK(h.chan_info[0].type_of_channel == kChannelPort);
  CHECK(h.chan_info[1].type_of_channel == kChannelStbd);
  CHECK(h.chan_info[0].channel_name == "PORT");
  CHECK(h.chan_info[1].channel_name == "STARBOARD");
  for (const auto& c : h.chan_info) {
    CHECK(c.bytes_per_sample == 2);
    CHECK(c.correction_flags == 1);  // slant-range imagery
    CHECK(c.uni_polar == 1);
    CHECK(c.sample_format == kSampleFormatInt16);  // X41 SampleFormat 3
    CHECK(c.beams_per_array == 1);
    CHECK(c.volt_scale_v == 5.0f);
    CHECK(c.frequency == 600.0f);  // the CHANINFO float holds kHz too, not Hz
    CHECK(c.reserved_samples_per_channel == 0);
  }
}

TEST_CASE("the real Iver recording: 461 pings of 2 x 1024 uint16 samples at 600 kHz",
          "[xtf][real]") {
  XtfReader reader(kRealFile);
  XtfRecord record;
  std::size_t pings = 0;
  std::uint32_t last_number = 0;
  std::int64_t first_t_ns = 0;
  std::int64_t last_t_ns = 0;
  std::size_t positioned = 0;
  while (reader.next(record)) {
    REQUIRE(record.is_ping);
    const XtfPing& p = record.ping;
    INFO("ping " << pings << " at byte offset " << record.packet.offset);
    CHECK(record.packet.offset == 1024 + pings * kRealPacketSize);
    CHECK(record.packet.bytes.size() == kRealPacketSize);
    CHECK(p.header.sound_velocity_mps == 750.0f);
    if (pings > 0) CHECK(p.header.ping_number > last_number);
    last_number = p.header.ping_number;
    const auto t_ns = time_utc_ns(p.header);
    REQUIRE(t_ns.has_value());
    if (pings == 0) first_t_ns = *t_ns;
    CHECK(*t_ns >= last_t_ns);
    last_t_ns = *t_ns;
    // NavUnits 3: sensor position is latitude / longitude in degrees (Rimouski area, Quebec)
    if (p.header.sensor_y != 0.0) {
      ++positioned;
      CHECK(p.header.sensor_y > 48.44);
      CHECK(p.header.sensor_y < 48.45);
      CHECK(p.header.sensor_x > -68.83);
      CHECK(p.header.sensor_x < -68.82);
      CHECK(p.header.sensor_heading_deg >= 0.0f);
      CHECK(p.header.sensor_heading_deg < 360.0f);
      CHECK(p.header.sensor_primary_altitude_m > 0.0f);
    }
    REQUIRE(p.channels.size() == 2);
    for (std::uint16_t k = 0; k < 2; ++k) {
      const XtfPingChannel& c = p.channels[k];
      CHECK(c.channel_number == k);
      CHECK(c.num_samples() == 1024);
      CHECK(c.bytes_per_sample() == 2);
      CHECK(std::holds_alternative<std::vector<std::uint16_t>>(c.samples));
      CHECK(c.frequency_khz == 600);  // WORD in kHz
      CHECK(std::abs(c.slant_range_m - 29.98f) < 0.01f);
      CHECK(c.processing_flags == 4);  // TVG applied
      CHECK(c.downsample_method == 2);
    }
    ++pings;
  }
  CHECK(pings == kRealPings);
  CHECK(last_number == kRealPings - 1);  // PingNumber counts 0 .. 460
  CHECK(reader.stats().sonar_pings == kRealPings);
  CHECK(reader.stats().other_packets == 0);
  CHECK(positioned == kRealPings - 1);  // ping 0 carries no navigation yet
  const double duration_s = static_cast<double>(last_t_ns - first_t_ns) * 1e-9;
  CHECK(duration_s > 50.0);  // 21:13:08.00 .. 21:14:00.23
  CHECK(duration_s < 54.0);
}

TEST_CASE("the real Iver recording: port samples are stored far range first", "[xtf][real]") {
  // Evidence for docs/formats.md 1.7: the first returns (transmit/nadir, saturated at 32767) are at
  // the END of the port array and the START of the starboard array; read nearest-first the two
  // sides' mean profiles agree.
  const XtfFileContents file = read_all_pings(kRealFile);
  REQUIRE(file.pings.size() == kRealPings);
  std::vector<double> port_mean(1024, 0.0), stbd_mean(1024, 0.0), port_file_order(1024, 0.0);
  for (const XtfPing& p : file.pings) {
    const auto port =
        samples_near_to_far<double>(p.channels[0], chan_info_for(file.header, p.channels[0]));
    const auto stbd =
        samples_near_to_far<double>(p.channels[1], chan_info_for(file.header, p.channels[1]));
    const auto& raw = std::get<std::vector<std::uint16_t>>(p.channels[0].samples);
    for (std::size_t i = 0; i < 8; ++i) {
      REQUIRE(port[i] == 32767.0);
      REQUIRE(stbd[i] == 32767.0);
    }
    for (std::size_t i = 0; i < 1024; ++i) {
      port_mean[i] += port[i];
      stbd_mean[i] += stbd[i];
      port_file_order[i] += raw[i];
    }
  }
  const double near_first = correlation(port_mean, stbd_mean);
  const double file_order = correlation(port_file_order, stbd_mean);
  INFO("correlation of mean profiles: nearest-first " << near_first << ", file order "
                                                      << file_order);
  CHECK(near_first > 0.85);
  CHECK(file_order < 0.5);
}

TEST_CASE("the real Iver recording re-encodes byte for byte", "[xtf][real]") {
  const std::vector<std::uint8_t> original = read_bytes(kRealFile);
  const XtfRawFile raw = read_raw_packets(kRealFile);
  REQUIRE(raw.packets.size() == kRealPings);

  // raw packets: header + concatenation is the file (what a byte-identical replay sends)
  std::vector<std::uint8_t> joined = raw.file_header;
  for (const auto& p : raw.packets)
    joined.insert(joined.end(), p.bytes.begin(), p.bytes.end());
  CHECK(joined == original);

  // decode -> encode of every structure reproduces its bytes
  const XtfFileHeader header = decode_file_header(raw.file_header);
  CHECK(encode_file_header(header) == raw.file_header);
  std::size_t differing = 0;
  for (const auto& p : raw.packets) {
    if (encode_ping(decode_ping(p.bytes, header), header) != p.bytes) ++differing;
  }
  CHECK(differing == 0);

  // and through the writer and reader: the rewritten file is identical
  TempDir dir("xtf_reencode");
  const std::string copy = dir.file("copy.xtf");
  {
    XtfWriter writer(copy, header);
    XtfReader reader(kRealFile);
    XtfRecord record;
    while (reader.next(record))
      writer.write_ping(record.ping);
    writer.close();
    CHECK(writer.packets_written() == kRealPings);
    CHECK(writer.bytes_written() == original.size());
  }
  CHECK(read_bytes(copy) == original);
}

TEST_CASE("writer and reader round trip: pings, other packet types, extended header", "[xtf]") {
  TempDir dir("xtf_roundtrip");
  for (const std::size_t channels : {std::size_t{2}, std::size_t{4}, std::size_t{8}}) {
    INFO(channels << " channels");
    const std::string path = dir.file("rt" + std::to_string(channels) + ".xtf");
    const XtfFileHeader h = header_with(channels, 1);
    std::vector<XtfPing> pings;
    // a notes packet (HeaderType 1, 256 bytes) and an unknown type (200, 64 bytes)
    std::vector<std::uint8_t> notes(256, 0), custom(64, 0xAB);
    for (auto* b : {&notes, &custom}) {
      (*b)[0] = 0xCE;
      (*b)[1] = 0xFA;
      put_u32(*b, 10, static_cast<std::uint32_t>(b->size()));
    }
    notes[2] = kHeaderTypeNotes;
    std::memcpy(notes.data() + 56, "hello", 5);
    custom[2] = 200;
    {
      XtfWriter writer(path, h, XtfWriterOptions{.sync_every_packets = 3});
      for (std::uint32_t i = 0; i < 10; ++i) {
        pings.push_back(ping_with(channels, 100 + 13 * i, i));
        writer.write_ping(pings.back());
        if (i == 4) writer.write_packet(notes);
        if (i == 6) writer.write_packet(custom);
      }
      CHECK_THROWS_AS(writer.write_packet(std::span(custom).first(60)), std::invalid_argument);
    }  // destructor closes

    XtfReader reader(path);
    CHECK(reader.file_header() == h);
    CHECK(reader.file_header_bytes().size() == (channels > 6 ? 2048u : 1024u));
    XtfRecord record;
    std::size_t n = 0;
    std::vector<std::uint8_t> seen_types;
    while (reader.next(record)) {
      seen_types.push_back(record.packet.header_type);
      if (record.is_ping) {
        REQUIRE(n < pings.size());
        CHECK(record.ping == pings[n]);
        CHECK(record.packet.bytes.size() % 64 == 0);
        ++n;
      }
    }
    CHECK(n == 10);
    CHECK(seen_types[5] == kHeaderTypeNotes);
    CHECK(seen_types[8] == 200);
    CHECK(reader.stats().packets == 12);
    CHECK(reader.stats().sonar_pings == 10);
    CHECK(reader.stats().other_packets == 2);
    CHECK(reader.stats().packets_by_type[kHeaderTypeNotes] == 1);
    CHECK(reader.stats().packets_by_type[200] == 1);
    CHECK(reader.offset() == reader.file_size());
    const XtfRawFile raw = read_raw_packets(path);
    CHECK(raw.packets[5].bytes == notes);
    CHECK(raw.packets[8].bytes == custom);
  }
}

TEST_CASE("a file being written is valid after every write_ping (no user-space buffering)",
          "[xtf]") {
  TempDir dir("xtf_live");
  const std::string path = dir.file("live.xtf");
  const XtfFileHeader h = header_with(2, 1);
  XtfWriter writer(path, h);
  CHECK(read_all_pings(path).pings.empty());
  for (std::uint32_t i = 0; i < 5; ++i) {
    writer.write_ping(ping_with(2, 1000, i));
    // as if the process stopped here: another reader sees whole packets only
    const XtfFileContents now = read_all_pings(path);
    CHECK(now.pings.size() == i + 1);
  }
  writer.close();
  writer.close();  // idempotent
  CHECK_THROWS_AS(writer.write_ping(ping_with(2, 10, 9)), std::runtime_error);
  CHECK(read_all_pings(path).pings.size() == 5);
}

TEST_CASE("a header the writer refuses leaves an existing file untouched", "[xtf]") {
  TempDir dir("xtf_badheader");
  const std::string path = dir.file("keep.xtf");
  write_bytes(path, std::vector<std::uint8_t>(10, 1));
  XtfFileHeader h = header_with(2, 2);
  h.sonar_name = std::string(40, 'x');
  CHECK_THROWS_AS(XtfWriter(path, h), std::invalid_argument);
  CHECK(read_bytes(path).size() == 10);
  CHECK_THROWS_AS(XtfWriter(dir.file("no/such/dir.xtf"), header_with(2, 2)), std::runtime_error);
}

TEST_CASE("corrupt and truncated files give errors that name the byte offset", "[xtf]") {
  TempDir dir("xtf_corrupt");
  const std::vector<std::uint8_t> original = read_bytes(kRealFile);
  const std::size_t p3 = 1024 + 3 * kRealPacketSize;  // start of the 4th packet: 14464
  auto check = [&](const std::string& name, const std::vector<std::uint8_t>& bytes,
                   std::uint64_t offset, const std::vector<std::string>& texts,
                   std::size_t pings_before) {
    const std::string path = dir.file(name);
    write_bytes(path, bytes);
    const auto e = read_error(path);
    REQUIRE(e.has_value());
    INFO(e->message);
    CHECK(e->offset == offset);
    CHECK(e->pings_before == pings_before);
    CHECK(e->message.find(path) != std::string::npos);
    for (const auto& t : texts)
      CHECK(e->message.find(t) != std::string::npos);
  };

  // cut in the middle of the 4th packet
  check("cut.xtf", {original.begin(), original.begin() + p3 + 100}, p3,
        {"byte offset 14464", "NumBytesThisRecord 4480 runs past the end of the file",
         "100 bytes left"},
        3);
  // cut inside the packet start of the 4th packet
  check("cut_start.xtf", {original.begin(), original.begin() + p3 + 5}, p3,
        {"byte offset 14464", "truncated packet start", "only 5 bytes left"}, 3);
  // magic flipped
  auto b = original;
  b[p3] = 0xEC;
  check("magic.xtf", b, p3, {"byte offset 14464", "bad magic 0xFAEC"}, 3);
  // NumBytesThisRecord = 10
  b = original;
  put_u32(b, p3 + 10, 10);
  check("nbytes10.xtf", b, p3, {"byte offset 14464", "NumBytesThisRecord 10 is smaller"}, 3);
  // NumBytesThisRecord = 200 for a sonar packet (smaller than the ping header)
  b = original;
  put_u32(b, p3 + 10, 200);
  check("nbytes200.xtf", b, p3, {"smaller than the 256-byte ping header"}, 3);
  // channel data larger than the record: starboard NumSamples 1025
  b = original;
  put_u32(b, p3 + 256 + 2112 + 42, 1025);
  check("nsamples.xtf", b, p3 + 256 + 2112 + 64,
        {"sonar packet at byte offset 14464", "channel 1 (ChannelNumber 1): 1025 samples",
         "run past NumBytesThisRecord 4480", "byte offset 16896 in the file"},
        3);
  // more channels than the file header declares
  b = original;
  b[p3 + 4] = 3;
  check("nchans.xtf", b, p3 + 4, {"NumChansToFollow 3 exceeds the 2 channels"}, 3);
  // truncated file header, and not an XTF file at all
  check("short.xtf", {original.begin(), original.begin() + 500}, 500,
        {"truncated file header", "500 bytes"}, 0);
  b = original;
  b[0] = 0x7A;
  check("format.xtf", b, 0, {"FileFormat byte is 0x7A"}, 0);
  // a header declaring 8 channels (2048 bytes) in a 1500-byte file
  b = {original.begin(), original.begin() + 1500};
  b[166] = 8;
  check("ext_short.xtf", b, 1500, {"2048 bytes long", "the file has 1500 bytes"}, 0);
  // an extended header whose packets start at 1024 (i.e. a writer that did not extend it)
  b = original;
  b[166] = 8;
  check("ext_wrong.xtf", b, 2048, {"bad magic", "extended to 2048 bytes for 8 channels"}, 0);

  // missing file: not a format error but a clear open error
  CHECK_THROWS_WITH(XtfReader(dir.file("missing.xtf")), Catch::Contains("missing.xtf"));
  // the undamaged file reads cleanly
  CHECK_FALSE(read_error(kRealFile).has_value());
}
