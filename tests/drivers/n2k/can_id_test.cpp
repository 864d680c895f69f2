#include "drivers/n2k/can_id.h"

#include <catch2/catch.hpp>

#include "tests/support/test_rng.h"

using namespace sonarloop::n2k;

TEST_CASE("n2k can id: the eight nav PGNs from source 0x23 (docs/formats.md 2.1 table)") {
  struct Row {
    std::uint32_t pgn;
    std::uint8_t prio;
    std::uint32_t id;
  };
  const Row rows[] = {{126992, 3, 0x0DF01023}, {127250, 2, 0x09F11223}, {127251, 2, 0x09F11323},
                      {127257, 3, 0x0DF11923}, {128259, 2, 0x09F50323}, {128267, 3, 0x0DF50B23},
                      {129025, 2, 0x09F80123}, {129026, 2, 0x09F80223}};
  for (const Row& r : rows) {
    CAPTURE(r.pgn);
    CHECK(is_pdu2(r.pgn));
    CHECK(encode_can_id(N2kId{r.prio, r.pgn, 0x23, kAddressGlobal}) == r.id);
    const N2kId back = decode_can_id(r.id);
    CHECK(back.pgn == r.pgn);
    CHECK(back.priority == r.prio);
    CHECK(back.source == 0x23);
    CHECK(back.destination == kAddressGlobal);
  }
}

TEST_CASE("n2k can id: PDU1 (addressed) ids carry the destination, not the PGN low byte") {
  // ISO Request PGN 59904 (PF 0xEA < 240) from 0x23 to 0x10 at priority 6
  const N2kId req{6, 59904, 0x23, 0x10};
  CHECK_FALSE(is_pdu2(59904));
  CHECK(encode_can_id(req) == 0x18EA1023u);
  CHECK(decode_can_id(0x18EA1023u) == req);
  // the PGN's low byte is ignored for PDU1, the destination wins
  CHECK(encode_can_id(N2kId{6, 59904 + 0x55, 0x23, 0x10}) == 0x18EA1023u);
  // PDU2 ignores the destination
  CHECK(encode_can_id(N2kId{2, 129025, 0x23, 0x10}) == 0x09F80123u);
  // data page 1 PDU1 (PGN 0x1EF00 proprietary addressed) keeps the DP bit
  CHECK(encode_can_id(N2kId{7, 0x1EF00, 0x01, 0x02}) == 0x1DEF0201u);
  // bits above 28 (SocketCAN flags) are ignored on decode
  CHECK(decode_can_id(0x89F80123u).pgn == 129025);
}

TEST_CASE("n2k can id: seeded random round trip over all fields") {
  sonarloop::testing::TestRng rng(0x2000);
  for (int i = 0; i < 20000; ++i) {
    N2kId id;
    id.priority = static_cast<std::uint8_t>(rng.below(8));
    id.pgn = static_cast<std::uint32_t>(rng.below(kPgnMask + 1));
    id.source = static_cast<std::uint8_t>(rng.below(256));
    id.destination = static_cast<std::uint8_t>(rng.below(256));
    if (is_pdu2(id.pgn)) {
      id.destination = kAddressGlobal;
    } else {
      id.pgn &= 0x3FF00u;
    }
    const std::uint32_t can_id = encode_can_id(id);
    CHECK(can_id <= 0x1FFFFFFFu);
    REQUIRE(decode_can_id(can_id) == id);
  }
}
