#include "drivers/xtf/xtf_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

#include "drivers/io/input_file.h"
#include "drivers/io/line_file.h"
#include "drivers/net/unique_fd.h"

namespace sonarloop::xtf {

// ---------------------------------------------------------------------------------------------
// XtfReader

void XtfReader::fail(const std::string& what, std::uint64_t offset) {
  failed_ = true;
  throw XtfFormatError("'" + path_ + "': " + what, offset);
}

void XtfReader::read_exact(std::uint8_t* dst, std::size_t n, std::uint64_t at) {
  if (std::fread(dst, 1, n, file_.get()) != n) {
    const bool eof = std::feof(file_.get()) != 0;
    fail(std::string(eof ? "file ended" : "read error") + " while reading " + std::to_string(n) +
             " bytes at byte offset " + std::to_string(at) +
             (eof ? " (the file shrank while being read?)" : ""),
         at);
  }
}

XtfReader::XtfReader(const std::string& path) : path_(path) {
  const std::uint64_t size = io::check_input_file(path, "XTF file");
  file_.reset(std::fopen(path.c_str(), "rb"));
  if (!file_) {
    throw std::runtime_error("cannot open XTF file '" + path + "': " + std::strerror(errno));
  }
  file_size_ = size;

  // the first 1024 bytes say how long the whole header is (> 6 channels: extra 1024 B blocks)
  if (file_size_ < kFileHeaderSize) {
    fail("truncated file header: the file has " + std::to_string(file_size_) +
             " bytes, an XTF file header needs " + std::to_string(kFileHeaderSize),
         file_size_);
  }
  header_bytes_.resize(kFileHeaderSize);
  read_exact(header_bytes_.data(), kFileHeaderSize, 0);
  std::size_t header_size = 0;
  try {
    header_size = declared_file_header_size(header_bytes_);
  } catch (const XtfFormatError& e) {
    fail(e.what(), e.offset());
  }
  if (header_size > file_size_) {
    fail("truncated file header: it declares more than 6 channels and so is " +
             std::to_string(header_size) + " bytes long (1024 + 1024 per 8 further channels), " +
             "the file has " + std::to_string(file_size_) + " bytes",
         file_size_);
  }
  header_bytes_.resize(header_size);
  if (header_size > kFileHeaderSize) {
    read_exact(header_bytes_.data() + kFileHeaderSize, header_size - kFileHeaderSize,
               kFileHeaderSize);
  }
  try {
    header_ = decode_file_header(header_bytes_);
  } catch (const XtfFormatError& e) {
    fail(e.what(), e.offset());
  }
  offset_ = header_size;
}

bool XtfReader::next_raw(XtfRawPacket& packet) {
  if (failed_) fail("cannot read on after an earlier error", offset_);
  if (offset_ == file_size_) return false;
  const std::uint64_t at = offset_;
  const std::uint64_t remaining = file_size_ - at;
  const std::string where = "packet at byte offset " + std::to_string(at) + ": ";
  if (remaining < kPacketStartSize) {
    fail(where + "truncated packet start: only " + std::to_string(remaining) +
             " bytes left in the file, a packet start needs 14",
         at);
  }
  packet.bytes.resize(kPacketStartSize);
  read_exact(packet.bytes.data(), kPacketStartSize, at);
  const PacketInfo info = *peek_packet(packet.bytes);
  if (!info.magic_ok) {
    char magic[8];
    std::snprintf(magic, sizeof magic, "0x%02X%02X", packet.bytes[1], packet.bytes[0]);
    std::string hint;
    if (at == header_bytes_.size() && at > kFileHeaderSize) {
      hint = " (first packet after a file header extended to " + std::to_string(at) +
             " bytes for " + std::to_string(declared_channel_count(header_)) + " channels)";
    }
    fail(where + "bad magic " + magic + ", expected 0xFACE (bytes CE FA)" + hint, at);
  }
  const std::uint64_t record = info.num_bytes_this_record;
  if (record < kPacketStartSize) {
    fail(where + "NumBytesThisRecord " + std::to_string(record) +
             " is smaller than the 14-byte packet start",
         at);
  }
  if (info.header_type == kHeaderTypeSonar && record < kPingHeaderSize) {
    fail(where + "NumBytesThisRecord " + std::to_string(record) +
             " of a sonar ping is smaller than the 256-byte ping header",
         at);
  }
  if (record > remaining) {
    fail(where + "NumBytesThisRecord " + std::to_string(record) +
             " runs past the end of the file (" + std::to_string(remaining) + " bytes left)",
         at);
  }
  packet.record_bytes = record;
  packet.skipped = record > skip_larger_than_;
  if (packet.skipped) {
    // not read: its start only, then past it
    if (std::fseek(file_.get(), static_cast<long>(at + record), SEEK_SET) != 0) {
      fail(where + "cannot seek past its " + std::to_string(record) + " bytes", at);
    }
  } else {
    if (record > kMaxXtfRecordBytes) {
      fail(where + "NumBytesThisRecord " + std::to_string(record) + " is more than the " +
               std::to_string(kMaxXtfRecordBytes >> 20) +
               " MB a packet may be here (a corrupt file?)",
           at);
    }
    packet.bytes.resize(static_cast<std::size_t>(record));
    read_exact(packet.bytes.data() + kPacketStartSize,
               static_cast<std::size_t>(record) - kPacketStartSize, at + kPacketStartSize);
  }
  packet.offset = at;
  packet.header_type = info.header_type;
  offset_ = at + record;
  ++stats_.packets;
  ++stats_.packets_by_type[info.header_type];
  if (info.header_type == kHeaderTypeSonar) {
    ++stats_.sonar_pings;
  } else {
    ++stats_.other_packets;
  }
  return true;
}

bool XtfReader::next(XtfRecord& record) {
  if (!next_raw(record.packet)) return false;
  // a skipped packet is not decoded
  record.is_ping = record.packet.header_type == kHeaderTypeSonar && !record.packet.skipped;
  if (record.is_ping) {
    const std::uint64_t at = record.packet.offset;
    try {
      decode_ping(record.packet.bytes, header_, record.ping);
    } catch (const XtfFormatError& e) {
      fail("sonar packet at byte offset " + std::to_string(at) + ": " + e.what() +
               " (byte offset " + std::to_string(at + e.offset()) + " in the file)",
           at + e.offset());
    }
  }
  return true;
}

XtfFileContents read_all_pings(const std::string& path) {
  XtfReader reader(path);
  XtfFileContents contents;
  contents.header = reader.file_header();
  XtfRecord record;
  while (reader.next(record)) {
    if (record.is_ping) contents.pings.push_back(record.ping);
  }
  contents.stats = reader.stats();
  return contents;
}

XtfRawFile read_raw_packets(const std::string& path) {
  XtfReader reader(path);
  XtfRawFile raw;
  raw.file_header = reader.file_header_bytes();
  XtfRawPacket packet;
  while (reader.next_raw(packet))
    raw.packets.push_back(packet);
  return raw;
}

// ---------------------------------------------------------------------------------------------
// XtfWriter

void XtfWriter::fail(const std::string& what, int err) {
  throw std::runtime_error("XTF file '" + path_ + "': " + what +
                           (err ? std::string(": ") + net::errno_text(err) : std::string()));
}

XtfWriter::XtfWriter(const std::string& path, const XtfFileHeader& header, XtfWriterOptions options)
    : path_(path), header_(header), options_(options) {
  // encode first: a bad header must not truncate an existing file
  const std::vector<std::uint8_t> bytes = encode_file_header(header_);
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) fail("cannot create", errno);
  append(bytes);
}

