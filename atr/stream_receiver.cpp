#include "atr/stream_receiver.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "drivers/xtf/xtf_codec.h"

namespace sonarloop::atr {

StreamReceiver::StreamReceiver(const ReceiverOptions& options, PingSink sink)
    : options_(options), sink_(std::move(sink)) {
  if (options_.reorder_window < 1 || options_.reorder_window > 65536) {
    throw std::invalid_argument("reorder window " + std::to_string(options_.reorder_window) +
                                " pings is outside 1..65536");
  }
  if (options_.history < options_.reorder_window || options_.history > (1 << 24)) {
    throw std::invalid_argument("sequence history " + std::to_string(options_.history) +
                                " must be at least the reorder window (" +
                                std::to_string(options_.reorder_window) + ") and at most 2^24");
  }
  if (options_.max_gap < static_cast<std::uint32_t>(options_.reorder_window) ||
      options_.max_gap > (1u << 30)) {
    throw std::invalid_argument("max ping gap " + std::to_string(options_.max_gap) +
                                " must be at least the reorder window and at most 2^30");
  }
  slots_.resize(static_cast<std::size_t>(options_.reorder_window));
  history_.resize(static_cast<std::size_t>(options_.history));
}

DatagramOutcome StreamReceiver::feed(std::span<const std::uint8_t> datagram) {
  ++stats_.datagrams;
  stats_.bytes += datagram.size();
  switch (xtf::classify_datagram(datagram)) {
    case xtf::DatagramKind::kFileHeader:
      return on_header(datagram);
    case xtf::DatagramKind::kPacket:
      return on_ping(datagram);
    case xtf::DatagramKind::kInvalid:
      break;
  }
  ++stats_.malformed;
  return DatagramOutcome::kMalformed;
}

DatagramOutcome StreamReceiver::on_header(std::span<const std::uint8_t> datagram) {
  if (has_header_ &&
      std::equal(datagram.begin(), datagram.end(), header_bytes_.begin(), header_bytes_.end())) {
    ++stats_.file_headers;
    return DatagramOutcome::kFileHeader;
  }
  xtf::XtfFileHeader decoded;
  try {
    decoded = xtf::decode_file_header(datagram);
  } catch (const std::exception&) {
    ++stats_.malformed;
    return DatagramOutcome::kMalformed;
  }
  ++stats_.file_headers;
  if (has_header_) {
    // the buffered pings were decoded with the old header: hand them over first
    ++stats_.header_changes;
    flush();
  }
  header_ = std::move(decoded);
  header_bytes_.assign(datagram.begin(), datagram.end());
  has_header_ = true;
  return DatagramOutcome::kFileHeader;
}

DatagramOutcome StreamReceiver::on_ping(std::span<const std::uint8_t> datagram) {
  const auto info = xtf::peek_packet(datagram);
  if (!info || info->header_type != xtf::kHeaderTypeSonar) {
    ++stats_.other_packets;
    return DatagramOutcome::kOther;
  }
  if (!has_header_) {
    ++stats_.before_header;
    return DatagramOutcome::kBeforeHeader;
  }
  try {
    xtf::decode_ping(datagram, header_, scratch_);
  } catch (const std::exception&) {
    ++stats_.malformed;
    return DatagramOutcome::kMalformed;
  }
  const std::uint32_t number = scratch_.header.ping_number;
  if (!started_) {
    started_ = true;
    next_ = number;
    max_seen_ = number;
  }
  if (n_held_ > 0) {
    const auto dc = static_cast<std::int32_t>(number - held_[0].number);
    const bool fits = dc != 0 && dc >= -options_.reorder_window && dc <= options_.reorder_window;
    for (int i = 0; i < n_held_; ++i) {
      if (held_[static_cast<std::size_t>(i)].number == number) {
        ++stats_.duplicates;
        return DatagramOutcome::kDuplicate;
      }
    }
    if (fits && n_held_ < kJumpConfirmations) {
      hold(number);
      return DatagramOutcome::kPing;
    }
    if (fits) {
      // confirmed: the held pings in arrival order, then this one
      std::swap(scratch_, stash_);
      const int n = n_held_;
      n_held_ = 0;
      for (int i = 0; i < n; ++i) {
        Slot& h = held_[static_cast<std::size_t>(i)];
        std::swap(scratch_, h.ping);
        place(h.number, true);
      }
      std::swap(scratch_, stash_);
      return place(number, true);
    }
  }
  return place(number, false);
}

bool StreamReceiver::is_jump(std::uint32_t number) const {
  const auto d = static_cast<std::int64_t>(static_cast<std::int32_t>(number - next_));
  if (d >= options_.reorder_window) return true;  // gives up numbers, or restarts
  if (d >= 0 || -d <= options_.reorder_window) return false;
  // far behind: a restart unless it is a number this sequence has seen (duplicate or late)
  const HistoryEntry& h = history_[number % history_.size()];
  return h.seen == Seen::kNone || h.number != number;
}

void StreamReceiver::hold(std::uint32_t number) {
  Slot& h = held_[static_cast<std::size_t>(n_held_++)];
  h.used = true;
  h.number = number;
  std::swap(h.ping, scratch_);
}

void StreamReceiver::drop_held() {
  stats_.unconfirmed += static_cast<std::uint64_t>(n_held_);
  n_held_ = 0;
}

DatagramOutcome StreamReceiver::place(std::uint32_t number, bool confirmed) {
  if (!confirmed && is_jump(number)) {
    // a jump waits for confirmation (see the header); one that did not come is dropped
    drop_held();
    hold(number);
    return DatagramOutcome::kPing;
  }
  // signed distance from the next expected number (ping numbers wrap modulo 2^32)
  const auto d = static_cast<std::int64_t>(static_cast<std::int32_t>(number - next_));
  if (d > static_cast<std::int64_t>(options_.max_gap)) return restart(number);
  if (d < 0) {
    HistoryEntry* h = find_history(number);
    if (h && h->seen == Seen::kLost) {
      h->seen = Seen::kLate;
      --stats_.lost;
      ++stats_.late;
      return DatagramOutcome::kLate;
    }
    if (h) {
      ++stats_.duplicates;
      return DatagramOutcome::kDuplicate;
    }
    // never seen: from before the sequence started (a window or less behind), else the sender
    // started again from a lower number
    if (-d > options_.reorder_window) return restart(number);
    ++stats_.late;
    return DatagramOutcome::kLate;
  }
  const Slot& slot = slots_[number % slots_.size()];
  if (d < options_.reorder_window && slot.used && slot.number == number) {
    ++stats_.duplicates;
    return DatagramOutcome::kDuplicate;
  }
  // the stream goes on where it was: a held jump was junk
  if (!confirmed) drop_held();
  // beyond the window: give up the oldest numbers until it fits
  while (static_cast<std::int32_t>(number - next_) >= options_.reorder_window)
    release_next();
  accept(number);
  return DatagramOutcome::kPing;
}

DatagramOutcome StreamReceiver::restart(std::uint32_t number) {
  flush();
  ++stats_.restarts;
  reset_sequence();
  next_ = number;
  max_seen_ = number;
  accept(number);
  return DatagramOutcome::kPing;
}

void StreamReceiver::accept(std::uint32_t number) {
  if (static_cast<std::int32_t>(number - max_seen_) < 0) {
    ++stats_.reordered;
  } else {
    max_seen_ = number;
  }
  Slot& slot = slots_[number % slots_.size()];
  slot.used = true;
  slot.number = number;
  std::swap(slot.ping, scratch_);  // no copy: the buffers trade places
  ++buffered_;
  deliver_ready();
}

void StreamReceiver::release_next() {
  Slot& slot = slots_[next_ % slots_.size()];
  if (slot.used && slot.number == next_) {
    slot.used = false;
    --buffered_;
    ++stats_.pings;
    remember(next_, Seen::kDelivered);
    if (sink_) sink_(header_, slot.ping);
  } else {
    ++stats_.lost;
    remember(next_, Seen::kLost);
  }
  ++next_;
}

void StreamReceiver::deliver_ready() {
  for (;;) {
    const Slot& slot = slots_[next_ % slots_.size()];
    if (!slot.used || slot.number != next_) return;
    release_next();
  }
}

void StreamReceiver::flush() {
  // an unconfirmed jump is dropped (see the header)
  drop_held();
  // give up numbers until the buffer is empty (only gaps between buffered pings count as lost)
  while (buffered_ > 0)
    release_next();
}

void StreamReceiver::remember(std::uint32_t number, Seen seen) {
  HistoryEntry& h = history_[number % history_.size()];
  h.number = number;
  h.seen = seen;
}

StreamReceiver::HistoryEntry* StreamReceiver::find_history(std::uint32_t number) {
  HistoryEntry& h = history_[number % history_.size()];
  return h.seen != Seen::kNone && h.number == number ? &h : nullptr;
}

void StreamReceiver::reset_sequence() {
  for (HistoryEntry& h : history_)
    h = HistoryEntry{};
  for (Slot& s : slots_)
    s.used = false;
  buffered_ = 0;
}

}  // namespace sonarloop::atr
