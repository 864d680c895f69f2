#pragma once
// An MCAP file writer (the MCAP format specification, version 0: mcap.dev/spec; docs/formats.md
// §8): what `run --record DIR` writes as DIR/run.mcap for ROS 2 tools (`ros2 bag`, Foxglove).
// Written from the specification: no MCAP library is in Debian.
//
// Layout written:
//   magic  Header(profile, library)
//   data section: Schema and Channel records as they are added, then Chunks of Message records
//                 (zstd-compressed, or uncompressed), each followed by its Message Index records
//                 (one per channel in the chunk: log time and offset of each message);
//                 DataEnd(CRC-32 of the data section)
//   summary: every Schema, every Channel, one Statistics, one Chunk Index per chunk
//   summary offsets: one Summary Offset per group of summary records
//   Footer(summary start, summary offset start, summary CRC)  magic
// So a reader can seek (chunk indexes), list topics and counts (statistics), and check every
// byte (CRCs). Little-endian throughout; strings u32-length-prefixed UTF-8.
//
// Time stamps are as given (ns; sonarloop passes simulation time on the run's UTC epoch).
// Durability: a chunk is written whole once it reaches chunk_bytes (or at close); a crash loses
// the open chunk and the summary (an MCAP reader can still recover the written chunks).
// Not thread-safe: one writer thread.
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace sonarloop::mcap {

inline constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', 0x30, '\r', '\n'};

struct WriterOptions {
  std::string profile = "ros2";
  std::string library = "sonarloop";
  bool compress = true;  // zstd chunks (else uncompressed)
  int zstd_level = 3;
  std::size_t chunk_bytes = 1u << 20;  // uncompressed records per chunk before it is written
};

// True when this build can write zstd chunks (libzstd found at configure).
bool zstd_available();

class Writer {
 public:
  // Creates (truncates) `path` and writes the magic and the header. Throws std::runtime_error
  // naming the path when it cannot be created.
  Writer(const std::string& path, WriterOptions options = {});
  ~Writer();  // close(), errors swallowed (call close() to see them)
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // Schema ids start at 1; channel ids at 0. Both write their record to the data section at once.
  std::uint16_t add_schema(const std::string& name, const std::string& encoding,
                           std::span<const std::uint8_t> data);
  std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic,
                            const std::string& message_encoding,
                            const std::map<std::string, std::string>& metadata = {});

  // One message on a channel (log and publish time ns). Throws std::invalid_argument for an
  // unknown channel, std::runtime_error on a write error (the file is then closed).
  void write(std::uint16_t channel, std::uint32_t sequence, std::uint64_t log_time_ns,
             std::uint64_t publish_time_ns, std::span<const std::uint8_t> data);

  // Writes the open chunk, the data end, the summary and the footer; idempotent. Throws
  // std::runtime_error on a write error.
  void close();

  const std::string& path() const { return path_; }
  std::uint64_t messages() const { return message_count_; }
  std::uint64_t chunks() const { return chunk_count_; }
  std::uint64_t bytes() const { return offset_; }

 private:
  struct ChunkIndex {
    std::uint64_t start_time = 0, end_time = 0, offset = 0, length = 0;
    std::map<std::uint16_t, std::uint64_t> message_index_offsets;
    std::uint64_t message_index_length = 0, compressed_size = 0, uncompressed_size = 0;
  };
  void emit(std::span<const std::uint8_t> bytes);  // to the file, counted, into the data CRC
  void flush_chunk();

  std::string path_;
  WriterOptions options_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
  bool closed_ = false;
  std::uint64_t offset_ = 0;
  std::uint32_t data_crc_ = 0;
  bool in_data_section_ = true;
  std::vector<std::vector<std::uint8_t>> schema_records_, channel_records_;  // for the summary
  std::vector<std::uint16_t> channel_ids_;
  // the open chunk
  std::vector<std::uint8_t> chunk_;
  std::uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;
  std::vector<std::uint8_t> compressed_;
  std::vector<ChunkIndex> chunk_indexes_;
  // statistics
  std::uint64_t message_count_ = 0, chunk_count_ = 0;
  std::uint64_t first_time_ = 0, last_time_ = 0;
  std::map<std::uint16_t, std::uint64_t> channel_counts_;
};

}  // namespace sonarloop::mcap
