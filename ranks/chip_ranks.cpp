#include "ranks/chip_ranks.h"

#include <atomic>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>

#include "ranks/mpi_world.h"

namespace sonarloop::ranks {
namespace {

using render::ChipImage;
using render::ChipJob;

enum Tag : int { kTagCall = 1, kTagChip = 2, kTagEnd = 3, kTagFinish = 4 };

// A field added to a chip must be added to encode_chip and decode_chip too: these sizes (of
// GCC/Clang on x86-64 and arm64) change with any new field and stop the build here.
static_assert(sizeof(render::ChipParams) == 96, "ChipParams changed: update encode/decode_chip");
static_assert(sizeof(render::ChipRowTruth) == 24, "ChipRowTruth changed: update encode_chip");
static_assert(sizeof(ChipImage) == 96 + 64 + 4 * 24,
              "ChipImage changed: update encode_chip and decode_chip");
static_assert(std::is_trivially_copyable_v<render::ChipRowTruth>);

// Appends plain values and arrays to a message.
class MessageWriter {
 public:
  explicit MessageWriter(std::vector<std::byte>& out) : out_(out) { out_.clear(); }
  template <typename T>
  void field(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    out_.insert(out_.end(), p, p + sizeof(T));
  }
  template <typename T>
  void array(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    field(static_cast<std::uint64_t>(v.size()));
    const auto* p = reinterpret_cast<const std::byte*>(v.data());
    out_.insert(out_.end(), p, p + v.size() * sizeof(T));
  }

 private:
  std::vector<std::byte>& out_;
};

// Reads them back in the same order, refusing to read past the end.
class MessageReader {
 public:
  explicit MessageReader(std::span<const std::byte> in) : in_(in) {}
  template <typename T>
  void field(T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    take(&v, sizeof(T));
  }
  template <typename T>
  void array(std::vector<T>& v) {
    std::uint64_t n = 0;
    field(n);
    if (n > (in_.size() - pos_) / sizeof(T)) throw std::runtime_error("chip message: truncated");
    v.resize(static_cast<std::size_t>(n));
    take(v.data(), v.size() * sizeof(T));
  }
  bool at_end() const { return pos_ == in_.size(); }

