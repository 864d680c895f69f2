// Contact reports out of the onboard consumer (atr/contact_writer.h): one JSON line per contact
// to a file (flushed line by line: a reader sees each at once), or one datagram per contact over
// real UDP on 127.0.0.1; unwritable places and malformed addresses refused with the reason.
#include "atr/contact_writer.h"

#include <array>
#include <catch2/catch.hpp>
#include <string>

#include "drivers/net/udp_receiver.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop;

namespace {

atr::Contact contact(std::uint64_t id) {
  atr::Contact c;
  c.id = id;
  c.ping_number = 100 + static_cast<std::uint32_t>(id);
  c.north_m = 1.5 * static_cast<double>(id);
  c.class_name = "manta";
  return c;
}

}  // namespace

TEST_CASE("contact writer: JSON lines to a file, each flushed as it is written") {
  const testing::TempDir dir("contact_writer");
  const std::string path = dir.file("contacts.jsonl");
  atr::ContactWriter w(path, stdout);
  CHECK(w.describe() == path);
  w.write(contact(1));
  // flushed: the line is in the file before the writer closes
  CHECK(testing::slurp(path) == atr::contact_json(contact(1)) + "\n");
  w.write(contact(2));
  CHECK(testing::slurp(path) ==
        atr::contact_json(contact(1)) + "\n" + atr::contact_json(contact(2)) + "\n");
  CHECK(atr::ContactWriter(std::nullopt, stderr).describe() == "stderr");
  CHECK(atr::ContactWriter(std::nullopt, stdout).describe() == "stdout");
  CHECK_THROWS_WITH(atr::ContactWriter(dir.file("no/such/folder/c.jsonl"), stdout),
                    Catch::Contains("cannot create contacts file"));
}

TEST_CASE("contact writer: one datagram per contact over UDP, its JSON line without newline") {
  net::UdpReceiver rx(net::parse_host_port("127.0.0.1:0"));
  const std::string to = "udp:127.0.0.1:" + std::to_string(rx.bound_port());
  atr::ContactWriter w(to, stdout);
  CHECK(w.describe() == to);
  w.write(contact(7));
  std::array<std::uint8_t, 4096> buffer{};
  const auto got = rx.receive(buffer, 20000);
  REQUIRE(got);
  CHECK(std::string(reinterpret_cast<const char*>(buffer.data()), got->size) ==
        atr::contact_json(contact(7)));
  CHECK_THROWS_AS(atr::ContactWriter("udp:nowhere", stdout), std::invalid_argument);
}