XtfWriter::~XtfWriter() {
  try {
    close();
  } catch (...) {
    // destructors do not throw; close() explicitly to see the error
  }
}

void XtfWriter::append(std::span<const std::uint8_t> bytes) {
  if (fd_ < 0) fail("write after close", 0);
  // at the end of the whole packets written so far; on failure cut the file back there
  if (const int err = io::append_whole(fd_, bytes_written_, bytes.data(), bytes.size())) {
    fail("write of " + std::to_string(bytes.size()) + " bytes at byte offset " +
             std::to_string(bytes_written_) + " failed (file cut back to whole packets)",
         err);
  }
  bytes_written_ += bytes.size();
}

void XtfWriter::write_ping(const XtfPing& ping) {
  const std::size_t size = encoded_ping_size(ping);
  if (buffer_.size() < size) buffer_.resize(size);
  const auto packet = std::span(buffer_).first(size);
  encode_ping(ping, header_, packet);
  append(packet);
  ++packets_written_;
  if (options_.sync_every_packets != 0 && packets_written_ % options_.sync_every_packets == 0) {
    flush();
  }
}

void XtfWriter::write_packet(std::span<const std::uint8_t> packet) {
  const auto info = peek_packet(packet);
  if (!info || !info->magic_ok || info->num_bytes_this_record != packet.size()) {
    throw std::invalid_argument(
        "XtfWriter::write_packet: not a whole XTF packet (magic CE FA and NumBytesThisRecord == " +
        std::to_string(packet.size()) + " bytes given)");
  }
  append(packet);
  ++packets_written_;
  if (options_.sync_every_packets != 0 && packets_written_ % options_.sync_every_packets == 0) {
    flush();
  }
}

void XtfWriter::flush() {
  if (fd_ < 0) fail("flush after close", 0);
  if (::fdatasync(fd_) != 0) fail("fdatasync failed", errno);
}

void XtfWriter::close() {
  if (fd_ < 0) return;
  const int fd = fd_;
  fd_ = -1;
  const int sync_rc = ::fdatasync(fd);
  const int sync_err = errno;
  if (::close(fd) != 0) fail("close failed", errno);
  if (sync_rc != 0) fail("fdatasync failed", sync_err);
}

}  // namespace sonarloop::xtf