 private:
  void take(void* dst, std::size_t n) {
    if (n > in_.size() - pos_) throw std::runtime_error("chip message: truncated");
    if (n > 0) std::memcpy(dst, in_.data() + pos_, n);
    pos_ += n;
  }
  std::span<const std::byte> in_;
  std::size_t pos_ = 0;
};

// Every field of a chip, in message order, for MessageWriter (const chip) and MessageReader.
template <typename Chip, typename Io>
void visit_chip_fields(Chip& c, Io& io) {
  auto& p = c.params;
  io.field(p.index);
  io.field(p.type);
  io.field(p.seabed);
  io.field(p.altitude_m);
  io.field(p.ground_range_m);
  io.field(p.target_heading_deg);
  io.field(p.track_heading_deg);
  io.field(p.aspect_deg);
  io.field(p.side);
  io.field(p.target_ne_m.x());
  io.field(p.target_ne_m.y());
  io.field(p.along_offset);
  io.field(c.resolution);
  io.field(c.resolution_m);
  io.field(c.rows);
  io.field(c.cols);
  io.field(c.slant_range_m);
  io.field(c.range_start_m);
  io.field(c.target_row);
  io.field(c.target_col);
  io.array(c.level_db);
  io.array(c.pixels);
  io.array(c.labels);
  io.array(c.truth);
}

// Identifies a call: its jobs and the dataset they come from (FNV-1a over the fields).
std::uint64_t call_fingerprint(const render::ChipRenderer& r, std::span<const ChipJob> jobs) {
  std::vector<std::byte> bytes;
  MessageWriter w(bytes);
  const render::ChipDatasetSpec& s = r.spec();
  w.field(s.seed);
  w.field(s.kind);
  w.field(s.renderer);
  w.field(static_cast<std::uint64_t>(s.classes.size()));
  w.field(static_cast<std::uint64_t>(s.seabeds.size()));
  w.array(s.resolutions_m);
  w.field(s.burial_fraction);
  w.field(s.sonar.source_level_db);
  w.field(static_cast<std::uint64_t>(jobs.size()));
  if (!jobs.empty()) {
    w.field(jobs.front().index);
    w.field(jobs.back().index);
    w.field(jobs.back().resolution);
  }
  std::uint64_t h = 14695981039346656037ull;
  for (std::byte b : bytes) {
    h ^= static_cast<std::uint64_t>(b);
    h *= 1099511628211ull;
  }
  return h;
}

std::vector<std::byte> u64_message(std::uint64_t v) {
  std::vector<std::byte> out;
  MessageWriter(out).field(v);
  return out;
}

std::uint64_t u64_of(const mpi::Message& m) {
  std::uint64_t v = 0;
  MessageReader in(m.bytes);
  in.field(v);
  return v;
}

// This rank's share of the jobs: j = rank, rank + size, ...
std::vector<ChipJob> share_of(std::span<const ChipJob> jobs, int rank, int size) {
  std::vector<ChipJob> mine;
  for (std::size_t j = static_cast<std::size_t>(rank); j < jobs.size();
       j += static_cast<std::size_t>(size)) {
    mine.push_back(jobs[j]);
  }
  return mine;
}

// Rank 0's own chips, from its render thread to its main thread (the only one that talks MPI),
// at most `capacity` waiting.
class ChipQueue {
 public:
  explicit ChipQueue(std::size_t capacity) : capacity_(capacity) {}
  void push(const ChipImage& c) {
    std::unique_lock lock(mutex_);
    cv_.wait(lock, [&] { return halted_ || chips_.size() < capacity_; });
    if (halted_) return;  // nobody takes it any more
    chips_.push_back(c);
    cv_.notify_all();
  }
  // The next chip; nullopt when the producer ended without one (stopped, or failed: error()).
  std::optional<ChipImage> pop() {
    std::unique_lock lock(mutex_);
    cv_.wait(lock, [&] { return !chips_.empty() || closed_; });
    if (chips_.empty()) return std::nullopt;
    std::optional<ChipImage> c(std::move(chips_.front()));
    chips_.pop_front();
    cv_.notify_all();
    return c;
  }
  void close(std::exception_ptr error) {
    const std::lock_guard lock(mutex_);
    closed_ = true;
    error_ = error;
    cv_.notify_all();
  }
  void halt() {
    const std::lock_guard lock(mutex_);
    halted_ = true;
    cv_.notify_all();
  }
  bool halted() const {
    const std::lock_guard lock(mutex_);
    return halted_;
  }
  std::exception_ptr error() const {
    const std::lock_guard lock(mutex_);
    return error_;
  }

 private:
  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<ChipImage> chips_;
  bool closed_ = false;
  bool halted_ = false;
  std::exception_ptr error_;
};

// Rank 0's render thread, joined (after halting it) when this goes out of scope.
class LocalRenderer {
 public:
  LocalRenderer(const render::ChipRenderer& r, std::vector<ChipJob> jobs, int threads)
      : jobs_(std::move(jobs)), queue_(2 * static_cast<std::size_t>(threads) + 2) {
    thread_ = std::thread([this, &r, threads] {
      std::exception_ptr error;
      try {
        render::render_chips(
            r, jobs_, threads, [this](const ChipImage& c) { queue_.push(c); },
            [this] { return queue_.halted(); });
      } catch (...) {
        error = std::current_exception();
      }
      queue_.close(error);
    });
  }
  ~LocalRenderer() {
    queue_.halt();
    thread_.join();
  }
  LocalRenderer(const LocalRenderer&) = delete;
  LocalRenderer& operator=(const LocalRenderer&) = delete;
  ChipQueue& queue() { return queue_; }

