// run --record DIR's MCAP file read by an independent reader (tests/tools/mcap_read.mjs: the npm
// registry's @mcap/core through the index and record by record with every CRC, each message
// decoded by @foxglove/rosmsg2-serialization with its own schema), compared with the run's XTF
// and candump recordings: every ping on both sides with the XTF channel's samples, every
// navigation fix with the NMEA 2000 position of the same instant, the truth and the waterfall
// images counted, time order, the index's count equal to the stream's and the statistics'.
// Skips (77, with the reason) without node and npm or when the npm registry cannot be reached.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "autonomy/json_line.h"
#include "drivers/can/candump_log.h"
#include "drivers/n2k/messages.h"
#include "drivers/xtf/xtf_file.h"
#include "tests/emulator/test_scenario.h"
#include "tests/support/skip.h"
#include "tests/support/temp_dir.h"
#include "tests/tools/mcap_reader.h"
#include "tests/tools/sonarloop_cli.h"

using namespace sonarloop;
using autonomy::JsonLine;
using testing::run_command;
using testing::slurp;

namespace {

std::vector<JsonLine> read_lines(const std::string& path) {
  std::vector<JsonLine> out;
  std::ifstream in(path);
  std::string line, error;
  while (std::getline(in, line)) {
    const auto j = JsonLine::parse(line, error);
    INFO(line << ": " << error);
    REQUIRE(j);
    out.push_back(*j);
  }
  return out;
}

template <class T>
void near_to_far(const xtf::XtfPingChannel& c, bool port, double& sum, double& first,
                 double& last) {
  const auto& v = std::get<std::vector<T>>(c.samples);
  sum = 0.0;
  for (T s : v)
    sum += static_cast<double>(s);
  first = static_cast<double>(port ? v.back() : v.front());
  last = static_cast<double>(port ? v.front() : v.back());
}

}  // namespace

TEST_CASE("run --record: run.mcap as @mcap/core reads it equals pings.xtf and nav.log",
          "[may_skip]") {
  if (const std::string why = testing::prepare_mcap_reader(); !why.empty()) testing::skip_test(why);
  testing::TempDir dir("mcap_cli");
  { std::ofstream(dir.file("s.yaml")) << testing::small_scenario_yaml(); }
  REQUIRE(run_command(testing::kBinary + " run " + dir.file("s.yaml") +
                      " --rate max --duration 4 --epoch 1767225600 --quiet --record " +
                      dir.file("rec") + " 2> " + dir.file("run.err")) == 0);
  REQUIRE(testing::read_mcap(dir.file("rec/run.mcap"), dir.file("read.jsonl"),
                             dir.file("read.err")) == 0);
  INFO(slurp(dir.file("read.err")));
  const std::vector<JsonLine> lines = read_lines(dir.file("read.jsonl"));
  REQUIRE(!lines.empty());
  const JsonLine& summary = lines.front();
  REQUIRE(summary.string("kind") == "summary");
  CHECK(summary.boolean("footer") == true);
  CHECK(summary.boolean("ordered") == true);
  CHECK(summary.string("profile") == "ros2");
  const double n = static_cast<double>(lines.size() - 1);
  CHECK(summary.number("indexed_messages") == n);
  CHECK(summary.number("stream_messages") == n);
  CHECK(summary.number("statistics_messages") == n);
  const JsonLine topics = *summary.object("topics");
  CHECK(topics.string("/sidescan/port") == "marine_acoustic_msgs/msg/RawSonarImage");
  CHECK(topics.string("/sidescan/waterfall") == "sensor_msgs/msg/Image");
  CHECK(topics.string("/nav/fix") == "sensor_msgs/msg/NavSatFix");
  CHECK(topics.string("/truth/pose") == "geometry_msgs/msg/PoseStamped");

  // the pings, both sides, against the XTF recording
  std::vector<xtf::XtfPing> pings;
  xtf::XtfReader xtf(dir.file("rec/pings.xtf"));
  xtf::XtfRecord rec;
  while (xtf.next(rec))
    if (rec.is_ping) pings.push_back(rec.ping);
  REQUIRE(!pings.empty());
  std::map<std::string, std::size_t> seen;
  std::vector<double> fix_lat, fix_lon;
  std::size_t images = 0, poses = 0;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const JsonLine& l = lines[i];
    const std::string kind = *l.string("kind");
    const std::string topic = *l.string("topic");
    if (kind == "ping") {
      const bool port = topic == "/sidescan/port";
      const std::size_t k = seen[topic]++;
      REQUIRE(k < pings.size());
      const xtf::XtfPingChannel& c = pings[k].channels[port ? 0 : 1];
      double sum = 0, first = 0, last = 0;
      near_to_far<std::uint16_t>(c, port, sum, first, last);
      INFO(topic << " ping " << k);
      CHECK(l.number("samples") == static_cast<double>(c.num_samples()));
      CHECK(l.number("samples_per_beam") == static_cast<double>(c.num_samples()));
      CHECK(l.number("beams") == 1);
      CHECK(l.number("dtype") == 2);
      CHECK(l.number("sum") == sum);
      CHECK(l.number("first") == first);
      CHECK(l.number("last") == last);
      CHECK(*l.number("rx_angle") == Approx(port ? -M_PI / 2 : M_PI / 2));
      // the XTF time is in hundredths of a second
      const double t = std::stod(*l.string("log_time")) * 1e-9;
      CHECK(t ==
            Approx(static_cast<double>(*xtf::time_utc_ns(pings[k].header)) * 1e-9).margin(0.011));
    } else if (kind == "fix" && topic == "/nav/fix") {
      fix_lat.push_back(*l.number("latitude"));
      fix_lon.push_back(*l.number("longitude"));
    } else if (kind == "image") {
      ++images;
      CHECK(l.string("encoding") == "mono8");
      CHECK(*l.number("width") <= 1024);
      CHECK(*l.number("bytes") == *l.number("width") * *l.number("height"));
    } else if (kind == "pose") {
      poses += topic == "/truth/pose" ? 1 : 0;
    }
  }
  CHECK(seen["/sidescan/port"] == pings.size());
  CHECK(seen["/sidescan/starboard"] == pings.size());
  CHECK(poses == pings.size());
  CHECK(images == pings.size() / 16);

  // every fix against the 129025 frame of the same sample in nav.log
  std::vector<n2k::PositionRapidUpdate> frames;
  std::ifstream log(dir.file("rec/nav.log"));
  std::string line, error;
  while (std::getline(log, line)) {
    can::CandumpRecord r;
    if (can::parse_candump_line(line, r, error) != can::CandumpLineStatus::kRecord) continue;
    const auto d = n2k::decode<n2k::PositionRapidUpdate>(r.frame);
    if (d) frames.push_back(*d);
  }
  REQUIRE(frames.size() == fix_lat.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    CHECK(fix_lat[i] == Approx(*frames[i].latitude_deg).margin(1.5e-7));
    CHECK(fix_lon[i] == Approx(*frames[i].longitude_deg).margin(1.5e-7));
  }
}

