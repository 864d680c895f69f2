#include "drivers/mcap/mcap_writer.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "drivers/io/crc32.h"

#ifdef SONARLOOP_HAVE_ZSTD
#include <zstd.h>
#endif

namespace sonarloop::mcap {
namespace {

// record opcodes (the specification's "Records")
constexpr std::uint8_t kOpHeader = 0x01;
constexpr std::uint8_t kOpFooter = 0x02;
constexpr std::uint8_t kOpSchema = 0x03;
constexpr std::uint8_t kOpChannel = 0x04;
constexpr std::uint8_t kOpMessage = 0x05;
constexpr std::uint8_t kOpChunk = 0x06;
constexpr std::uint8_t kOpMessageIndex = 0x07;
constexpr std::uint8_t kOpChunkIndex = 0x08;
constexpr std::uint8_t kOpStatistics = 0x0B;
constexpr std::uint8_t kOpSummaryOffset = 0x0E;
constexpr std::uint8_t kOpDataEnd = 0x0F;

// Little-endian serialization into a byte vector (the specification's "Serialization").
class Bytes {
 public:
  explicit Bytes(std::vector<std::uint8_t>& out) : out_(out) {}
  template <class T>
  void put(T v) {
    for (std::size_t i = 0; i < sizeof(T); ++i)
      out_.push_back(static_cast<std::uint8_t>((static_cast<std::uint64_t>(v) >> (8 * i)) & 0xFF));
  }
  void put_bytes(std::span<const std::uint8_t> b) {
    if (b.empty()) return;
    const std::size_t at = out_.size();
    out_.resize(at + b.size());
    std::memcpy(out_.data() + at, b.data(), b.size());
  }
  void put_string(const std::string& s) {
    put(static_cast<std::uint32_t>(s.size()));
    put_bytes({reinterpret_cast<const std::uint8_t*>(s.data()), s.size()});
  }
  // A record: opcode, u64 content length (patched by end_record), content.
  std::size_t begin_record(std::uint8_t op) {
    out_.push_back(op);
    const std::size_t at = out_.size();
    put(std::uint64_t{0});
    return at;
  }
  void end_record(std::size_t at) {
    const std::uint64_t n = out_.size() - at - 8;
    for (std::size_t i = 0; i < 8; ++i)
      out_[at + i] = static_cast<std::uint8_t>((n >> (8 * i)) & 0xFF);
  }
  // A u32 byte-length prefix (Map, Array), patched by end_prefix.
  std::size_t begin_prefix() {
    const std::size_t at = out_.size();
    put(std::uint32_t{0});
    return at;
  }
  void end_prefix(std::size_t at) {
    const std::uint64_t n = out_.size() - at - 4;
    for (std::size_t i = 0; i < 4; ++i)
      out_[at + i] = static_cast<std::uint8_t>((n >> (8 * i)) & 0xFF);
  }
  std::size_t size() const { return out_.size(); }

 private:
  std::vector<std::uint8_t>& out_;
};

}  // namespace

bool zstd_available() {
#ifdef SONARLOOP_HAVE_ZSTD
  return true;
#else
  return false;
#endif
}

Writer::Writer(const std::string& path, WriterOptions options)
    : path_(path),
      options_(std::move(options)),
      file_(std::fopen(path.c_str(), "wb"), &std::fclose) {
  if (!file_) {
    throw std::runtime_error(path + ": cannot create: " + std::strerror(errno));
  }
  if (!zstd_available()) options_.compress = false;
  std::vector<std::uint8_t> b;
  Bytes w(b);
  w.put_bytes(kMagic);
  const std::size_t h = w.begin_record(kOpHeader);
  w.put_string(options_.profile);
  w.put_string(options_.library);
  w.end_record(h);
  emit(b);
}

Writer::~Writer() {
  try {
    close();
  } catch (...) {
  }
}

void Writer::emit(std::span<const std::uint8_t> bytes) {
  if (bytes.empty()) return;
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_.get()) != bytes.size()) {
    const std::string why = std::strerror(errno);
    closed_ = true;
    file_.reset();
    throw std::runtime_error(path_ + ": write failed: " + why);
  }
  offset_ += bytes.size();
  if (in_data_section_) data_crc_ = io::crc32_update(data_crc_, bytes);
}

