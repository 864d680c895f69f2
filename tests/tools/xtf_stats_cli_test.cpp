// End-to-end: tools/xtf_stats.py on the real recording (tests/data/xtf/scotsman-iver2.xtf) and on
// the same dive rendered by the built sonarloop with the iver2_600khz preset
// (config/realism_iver2.yaml, `run --rate max`: 475 pings, about 6 s of CPU). Checks that both
// parse, that the channel and sample counts are the headers', that the real file's speckle
// statistics are sane, and that the rendered file's statistics are within the tolerances
// docs/realism.md claims of the real file's. Skipped (exit 77) when /usr/bin/python3 has no numpy.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "tests/support/skip.h"
#include "tests/support/temp_dir.h"
#include "tests/tools/sonarloop_cli.h"

using sonarloop::testing::run_command;
using sonarloop::testing::slurp;
using sonarloop::testing::TempDir;

namespace {

using sonarloop::testing::kBinary;
using sonarloop::testing::kPython;
using sonarloop::testing::kRealXtf;

const std::string kScript = std::string(SONARLOOP_SOURCE_DIR) + "/tools/xtf_stats.py";
const std::string kRealismScenario =
    std::string(SONARLOOP_SOURCE_DIR) + "/config/realism_iver2.yaml";

void skip_without_numpy() {
  if (run_command(kPython + " -c 'import numpy' > /dev/null 2>&1") != 0) {
    sonarloop::testing::skip_test(kPython + " cannot import numpy (tools/xtf_stats.py needs it)");
  }
}

// Where each `"key": ` occurs in the script's JSON, the text just after it, in order (port then
// starboard). A plain scan: std::regex trips GCC 12's -Wmaybe-uninitialized under ASan.
std::vector<const char*> after_key(const std::string& json, const std::string& key) {
  const std::string needle = "\"" + key + "\": ";
  std::vector<const char*> out;
  for (std::size_t at = json.find(needle); at != std::string::npos;
       at = json.find(needle, at + needle.size()))
    out.push_back(json.c_str() + at + needle.size());
  return out;
}

// The values of `"key": number` (NaN for `NaN`); a key followed by something else is skipped.
std::vector<double> values(const std::string& json, const std::string& key) {
  std::vector<double> out;
  for (const char* p : after_key(json, key)) {
    if (std::strncmp(p, "NaN", 3) == 0) {
      out.push_back(std::nan(""));
      continue;
    }
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end != p) out.push_back(v);
  }
  return out;
}

// The values of `"key": "text"`.
std::vector<std::string> words(const std::string& json, const std::string& key) {
  std::vector<std::string> out;
  for (const char* p : after_key(json, key)) {
    if (*p != '"') continue;
    const char* end = std::strchr(p + 1, '"');
    if (end) out.emplace_back(p + 1, end);
  }
  return out;
}

// Runs the script with --json on `xtf`; returns its JSON (and CHECKs exit status 0).
std::string stats_json(const TempDir& dir, const std::string& xtf, const std::string& name) {
  const std::string out = dir.file(name + ".json");
  const int rc =
      run_command(kPython + " " + kScript + " " + xtf + " --json > " + out + " 2> " + out + ".err");
  INFO(slurp(out + ".err"));
  CHECK(rc == 0);
  return slurp(out);
}

// Checks the two channels' header facts of a 2 x 1024-sample, 600 kHz, int16 file.
void check_header(const std::string& json, double pings) {
  CHECK(values(json, "sonar_channels") == std::vector<double>{2});
  CHECK(words(json, "sample_type") == std::vector<std::string>{"int16", "int16"});
  CHECK(words(json, "name") == std::vector<std::string>{"PORT", "STARBOARD"});
  CHECK(values(json, "samples") == std::vector<double>{1024, 1024});
  CHECK(values(json, "pings") == std::vector<double>{pings, pings});
  CHECK(values(json, "frequency_khz") == std::vector<double>{600, 600});
  for (double r : values(json, "slant_range_m"))
    CHECK(r == Approx(29.9835).margin(1e-3));
  for (double m : values(json, "max_sample"))
    CHECK(m <= 32767);  // readable as signed 16-bit samples, as the file says
}

}  // namespace

