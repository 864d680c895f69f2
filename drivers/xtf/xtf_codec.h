#pragma once
// Pure XTF encode/decode: plain structs (xtf_types.h) <-> bytes. No files, no sockets.
//
// Wire rules (docs/formats.md 1.1): little-endian, packed, every field written one by one (no
// memcpy of structs, so host endianness and alignment do not matter). A file is the XTFFILEHEADER
// (1024 bytes for <= 6 channels) followed by packets; each packet starts with the magic 0xFACE
// (bytes CE FA) and its own total length NumBytesThisRecord.
//
// A sonar packet as encoded here (docs/formats.md 1.7), e.g. 2 channels x 1024 uint16 samples:
//   [0, 256)      XTFPINGHEADER: CE FA | 00 (HeaderType sonar) | SubChannel | 02 00 (channels)
//                 | Reserved1 | 80 11 00 00 (NumBytesThisRecord 4480) | Year ... (1.5)
//   [256, 320)    XTFPINGCHANHEADER of ChannelNumber 0 (port) ... NumSamples 1024 at +42
//   [320, 2368)   1024 port samples, little-endian, far range first
//   [2368, 2432)  XTFPINGCHANHEADER of ChannelNumber 1 (stbd)
//   [2432, 4480)  1024 starboard samples, nadir first
//   then zero padding up to a multiple of 64 bytes (none here: 4480 = 70 x 64);
//   NumBytesThisRecord = the padded size.
//
// Errors: malformed bytes throw XtfFormatError carrying the byte offset (relative to the start of
// the span that was given); inconsistent structs given to an encoder throw std::invalid_argument.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "drivers/xtf/xtf_types.h"

namespace sonarloop::xtf {

// Malformed XTF bytes. offset() is the byte offset of the problem: within the span given to a
// codec function, or within the file for XtfReader.
class XtfFormatError : public std::runtime_error {
 public:
  XtfFormatError(const std::string& message, std::uint64_t offset)
      : std::runtime_error(message), offset_(offset) {}
  std::uint64_t offset() const { return offset_; }

 private:
  std::uint64_t offset_;
};

// ---- file header ----

// Encodes the file header (zero-filled, strings NUL-padded, ChanInfo[i] at 256 + 128 i). Throws
// std::invalid_argument if a string is longer than its field, if file_format is not 0x7B, or if
// chan_info has fewer entries than the channel counts declare or more than fit (more than
// max(declared, 6)).
std::vector<std::uint8_t> encode_file_header(const XtfFileHeader& header);
// Header size a file declares, from its first 1024 bytes (1024, or more for > 6 channels).
// Throws XtfFormatError if fewer than 1024 bytes are given or byte 0 is not 0x7B.
std::size_t declared_file_header_size(std::span<const std::uint8_t> first_bytes);
// Decodes a file header; `bytes` must hold at least declared_file_header_size() bytes (extra
// bytes are ignored). Char fields end at their first NUL.
XtfFileHeader decode_file_header(std::span<const std::uint8_t> bytes);

// ---- any packet ----

// The 14-byte packet start (docs/formats.md 1.4) of a packet or datagram.
struct PacketInfo {
  bool magic_ok = false;  // bytes 0-1 are CE FA
  std::uint8_t header_type = 0;
  std::uint8_t sub_channel_number = 0;
  std::uint16_t num_chans_to_follow = 0;
  std::uint32_t num_bytes_this_record = 0;
  // the magic is right and the record is at least as long as the packet start
  bool valid() const { return magic_ok && num_bytes_this_record >= kPacketStartSize; }
};
// Reads the packet start without validating; nullopt if fewer than 14 bytes are given.
std::optional<PacketInfo> peek_packet(std::span<const std::uint8_t> bytes);

// What a received datagram holds (docs/formats.md 1.11: one XTF packet or the file header per
// datagram).
enum class DatagramKind {
  kFileHeader,  // byte 0 is 0x7B and the size equals the header size it declares (1024)
  kPacket,      // starts CE FA and NumBytesThisRecord equals the datagram size
  kInvalid,     // anything else (too short, wrong magic, size mismatch)
};
DatagramKind classify_datagram(std::span<const std::uint8_t> datagram);

// ---- sonar ping packets ----

// Size of the encoded packet: 256 + sum(64 + samples x bytes) rounded up to a multiple of 64.
std::size_t encoded_ping_size(const XtfPing& ping);
// Encodes a sonar packet into out[0, encoded_ping_size) and returns that size; does not
// allocate. Checks the ping against the file header: every channel's ChannelNumber must have a
// CHANINFO whose BytesPerSample (and float SampleFormat) matches the channel's sample type, and
// there may not be more channels than the header declares. Throws std::invalid_argument on a
// mismatch or if `out` is too small.
std::size_t encode_ping(const XtfPing& ping, const XtfFileHeader& header,
                        std::span<std::uint8_t> out);
std::vector<std::uint8_t> encode_ping(const XtfPing& ping, const XtfFileHeader& header);

// Decodes a sonar packet (HeaderType 0). Reads NumBytesThisRecord bytes; `packet` may be longer.
// Each channel's sample type comes from ChanInfo[ChannelNumber]. Throws XtfFormatError (offset
// within `packet`) on: fewer than 256 bytes, bad magic, another HeaderType, NumBytesThisRecord
// smaller than the ping header or larger than `packet`, more channels than the file header
// declares, a ChannelNumber without CHANINFO, BytesPerSample not 1/2/4, or channel data
// running past NumBytesThisRecord. Padding bytes are not checked.
XtfPing decode_ping(std::span<const std::uint8_t> packet, const XtfFileHeader& header);
// Same, into an existing XtfPing whose buffers are reused (no allocation once they are large
// enough: for a receiver decoding every datagram).
void decode_ping(std::span<const std::uint8_t> packet, const XtfFileHeader& header, XtfPing& out);

}  // namespace sonarloop::xtf
