// The onboard stream receiver under injected loss, duplication, reordering, late arrival and
// corruption: it keeps running and counts every event exactly, fed directly and over a real UDP
// socket on 127.0.0.1; random mutations never crash it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "atr/stream_receiver.h"
#include "drivers/net/udp_receiver.h"
#include "drivers/net/udp_sender.h"
#include "tests/atr/synthetic_pings.h"

using namespace sonarloop;

namespace {

using Bytes = std::vector<std::uint8_t>;

constexpr int kBins = 100;
constexpr double kBin_m = 0.05;
constexpr std::uint32_t kFirstNumber = 1000;
constexpr int kWindow = 32;     // the receiver's reorder window in these tests
constexpr int kLateDelay = 60;  // sends a late ping is held back: beyond the window

// A ping of `bins` samples per side whose bin (number mod bins) is marked.
Bytes ping_bytes(const xtf::XtfFileHeader& h, std::uint32_t number, int bins = kBins) {
  testing::PingPose pose;
  pose.number = number;
  pose.north_m = 0.135 * number;
  std::vector<float> line(static_cast<std::size_t>(bins), -20.0f);
  line[number % static_cast<std::uint32_t>(bins)] = -3.0f;  // tells pings apart
  return xtf::encode_ping(testing::make_ping(h, pose, line, line, kBin_m), h);
}

// A malformed copy of a valid ping datagram, by one of several kinds of corruption.
Bytes corrupt(Bytes b, Rng& rng) {
  switch (rng.below(4)) {
    case 0:  // truncated
      b.resize(static_cast<std::size_t>(rng.below(b.size() - 1)) + 1);
      break;
    case 1:  // bad magic
      b[0] ^= 0xFF;
      break;
    case 2:  // NumBytesThisRecord no longer the datagram size
      b[10] = static_cast<std::uint8_t>(b[10] + 64);
      break;
    default:  // noise
      for (auto& x : b)
        x = static_cast<std::uint8_t>(rng.below(256));
      b[0] = 0x11;
      break;
  }
  return b;
}

// The counts a correct receiver reports for an injected stream.
struct Expected {
  std::uint64_t pings = 0, lost = 0, late = 0, duplicates = 0, reordered = 0, malformed = 0,
                file_headers = 0;
  std::uint64_t dropped = 0, corrupted = 0;  // the injector's split of lost (and of malformed)
  std::uint64_t datagrams = 0;               // everything emitted
};

// Per-ping probability of each injected event; a ping meets at most one, and a swap takes the
// ping after it along.
struct Rates {
  double drop = 0.0;
  double duplicate = 0.0;
  double swap = 0.0;
  double corrupt = 0.0;
  double late = 0.0;
};
// A mix of every event, rare enough to leave most of the stream clean.
constexpr Rates kMixedRates{0.05, 0.04, 0.04, 0.03, 0.015};
// issue 11 section 4: loss, duplication, reordering, late arrival and corruption at 10 % of the
// pings each. A swap takes two pings, so only 9 in 10 pings draw an event: 1/9 per draw is 10 %
// of all pings.
constexpr double kTenthOfPings = 1.0 / 9.0;
constexpr Rates kTenPercentEach{kTenthOfPings, kTenthOfPings, kTenthOfPings, kTenthOfPings,
                                kTenthOfPings};

struct Injected {
  std::vector<Bytes> datagrams;
  std::vector<std::uint32_t> delivered;  // the numbers that must come out, in order
  Expected expect;
};

enum class Fate { kNormal, kDrop, kDuplicate, kSwap, kSwapPartner, kCorrupt, kLate };

// The event each of n pings meets; the first and last few and the last 2 x kLateDelay pings are
// left alone so that every event completes.
std::vector<Fate> draw_fates(int n, const Rates& r, Rng& rng) {
  std::vector<Fate> fate(static_cast<std::size_t>(n), Fate::kNormal);
  const double drop = r.drop;
  const double dup = drop + r.duplicate;
  const double swap = dup + r.swap;
  const double corrupt = swap + r.corrupt;
  const double late = corrupt + r.late;
  for (int i = 5; i < n - 2 * kLateDelay; ++i) {
    if (fate[static_cast<std::size_t>(i)] != Fate::kNormal) continue;
    const double u = rng.uniform();
    if (u < drop) {
      fate[static_cast<std::size_t>(i)] = Fate::kDrop;
    } else if (u < dup) {
      fate[static_cast<std::size_t>(i)] = Fate::kDuplicate;
    } else if (u < swap && fate[static_cast<std::size_t>(i + 1)] == Fate::kNormal) {
      fate[static_cast<std::size_t>(i)] = Fate::kSwap;
      fate[static_cast<std::size_t>(i + 1)] = Fate::kSwapPartner;
    } else if (u < corrupt) {
      fate[static_cast<std::size_t>(i)] = Fate::kCorrupt;
    } else if (u < late) {
      fate[static_cast<std::size_t>(i)] = Fate::kLate;
    }
  }
  return fate;
}

// Streams n pings numbered from kFirstNumber, `bins` samples per side, through the events of
// `rates` into emit(datagram), with a file header every 100 sends and a junk datagram every 37.
// Returns the counts a correct receiver reports; `delivered` gets the numbers that must come out.
Expected inject(int n, std::uint64_t seed, const Rates& rates, int bins,
                const std::function<void(Bytes)>& emit, std::vector<std::uint32_t>& delivered) {
  const xtf::XtfFileHeader h = testing::make_stream_header();
  const Bytes header = xtf::encode_file_header(h);
  Rng rng(seed, RngStream::kTraining, 77);
  const std::vector<Fate> fate = draw_fates(n, rates, rng);

  Expected e;
  std::deque<std::pair<int, Bytes>> held;  // (sends to wait, datagram): duplicates and late pings
  int sends = 0;
  const auto emit_counted = [&](Bytes b) {
    ++e.datagrams;
    emit(std::move(b));
  };
  auto send = [&](Bytes b) {
    if (sends % 100 == 0) {
      emit_counted(header);
      ++e.file_headers;
    }
    if (sends % 37 == 17) {
      emit_counted(Bytes{0xCE, 0xFA, 0x00});  // junk: too short
      ++e.malformed;
    }
    emit_counted(std::move(b));
    ++sends;
    for (auto& [wait, bytes] : held)
      --wait;
    while (!held.empty() && held.front().first <= 0) {
      emit_counted(std::move(held.front().second));
      held.pop_front();
    }
  };
  for (int i = 0; i < n; ++i) {
    const auto number = kFirstNumber + static_cast<std::uint32_t>(i);
    switch (fate[static_cast<std::size_t>(i)]) {
      case Fate::kNormal:
        send(ping_bytes(h, number, bins));
        delivered.push_back(number);
        break;
      case Fate::kDrop:
        ++e.lost;
        ++e.dropped;
        break;
      case Fate::kCorrupt:
        send(corrupt(ping_bytes(h, number, bins), rng));
        ++e.lost;
        ++e.malformed;
        ++e.corrupted;
        break;
      case Fate::kDuplicate:
        send(ping_bytes(h, number, bins));
        held.emplace_back(static_cast<int>(rng.below(6)), ping_bytes(h, number, bins));
        delivered.push_back(number);
        ++e.duplicates;
        break;
      case Fate::kLate:
        held.emplace_back(kLateDelay, ping_bytes(h, number, bins));
        ++e.late;
        break;
      case Fate::kSwap:
        send(ping_bytes(h, number + 1, bins));
        send(ping_bytes(h, number, bins));
        delivered.push_back(number);
        delivered.push_back(number + 1);
        ++e.reordered;  // `number` arrives after number + 1
        ++i;
        break;
      case Fate::kSwapPartner:
        FAIL("a swap partner is sent with its pair");
        break;
    }
  }
  REQUIRE(held.empty());
  e.pings = delivered.size();
  return e;
}

// The injected stream of n pings (kMixedRates, kBins samples per side), kept in memory.
Injected make_injected(int n, std::uint64_t seed) {
  Injected out;
  out.expect = inject(
      n, seed, kMixedRates, kBins, [&out](Bytes b) { out.datagrams.push_back(std::move(b)); },
      out.delivered);
  return out;
}

struct Collected {
  std::vector<std::uint32_t> numbers;
  bool samples_ok = true;
};

atr::StreamReceiver make_receiver(Collected& got) {
  atr::ReceiverOptions o;
  o.reorder_window = kWindow;
  return atr::StreamReceiver(o, [&got](const xtf::XtfFileHeader& h, const xtf::XtfPing& p) {
    got.numbers.push_back(p.header.ping_number);
    // the ping is the one sent with this number (its marked bin)
    const auto s = xtf::samples_near_to_far<float>(p.channels[1], h.chan_info[1]);
    const auto peak = std::max_element(s.begin(), s.end()) - s.begin();
    got.samples_ok = got.samples_ok && peak == static_cast<long>(p.header.ping_number % s.size());
  });
}

// The receiver's counts equal the injector's bookkeeping exactly, and nothing else happened.
void check_expected_counts(const atr::ReceiverStats& s, const Expected& e) {
  CHECK(s.datagrams == e.datagrams);
  CHECK(s.pings == e.pings);
  CHECK(s.lost == e.lost);
  CHECK(s.late == e.late);
  CHECK(s.duplicates == e.duplicates);
  CHECK(s.reordered == e.reordered);
  CHECK(s.malformed == e.malformed);
  CHECK(s.file_headers == e.file_headers);
  CHECK(s.before_header == 0);
  CHECK(s.restarts == 0);
}

void check_counts(const atr::ReceiverStats& s, const Injected& in, const Collected& got) {
  check_expected_counts(s, in.expect);
  CHECK(s.datagrams == in.datagrams.size());
  CHECK(got.numbers == in.delivered);
  CHECK(got.samples_ok);
}

}  // namespace

