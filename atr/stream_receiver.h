#pragma once
// The onboard consumer's input: the emulator's sonar stream (docs/design.md "Wire conventions"),
// one datagram at a time, turned into decoded XTF pings handed over IN PING-NUMBER ORDER.
//
// Input: datagrams as `sonarloop run --udp` sends them (or as cut from an .xtf file): the
// 1024-byte XTF file header (repeated every 2 s) and one XTF sonar packet per datagram, told apart
// by xtf::classify_datagram. Pings need a file header to decode (channel layout, sample type):
// pings that arrive before the first header are dropped and counted (before_header). A header
// that differs from the current one replaces it (header_changes) after the buffered pings have
// been handed over.
//
// Sequencing. XTF PingNumber counts consecutively (docs/formats.md 1.5). The first ping received
// starts the sequence; after it the receiver expects next = last handed over + 1:
//   - a ping within the reorder window (next <= n < next + W) waits in a slot until every
//     earlier number has arrived or been given up, then goes out in order;
//   - a ping beyond the window (n >= next + W) makes the receiver give up the oldest numbers
//     until it fits: buffered ones go out, missing ones count as lost;
//   - flush() (end of stream, or the stream idle) hands over everything buffered and counts the
//     missing numbers between them as lost;
//   - a ping behind the window (n < next) is a duplicate if it was handed over, and late if it
//     had been given up as lost (then lost - 1, late + 1); either way it is dropped. A number
//     never seen is late when it is at most W behind (it predates the first ping received);
//   - a new sequence starts (the sender restarted) on a jump forward of more than max_gap
//     numbers, or back by more than W to a number never seen: the buffer is flushed,
//     restarts + 1, and the jump is not counted as lost.
// Jumps are confirmed first. A ping that would move the sequence (beyond the window, or a
// restart) is held, not acted on, until kJumpConfirmations more pings arrive within W numbers
// of it (a real stream goes on from where it jumped to); then all of them are placed as above.
// A ping in the current window, or a ping that does not fit the held one, drops what is held
// (counted as unconfirmed); so does flush(). XTF has no checksum: junk that decodes as a ping
// with a random high PingNumber would otherwise give up every ping up to it as lost and then
// count the real stream, now behind, as late (issue 11: 0 of 4 targets found after a junk
// burst). The cost: a real jump of W or more reaches the sink two pings later, and a jump in
// the last two pings before a flush is dropped.
// The counts are exact while every event stays within `history` numbers of the newest ping:
//   received pings = pings + duplicates + late + unconfirmed (+ before_header), and after
//   flush() pings + lost + late = the numbers spanned, last - first + 1, per sequence.
// reordered counts pings handed over that arrived after a higher-numbered one.
//
// Malformed datagrams (classify_datagram kInvalid, a header or ping that does not decode, a
// sonar ping whose channels do not match the header) are counted and dropped, never a crash.
// Limits: XTF carries no checksum, so corruption that keeps the packet's structure intact (a
// flipped bit in the samples, or in PingNumber) cannot be detected here.
//
// Allocation: none per datagram once warmed up. The W slots hold decoded pings whose sample
// buffers are reused (a ping is decoded into a scratch ping and swapped into its slot); the
// history is a fixed ring. Exceptions (malformed input only) are the error path.
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "drivers/xtf/xtf_types.h"

