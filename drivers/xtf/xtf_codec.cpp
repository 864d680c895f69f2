// The file header (encode, decode, declared size) and the packet start every packet shares
// (peek_packet, classify_datagram). The sonar ping packets are in xtf_ping_encode.cpp and
// xtf_ping_decode.cpp; the byte layouts in xtf_fields.h.
#include "drivers/xtf/xtf_codec.h"

#include <algorithm>

#include "drivers/xtf/xtf_fields.h"

namespace sonarloop::xtf {

// the byte layouts (xtf_fields.h)
using wire::all_zero;
using wire::chan_info_fields;
using wire::FieldReader;
using wire::FieldWriter;
using wire::file_header_fields;
using wire::get_le;
using wire::hex;

// ---------------------------------------------------------------------------------------------
// file header

std::vector<std::uint8_t> encode_file_header(const XtfFileHeader& header) {
  if (header.file_format != kFileFormat) {
    throw std::invalid_argument("XTF file header: FileFormat must be 0x7B, got " +
                                hex(header.file_format, 2));
  }
  const std::size_t declared = declared_channel_count(header);
  const std::size_t slots = std::max(declared, kChanInfosInBaseHeader);
  if (header.chan_info.size() < declared) {
    throw std::invalid_argument("XTF file header declares " + std::to_string(declared) +
                                " channels but chan_info has only " +
                                std::to_string(header.chan_info.size()) + " entries");
  }
  if (header.chan_info.size() > slots) {
    throw std::invalid_argument("XTF file header: chan_info has " +
                                std::to_string(header.chan_info.size()) +
                                " entries but a header declaring " + std::to_string(declared) +
                                " channels holds at most " + std::to_string(slots));
  }
  std::vector<std::uint8_t> bytes(file_header_size_for(declared), 0);
  FieldWriter w(bytes);
  file_header_fields(w, header);
  for (std::size_t i = 0; i < header.chan_info.size(); ++i) {
    FieldWriter cw{std::span(bytes).subspan(kChanInfoOffset + kChanInfoSize * i, kChanInfoSize)};
    chan_info_fields(cw, header.chan_info[i]);
  }
  return bytes;
}

std::size_t declared_file_header_size(std::span<const std::uint8_t> first_bytes) {
  if (first_bytes.size() < kFileHeaderSize) {
    throw XtfFormatError("XTF file header truncated: " + std::to_string(first_bytes.size()) +
                             " bytes, it needs " + std::to_string(kFileHeaderSize),
                         first_bytes.size());
  }
  if (first_bytes[0] != kFileFormat) {
    throw XtfFormatError(
        "not an XTF file header: FileFormat byte is " + hex(first_bytes[0], 2) + " (expected 0x7B)",
        0);
  }
  XtfFileHeader counts;
  FieldReader r(first_bytes);
  file_header_fields(r, counts);
  return file_header_size_for(declared_channel_count(counts));
}

XtfFileHeader decode_file_header(std::span<const std::uint8_t> bytes) {
  const std::size_t size = declared_file_header_size(bytes);
  XtfFileHeader h;
  FieldReader r(bytes);
  file_header_fields(r, h);
  const std::size_t declared = declared_channel_count(h);
  if (bytes.size() < size) {
    throw XtfFormatError("XTF file header declares " + std::to_string(declared) +
                             " channels and so is " + std::to_string(size) + " bytes long, only " +
                             std::to_string(bytes.size()) + " bytes given",
                         bytes.size());
  }
  // keep every declared channel, plus non-empty slots of the base block (byte-exact re-encoding)
  std::size_t count = declared;
  for (std::size_t i = kChanInfosInBaseHeader; i > declared; --i) {
    if (!all_zero(bytes.subspan(kChanInfoOffset + kChanInfoSize * (i - 1), kChanInfoSize))) {
      count = i;
      break;
    }
  }
  h.chan_info.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    FieldReader cr(bytes.subspan(kChanInfoOffset + kChanInfoSize * i, kChanInfoSize));
    chan_info_fields(cr, h.chan_info[i]);
  }
  return h;
}

// ---------------------------------------------------------------------------------------------
// packets

std::optional<PacketInfo> peek_packet(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < kPacketStartSize) return std::nullopt;
  PacketInfo info;
  info.magic_ok = get_le<std::uint16_t>(bytes, 0) == kMagicNumber;
  info.header_type = bytes[2];
  info.sub_channel_number = bytes[3];
  info.num_chans_to_follow = get_le<std::uint16_t>(bytes, 4);
  info.num_bytes_this_record = get_le<std::uint32_t>(bytes, 10);
  return info;
}

DatagramKind classify_datagram(std::span<const std::uint8_t> datagram) {
  if (datagram.size() >= kFileHeaderSize && datagram[0] == kFileFormat &&
      declared_file_header_size(datagram) == datagram.size()) {
    return DatagramKind::kFileHeader;
  }
  const auto info = peek_packet(datagram);
  if (info && info->valid() && info->num_bytes_this_record == datagram.size()) {
    return DatagramKind::kPacket;
  }
  return DatagramKind::kInvalid;
}

}  // namespace sonarloop::xtf