TEST_CASE("stream receiver: injected loss, duplicates, swaps, late pings, corruption") {
  const Injected in = make_injected(1500, 1);
  // every kind of event happens, more than a handful of times
  CHECK(in.expect.lost > 40);
  CHECK(in.expect.duplicates > 30);
  CHECK(in.expect.reordered > 30);
  CHECK(in.expect.late > 10);
  CHECK(in.expect.malformed > 60);
  Collected got;
  atr::StreamReceiver rx = make_receiver(got);
  for (const Bytes& d : in.datagrams)
    rx.feed(d);
  rx.flush();
  check_counts(rx.stats(), in, got);
  // pings handed over + lost + late = every number of the sequence
  const auto& s = rx.stats();
  CHECK(s.pings + s.lost + s.late == 1500);
}

TEST_CASE("stream receiver: 10^5 pings at 10 % each of loss, duplicates, swaps, late, corruption") {
  // issue 11 section 4.s figure. Few samples per ping keep the 10^5 datagrams cheap (they
  // are made and fed one at a time, never all held in memory).
  constexpr int kPings = 100'000;
  constexpr int kSmallBins = 8;
  Collected got;
  atr::StreamReceiver rx = make_receiver(got);
  std::vector<std::uint32_t> delivered;
  const auto t0 = std::chrono::steady_clock::now();
  const Expected e = inject(
      kPings, 4, kTenPercentEach, kSmallBins, [&rx](Bytes b) { rx.feed(b); }, delivered);
  rx.flush();
  const double run_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // each event met about 10 % of the pings (+-1 %: far beyond the binomial spread of 0.1 %)
  const auto about_a_tenth = [](std::uint64_t count) {
    return count >= kPings * 9 / 100 && count <= kPings * 11 / 100;
  };
  CHECK(about_a_tenth(e.dropped));
  CHECK(about_a_tenth(e.duplicates));
  CHECK(about_a_tenth(e.reordered));  // a swap: the lower number arrives second
  CHECK(about_a_tenth(e.late));
  CHECK(about_a_tenth(e.corrupted));
  // the receiver's counts equal the injector's bookkeeping exactly
  const auto& s = rx.stats();
  check_expected_counts(s, e);
  CHECK(s.unconfirmed == 0);
  CHECK(s.pings + s.lost + s.late == static_cast<std::uint64_t>(kPings));
  CHECK(got.numbers == delivered);
  CHECK(got.samples_ok);
  std::printf(
      "stream receiver, %d pings at 10 %% each: %llu datagrams, %llu pings, %llu lost (%llu "
      "dropped + %llu corrupt), %llu duplicates, %llu reordered, %llu late, %llu malformed, "
      "%.2f s\n",
      kPings, static_cast<unsigned long long>(s.datagrams),
      static_cast<unsigned long long>(s.pings), static_cast<unsigned long long>(s.lost),
      static_cast<unsigned long long>(e.dropped), static_cast<unsigned long long>(e.corrupted),
      static_cast<unsigned long long>(s.duplicates), static_cast<unsigned long long>(s.reordered),
      static_cast<unsigned long long>(s.late), static_cast<unsigned long long>(s.malformed), run_s);
}