TEST_CASE("xtf_stats: the real recording and its rendered twin") {
  skip_without_numpy();
  TempDir dir("xtf-stats-cli");

  // the real file: its header, and speckle statistics in a sane band
  const std::string real = stats_json(dir, kRealXtf, "real");
  check_header(real, 461);
  const auto real_ratio = values(real, "moment_ratio");
  const auto real_cv = values(real, "amplitude_cv");
  REQUIRE(real_ratio.size() == 2);
  REQUIRE(real_cv.size() == 2);
  for (int c = 0; c < 2; ++c) {
    CHECK(real_ratio[c] > 1.8);  // not smoothed below speckle
    CHECK(real_ratio[c] < 3.5);  // not dominated by clutter
    CHECK(real_cv[c] > 0.35);
    CHECK(real_cv[c] < 0.7);
  }

  // the rendered dive: the preset's header, written and read back
  const std::string rec = dir.file("run");
  REQUIRE(run_command(kBinary + " run " + kRealismScenario +
                      " --rate max --threads 2 --quiet --record " + rec + " > /dev/null 2> " +
                      dir.file("run.err")) == 0);
  const std::string sim = stats_json(dir, rec + "/pings.xtf", "sim");
  check_header(sim, 475);
  CHECK(values(sim, "nominal_samples") == std::vector<double>{1024, 1024});

  // the statistics docs/realism.md claims within 10 %, on the channels it claims them (relative
  // tolerance, or dB: 10 % of intensity is +0.41 / -0.46 dB)
  struct Claim {
    const char* key;
    double tolerance;
    bool relative;
    bool port;
    bool starboard;
  };
  const Claim claims[] = {
      {"amplitude_cv", 0.10, true, true, true},
      {"corr_along_pings", 0.10, true, true, true},
      {"corr_across_samples", 0.10, true, true, true},
      {"seabed_start_m", 0.10, true, true, true},
      {"ping_interval_s", 0.05, true, true, true},
      {"ping_spacing_m", 0.05, true, true, true},
      {"median_amplitude_pct_fs", 0.10, true, true, false},  // port: no wreck
      {"level_db", 0.41, false, true, false},
      {"p95_db", 0.41, false, true, false},
      {"highlight_db", 0.41, false, true, false},
      {"shadow_db", 0.41, false, false, true},  // the wreck's shadow, filled to the noise floor
  };
  for (const Claim& claim : claims) {
    const auto a = values(real, claim.key);
    const auto b = values(sim, claim.key);
    REQUIRE(a.size() == 2);
    REQUIRE(b.size() == 2);
    for (int c = 0; c < 2; ++c) {
      if (!(c == 0 ? claim.port : claim.starboard)) continue;
      INFO(claim.key << " channel " << c << ": real " << a[c] << ", rendered " << b[c]);
      const double gap = claim.relative ? std::abs(b[c] / a[c] - 1.0) : std::abs(b[c] - a[c]);
      CHECK(gap <= claim.tolerance);
    }
  }
}

TEST_CASE("xtf_stats: a file that is not XTF is refused with its reason") {
  skip_without_numpy();
  TempDir dir("xtf-stats-bad");
  std::FILE* f = std::fopen(dir.file("bad.xtf").c_str(), "wb");
  REQUIRE(f != nullptr);
  const std::string junk(2000, 'x');
  std::fwrite(junk.data(), 1, junk.size(), f);
  std::fclose(f);
  const int rc = run_command(kPython + " " + kScript + " " + dir.file("bad.xtf") + " > " +
                             dir.file("out.txt") + " 2> " + dir.file("err.txt"));
  CHECK(rc != 0);
  CHECK(slurp(dir.file("err.txt")).find("not an XTF file") != std::string::npos);
  // truncated: the real file cut inside a packet
  const std::string real = slurp(kRealXtf);
  f = std::fopen(dir.file("cut.xtf").c_str(), "wb");
  REQUIRE(f != nullptr);
  std::fwrite(real.data(), 1, 1024 + 4480 + 100, f);
  std::fclose(f);
  CHECK(run_command(kPython + " " + kScript + " " + dir.file("cut.xtf") + " > /dev/null 2> " +
                    dir.file("err2.txt")) != 0);
  CHECK(slurp(dir.file("err2.txt")).find("truncated") != std::string::npos);
}
