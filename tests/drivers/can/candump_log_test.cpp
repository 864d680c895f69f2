#include "drivers/can/candump_log.h"

#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/support/temp_dir.h"
#include "tests/support/test_rng.h"

using namespace sonarloop::can;
using sonarloop::testing::run_command;
using sonarloop::testing::TempDir;

namespace {

CanFrame frame_of(std::uint32_t id, bool extended, std::vector<std::uint8_t> data) {
  CanFrame f;
  f.id = id;
  f.extended = extended;
  f.len = static_cast<std::uint8_t>(data.size());
  for (std::size_t i = 0; i < data.size(); ++i)
    f.data[i] = data[i];
  return f;
}

CanFrame frame_of_hex(std::uint32_t id, const std::string& hex) {
  std::vector<std::uint8_t> data;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2)
    data.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  return frame_of(id, true, data);
}

using sonarloop::testing::slurp;

std::string script(const std::string& name) {
  return std::string(SONARLOOP_SOURCE_DIR) + "/tests/drivers/can/" + name;
}

CandumpRecord parse_ok(const std::string& line) {
  CandumpRecord rec;
  std::string error;
  const auto status = parse_candump_line(line, rec, error);
  INFO(line << " -> " << error);
  REQUIRE(status == CandumpLineStatus::kRecord);
  return rec;
}

std::string parse_error(const std::string& line) {
  CandumpRecord rec;
  std::string error;
  const auto status = parse_candump_line(line, rec, error);
  INFO(line);
  CHECK(status == CandumpLineStatus::kError);
  return error;
}

// The eight reference frames of docs/formats.md 2.4 (SA 0x23, SID 7).
struct Reference {
  std::int64_t t_ns;
  std::uint32_t id;
  const char* hex;
};
constexpr Reference kReference[] = {
    {1699999999123456000, 0x09F80123, "00E6B523B1AC6A06"},
    {1699999999133456000, 0x09F80223, "07FCAE1EFA00FFFF"},
    {1699999999143456000, 0x09F11223, "072154FF7FA3FEFC"},
    {1699999999153456000, 0x0DF11923, "070C02FAFE8901FF"},
    {1699999999163456000, 0x0DF50B23, "078D1000000CFEFF"},
    {1699999999173456000, 0x09F11323, "07A9850800FFFFFF"},
    {1699999999183456000, 0x0DF01023, "07F0DB4CC2E5AE2F"},
    {1699999999193456000, 0x09F50323, "07F000FFFF02F0FF"},
};

}  // namespace

TEST_CASE("candump writer: exact can-utils line format (docs/formats.md 2.4 reference log)") {
  TempDir dir("candump-format");
  const std::string path = dir.file("nav.log");
  {
    CandumpLogWriter w(path);
    for (const Reference& r : kReference)
      w.send(frame_of_hex(r.id, r.hex), r.t_ns);
    CHECK(w.frames_written() == 8);
    CHECK(w.describe() == "candump log " + path);
  }  // destructor flushes
  const std::string expected =
      "(1699999999.123456) vcan0 09F80123#00E6B523B1AC6A06\n"
      "(1699999999.133456) vcan0 09F80223#07FCAE1EFA00FFFF\n"
      "(1699999999.143456) vcan0 09F11223#072154FF7FA3FEFC\n"
      "(1699999999.153456) vcan0 0DF11923#070C02FAFE8901FF\n"
      "(1699999999.163456) vcan0 0DF50B23#078D1000000CFEFF\n"
      "(1699999999.173456) vcan0 09F11323#07A9850800FFFFFF\n"
      "(1699999999.183456) vcan0 0DF01023#07F0DB4CC2E5AE2F\n"
      "(1699999999.193456) vcan0 09F50323#07F000FFFF02F0FF\n";
  CHECK(slurp(path) == expected);

  char line[128];
  // 10-digit zero-padded seconds, time truncated to microseconds, SFF ids with 3 digits,
  // empty payloads, another channel name
  CHECK(format_candump_line(frame_of(0x123, false, {0xAB}), 5'000'999'999, "can1", line,
                            sizeof line) > 0);
  CHECK(std::string(line) == "(0000000005.000999) can1 123#AB\n");
  format_candump_line(frame_of(0x1FFFFFFF, true, {}), 0, "vcan0", line, sizeof line);
  CHECK(std::string(line) == "(0000000000.000000) vcan0 1FFFFFFF#\n");
  CHECK(format_candump_line(frame_of(0x1, true, {}), 0, "vcan0", line, 10) == 0);
}

