#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <vector>

#include "common/rng.h"
#include "emulator/run_stats.h"

using namespace sonarloop::emulator;

TEST_CASE("LatencyHistogram: quantiles within the bucket accuracy of exact order statistics") {
  sonarloop::Rng rng(7);
  LatencyHistogram h;
  std::vector<std::int64_t> v;
  for (int i = 0; i < 20000; ++i) {
    // log-uniform from 5 us to 50 ms: the range of publishing lateness
    const double x = 5e3 * std::pow(1e4, rng.uniform());
    v.push_back(static_cast<std::int64_t>(x));
    h.add(v.back());
  }
  std::sort(v.begin(), v.end());
  for (double q : {0.01, 0.5, 0.9, 0.99, 0.999}) {
    const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size()))) - 1;
    const double exact = static_cast<double>(v[rank]);
    INFO("q " << q << " exact " << exact << " got " << h.quantile_ns(q));
    CHECK(std::abs(h.quantile_ns(q) / exact - 1.0) < 0.125);  // within a bucket (12.2 %)
  }
  CHECK(h.max_ns() == v.back());
  CHECK(h.min_ns() == v.front());
  CHECK(h.count() == v.size());
  CHECK(h.quantile_ns(1.0) <= static_cast<double>(v.back()));
}

TEST_CASE("LatencyHistogram: edges, clamping and merging") {
  LatencyHistogram h;
  CHECK(h.quantile_ns(0.5) == 0.0);
  CHECK(h.max_ns() == 0);
  h.add(-5);  // counts as 0
  CHECK(h.min_ns() == 0);
  h.add(2'000'000'000'000'000);  // beyond 1000 s
  CHECK(h.quantile_ns(1.0) == 2e15);
  CHECK(LatencyHistogram::bucket_of(999) == 0);
  CHECK(LatencyHistogram::bucket_of(1000) == 1);
  CHECK(LatencyHistogram::bucket_of(LatencyHistogram::kMaxNs) == LatencyHistogram::kBuckets - 1);
  // bucket edges are increasing and a decade is kBucketsPerDecade buckets
  for (int b = 1; b < LatencyHistogram::kBuckets - 1; ++b)
    CHECK(LatencyHistogram::bucket_lower_ns(b + 1) > LatencyHistogram::bucket_lower_ns(b));
  CHECK(LatencyHistogram::bucket_lower_ns(1 + LatencyHistogram::kBucketsPerDecade) ==
        Approx(10.0 * LatencyHistogram::bucket_lower_ns(1)));
  LatencyHistogram a, b;
  a.add(10'000);
  b.add(30'000'000);
  a.merge(b);
  CHECK(a.count() == 2);
  CHECK(a.max_ns() == 30'000'000);
  CHECK(a.min_ns() == 10'000);
  // a single value is reported exactly (clamped to min = max)
  LatencyHistogram one;
  one.add(123'456);
  CHECK(one.quantile_ns(0.5) == 123'456.0);
}

TEST_CASE("stats line and JSON carry the counters") {
  RunStats s;
  s.rate = "realtime";
  s.sim_time_s = 12.0;
  s.wall_time_s = 12.0;
  s.cpu_time_s = 1.2;
  s.pings_sent = 180;
  s.pings_late = 2;
  s.pings_dropped = 1;
  s.ping_lateness.add(100'000);
  s.ping_lateness.add(300'000);
  s.nav_frames = 1234;
  char line[512];
  format_stats_line(s, line, sizeof line);
  const std::string l(line);
  CHECK(l.find("pings 180 sent, 3 missed (2 late, 1 dropped)") != std::string::npos);
  CHECK(l.find("nav 1234 frames") != std::string::npos);
  CHECK(l.find("cpu 10 %") != std::string::npos);
  // a short buffer is cut, still terminated
  char small[16];
  format_stats_line(s, small, sizeof small);
  CHECK(std::strlen(small) == 15);

  const std::string j = stats_json(s);
  for (const char* key : {"\"deadline_misses\": 3", "\"sent\": 180", "\"lateness\"", "\"p99_ms\"",
                          "\"cpu_percent\": 10", "\"frames\": 1234"}) {
    INFO(key);
    CHECK(j.find(key) != std::string::npos);
  }
}
