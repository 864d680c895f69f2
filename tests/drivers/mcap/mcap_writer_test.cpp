// The MCAP writer (drivers/mcap/mcap_writer.h) read back by a small reader written here from the
// specification: the magic at both ends, every record's length, the data end's CRC, each chunk's
// CRC of its (decompressed) records, each message index pointing at its messages, each chunk
// index pointing at its chunk and indexes, the statistics, the summary offsets and the footer's
// CRC. Uncompressed and zstd chunks; several chunks. (An independent reader, @mcap/core, reads a
// whole run's file in tests/tools/mcap_cli_test.cpp.)
#include "drivers/mcap/mcap_writer.h"

#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "drivers/io/crc32.h"
#include "tests/support/temp_dir.h"

#ifdef SONARLOOP_TEST_ZSTD
#include <zstd.h>
#endif

using namespace sonarloop;

namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes slurp_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

template <class T>
T le(const Bytes& b, std::size_t at) {
  REQUIRE(at + sizeof(T) <= b.size());
  T v = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i)
    v = static_cast<T>(v | (static_cast<T>(b[at + i]) << (8 * i)));
  return v;
}

std::string str(const Bytes& b, std::size_t& at) {
  const auto n = le<std::uint32_t>(b, at);
  std::string s(b.begin() + static_cast<long>(at + 4), b.begin() + static_cast<long>(at + 4 + n));
  at += 4 + n;
  return s;
}

struct Record {
  std::uint8_t op;
  std::size_t start, content, end;  // the opcode's offset, the content's, one past the end
};

// The records of [from, to) of `b`.
std::vector<Record> records(const Bytes& b, std::size_t from, std::size_t to) {
  std::vector<Record> out;
  std::size_t at = from;
  while (at < to) {
    const auto len = le<std::uint64_t>(b, at + 1);
    out.push_back({b[at], at, at + 9, at + 9 + static_cast<std::size_t>(len)});
    at = out.back().end;
  }
  REQUIRE(at == to);
  return out;
}

struct Written {
  std::map<std::uint16_t, std::vector<std::uint64_t>> times;  // per channel, message log times
  std::uint64_t messages = 0, chunks = 0;
};

// Reads and checks everything; returns what the messages were.
Written read_and_check(const Bytes& b, bool compressed) {
  Written w;
  REQUIRE(b.size() > 16);
  REQUIRE(std::memcmp(b.data(), mcap::kMagic, 8) == 0);
  REQUIRE(std::memcmp(b.data() + b.size() - 8, mcap::kMagic, 8) == 0);
  // footer: op 0x02, 20 bytes, before the trailing magic
  const std::size_t footer = b.size() - 8 - 29;
  REQUIRE(b[footer] == 0x02);
  const auto summary_start = le<std::uint64_t>(b, footer + 9);
  const auto summary_offset_start = le<std::uint64_t>(b, footer + 17);
  const auto summary_crc = le<std::uint32_t>(b, footer + 25);
  CHECK(summary_crc == io::crc32(std::span<const std::uint8_t>(b).subspan(
                           summary_start, footer + 25 - summary_start)));

  // the data section: header first, data end last, with the CRC of everything before it
  const auto data = records(b, 8, summary_start);
  REQUIRE(data.front().op == 0x01);
  std::size_t at = data.front().content;
  CHECK(str(b, at) == "ros2");
  CHECK(str(b, at) == "sonarloop");
  REQUIRE(data.back().op == 0x0F);
  CHECK(le<std::uint32_t>(b, data.back().content) ==
        io::crc32(std::span<const std::uint8_t>(b).first(data.back().start)));

  std::map<std::uint64_t, std::size_t> chunk_at;  // chunk offset -> index in data
  for (std::size_t i = 0; i < data.size(); ++i) {
    const Record& r = data[i];
    if (r.op != 0x06) continue;
    chunk_at[r.start] = i;
    ++w.chunks;
    std::size_t c = r.content;
    const auto start_time = le<std::uint64_t>(b, c);
    const auto end_time = le<std::uint64_t>(b, c + 8);
    const auto uncompressed_size = le<std::uint64_t>(b, c + 16);
    const auto crc = le<std::uint32_t>(b, c + 24);
    c += 28;
    const std::string compression = str(b, c);
    CHECK(compression == (compressed ? "zstd" : ""));
    const auto size = le<std::uint64_t>(b, c);
    c += 8;
    Bytes inner(b.begin() + static_cast<long>(c), b.begin() + static_cast<long>(c + size));
    CHECK(c + size == r.end);
    if (compressed) {
#ifdef SONARLOOP_TEST_ZSTD
      Bytes out(uncompressed_size);
      REQUIRE(ZSTD_decompress(out.data(), out.size(), inner.data(), inner.size()) ==
              uncompressed_size);
      inner = std::move(out);
#else
      WARN("built without zstd: the compressed chunk's contents are not checked");
      continue;
#endif
    }
    REQUIRE(inner.size() == uncompressed_size);
    CHECK(io::crc32(inner) == crc);
    // the messages, and the message indexes after the chunk point at them
    std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> seen;
    for (const Record& m : records(inner, 0, inner.size())) {
      REQUIRE(m.op == 0x05);
      const auto channel = le<std::uint16_t>(inner, m.content);
      const auto t = le<std::uint64_t>(inner, m.content + 6);
      CHECK(t >= start_time);
      CHECK(t <= end_time);
      seen[channel].emplace_back(t, m.start);
      w.times[channel].push_back(t);
      ++w.messages;
    }
    std::size_t k = i + 1;
    for (const auto& [channel, entries] : seen) {
      REQUIRE(k < data.size());
      REQUIRE(data[k].op == 0x07);
      CHECK(le<std::uint16_t>(b, data[k].content) == channel);
      const auto bytes = le<std::uint32_t>(b, data[k].content + 2);
      REQUIRE(bytes == entries.size() * 16);
      for (std::size_t e = 0; e < entries.size(); ++e) {
        CHECK(le<std::uint64_t>(b, data[k].content + 6 + 16 * e) == entries[e].first);
        CHECK(le<std::uint64_t>(b, data[k].content + 14 + 16 * e) == entries[e].second);
      }
      ++k;
    }
  }

  // the summary: schemas, channels, statistics, chunk indexes, grouped; then the offsets
  const auto summary = records(b, summary_start, summary_offset_start);
  std::map<std::uint8_t, std::pair<std::size_t, std::size_t>> groups;  // op -> (start, end)
  for (const Record& r : summary) {
    auto& g = groups[r.op];
    if (g.second == 0) g.first = r.start;
    CHECK((g.second == 0 || g.second == r.start));  // grouped: contiguous
    g.second = r.end;
    if (r.op == 0x0B) {
      CHECK(le<std::uint64_t>(b, r.content) == w.messages);
      CHECK(le<std::uint32_t>(b, r.content + 22) == w.chunks);
    }
    if (r.op == 0x08) {
      const auto offset = le<std::uint64_t>(b, r.content + 16);
      REQUIRE(chunk_at.count(offset) == 1);
      CHECK(le<std::uint64_t>(b, r.content + 24) == data[chunk_at[offset]].end - offset);
    }
  }
  CHECK(groups.count(0x03) == (w.messages > 0 ? 1 : 0));
  CHECK(groups.count(0x04) == (w.messages > 0 ? 1 : 0));
  CHECK(groups.count(0x0B) == 1);
  const auto offsets = records(b, summary_offset_start, footer);
  CHECK(offsets.size() == groups.size());
  for (const Record& r : offsets) {
    REQUIRE(r.op == 0x0E);
    const std::uint8_t op = b[r.content];
    REQUIRE(groups.count(op) == 1);
    CHECK(le<std::uint64_t>(b, r.content + 1) == groups[op].first);
    CHECK(le<std::uint64_t>(b, r.content + 9) == groups[op].second - groups[op].first);
  }
  return w;
}

