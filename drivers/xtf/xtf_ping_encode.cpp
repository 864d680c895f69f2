// Encoding sonar ping packets (HeaderType 0, docs/formats.md 1.7): the ping checked against the
// file header, then the ping header, each channel's header and its samples written into a caller's
// buffer without allocating (docs/style.md habit 2). The byte layouts are in xtf_fields.h.
#include <algorithm>
#include <limits>
#include <variant>

#include "drivers/xtf/xtf_codec.h"
#include "drivers/xtf/xtf_fields.h"

namespace sonarloop::xtf {

// the byte layouts (xtf_fields.h)
using wire::FieldWriter;
using wire::kNumSamplesOffset;
using wire::padded;
using wire::ping_chan_fields;
using wire::ping_header_fields;
using wire::put_le;
using wire::sample_type_index;
using wire::sample_type_name;

std::size_t encoded_ping_size(const XtfPing& ping) {
  std::size_t n = kPingHeaderSize;
  for (const auto& c : ping.channels)
    n += kPingChanHeaderSize + c.num_samples() * c.bytes_per_sample();
  return padded(n);
}

namespace {

// Throws std::invalid_argument unless every channel of `ping` fits the file header: no more
// channels than it declares, each with a CHANINFO whose sample type matches its samples.
void check_channels(const XtfPing& ping, const XtfFileHeader& header) {
  const std::size_t declared = declared_channel_count(header);
  if (ping.channels.size() > declared) {
    throw std::invalid_argument("XTF ping has " + std::to_string(ping.channels.size()) +
                                " channels but the file header declares " +
                                std::to_string(declared));
  }
  for (std::size_t k = 0; k < ping.channels.size(); ++k) {
    const auto& c = ping.channels[k];
    // built only on error: the happy path must not allocate
    const auto which = [&] {
      return "XTF ping channel " + std::to_string(k) + " (ChannelNumber " +
             std::to_string(c.channel_number) + ")";
    };
    if (c.channel_number >= header.chan_info.size()) {
      throw std::invalid_argument(which() + " has no CHANINFO: the file header has " +
                                  std::to_string(header.chan_info.size()));
    }
    const XtfChanInfo& info = header.chan_info[c.channel_number];
    const std::size_t want = sample_type_index(info);
    if (want != c.samples.index()) {
      throw std::invalid_argument(which() + " holds " + sample_type_name(c.samples.index()) +
                                  " samples but its CHANINFO has BytesPerSample " +
                                  std::to_string(info.bytes_per_sample) + ", SampleFormat " +
                                  std::to_string(info.sample_format) + " (" +
                                  sample_type_name(want) + ")");
    }
    if (c.num_samples() > std::numeric_limits<std::uint32_t>::max()) {
      throw std::invalid_argument(which() + " has too many samples for the DWORD NumSamples");
    }
    if (c.num_samples_from_chan_info && c.num_samples() != info.reserved_samples_per_channel) {
      throw std::invalid_argument(which() + " is marked num_samples_from_chan_info but holds " +
                                  std::to_string(c.num_samples()) + " samples, CHANINFO says " +
                                  std::to_string(info.reserved_samples_per_channel));
    }
  }
}

// Throws std::invalid_argument unless a packet of `total` bytes fits NumBytesThisRecord and `out`.
void check_packet_size(std::size_t total, std::span<const std::uint8_t> out) {
  if (total > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("XTF ping of " + std::to_string(total) +
                                " bytes does not fit the DWORD NumBytesThisRecord");
  }
  if (out.size() < total) {
    throw std::invalid_argument("XTF ping needs " + std::to_string(total) +
                                " bytes, the output buffer holds " + std::to_string(out.size()));
  }
}

// Writes the packet into b (exactly the packet's size, zero-filled here first).
void write_packet(const XtfPing& ping, std::span<std::uint8_t> b) {
  const std::size_t total = b.size();
  std::fill(b.begin(), b.end(), std::uint8_t{0});

  // packet start + ping header
  put_le(b, 0, kMagicNumber);
  put_le(b, 2, kHeaderTypeSonar);
  put_le(b, 4, static_cast<std::uint16_t>(ping.channels.size()));
  put_le(b, 10, static_cast<std::uint32_t>(total));
  FieldWriter hw(b.first(kPingHeaderSize));
  ping_header_fields(hw, ping.header);

  // channel blocks: header then samples, little-endian
  std::size_t pos = kPingHeaderSize;
  for (const auto& c : ping.channels) {
    auto ch = b.subspan(pos, kPingChanHeaderSize);
    FieldWriter cw(ch);
    ping_chan_fields(cw, c);
    const auto n = static_cast<std::uint32_t>(c.num_samples_from_chan_info ? 0 : c.num_samples());
    put_le(ch, kNumSamplesOffset, n);
    pos += kPingChanHeaderSize;
    std::visit(
        [&](const auto& v) {
          using T = typename std::decay_t<decltype(v)>::value_type;
          for (const T s : v) {
            put_le(b, pos, s);
            pos += sizeof(T);
          }
        },
        c.samples);
  }
  // bytes [pos, total) stay zero: padding to a multiple of 64
}

}  // namespace

std::size_t encode_ping(const XtfPing& ping, const XtfFileHeader& header,
                        std::span<std::uint8_t> out) {
  check_channels(ping, header);
  const std::size_t total = encoded_ping_size(ping);
  check_packet_size(total, out);
  write_packet(ping, out.first(total));
  return total;
}

std::vector<std::uint8_t> encode_ping(const XtfPing& ping, const XtfFileHeader& header) {
  std::vector<std::uint8_t> bytes(encoded_ping_size(ping));
  encode_ping(ping, header, bytes);
  return bytes;
}

}  // namespace sonarloop::xtf
