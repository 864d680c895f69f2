// End-to-end: the `sonarloop render` command as a user runs it.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "drivers/xtf/xtf_file.h"
#include "tests/support/temp_dir.h"
#include "tests/tools/sonarloop_cli.h"

namespace {

using sonarloop::testing::kBinary;
using sonarloop::testing::run_quiet;
using sonarloop::testing::slurp;

}  // namespace

TEST_CASE(
    "render cli: the same scenario and seed give byte-identical pings.xtf on 1 or 2 threads") {
  sonarloop::testing::TempDir dir("render-cli");
  const std::string common = " --resolution-cm 10 --track -32,5:-28,5 --altitude 6";
  REQUIRE(run_quiet("render --out " + dir.file("a") + common + " --threads 1") == 0);
  REQUIRE(run_quiet("render --out " + dir.file("b") + common + " --threads 2") == 0);
  const std::string a = slurp(dir.file("a/pings.xtf"));
  const std::string b = slurp(dir.file("b/pings.xtf"));
  REQUIRE(!a.empty());
  CHECK(a == b);
  CHECK(slurp(dir.file("a/waterfall.png")) == slurp(dir.file("b/waterfall.png")));
  // the recording is a valid XTF file: one ping per 10 cm of the 4 m line, 2 channels
  const auto file = sonarloop::xtf::read_all_pings(dir.file("a/pings.xtf"));
  CHECK(file.pings.size() == 41);
  CHECK(file.header.chan_info.size() >= 2);
  for (std::size_t k = 0; k < file.pings.size(); ++k) {
    REQUIRE(file.pings[k].channels.size() == 2);
    CHECK(file.pings[k].header.ping_number == k);
  }
  // the manta at (-30, 10) lies 5 m to starboard of the line: truth.json says so
  const std::string py = std::string(SONARLOOP_PYTHON) +
                         " -c \"import json,sys; t=json.load(open(sys.argv[1])); "
                         "m=[x for x in t['targets'] if x['type']=='manta'][0]; "
                         "sys.exit(0 if m['seen'] and m['side']=='starboard' else 1)\" " +
                         dir.file("a/truth.json");
  CHECK(sonarloop::testing::run_command(py) == 0);
}

TEST_CASE("render cli: bad options are usage errors") {
  sonarloop::testing::TempDir dir("render-cli-bad");
  CHECK(run_quiet("render --out " + dir.file("x") + " --resolution-cm 0") == 2);
  CHECK(run_quiet("render --out " + dir.file("x") + " --track 1,2:1,2") == 2);
  CHECK(run_quiet("render") == 2);
  CHECK(run_quiet("render " + dir.file("missing.yaml") + " --out " + dir.file("x")) == 1);
}

TEST_CASE("render cli: a track too long for memory is refused up front, naming the size") {
  // issue 11: this said only "std::bad_alloc"
  sonarloop::testing::TempDir dir("render-cli-huge");
  const int rc =
      sonarloop::testing::run_command(kBinary + " render --out " + dir.file("x") +
                                      " --track -1e7,0:1e7,0 > /dev/null 2> " + dir.file("err"));
  const std::string err = slurp(dir.file("err"));
  INFO(err);
  CHECK(rc == 2);
  CHECK(err.find("--track -1e7,0:1e7,0: a line of 2e+07 m at 0.05 m per ping is 4e+08 pings") !=
        std::string::npos);
  CHECK(err.find("GiB of memory for the waterfall, more than the ") != std::string::npos);
  CHECK(err.find("bad_alloc") == std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("x")));
  CHECK(run_quiet("render --out " + dir.file("y") + " --track 0,0:nan,1") == 2);
}