TEST_CASE("candump writer: flush makes lines visible, errors name the file") {
  TempDir dir("candump-flush");
  const std::string path = dir.file("a.log");
  CandumpLogWriter w(path, "can0");
  w.write(frame_of(0x18EA1023, true, {1, 2, 3}), 1'000'000'000);
  w.flush();
  CHECK(slurp(path) == "(0000000001.000000) can0 18EA1023#010203\n");
  CHECK_THROWS_AS(w.write(frame_of(1, true, {}), -1), std::invalid_argument);
  w.close();
  CHECK_THROWS_WITH(w.write(frame_of(1, true, {}), 0), Catch::Contains("after close"));
  CHECK_THROWS_WITH(CandumpLogWriter(dir.file("no/such/dir/x.log")),
                    Catch::Contains("no/such/dir/x.log"));
  CHECK_THROWS_AS(CandumpLogWriter(dir.file("b.log"), "has space"), std::invalid_argument);
}

TEST_CASE("candump: writer output parses back exactly (seeded random frames)") {
  TempDir dir("candump-roundtrip");
  const std::string path = dir.file("random.log");
  sonarloop::testing::TestRng rng(0xCA7);
  std::vector<TimedCanFrame> sent;
  {
    CandumpLogWriter w(path);
    std::int64_t t = 1'700'000'000'000'000'000;
    for (int i = 0; i < 3000; ++i) {
      CanFrame f;
      f.extended = rng.below(4) != 0;
      f.id = static_cast<std::uint32_t>(rng.below(f.extended ? 0x20000000u : 0x800u));
      f.len = static_cast<std::uint8_t>(rng.below(9));
      for (std::uint8_t k = 0; k < f.len; ++k)
        f.data[k] = static_cast<std::uint8_t>(rng.below(256));
      t += static_cast<std::int64_t>(rng.below(50'000'000));  // ns, not whole microseconds
      w.write(f, t);
      sent.push_back({t - t % 1000, f});  // the log keeps microseconds (truncated)
    }
  }
  CandumpReader reader(path);
  std::size_t i = 0;
  while (auto rec = reader.next()) {
    REQUIRE(i < sent.size());
    CHECK(rec->kind == CandumpFrameKind::kData);
    CHECK(rec->channel == "vcan0");
    CHECK(rec->t_ns == sent[i].t_ns);
    CHECK(rec->frame == sent[i].frame);
    CHECK(rec->direction == 0);
    ++i;
  }
  CHECK(i == sent.size());
  CHECK(reader.malformed_lines() == 0);
}

TEST_CASE("candump: python-can's CanutilsLogReader reads our log, every frame matches") {
  TempDir dir("candump-python");
  const std::string path = dir.file("nav.log");
  const std::string out = dir.file("python.txt");
  sonarloop::testing::TestRng rng(0xCA8);
  std::vector<TimedCanFrame> sent;
  {
    CandumpLogWriter w(path);
    for (const Reference& r : kReference)
      sent.push_back({r.t_ns, frame_of_hex(r.id, r.hex)});
    for (int i = 0; i < 500; ++i) {
      CanFrame f;
      f.extended = rng.below(5) != 0;
      f.id = static_cast<std::uint32_t>(rng.below(f.extended ? 0x20000000u : 0x800u));
      f.len = static_cast<std::uint8_t>(rng.below(9));
      for (std::uint8_t k = 0; k < f.len; ++k)
        f.data[k] = static_cast<std::uint8_t>(rng.below(256));
      sent.push_back({1'700'000'000'000'000'000 + i * 1'234'000LL, f});
    }
    for (const auto& s : sent)
      w.write(s.frame, s.t_ns);
  }
  const int rc = run_command(std::string(SONARLOOP_PYTHON) + " " +
                             script("python_candump_read.py") + " " + path + " " + out);
  REQUIRE(rc == 0);
  std::ifstream in(out);
  std::string line;
  std::size_t i = 0;
  while (std::getline(in, line)) {
    REQUIRE(i < sent.size());
    const auto& s = sent[i];
    char want[128];
    int n = std::snprintf(want, sizeof want, "%lld.%06lld %X %d %d ",
                          static_cast<long long>(s.t_ns / 1'000'000'000),
                          static_cast<long long>(s.t_ns % 1'000'000'000 / 1000), s.frame.id,
                          s.frame.extended ? 1 : 0, s.frame.len);
    for (int k = 0; k < s.frame.len; ++k)
      n += std::snprintf(want + n, sizeof want - static_cast<std::size_t>(n), "%02X",
                         s.frame.data[static_cast<std::size_t>(k)]);
    std::snprintf(want + n, sizeof want - static_cast<std::size_t>(n), " vcan0");
    CHECK(line == want);
    ++i;
  }
  CHECK(i == sent.size());
}

TEST_CASE("candump reader: reads python-can's CanutilsLogWriter output") {
  TempDir dir("candump-python-writer");
  const std::string path = dir.file("py.log");
  REQUIRE(run_command(std::string(SONARLOOP_PYTHON) + " " + script("python_candump_write.py") +
                      " " + path) == 0);
  CandumpReader reader(path);
  auto r = reader.next();
  REQUIRE(r);
  CHECK(r->t_ns == 1699999999123456000);
  CHECK(r->frame == frame_of_hex(0x09F80123, "00E6B523B1AC6A06"));
  CHECK(r->direction == 'R');
  r = reader.next();
  REQUIRE(r);
  CHECK(r->frame == frame_of(0x123, false, {1, 2}));
  CHECK(r->direction == 'T');
  CHECK(r->t_ns == 1699999999500000000);
  r = reader.next();
  REQUIRE(r);
  CHECK(r->frame == frame_of(0x18FF0001, true, {}));
  r = reader.next();
  REQUIRE(r);
  CHECK(r->kind == CandumpFrameKind::kRemote);
  CHECK(r->frame.id == 0x7FF);
  CHECK_FALSE(r->frame.extended);
  r = reader.next();
  REQUIRE(r);
  CHECK(r->kind == CandumpFrameKind::kFd);
  CHECK(r->fd_flags == 1);
  CHECK(r->fd_len == 12);
  CHECK(r->fd_data[11] == 11);
  CHECK_FALSE(reader.next());
}

TEST_CASE("candump parser: the line variants of can-utils and python-can") {
  auto r = parse_ok("(1699999999.123456) vcan0 09F80123#00E6B523B1AC6A06");
  CHECK(r.t_ns == 1699999999123456000);
  CHECK(r.channel == "vcan0");
  CHECK(r.frame == frame_of_hex(0x09F80123, "00E6B523B1AC6A06"));
  CHECK(r.direction == 0);

  r = parse_ok("(1699999999.123456) vcan0 09F80123#00E6B523B1AC6A06 R\r\n");
  CHECK(r.direction == 'R');
  r = parse_ok("(1699999999.123456) vcan0 09f80123#00e6b523b1ac6a06 t");
  CHECK(r.direction == 'T');
  CHECK(r.frame == frame_of_hex(0x09F80123, "00E6B523B1AC6A06"));
  r = parse_ok("(1699999999.5) can0 123#0102");  // python-can writes %f, any fraction width
  CHECK(r.t_ns == 1699999999500000000);
  CHECK(r.frame == frame_of(0x123, false, {1, 2}));
  r = parse_ok("(1699999999.123456789) vcan0 123#");  // candump -N: nanoseconds
  CHECK(r.t_ns == 1699999999123456789);
  CHECK(r.frame.len == 0);
  r = parse_ok("  (0000000001.000001)   vcan10   1FFFFFFF#11.22.33  ");  // '.' separators
  CHECK(r.frame == frame_of(0x1FFFFFFF, true, {0x11, 0x22, 0x33}));
  CHECK(r.channel == "vcan10");
  r = parse_ok("(1.0) vcan0 123#R");
  CHECK(r.kind == CandumpFrameKind::kRemote);
  CHECK(r.frame.len == 0);
  r = parse_ok("(1.0) vcan0 18F11300#r5");
  CHECK(r.kind == CandumpFrameKind::kRemote);
  CHECK(r.frame.len == 5);
  CHECK(r.frame.extended);
  r = parse_ok("(1.0) vcan0 123#1122334455667788_C");  // len8_dlc
  CHECK(r.len8_dlc == 0xC);
  CHECK(r.frame.len == 8);
  r = parse_ok("(1699999999.200000) vcan0 18F11300##10102030405060708");  // FD, BRS
  CHECK(r.kind == CandumpFrameKind::kFd);
  CHECK(r.fd_flags == 1);
  CHECK(r.fd_len == 8);
  CHECK(r.fd_data[7] == 8);
  CHECK(r.frame.id == 0x18F11300);
  r = parse_ok("(1.0) vcan0 123##4");  // FD, no data
  CHECK(r.fd_len == 0);
  r = parse_ok("(1.0) vcan0 20000080#0000000000000000");  // error frame
  CHECK(r.kind == CandumpFrameKind::kError);
  CHECK(r.frame.id == 0x80);

  CandumpRecord rec;
  std::string error;
  CHECK(parse_candump_line("", rec, error) == CandumpLineStatus::kSkip);
  CHECK(parse_candump_line("   \r\n", rec, error) == CandumpLineStatus::kSkip);
  CHECK(parse_candump_line("# a comment", rec, error) == CandumpLineStatus::kSkip);
}

TEST_CASE("candump parser: malformed lines say what is wrong") {
  using Catch::Contains;
  CHECK_THAT(parse_error("(1.0) vcan0"), Contains("found 2 fields"));
  CHECK_THAT(parse_error("(1.0) vcan0 123#00 R extra"), Contains("too many fields"));
  CHECK_THAT(parse_error("(1.0) vcan0 123#00 X"), Contains("only R or T"));
  CHECK_THAT(parse_error("1.0 vcan0 123#00"), Contains("timestamp '1.0'"));
  CHECK_THAT(parse_error("(abc) vcan0 123#00"), Contains("no valid seconds"));
  CHECK_THAT(parse_error("(1.12x) vcan0 123#00"), Contains("non-digit"));
  CHECK_THAT(parse_error("(1.1234567891) vcan0 123#00"), Contains("more than 9"));
  CHECK_THAT(parse_error("(1.0) vcan0 12300"), Contains("no '#'"));
  CHECK_THAT(parse_error("(1.0) vcan0 12G#00"), Contains("not hexadecimal"));
  CHECK_THAT(parse_error("(1.0) vcan0 1234#00"), Contains("3 (11-bit) or 8 (29-bit)"));
  CHECK_THAT(parse_error("(1.0) vcan0 800#00"), Contains("larger than 7FF"));
  CHECK_THAT(parse_error("(1.0) vcan0 89F80123#00"), Contains("flag bits"));
  CHECK_THAT(parse_error("(1.0) vcan0 123#0"), Contains("2-digit hex"));
  CHECK_THAT(parse_error("(1.0) vcan0 123#0G"), Contains("2-digit hex"));
  CHECK_THAT(parse_error("(1.0) vcan0 123#001122334455667788"), Contains("more than 8 bytes"));
  CHECK_THAT(parse_error("(1.0) vcan0 123#0011_9"), Contains("_9.._F"));
  CHECK_THAT(parse_error("(1.0) vcan0 123#R9"), Contains("larger than 8"));
  CHECK_THAT(parse_error("(1.0) vcan0 123#R3x"), Contains("trailing"));
  CHECK_THAT(parse_error("(1.0) vcan0 123##"), Contains("flags digit"));
  CHECK_THAT(parse_error("(1.0) vcan0 123##1" + std::string(18, 'A')), Contains("9 bytes"));
}

TEST_CASE("candump reader: a malformed line is an error naming the file and line number") {
  TempDir dir("candump-bad");
  const std::string path = dir.file("bad.log");
  std::ofstream(path) << "(1699999999.123456) vcan0 09F80123#00E6B523B1AC6A06\n"
                         "\n"
                         "(1699999999.133456) vcan0 09F80223#07FCAE1EFA00FFF\n"
                         "(1699999999.143456) vcan0 09F11223#072154FF7FA3FEFC\n";
  {
    CandumpReader strict(path);
    CHECK(strict.next().has_value());
    try {
      strict.next();
      FAIL("no error for line 3");
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      CHECK_THAT(what, Catch::Contains(path + ":3:"));
      CHECK_THAT(what, Catch::Contains("07FCAE1EFA00FFF"));
      CHECK_THAT(what, Catch::Contains("2-digit hex bytes"));
    }
    CHECK(strict.line_number() == 3);
  }
  {
    CandumpReader lenient(path, false);
    int records = 0;
    while (lenient.next())
      ++records;
    CHECK(records == 2);
    CHECK(lenient.malformed_lines() == 1);
    CHECK_THAT(lenient.last_error(), Catch::Contains("bad.log:3:"));
  }
  CHECK_THROWS_WITH(CandumpReader(dir.file("missing.log")), Catch::Contains("missing.log"));
}

TEST_CASE("candump log: a huge malformed line is quoted in part, not echoed whole") {
  // issue 11: a 10 MB line was echoed whole to stderr
  sonarloop::testing::TempDir dir("candump-huge-line");
  const std::string line = "(1.000000) vcan0 123#" + std::string(10'000'000, 'A');
  std::ofstream(dir.file("big.log")) << line << "\n";
  sonarloop::can::CandumpReader reader(dir.file("big.log"), true);
  try {
    reader.next();
    FAIL("a malformed line was accepted");
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    CHECK(msg.size() < 600);
    CHECK_THAT(msg, Catch::Contains("big.log:1: data 'AAAA") &&
                        Catch::Contains("...' (10000000 characters)") &&
                        Catch::Contains("...' (10000021 characters)"));
  }
}