std::uint16_t Writer::add_schema(const std::string& name, const std::string& encoding,
                                 std::span<const std::uint8_t> data) {
  const auto id = static_cast<std::uint16_t>(schema_records_.size() + 1);
  std::vector<std::uint8_t> b;
  Bytes w(b);
  const std::size_t r = w.begin_record(kOpSchema);
  w.put(id);
  w.put_string(name);
  w.put_string(encoding);
  w.put(static_cast<std::uint32_t>(data.size()));
  w.put_bytes(data);
  w.end_record(r);
  emit(b);
  schema_records_.push_back(std::move(b));
  return id;
}

std::uint16_t Writer::add_channel(std::uint16_t schema_id, const std::string& topic,
                                  const std::string& message_encoding,
                                  const std::map<std::string, std::string>& metadata) {
  if (schema_id == 0 || schema_id > schema_records_.size())
    throw std::invalid_argument("MCAP channel " + topic + ": unknown schema id");
  const auto id = static_cast<std::uint16_t>(channel_records_.size());
  std::vector<std::uint8_t> b;
  Bytes w(b);
  const std::size_t r = w.begin_record(kOpChannel);
  w.put(id);
  w.put(schema_id);
  w.put_string(topic);
  w.put_string(message_encoding);
  const std::size_t m = w.begin_prefix();
  for (const auto& [k, v] : metadata) {
    w.put_string(k);
    w.put_string(v);
  }
  w.end_prefix(m);
  w.end_record(r);
  emit(b);
  channel_records_.push_back(std::move(b));
  channel_ids_.push_back(id);
  return id;
}

void Writer::write(std::uint16_t channel, std::uint32_t sequence, std::uint64_t log_time_ns,
                   std::uint64_t publish_time_ns, std::span<const std::uint8_t> data) {
  if (closed_) throw std::runtime_error(path_ + ": written after close");
  if (channel >= channel_records_.size())
    throw std::invalid_argument("MCAP: unknown channel " + std::to_string(channel));
  if (chunk_index_.empty()) {
    chunk_start_ = log_time_ns;
    chunk_end_ = log_time_ns;
  }
  chunk_start_ = std::min(chunk_start_, log_time_ns);
  chunk_end_ = std::max(chunk_end_, log_time_ns);
  chunk_index_[channel].emplace_back(log_time_ns, chunk_.size());
  Bytes w(chunk_);
  const std::size_t r = w.begin_record(kOpMessage);
  w.put(channel);
  w.put(sequence);
  w.put(log_time_ns);
  w.put(publish_time_ns);
  w.put_bytes(data);
  w.end_record(r);
  if (message_count_ == 0) {
    first_time_ = log_time_ns;
    last_time_ = log_time_ns;
  }
  first_time_ = std::min(first_time_, log_time_ns);
  last_time_ = std::max(last_time_, log_time_ns);
  ++message_count_;
  ++channel_counts_[channel];
  if (chunk_.size() >= options_.chunk_bytes) flush_chunk();
}

void Writer::flush_chunk() {
  if (chunk_index_.empty()) return;
  const std::uint32_t crc = io::crc32(chunk_);
  std::span<const std::uint8_t> records = chunk_;
  std::string compression;
#ifdef SONARLOOP_HAVE_ZSTD
  if (options_.compress) {
    compressed_.resize(ZSTD_compressBound(chunk_.size()));
    const std::size_t n = ZSTD_compress(compressed_.data(), compressed_.size(), chunk_.data(),
                                        chunk_.size(), options_.zstd_level);
    if (ZSTD_isError(n)) throw std::runtime_error(path_ + ": zstd: " + ZSTD_getErrorName(n));
    compressed_.resize(n);
    records = compressed_;
    compression = "zstd";
  }
#endif
  ChunkIndex index;
  index.start_time = chunk_start_;
  index.end_time = chunk_end_;
  index.offset = offset_;
  index.compressed_size = records.size();
  index.uncompressed_size = chunk_.size();
  std::vector<std::uint8_t> b;
  Bytes w(b);
  const std::size_t r = w.begin_record(kOpChunk);
  w.put(chunk_start_);
  w.put(chunk_end_);
  w.put(static_cast<std::uint64_t>(chunk_.size()));
  w.put(crc);
  w.put_string(compression);
  w.put(static_cast<std::uint64_t>(records.size()));
  w.put_bytes(records);
  w.end_record(r);
  index.length = b.size();
  // the message indexes, one per channel of the chunk, right after it
  for (const auto& [channel, entries] : chunk_index_) {
    index.message_index_offsets[channel] = offset_ + b.size();
    const std::size_t mi = w.begin_record(kOpMessageIndex);
    w.put(channel);
    const std::size_t a = w.begin_prefix();
    for (const auto& [t, off] : entries) {
      w.put(t);
      w.put(off);
    }
    w.end_prefix(a);
    w.end_record(mi);
  }
  index.message_index_length = b.size() - index.length;
  emit(b);
  chunk_indexes_.push_back(std::move(index));
  ++chunk_count_;
  chunk_.clear();
  chunk_index_.clear();
  std::fflush(file_.get());
}

