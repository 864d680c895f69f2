// Contact reports: one valid JSON object per line with the documented fields, nulls for what is
// unknown, and times in UTC to the hundredth (read back by Python's json module).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "atr/contact.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop;

namespace {

atr::Contact classified() {
  atr::Contact c;
  c.id = 3;
  c.time_utc_ns = 1767225608880000000LL;  // 2026-01-01T00:00:08.88Z
  c.ping_number = 132;
  c.side = 0;
  c.latitude_deg = 55.8998634;
  c.longitude_deg = -3.19983958;
  c.north_m = -29.91;
  c.east_m = 10.07;
  c.slant_range_m = 12.31;
  c.ground_range_m = 9.98;
  c.class_name = "manta";
  c.mine_like = true;
  c.distance = 43.2;
  c.runner_up = "rockan";
  c.runner_up_distance = 45.1;
  c.scores = {{"manta", 43.2}, {"rockan", 45.1}};
  c.mine_distance = 43.2;
  c.non_mine_distance = std::numeric_limits<double>::infinity();
  c.aspect_min_deg = 45;
  c.aspect_max_deg = 90;
  c.pings = 6;
  c.shift_rows = -1;
  c.shift_cols = 3;
  c.windows = 110;
  return c;
}

}  // namespace

TEST_CASE("contact: UTC to the hundredth") {
  CHECK(atr::format_utc(1767225608880000000LL) == "2026-01-01T00:00:08.88Z");
  CHECK(atr::format_utc(1767225608889999999LL) == "2026-01-01T00:00:08.88Z");
  CHECK(atr::format_utc(0) == "1970-01-01T00:00:00.00Z");
  CHECK(atr::format_utc(-10'000'000) == "1969-12-31T23:59:59.99Z");
}

TEST_CASE("contact: JSON lines, read back by Python") {
  const std::string a = atr::contact_json(classified());
  CHECK(a.find('\n') == std::string::npos);
  CHECK(a.rfind("{\"contact\":3,\"time_utc\":\"2026-01-01T00:00:08.88Z\",", 0) == 0);
  atr::Contact unclassified;
  unclassified.id = 4;
  unclassified.status = "no_model";
  const std::string b = atr::contact_json(unclassified);
  CHECK(b.find("\"class\":null") != std::string::npos);
  CHECK(b.find("\"time_utc\":null") != std::string::npos);
  CHECK(b.find("latitude_deg") == std::string::npos);  // no geodetic position: left out

  testing::TempDir dir("contact");
  std::ofstream(dir.file("c.jsonl")) << a << '\n' << b << '\n';
  const std::string py =
      std::string(SONARLOOP_PYTHON) +
      " -c \"import json,sys; L=[json.loads(l) for l in open(sys.argv[1])]; a,b=L; "
      "ok = a['contact']==3 and a['ping']==132 and a['side']=='port' and "
      "abs(a['latitude_deg']-55.8998634)<1e-9 and abs(a['longitude_deg']+3.19983958)<1e-9 and "
      "a['class']=='manta' and a['mine_like'] is True and a['runner_up']=='rockan' and "
      "a['scores']=={'manta':43.2,'rockan':45.1} and a['non_mine_distance'] is None and "
      "a['aspect_sector_deg']==[45,90] and a['alignment']=={'rows':-1,'cols':3,'windows':110} "
      "and a['time_utc_ns']==1767225608880000000 and a['detection']['pings']==6 and "
      "'status' not in a and b['status']=='no_model' and b['class'] is None and "
      "b['mine_like'] is None; sys.exit(0 if ok else 1)\" " +
      dir.file("c.jsonl");
  CHECK(testing::run_command(py) == 0);
}

TEST_CASE("contact: open-set fields only for a model with rejection") {
  atr::Contact c = classified();
  CHECK(atr::contact_json(c).find("unknown") == std::string::npos);
  CHECK(atr::contact_json(c).find("open_set_score") == std::string::npos);
  c.open_set_score = 1.25;
  c.unknown = true;
  const std::string j = atr::contact_json(c);
  CHECK(j.find("\"unknown\":true,\"open_set_score\":1.25") != std::string::npos);
  c.open_set_score = 0.5;
  c.unknown = false;
  CHECK(atr::contact_json(c).find("\"unknown\":false,\"open_set_score\":0.5") != std::string::npos);
}

TEST_CASE("contact: multi-look fields only for an object seen before") {
  atr::Contact c = classified();
  CHECK(atr::contact_json(c).find("looks") == std::string::npos);
  c.looks = 2;
  c.object = 1;
  c.fused_class = "rockan";
  c.fused_mine_like = true;
  CHECK(atr::contact_json(c).find(
            "\"looks\":2,\"object\":1,\"fused_class\":\"rockan\",\"fused_mine_like\":true") !=
        std::string::npos);
}
