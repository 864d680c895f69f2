#pragma once
// CDR, the serialization of ROS 2 messages (OMG DDS-XTypes "XCDR1" plain CDR, little-endian, as
// rmw_fastrtps / rmw_cyclonedds write it and MCAP's "cdr" message encoding names it): a 4-byte
// encapsulation header 00 01 00 00 (CDR_LE), then the fields in order, each primitive aligned to
// its own size (at most 8) counted from the end of the header; a string is a u32 length
// including its terminating NUL, the bytes and the NUL; a sequence (T[]) a u32 element count and
// the elements; a fixed array (T[N]) the N elements alone; bool one byte.
#include <cstdint>
#include <cstring>
#include <span>
#include <string_view>
#include <type_traits>
#include <vector>

namespace sonarloop::ros2 {

class CdrWriter {
 public:
  // Writes the encapsulation header into `out` (cleared; its capacity is reused).
  explicit CdrWriter(std::vector<std::uint8_t>& out) : out_(out) {
    out_.clear();
    const std::uint8_t header[4] = {0x00, 0x01, 0x00, 0x00};
    append(header, 4);
  }

  template <class T>
  void put(T v) {
    static_assert(std::is_arithmetic_v<T> && sizeof(T) <= 8);
    align(sizeof(T));
    append(&v, sizeof(T));  // little-endian hosts (x86-64, ARM64): CDR_LE as is
  }
  void put_bool(bool v) { put<std::uint8_t>(v ? 1 : 0); }
  void put_string(std::string_view s) {
    put(static_cast<std::uint32_t>(s.size() + 1));
    append(s.data(), s.size());
    out_.push_back(0);
  }
  // A sequence of primitives: its count, then the elements.
  template <class T>
  void put_sequence(std::span<const T> v) {
    put(static_cast<std::uint32_t>(v.size()));
    if (v.empty()) return;
    align(sizeof(T));
    append(v.data(), v.size_bytes());
  }
  // builtin_interfaces/Time of t_ns (ns since 1970-01-01 UTC, >= 0).
  void put_time(std::int64_t t_ns) {
    put(static_cast<std::int32_t>(t_ns / 1'000'000'000));
    put(static_cast<std::uint32_t>(t_ns % 1'000'000'000));
  }

 private:
  // (resize and copy: GCC 12 warns falsely about vector::insert of a few bytes)
  void append(const void* p, std::size_t n) {
    if (n == 0) return;
    const std::size_t at = out_.size();
    out_.resize(at + n);
    std::memcpy(out_.data() + at, p, n);
  }
  void align(std::size_t n) {
    const std::size_t pos = out_.size() - 4;  // from the end of the encapsulation header
    out_.resize(out_.size() + (n - pos % n) % n, 0);
  }
  std::vector<std::uint8_t>& out_;
};

}  // namespace sonarloop::ros2
