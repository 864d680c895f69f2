#pragma once
// XTF files: a sequential reader (file header, then packet by packet) and an appending writer.
//
// Reader: sonar pings (HeaderType 0) are decoded; every other packet type is returned raw (type +
// bytes), counted, and skipped by its NumBytesThisRecord. Every packet's raw bytes and offset are
// available, so a file can be replayed byte for byte (file header + packets == the file).
// Corrupt files throw XtfFormatError whose message names the file and the byte offset (also
// given by offset()): truncated file header, truncated packet start, bad magic, NumBytesThisRecord
// smaller than the packet start / ping header or running past the end of the file, channel data
// larger than the record, more channels than the file header declares. After an error the reader
// cannot go on.
//
// Writer: creates/truncates the file and writes the file header at once; each packet is then
// encoded into a reused buffer and handed to the kernel with write(2) (no user-space buffering),
// so once write_ping() returns the file holds only whole packets and is a valid XTF file even if
// the process stops right after (e.g. SIGINT handler -> close()). A failed write is rolled back
// with ftruncate to the last whole packet. fdatasync every N packets is optional (power loss).
#include <array>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "drivers/xtf/xtf_codec.h"
#include "drivers/xtf/xtf_types.h"

namespace sonarloop::xtf {

// One packet as stored in the file.
struct XtfRawPacket {
  std::uint64_t offset = 0;         // byte offset of the packet in the file
  std::uint8_t header_type = 0;     // HeaderType of its packet start
  std::vector<std::uint8_t> bytes;  // the whole record: NumBytesThisRecord bytes incl. padding
  std::uint64_t record_bytes = 0;   // NumBytesThisRecord
  // larger than XtfReader::skip_larger_than: not read (bytes: its 14-byte start only)
  bool skipped = false;
};

// The largest packet a reader reads (a corrupt length field must not make it allocate gigabytes):
// 64 MB, hundreds of times a real ping (two channels of 65,535 16-bit samples are 262 kB).
inline constexpr std::uint64_t kMaxXtfRecordBytes = std::uint64_t{64} << 20;

// What XtfReader::next() returns: the raw packet, and for a sonar ping its decoded form.
struct XtfRecord {
  XtfRawPacket packet;
  bool is_ping = false;  // HeaderType 0; `ping` is valid only then
  XtfPing ping;
};

// Counts of the packets read so far.
struct XtfReadStats {
  std::uint64_t packets = 0;
  std::uint64_t sonar_pings = 0;
  std::uint64_t other_packets = 0;                   // any HeaderType other than 0
  std::array<std::uint64_t, 256> packets_by_type{};  // indexed by HeaderType
};

class XtfReader {
 public:
  // Opens `path` and reads its file header (1024 bytes, or more for > 6 channels). Throws
  // std::runtime_error if the file cannot be opened, XtfFormatError if the header is bad.
  explicit XtfReader(const std::string& path);

  const XtfFileHeader& file_header() const { return header_; }
  // The file header exactly as stored (file_header_size_for(declared channels) bytes).
  const std::vector<std::uint8_t>& file_header_bytes() const { return header_bytes_; }
  const std::string& path() const { return path_; }
  std::uint64_t file_size() const { return file_size_; }
  // Byte offset of the next packet.
  std::uint64_t offset() const { return offset_; }
  const XtfReadStats& stats() const { return stats_; }

  // Reads the next packet; false at the end of the file. Sonar pings are decoded into
  // record.ping (buffers of `record` are reused).
  bool next(XtfRecord& record);
  // Reads the next packet without decoding it; false at the end of the file.
  bool next_raw(XtfRawPacket& packet);
  // Packets longer than `bytes` are skipped by seeking past them, not read (XtfRawPacket::skipped;
  // next() does not decode them): `replay` sends none longer than a datagram. Others longer than
  // kMaxXtfRecordBytes are a format error.
  void skip_larger_than(std::uint64_t bytes) { skip_larger_than_ = bytes; }

 private:
  struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  [[noreturn]] void fail(const std::string& what, std::uint64_t offset);
  void read_exact(std::uint8_t* dst, std::size_t n, std::uint64_t at);

  std::string path_;
  std::unique_ptr<std::FILE, FileCloser> file_;
  std::uint64_t file_size_ = 0;
  std::uint64_t offset_ = 0;
  XtfFileHeader header_;
  std::vector<std::uint8_t> header_bytes_;
  XtfReadStats stats_;
  bool failed_ = false;
  std::uint64_t skip_larger_than_ = UINT64_MAX;
};

// Every sonar ping of a file, with its header and the packet counts.
struct XtfFileContents {
  XtfFileHeader header;
  std::vector<XtfPing> pings;
  XtfReadStats stats;
};
XtfFileContents read_all_pings(const std::string& path);

// The file header bytes and every packet's raw bytes and offset: file_header followed by the
// packets in order is the file, byte for byte (for replay over UDP).
struct XtfRawFile {
  std::vector<std::uint8_t> file_header;
  std::vector<XtfRawPacket> packets;
};
XtfRawFile read_raw_packets(const std::string& path);

struct XtfWriterOptions {
  // fdatasync after every this many packets (0 = only on flush()/close()). Not needed for a
  // valid file after a crash of the process, only against power loss.
  std::size_t sync_every_packets = 0;
};

class XtfWriter {
 public:
  // Creates or truncates `path` and writes the encoded file header. Throws std::runtime_error
  // (with the path and the system error) or std::invalid_argument (bad header).
  XtfWriter(const std::string& path, const XtfFileHeader& header, XtfWriterOptions options = {});
  ~XtfWriter();  // closes; errors are swallowed, call close() to see them
  XtfWriter(const XtfWriter&) = delete;
  XtfWriter& operator=(const XtfWriter&) = delete;

  // Encodes the ping against the file header and appends it with a single write.
  void write_ping(const XtfPing& ping);
  // Appends an already encoded packet (any HeaderType). Checks the magic and that
  // NumBytesThisRecord equals its size.
  void write_packet(std::span<const std::uint8_t> packet);
  // fdatasync: data and size on stable storage.
  void flush();
  // Flushes and closes; the file is complete. Idempotent.
  void close();

  bool is_open() const { return fd_ >= 0; }
  const XtfFileHeader& file_header() const { return header_; }
  std::uint64_t bytes_written() const { return bytes_written_; }
  std::uint64_t packets_written() const { return packets_written_; }

 private:
  void append(std::span<const std::uint8_t> bytes);
  [[noreturn]] void fail(const std::string& what, int err);

  std::string path_;
  XtfFileHeader header_;
  XtfWriterOptions options_;
  int fd_ = -1;
  std::uint64_t bytes_written_ = 0;
  std::uint64_t packets_written_ = 0;
  std::vector<std::uint8_t> buffer_;  // reused packet buffer
};

}  // namespace sonarloop::xtf