void Writer::close() {
  if (closed_) return;
  flush_chunk();
  std::vector<std::uint8_t> b;
  Bytes w(b);
  const std::size_t de = w.begin_record(kOpDataEnd);
  w.put(data_crc_);
  w.end_record(de);
  in_data_section_ = false;
  emit(b);

  // the summary, grouped by opcode, and an offset record per group
  const std::uint64_t summary_start = offset_;
  b.clear();
  struct Group {
    std::uint8_t op;
    std::uint64_t start, length;
  };
  std::vector<Group> groups;
  const auto group = [&](std::uint8_t op, const auto& write_records) {
    const std::size_t start = b.size();
    write_records();
    if (b.size() > start) groups.push_back({op, summary_start + start, b.size() - start});
  };
  group(kOpSchema, [&] {
    for (const auto& s : schema_records_)
      w.put_bytes(s);
  });
  group(kOpChannel, [&] {
    for (const auto& c : channel_records_)
      w.put_bytes(c);
  });
  group(kOpStatistics, [&] {
    const std::size_t r = w.begin_record(kOpStatistics);
    w.put(message_count_);
    w.put(static_cast<std::uint16_t>(schema_records_.size()));
    w.put(static_cast<std::uint32_t>(channel_records_.size()));
    w.put(std::uint32_t{0});  // attachments
    w.put(std::uint32_t{0});  // metadata
    w.put(static_cast<std::uint32_t>(chunk_count_));
    w.put(first_time_);
    w.put(last_time_);
    const std::size_t m = w.begin_prefix();
    for (const auto& [channel, n] : channel_counts_) {
      w.put(channel);
      w.put(n);
    }
    w.end_prefix(m);
    w.end_record(r);
  });
  group(kOpChunkIndex, [&] {
    for (const ChunkIndex& c : chunk_indexes_) {
      const std::size_t r = w.begin_record(kOpChunkIndex);
      w.put(c.start_time);
      w.put(c.end_time);
      w.put(c.offset);
      w.put(c.length);
      const std::size_t m = w.begin_prefix();
      for (const auto& [channel, off] : c.message_index_offsets) {
        w.put(channel);
        w.put(off);
      }
      w.end_prefix(m);
      w.put(c.message_index_length);
      w.put_string(options_.compress ? std::string("zstd") : std::string());
      w.put(c.compressed_size);
      w.put(c.uncompressed_size);
      w.end_record(r);
    }
  });
  const std::uint64_t summary_offset_start = summary_start + b.size();
  for (const Group& g : groups) {
    const std::size_t r = w.begin_record(kOpSummaryOffset);
    w.put(g.op);
    w.put(g.start);
    w.put(g.length);
    w.end_record(r);
  }
  // the footer (20 bytes of content): its CRC covers the summary, the offsets and the footer up
  // to the CRC itself
  w.put(kOpFooter);
  w.put(std::uint64_t{20});
  w.put(summary_start);
  w.put(summary_offset_start);
  w.put(io::crc32(b));
  w.put_bytes(kMagic);
  emit(b);
  closed_ = true;
  if (std::fflush(file_.get()) != 0 || std::fclose(file_.release()) != 0)
    throw std::runtime_error(path_ + ": write failed: " + std::strerror(errno));
}

}  // namespace sonarloop::mcap
