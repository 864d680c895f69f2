// The onboard consumer in the emulator's process (atr/in_process_onboard.h): pings pushed as the
// emulator pushes them reach the pipeline on its own thread, every contact goes to the contacts
// file and to the observer, lossless pushes drop nothing; and the end-of-run statistics
// (atr/onboard_report.h) say so in the JSON of --stats-json.
#include "atr/in_process_onboard.h"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "atr/onboard_report.h"
#include "tests/atr/synthetic_chips.h"
#include "tests/atr/synthetic_pings.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop;

TEST_CASE("in-process onboard: the emulator's pings in, every contact out, nothing dropped") {
  const testing::TempDir dir("in_process_onboard");
  const xtf::XtfFileHeader h = testing::make_stream_header();
  const std::vector<std::uint8_t> header = xtf::encode_file_header(h);
  std::vector<std::vector<std::uint8_t>> pings;
  const std::vector<testing::SeabedObject> objects = {{1, 10.0, 12.0, 0.8, 0.40},
                                                      {0, 20.0, 18.0, 1.0, 0.35}};
  testing::stream_line(
      300, objects, [](int) { return 0.0; }, h,
      [&](const xtf::XtfPing& p) { pings.push_back(xtf::encode_ping(p, h)); });
  std::size_t packet_bytes = 0;
  for (const auto& p : pings)
    packet_bytes = std::max(packet_bytes, p.size());

  std::vector<atr::Contact> observed;
  const std::string path = dir.file("contacts.jsonl");
  atr::OnboardStats stats;
  {
    atr::InProcessOnboard onboard(testing::small_two_class_model(), atr::OnboardOptions{}, path,
                                  header, packet_bytes, true,
                                  [&](const atr::Contact& c) { observed.push_back(c); });
    CHECK(onboard.contacts_destination() == path);
    for (const auto& p : pings)
      onboard.on_ping(p);
    stats = onboard.finish();
    CHECK(onboard.queue().dropped_full() == 0);
    CHECK(onboard.queue().pushed() == pings.size() + 1);  // and the file header
    const std::string json = atr::onboard_stats_json(stats, &onboard.queue());
    CHECK_THAT(json, Catch::Contains("\"pings\":300") && Catch::Contains("\"lost\":0") &&
                         Catch::Contains("\"dropped_full\":0") &&
                         Catch::Contains("\"contacts\":" + std::to_string(stats.contacts)));
  }
  // both objects, in the file and to the observer alike (the small model's chips are not this
  // sonar's: whether they were classified is the pipeline's test, not this one's)
  CHECK(stats.receiver.pings == 300);
  REQUIRE(stats.contacts == objects.size());
  CHECK(stats.classified + stats.unclassified == stats.contacts);
  REQUIRE(observed.size() == objects.size());
  std::string expected;
  for (const atr::Contact& c : observed)
    expected += atr::contact_json(c) + "\n";
  CHECK(testing::slurp(path) == expected);
}