namespace sonarloop::atr {

// Default reorder window: 32 pings, about 2 s of the default sonar (15 pings/s).
inline constexpr int kDefaultReorderWindow = 32;
// Ping numbers remembered behind the window, to tell duplicates from late pings.
inline constexpr int kDefaultSequenceHistory = 4096;
// A jump forward of more ping numbers than this starts a new sequence (about 11 min at 15
// pings/s).
inline constexpr std::uint32_t kDefaultMaxPingGap = 10000;
// Pings that must follow a jump, each within the reorder window of it, before it is acted on.
inline constexpr int kJumpConfirmations = 2;

struct ReceiverOptions {
  int reorder_window = kDefaultReorderWindow;  // W >= 1 slots
  int history = kDefaultSequenceHistory;       // >= W
  std::uint32_t max_gap = kDefaultMaxPingGap;  // >= W
};

struct ReceiverStats {
  std::uint64_t datagrams = 0;       // everything fed
  std::uint64_t bytes = 0;           // their total size
  std::uint64_t file_headers = 0;    // file header datagrams (valid)
  std::uint64_t header_changes = 0;  // headers that differed from the current one
  std::uint64_t pings = 0;           // pings handed over, in order
  std::uint64_t lost = 0;            // ping numbers never received (gaps)
  std::uint64_t late = 0;            // received after being given up as lost; dropped
  std::uint64_t duplicates = 0;      // second copies; dropped
  std::uint64_t reordered = 0;       // handed over, but arrived after a higher number
  std::uint64_t malformed = 0;       // undecodable datagrams; dropped
  std::uint64_t before_header = 0;   // pings before any file header; dropped
  std::uint64_t other_packets = 0;   // valid XTF packets that are not sonar pings; ignored
  std::uint64_t restarts = 0;        // new sequences (jumps beyond max_gap)
  std::uint64_t unconfirmed = 0;     // jumps no following ping confirmed (junk); dropped
};

// What feed() made of a datagram.
enum class DatagramOutcome {
  kFileHeader,
  kPing,  // accepted (buffered or handed over)
  kDuplicate,
  kLate,
  kMalformed,
  kBeforeHeader,
  kOther,
};

class StreamReceiver {
 public:
  // Called for each ping in order, with the file header it was decoded with. The ping is only
  // valid during the call.
  using PingSink = std::function<void(const xtf::XtfFileHeader&, const xtf::XtfPing&)>;

  // Throws std::invalid_argument for options out of range.
  StreamReceiver(const ReceiverOptions& options, PingSink sink);

  DatagramOutcome feed(std::span<const std::uint8_t> datagram);
  // Hands over every buffered ping, counting the numbers missing between them as lost.
  void flush();

  const ReceiverStats& stats() const { return stats_; }
  bool has_header() const { return has_header_; }
  const xtf::XtfFileHeader& header() const { return header_; }
  // Pings waiting in the reorder buffer.
  int buffered() const { return buffered_; }

 private:
  enum class Seen : std::uint8_t { kNone, kDelivered, kLost, kLate };
  struct Slot {
    bool used = false;
    std::uint32_t number = 0;
    xtf::XtfPing ping;
  };
  struct HistoryEntry {
    std::uint32_t number = 0;
    Seen seen = Seen::kNone;
  };

  DatagramOutcome on_header(std::span<const std::uint8_t> datagram);
  DatagramOutcome on_ping(std::span<const std::uint8_t> datagram);
  // scratch_ holds the decoded ping in place() .. accept(). confirmed: a jump is acted on.
  DatagramOutcome place(std::uint32_t number, bool confirmed);
  bool is_jump(std::uint32_t number) const;
  void hold(std::uint32_t number);                // scratch_ -> the next held slot
  void drop_held();                               // counted as unconfirmed
  DatagramOutcome restart(std::uint32_t number);  // scratch_ holds the decoded ping
  void accept(std::uint32_t number);              // scratch_ holds the decoded ping
  void release_next();  // hands over or gives up number next_, then next_ + 1
  void deliver_ready();
  void remember(std::uint32_t number, Seen seen);
  HistoryEntry* find_history(std::uint32_t number);
  void reset_sequence();

  ReceiverOptions options_;
  PingSink sink_;
  ReceiverStats stats_;
  bool has_header_ = false;
  xtf::XtfFileHeader header_;
  std::vector<std::uint8_t> header_bytes_;  // the current header as received
  xtf::XtfPing scratch_;
  xtf::XtfPing stash_;                         // the confirming ping while the held ones are placed
  std::array<Slot, kJumpConfirmations> held_;  // a jump awaiting confirmation, in arrival order
  int n_held_ = 0;
  std::vector<Slot> slots_;  // (W) indexed by number mod W
  std::vector<HistoryEntry> history_;
  int buffered_ = 0;
  bool started_ = false;
  std::uint32_t next_ = 0;      // next number to hand over
  std::uint32_t max_seen_ = 0;  // highest number accepted in this sequence
};

}  // namespace sonarloop::atr