TEST_CASE("run --mcap: the file alone, none, a bad path, and the same bytes run after run") {
  testing::TempDir dir("mcap_cli_options");
  { std::ofstream(dir.file("s.yaml")) << testing::small_scenario_yaml(); }
  const std::string run = testing::kBinary + " run " + dir.file("s.yaml") +
                          " --rate max --duration 2 --epoch 1767225600 --quiet ";
  // alone, on 1 and on 2 render threads: byte-identical files, the magic at both ends
  REQUIRE(run_command(run + "--threads 1 --mcap " + dir.file("a.mcap") + " 2> /dev/null") == 0);
  REQUIRE(run_command(run + "--threads 2 --mcap " + dir.file("b.mcap") + " 2> /dev/null") == 0);
  const std::string a = slurp(dir.file("a.mcap"));
  REQUIRE(a.size() > 1000);
  CHECK(a == slurp(dir.file("b.mcap")));
  CHECK(a.substr(0, 8) == std::string("\x89MCAP0\r\n", 8));
  CHECK(a.substr(a.size() - 8) == std::string("\x89MCAP0\r\n", 8));
  CHECK_FALSE(std::filesystem::exists(dir.file("pings.xtf")));
  // --record writes run.mcap beside the other files, unless --mcap none
  REQUIRE(run_command(run + "--record " + dir.file("r") + " 2> /dev/null") == 0);
  CHECK(slurp(dir.file("r/run.mcap")) == a);
  REQUIRE(run_command(run + "--record " + dir.file("n") + " --mcap none 2> /dev/null") == 0);
  CHECK(std::filesystem::exists(dir.file("n/pings.xtf")));
  CHECK_FALSE(std::filesystem::exists(dir.file("n/run.mcap")));
  // a place it cannot be created: an error naming it, before the run
  CHECK(run_command(run + "--mcap " + dir.file("no/dir/x.mcap") + " 2> " + dir.file("err")) == 1);
  CHECK_THAT(slurp(dir.file("err")), Catch::Contains(dir.file("no/dir/x.mcap")));
}