Written write_and_read(const testing::TempDir& dir, bool compress, std::size_t chunk_bytes) {
  const std::string path = dir.file(compress ? "z.mcap" : "u.mcap");
  mcap::WriterOptions o;
  o.compress = compress;
  o.chunk_bytes = chunk_bytes;
  {
    mcap::Writer w(path, o);
    const std::string def = "string data\n";
    const std::uint16_t s =
        w.add_schema("std_msgs/msg/String", "ros2msg",
                     {reinterpret_cast<const std::uint8_t*>(def.data()), def.size()});
    CHECK(s == 1);
    const std::uint16_t a = w.add_channel(s, "/a", "cdr", {{"k", "v"}});
    const std::uint16_t c = w.add_channel(s, "/b", "cdr");
    const Bytes payload(100, 0x5A);
    for (std::uint32_t i = 0; i < 40; ++i)
      w.write(i % 3 == 0 ? c : a, i, 1000 + 10 * i, 1000 + 10 * i, payload);
    CHECK(w.messages() == 40);
    CHECK_THROWS_AS(w.write(7, 0, 0, 0, payload), std::invalid_argument);
    w.close();
    w.close();  // idempotent
  }
  return read_and_check(slurp_bytes(path), compress && mcap::zstd_available());
}

}  // namespace

TEST_CASE("mcap writer: uncompressed chunks, every offset, index and CRC") {
  testing::TempDir dir("mcap");
  const Written w = write_and_read(dir, false, 1000);  // ~8 messages per chunk
  CHECK(w.messages == 40);
  CHECK(w.chunks >= 4);
  CHECK(w.times.at(0).size() == 26);
  CHECK(w.times.at(1).size() == 14);
}

TEST_CASE("mcap writer: zstd chunks") {
  testing::TempDir dir("mcap");
  if (!mcap::zstd_available()) WARN("built without libzstd: chunks are written uncompressed");
  const Written w = write_and_read(dir, true, 1u << 20);  // one chunk
  CHECK(w.chunks == 1);
#ifdef SONARLOOP_TEST_ZSTD
  CHECK(w.messages == 40);
#endif
}

TEST_CASE("mcap writer: an empty file is valid, a bad path a clear error") {
  testing::TempDir dir("mcap");
  {
    mcap::Writer w(dir.file("empty.mcap"));
    w.close();
  }
  const Written w = read_and_check(slurp_bytes(dir.file("empty.mcap")), false);
  CHECK(w.messages == 0);
  CHECK_THROWS_WITH(mcap::Writer(dir.file("no/such/dir/x.mcap")),
                    Catch::Contains("no/such/dir/x.mcap") && Catch::Contains("cannot create"));
}
