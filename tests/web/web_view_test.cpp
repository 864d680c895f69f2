// The live view as the commands open it (web/web_view.h): no address, no view; on 127.0.0.1 port
// 0 a server on a free port of the loopback; the onboard consumer's
// statistics as the page shows them; the process's CPU use.
#include "web/web_view.h"

#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <string>

using namespace sonarloop;

TEST_CASE("web view: opened only when asked for, on the loopback address given") {
  CHECK(web::open_web_view(std::nullopt, std::nullopt, "test") == nullptr);
  const auto view =
      web::open_web_view(net::parse_host_port("127.0.0.1:0"), GeoPoint{59.9, 10.75}, "test");
  REQUIRE(view);
  const std::string url = view->server.url();
  CHECK(url.rfind("http://127.0.0.1:", 0) == 0);
  CHECK(url != "http://127.0.0.1:0/");
  CHECK(view->hub.counters().clients_total == 0);
}

TEST_CASE("web view: the onboard consumer's statistics, and the CPU meter") {
  atr::OnboardStats s;
  s.receiver.pings = 1234;
  s.receiver.lost = 5;
  s.contacts = 7;
  const web::WebStats w = web::web_stats_of(s, 42.5);
  CHECK(std::string(w.source) == "onboard");
  CHECK(w.pings == 1234);
  CHECK(w.datagrams_lost == 5);
  CHECK(w.contacts == 7);
  CHECK(w.cpu_percent == 42.5);

  const web::CpuMeter cpu;
  // busy for a while: the meter sees this thread's work (a bound, not a timing assertion)
  volatile double x = 0.0;
  const auto t0 = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - t0 < std::chrono::milliseconds(50))
    x = x + std::sqrt(2.0);
  const double p = cpu.percent();
  CHECK(std::isfinite(p));
  CHECK(p > 0.0);
}