 private:
  std::vector<ChipJob> jobs_;
  ChipQueue queue_;
  std::thread thread_;
};

std::size_t root_side(const render::ChipRenderer& r, std::span<const ChipJob> jobs, int threads,
                      const std::function<void(const ChipImage&)>& sink,
                      const std::function<bool()>& stop) {
  const int size = mpi::size();
  std::vector<std::byte> header;
  MessageWriter hw(header);
  hw.field(static_cast<std::uint64_t>(jobs.size()));
  hw.field(call_fingerprint(r, jobs));
  for (int rank = 1; rank < size; ++rank)
    mpi::send(rank, kTagCall, header);

  LocalRenderer local(r, share_of(jobs, 0, size), threads);
  std::vector<bool> ended(static_cast<std::size_t>(size), false);
  std::size_t emitted = 0;
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    if (stop && stop()) break;
    const int from = static_cast<int>(j % static_cast<std::size_t>(size));
    std::optional<ChipImage> chip;
    if (from == 0) {
      chip = local.queue().pop();
      if (!chip) {
        if (const auto e = local.queue().error()) std::rethrow_exception(e);
        break;
      }
    } else {
      mpi::Message m = mpi::receive(from);
      if (m.tag == kTagEnd) {
        ended[static_cast<std::size_t>(from)] = true;
        break;
      }
      chip = decode_chip(m.bytes);
    }
    sink(*chip);
    ++emitted;
  }
  // tell every rank how many chips were taken, then drain what they still send
  local.queue().halt();
  const std::vector<std::byte> done = u64_message(emitted);
  for (int rank = 1; rank < size; ++rank)
    mpi::send(rank, kTagFinish, done);
  for (int rank = 1; rank < size; ++rank) {
    while (!ended[static_cast<std::size_t>(rank)]) {
      ended[static_cast<std::size_t>(rank)] = mpi::receive(rank).tag == kTagEnd;
    }
  }
  if (const auto e = local.queue().error()) std::rethrow_exception(e);
  return emitted;
}

std::size_t other_side(const render::ChipRenderer& r, std::span<const ChipJob> jobs, int threads,
                       const std::function<bool()>& stop) {
  // the call must be the one rank 0 makes
  const mpi::Message call = mpi::receive(0, kTagCall);
  MessageReader hr(call.bytes);
  std::uint64_t n = 0, fingerprint = 0;
  hr.field(n);
  hr.field(fingerprint);
  if (n != jobs.size() || fingerprint != call_fingerprint(r, jobs)) {
    throw std::logic_error("rank " + std::to_string(mpi::rank()) +
                           " is out of step with rank 0 (a different chip set: same command and "
                           "options on every rank?)");
  }

  std::atomic<bool> finished{false};
  std::uint64_t emitted = 0;
  const auto take_finish = [&] {
    if (finished || !mpi::message_waiting(0, kTagFinish)) return;
    emitted = u64_of(mpi::receive(0, kTagFinish));
    finished = true;
  };
  std::vector<std::byte> message;
  render::render_chips(
      r, share_of(jobs, mpi::rank(), mpi::size()), threads,
      [&](const ChipImage& c) {
        if (finished) return;  // rank 0 no longer takes chips
        encode_chip(c, message);
        mpi::send(0, kTagChip, message, take_finish);
      },
      [&] { return finished.load() || (stop && stop()); });
  mpi::send(0, kTagEnd, {}, take_finish);
  if (!finished) emitted = u64_of(mpi::receive(0, kTagFinish));
  return static_cast<std::size_t>(emitted);
}

}  // namespace

std::size_t render_chips_on_ranks(const render::ChipRenderer& renderer,
                                  std::span<const ChipJob> jobs, int threads,
                                  const std::function<void(const ChipImage&)>& sink,
                                  const std::function<bool()>& stop) {
  if (mpi::size() == 1) return render::render_chips(renderer, jobs, threads, sink, stop);
  return mpi::is_root() ? root_side(renderer, jobs, threads, sink, stop)
                        : other_side(renderer, jobs, threads, stop);
}

std::vector<ChipJob> dataset_jobs(std::uint64_t count, std::size_t resolutions) {
  std::vector<ChipJob> jobs;
  jobs.reserve(static_cast<std::size_t>(count) * resolutions);
  for (std::uint64_t i = 0; i < count; ++i) {
    for (std::size_t r = 0; r < resolutions; ++r)
      jobs.push_back(ChipJob{i, static_cast<int>(r)});
  }
  return jobs;
}

int serve_dataset(const render::ChipDatasetSpec& spec, std::uint64_t count, int threads,
                  const std::function<bool()>& stop) {
  const render::ChipRenderer renderer(spec);
  const std::vector<ChipJob> jobs = dataset_jobs(count, spec.resolutions_m.size());
  return render_chips_on_ranks(renderer, jobs, threads, {}, stop) == jobs.size() ? 0 : 130;
}

void encode_chip(const ChipImage& c, std::vector<std::byte>& out) {
  MessageWriter w(out);
  visit_chip_fields(c, w);
}

ChipImage decode_chip(std::span<const std::byte> bytes) {
  MessageReader in(bytes);
  ChipImage c;
  visit_chip_fields(c, in);
  if (!in.at_end()) throw std::runtime_error("chip message: bytes left over");
  return c;
}

std::string ranks_note() {
  return mpi::size() > 1 ? " on " + std::to_string(mpi::size()) + " ranks" : "";
}

}  // namespace sonarloop::ranks
