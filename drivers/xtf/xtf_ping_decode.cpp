// Decoding sonar ping packets (HeaderType 0, docs/formats.md 1.7), into reused buffers. Every
// malformed byte is an XtfFormatError naming its byte offset within the packet: the packet start
// (magic, HeaderType, NumBytesThisRecord, NumChansToFollow), then each channel's header and its
// samples against the file header's CHANINFO. The byte layouts are in xtf_fields.h.
#include <variant>

#include "drivers/xtf/xtf_codec.h"
#include "drivers/xtf/xtf_fields.h"

namespace sonarloop::xtf {

// the byte layouts (xtf_fields.h)
using wire::FieldReader;
using wire::get_le;
using wire::hex;
using wire::kBadSampleType;
using wire::kNumSamplesOffset;
using wire::ping_chan_fields;
using wire::ping_header_fields;
using wire::sample_type_index;

XtfPing decode_ping(std::span<const std::uint8_t> packet, const XtfFileHeader& header) {
  XtfPing ping;
  decode_ping(packet, header, ping);
  return ping;
}

namespace {

template <class T>
void read_samples(std::span<const std::uint8_t> b, std::size_t pos, std::size_t n,
                  XtfSamples& samples) {
  if (!std::holds_alternative<std::vector<T>>(samples)) samples = std::vector<T>{};
  auto& v = std::get<std::vector<T>>(samples);
  v.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    v[i] = get_le<T>(b, pos + i * sizeof(T));
}

// Checks the packet start against the bytes given and the file header, and returns it. Throws
// XtfFormatError at the offending field's offset.
PacketInfo check_packet_start(std::span<const std::uint8_t> packet, const XtfFileHeader& header) {
  if (packet.size() < kPingHeaderSize) {
    throw XtfFormatError("XTF sonar packet truncated: " + std::to_string(packet.size()) +
                             " bytes, the ping header alone needs 256",
                         packet.size());
  }
  const PacketInfo info = *peek_packet(packet);
  if (!info.magic_ok) {
    throw XtfFormatError(
        "bad magic " + hex(get_le<std::uint16_t>(packet, 0), 4) + " (expected 0xFACE, bytes CE FA)",
        0);
  }
  if (info.header_type != kHeaderTypeSonar) {
    throw XtfFormatError(
        "HeaderType " + std::to_string(info.header_type) + " is not a sonar ping (0)", 2);
  }
  const std::size_t record = info.num_bytes_this_record;
  if (record < kPingHeaderSize) {
    throw XtfFormatError("NumBytesThisRecord " + std::to_string(record) +
                             " is smaller than the 256-byte ping header",
                         10);
  }
  if (record > packet.size()) {
    throw XtfFormatError("NumBytesThisRecord " + std::to_string(record) + " exceeds the " +
                             std::to_string(packet.size()) + " bytes available",
                         10);
  }
  const std::size_t declared = declared_channel_count(header);
  if (info.num_chans_to_follow > declared) {
    throw XtfFormatError("NumChansToFollow " + std::to_string(info.num_chans_to_follow) +
                             " exceeds the " + std::to_string(declared) +
                             " channels the file header declares",
                         4);
  }
  return info;
}

// Decodes channel k, whose header starts at `pos` of the record b, into c; returns the offset
// after its samples. Throws XtfFormatError at the channel header's offset.
std::size_t decode_channel(std::span<const std::uint8_t> b, std::size_t k, std::size_t pos,
                           const XtfFileHeader& header, XtfPingChannel& c) {
  const std::size_t record = b.size();
  const auto ch = b.subspan(pos, kPingChanHeaderSize);
  FieldReader cr(ch);
  ping_chan_fields(cr, c);
  if (c.channel_number >= header.chan_info.size()) {
    throw XtfFormatError("channel " + std::to_string(k) + " has ChannelNumber " +
                             std::to_string(c.channel_number) + " but the file header has only " +
                             std::to_string(header.chan_info.size()) + " CHANINFO entries",
                         pos);
  }
  const XtfChanInfo& ci = header.chan_info[c.channel_number];
  const std::size_t type = sample_type_index(ci);
  if (type == kBadSampleType) {
    throw XtfFormatError("CHANINFO " + std::to_string(c.channel_number) + " gives BytesPerSample " +
                             std::to_string(ci.bytes_per_sample) + " (1, 2 or 4 allowed)",
                         pos);
  }
  std::uint64_t n = get_le<std::uint32_t>(ch, kNumSamplesOffset);
  c.num_samples_from_chan_info = n == 0 && ci.reserved_samples_per_channel > 0;
  if (c.num_samples_from_chan_info) n = ci.reserved_samples_per_channel;
  pos += kPingChanHeaderSize;
  const std::uint64_t data_bytes = n * ci.bytes_per_sample;
  if (pos + data_bytes > record) {
    throw XtfFormatError("channel " + std::to_string(k) + " (ChannelNumber " +
                             std::to_string(c.channel_number) + "): " + std::to_string(n) +
                             " samples x " + std::to_string(ci.bytes_per_sample) +
                             " bytes at packet offset " + std::to_string(pos) +
                             " run past NumBytesThisRecord " + std::to_string(record),
                         pos);
  }
  const auto count = static_cast<std::size_t>(n);
  switch (type) {
    case 0:
      read_samples<std::uint8_t>(b, pos, count, c.samples);
      break;
    case 1:
      read_samples<std::uint16_t>(b, pos, count, c.samples);
      break;
    case 2:
      read_samples<std::uint32_t>(b, pos, count, c.samples);
      break;
    default:
      read_samples<float>(b, pos, count, c.samples);
      break;
  }
  return pos + static_cast<std::size_t>(data_bytes);
}

}  // namespace

void decode_ping(std::span<const std::uint8_t> packet, const XtfFileHeader& header, XtfPing& out) {
  const PacketInfo info = check_packet_start(packet, header);
  const std::size_t record = info.num_bytes_this_record;
  const auto b = packet.first(record);
  FieldReader hr(b.first(kPingHeaderSize));
  ping_header_fields(hr, out.header);

  out.channels.resize(info.num_chans_to_follow);
  std::size_t pos = kPingHeaderSize;
  for (std::size_t k = 0; k < out.channels.size(); ++k) {
    if (pos + kPingChanHeaderSize > record) {
      throw XtfFormatError("channel " + std::to_string(k) + " header at packet offset " +
                               std::to_string(pos) + " runs past NumBytesThisRecord " +
                               std::to_string(record),
                           pos);
    }
    pos = decode_channel(b, k, pos, header, out.channels[k]);
  }
}

}  // namespace sonarloop::xtf