TEST_CASE("stream receiver: the same over a real UDP socket on 127.0.0.1") {
  const Injected in = make_injected(1200, 2);
  net::UdpReceiver rx_socket(net::parse_host_port("127.0.0.1:0"), 8 << 20);
  net::UdpSender tx(net::parse_host_port("127.0.0.1:" + std::to_string(rx_socket.bound_port())));
  std::vector<Bytes> received;
  std::mutex mu;
  std::atomic<bool> stop{false};
  std::thread reader([&] {
    std::vector<std::uint8_t> buf(70000);
    while (!stop) {
      const auto d = rx_socket.receive(buf, 20);
      if (!d) continue;
      const std::lock_guard lock(mu);
      received.emplace_back(buf.begin(), buf.begin() + static_cast<long>(d->size));
    }
  });
  for (std::size_t i = 0; i < in.datagrams.size(); ++i) {
    REQUIRE(tx.send(in.datagrams[i]));
    if (i % 20 == 19) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  for (int tries = 0; tries < 200; ++tries) {
    {
      const std::lock_guard lock(mu);
      if (received.size() >= in.datagrams.size()) break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  stop = true;
  reader.join();
  // loopback keeps order and loses nothing at this rate: the injected events are all there are
  REQUIRE(received.size() == in.datagrams.size());
  Collected got;
  atr::StreamReceiver rx = make_receiver(got);
  for (const Bytes& d : received)
    rx.feed(d);
  rx.flush();
  check_counts(rx.stats(), in, got);
}

TEST_CASE("stream receiver: pings before the first header, other packets, restarts") {
  const xtf::XtfFileHeader h = testing::make_stream_header();
  const Bytes header = xtf::encode_file_header(h);
  Collected got;
  atr::StreamReceiver rx = make_receiver(got);
  CHECK(rx.feed(ping_bytes(h, 5)) == atr::DatagramOutcome::kBeforeHeader);
  CHECK(rx.feed(ping_bytes(h, 6)) == atr::DatagramOutcome::kBeforeHeader);
  CHECK(rx.feed(header) == atr::DatagramOutcome::kFileHeader);
  // a valid XTF packet of another type (notes, HeaderType 1): ignored
  Bytes notes(64, 0);
  notes[0] = 0xCE;
  notes[1] = 0xFA;
  notes[2] = xtf::kHeaderTypeNotes;
  notes[10] = 64;
  CHECK(rx.feed(notes) == atr::DatagramOutcome::kOther);
  for (std::uint32_t k = 5000; k < 5005; ++k)
    CHECK(rx.feed(ping_bytes(h, k)) == atr::DatagramOutcome::kPing);
  // a duplicate, and a number from just before the first one received
  CHECK(rx.feed(ping_bytes(h, 5002)) == atr::DatagramOutcome::kDuplicate);
  CHECK(rx.feed(ping_bytes(h, 4999)) == atr::DatagramOutcome::kLate);
  // the sender restarts from 0: a new sequence, not 4 billion lost pings
  for (std::uint32_t k = 0; k < 3; ++k)
    CHECK(rx.feed(ping_bytes(h, k)) == atr::DatagramOutcome::kPing);
  // a jump within max_gap is loss
  CHECK(rx.feed(ping_bytes(h, 10)) == atr::DatagramOutcome::kPing);
  rx.flush();
  const auto& s = rx.stats();
  CHECK(s.before_header == 2);
  CHECK(s.other_packets == 1);
  CHECK(s.restarts == 1);
  CHECK(s.pings == 9);
  CHECK(s.lost == 7);  // 3 .. 9
  CHECK(s.duplicates == 1);
  CHECK(s.late == 1);
  CHECK(got.numbers == std::vector<std::uint32_t>{5000, 5001, 5002, 5003, 5004, 0, 1, 2, 10});
}

TEST_CASE("stream receiver: a changed header hands the buffered pings over first") {
  const xtf::XtfFileHeader h = testing::make_stream_header();
  Collected got;
  atr::StreamReceiver rx = make_receiver(got);
  rx.feed(xtf::encode_file_header(h));
  rx.feed(ping_bytes(h, 1));
  rx.feed(ping_bytes(h, 3));  // waits for 2
  CHECK(rx.buffered() == 1);
  xtf::XtfFileHeader h2 = h;
  h2.sonar_name = "other";
  CHECK(rx.feed(xtf::encode_file_header(h2)) == atr::DatagramOutcome::kFileHeader);
  CHECK(rx.buffered() == 0);
  CHECK(rx.stats().header_changes == 1);
  CHECK(rx.stats().lost == 1);
  CHECK(got.numbers == std::vector<std::uint32_t>{1, 3});
  CHECK(rx.header().sonar_name == "other");
}

TEST_CASE("stream receiver: random mutations never crash it, and every datagram is counted") {
  const xtf::XtfFileHeader h = testing::make_stream_header();
  Collected got;
  atr::StreamReceiver rx = make_receiver(got);
  rx.feed(xtf::encode_file_header(h));
  Rng rng(3, RngStream::kTraining, 78);
  std::uint64_t accepted = 0;
  for (int i = 0; i < 4000; ++i) {
    Bytes b = ping_bytes(h, static_cast<std::uint32_t>(i));
    const int flips = static_cast<int>(rng.below(4));
    for (int f = 0; f < flips; ++f) {
      // mostly in the headers, where the structure lives
      const auto at = static_cast<std::size_t>(rng.below(rng.uniform() < 0.8 ? 400 : b.size()));
      b[at] = static_cast<std::uint8_t>(rng.below(256));
    }
    if (rng.uniform() < 0.1) b.resize(static_cast<std::size_t>(rng.below(b.size() + 100)));
    if (rx.feed(b) == atr::DatagramOutcome::kPing) ++accepted;
  }
  rx.flush();
  const auto& s = rx.stats();
  CHECK(s.datagrams == 4001);
  CHECK(s.datagrams == s.file_headers + s.malformed + accepted + s.duplicates + s.late +
                           s.before_header + s.other_packets);
  CHECK(accepted == s.pings + s.unconfirmed);
  CHECK(s.malformed > 100);
  CHECK(accepted > 1000);
  CHECK(s.pings == got.numbers.size());
}

namespace {

// Feeds pings first .. last - 1 in order, noting their numbers in `sent`.
void feed_run(atr::StreamReceiver& rx, const xtf::XtfFileHeader& h, std::uint32_t first,
              std::uint32_t last, std::vector<std::uint32_t>& sent) {
  for (std::uint32_t k = first; k < last; ++k) {
    CHECK(rx.feed(ping_bytes(h, k)) == atr::DatagramOutcome::kPing);
    sent.push_back(k);
  }
}

}  // namespace

TEST_CASE("stream receiver: a burst of junk with high ping numbers does not derail the stream") {
  // issue 11: after such a burst the clean stream was counted late (the junk had moved the
  // expected number far ahead) and onboard found 0 of 4 targets
  const xtf::XtfFileHeader h = testing::make_stream_header();
  Collected got;
  atr::StreamReceiver rx = make_receiver(got);
  rx.feed(xtf::encode_file_header(h));
  std::vector<std::uint32_t> clean;
  feed_run(rx, h, kFirstNumber, kFirstNumber + 100, clean);
  // 60 well-formed pings with random numbers ahead: within max_gap, beyond it, and behind
  Rng rng(11, RngStream::kTraining, 79);
  const std::uint32_t next = kFirstNumber + 100;
  for (int j = 0; j < 60; ++j) {
    const std::uint32_t number =
        j % 3 == 0 ? next + kWindow + static_cast<std::uint32_t>(rng.below(atr::kDefaultMaxPingGap))
        : j % 3 == 1
            ? next + atr::kDefaultMaxPingGap + 1 + static_cast<std::uint32_t>(rng.below(1u << 30))
            : static_cast<std::uint32_t>(rng.below(kFirstNumber - kWindow));
    CHECK(rx.feed(ping_bytes(h, number)) == atr::DatagramOutcome::kPing);  // held
  }
  feed_run(rx, h, next, next + 300, clean);
  rx.flush();
  const auto& s = rx.stats();
  CHECK(got.numbers == clean);
  CHECK(s.pings == 400);
  CHECK(s.late == 0);
  CHECK(s.lost == 0);
  CHECK(s.restarts == 0);
  CHECK(s.unconfirmed == 60);
  CHECK(got.samples_ok);
}

TEST_CASE("stream receiver: a real jump is followed once the next pings confirm it") {
  const xtf::XtfFileHeader h = testing::make_stream_header();
  Collected got;
  atr::StreamReceiver rx = make_receiver(got);
  rx.feed(xtf::encode_file_header(h));
  std::vector<std::uint32_t> want;
  feed_run(rx, h, 0, 50, want);
  // 50 pings lost in a row (more than the window), then the stream goes on
  feed_run(rx, h, 100, 150, want);
  // held, not confirmed before the flush: dropped
  rx.feed(ping_bytes(h, 500));
  rx.feed(ping_bytes(h, 501));
  rx.flush();
  const auto& s = rx.stats();
  CHECK(got.numbers == want);
  CHECK(s.lost == 50);
  CHECK(s.unconfirmed == 2);
  CHECK(s.late == 0);
}

TEST_CASE("stream receiver: bad options are refused") {
  atr::ReceiverOptions o;
  o.reorder_window = 0;
  CHECK_THROWS_AS(atr::StreamReceiver(o, {}), std::invalid_argument);
  o.reorder_window = 64;
  o.history = 10;
  CHECK_THROWS_AS(atr::StreamReceiver(o, {}), std::invalid_argument);
}
