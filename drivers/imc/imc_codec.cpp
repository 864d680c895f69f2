#include "drivers/imc/imc_codec.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace sonarloop::imc {
namespace {

// ---- writing (little-endian) ----

class Writer {
 public:
  explicit Writer(std::vector<std::uint8_t>& out) : out_(out) {}

  template <class T>
  void put(T value) {
    static_assert(std::is_arithmetic_v<T>);
    std::array<std::uint8_t, sizeof(T)> b;
    std::memcpy(b.data(), &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) std::reverse(b.begin(), b.end());
    out_.insert(out_.end(), b.begin(), b.end());
  }
  void put_u16_at(std::size_t offset, std::uint16_t v) {
    out_[offset] = static_cast<std::uint8_t>(v & 0xFF);
    out_[offset + 1] = static_cast<std::uint8_t>(v >> 8);
  }
  // a u16 length or count prefix
  void put_count(std::size_t n, const char* what) {
    if (n > std::numeric_limits<std::uint16_t>::max())
      throw std::length_error(std::string("IMC: ") + what + " longer than 65535");
    put(static_cast<std::uint16_t>(n));
  }
  void put_bytes(std::span<const std::uint8_t> b, const char* what) {
    put_count(b.size(), what);
    out_.insert(out_.end(), b.begin(), b.end());
  }
  void put_text(const std::string& s, const char* what) {
    put_bytes({reinterpret_cast<const std::uint8_t*>(s.data()), s.size()}, what);
  }
  std::size_t size() const { return out_.size(); }

 private:
  std::vector<std::uint8_t>& out_;
};

void write_fields(Writer&, const Heartbeat&) {}

void write_fields(Writer& w, const Announce& m) {
  w.put_text(m.sys_name, "Announce.sys_name");
  w.put(m.sys_type);
  w.put(m.owner);
  w.put(m.lat_rad);
  w.put(m.lon_rad);
  w.put(m.height_m);
  w.put_text(m.services, "Announce.services");
}

void write_fields(Writer& w, const BeamConfig& m) {
  w.put(m.beam_width_rad);
  w.put(m.beam_height_rad);
}

void write_fields(Writer& w, const SonarData& m) {
  w.put(m.type);
  w.put(m.frequency_hz);
  w.put(m.min_range_m);
  w.put(m.max_range_m);
  w.put(m.bits_per_point);
  w.put(m.scale_factor);
  w.put_count(m.beam_config.size(), "SonarData.beam_config");
  for (const BeamConfig& b : m.beam_config) {
    w.put(BeamConfig::kId);
    write_fields(w, b);
  }
  w.put_bytes(m.data, "SonarData.data");
}

void write_fields(Writer& w, const EstimatedState& m) {
  w.put(m.lat_rad);
  w.put(m.lon_rad);
  for (float v :
       {m.height_m, m.x_m, m.y_m, m.z_m, m.phi_rad, m.theta_rad, m.psi_rad, m.u_m_s, m.v_m_s,
        m.w_m_s, m.vx_m_s, m.vy_m_s, m.vz_m_s, m.p_rad_s, m.q_rad_s, m.r_rad_s, m.depth_m, m.alt_m})
    w.put(v);
}

void write_fields(Writer& w, const MapPoint& m) {
  w.put(m.lat_rad);
  w.put(m.lon_rad);
  w.put(m.alt_m);
}

void write_fields(Writer& w, const MapFeature& m) {
  w.put_text(m.id, "MapFeature.id");
  w.put(m.feature_type);
  w.put(m.rgb_red);
  w.put(m.rgb_green);
  w.put(m.rgb_blue);
  w.put_count(m.feature.size(), "MapFeature.feature");
  for (const MapPoint& p : m.feature) {
    w.put(MapPoint::kId);
    write_fields(w, p);
  }
}

void write_fields(Writer& w, const CcuEvent& m) {
  w.put(m.type);
  w.put_text(m.id, "CcuEvent.id");
  if (m.arg) {
    w.put(MapFeature::kId);
    write_fields(w, *m.arg);
  } else {
    w.put(kNoMessage);
  }
}

// ---- reading (either byte order, bounds-checked) ----

class Reader {
 public:
  Reader(std::span<const std::uint8_t> bytes, bool big_endian) : b_(bytes), big_(big_endian) {}

  template <class T>
  bool get(T& value) {
    static_assert(std::is_arithmetic_v<T>);
    if (b_.size() - pos_ < sizeof(T)) return false;
    std::array<std::uint8_t, sizeof(T)> raw;
    std::memcpy(raw.data(), b_.data() + pos_, sizeof(T));
    const bool swap = big_ != (std::endian::native == std::endian::big);
    if (swap) std::reverse(raw.begin(), raw.end());
    std::memcpy(&value, raw.data(), sizeof(T));
    pos_ += sizeof(T);
    return true;
  }
  bool get_bytes(std::vector<std::uint8_t>& out) {
    std::uint16_t n = 0;
    if (!get(n) || b_.size() - pos_ < n) return false;
    out.assign(b_.begin() + static_cast<std::ptrdiff_t>(pos_),
               b_.begin() + static_cast<std::ptrdiff_t>(pos_ + n));
    pos_ += n;
    return true;
  }
  bool get_text(std::string& out) {
    std::uint16_t n = 0;
    if (!get(n) || b_.size() - pos_ < n) return false;
    out.assign(reinterpret_cast<const char*>(b_.data() + pos_), n);
    pos_ += n;
    return true;
  }
  bool done() const { return pos_ == b_.size(); }

 private:
  std::span<const std::uint8_t> b_;
  bool big_;
  std::size_t pos_ = 0;
};

bool read_fields(Reader&, Heartbeat&) {
  return true;
}

bool read_fields(Reader& r, Announce& m) {
  return r.get_text(m.sys_name) && r.get(m.sys_type) && r.get(m.owner) && r.get(m.lat_rad) &&
         r.get(m.lon_rad) && r.get(m.height_m) && r.get_text(m.services);
}

bool read_fields(Reader& r, BeamConfig& m) {
  return r.get(m.beam_width_rad) && r.get(m.beam_height_rad);
}

// A message-list whose every element must be of type T.
template <class T>
bool read_list(Reader& r, std::vector<T>& out) {
  std::uint16_t n = 0;
  if (!r.get(n)) return false;
  out.clear();
  for (std::uint16_t i = 0; i < n; ++i) {
    std::uint16_t id = 0;
    T item;
    if (!r.get(id) || id != T::kId || !read_fields(r, item)) return false;
    out.push_back(item);
  }
  return true;
}

bool read_fields(Reader& r, SonarData& m) {
  return r.get(m.type) && r.get(m.frequency_hz) && r.get(m.min_range_m) && r.get(m.max_range_m) &&
         r.get(m.bits_per_point) && r.get(m.scale_factor) && read_list(r, m.beam_config) &&
         r.get_bytes(m.data);
}

bool read_fields(Reader& r, EstimatedState& m) {
  if (!r.get(m.lat_rad) || !r.get(m.lon_rad)) return false;
  for (float* v : {&m.height_m, &m.x_m, &m.y_m, &m.z_m, &m.phi_rad, &m.theta_rad, &m.psi_rad,
                   &m.u_m_s, &m.v_m_s, &m.w_m_s, &m.vx_m_s, &m.vy_m_s, &m.vz_m_s, &m.p_rad_s,
                   &m.q_rad_s, &m.r_rad_s, &m.depth_m, &m.alt_m})
    if (!r.get(*v)) return false;
  return true;
}

bool read_fields(Reader& r, MapPoint& m) {
  return r.get(m.lat_rad) && r.get(m.lon_rad) && r.get(m.alt_m);
}

bool read_fields(Reader& r, MapFeature& m) {
  return r.get_text(m.id) && r.get(m.feature_type) && r.get(m.rgb_red) && r.get(m.rgb_green) &&
         r.get(m.rgb_blue) && read_list(r, m.feature);
}

bool read_fields(Reader& r, CcuEvent& m) {
  std::uint16_t arg_id = 0;
  if (!r.get(m.type) || !r.get_text(m.id) || !r.get(arg_id)) return false;
  if (arg_id == kNoMessage) {
    m.arg.reset();
    return true;
  }
  if (arg_id != MapFeature::kId) return false;  // another inline message: not spoken here
  m.arg.emplace();
  return read_fields(r, *m.arg);
}

template <class M>
DecodeStatus read_message(Reader& r, Message& out) {
  M m;
  if (!read_fields(r, m) || !r.done()) return DecodeStatus::kBadFields;
  out = std::move(m);
  return DecodeStatus::kOk;
}

}  // namespace

std::uint16_t crc16(std::span<const std::uint8_t> bytes) {
  // bit by bit, least significant bit first (the reflected form of 0x8005 is 0xA001)
  std::uint16_t crc = 0;
  for (std::uint8_t byte : bytes) {
    crc ^= byte;
    for (int k = 0; k < 8; ++k)
      crc = (crc & 1u) ? static_cast<std::uint16_t>((crc >> 1) ^ 0xA001u)
                       : static_cast<std::uint16_t>(crc >> 1);
  }
  return crc;
}

template <class M>
void encode(const Header& header, const M& message, std::vector<std::uint8_t>& out) {
  out.clear();
  Writer w(out);
  w.put(kSync);
  w.put(M::kId);
  w.put(std::uint16_t{0});  // the size, once the fields are written
  w.put(header.timestamp_s);
  w.put(header.src);
  w.put(header.src_ent);
  w.put(header.dst);
  w.put(header.dst_ent);
  write_fields(w, message);
  const std::size_t payload = w.size() - kHeaderBytes;
  if (payload > std::numeric_limits<std::uint16_t>::max())
    throw std::length_error("IMC: message fields longer than 65535 bytes");
  w.put_u16_at(4, static_cast<std::uint16_t>(payload));
  w.put(crc16(out));
}

template void encode(const Header&, const Heartbeat&, std::vector<std::uint8_t>&);
template void encode(const Header&, const Announce&, std::vector<std::uint8_t>&);
template void encode(const Header&, const SonarData&, std::vector<std::uint8_t>&);
template void encode(const Header&, const EstimatedState&, std::vector<std::uint8_t>&);
template void encode(const Header&, const MapFeature&, std::vector<std::uint8_t>&);
template void encode(const Header&, const CcuEvent&, std::vector<std::uint8_t>&);

void encode_message(const Header& header, const Message& message, std::vector<std::uint8_t>& out) {
  std::visit([&](const auto& m) { encode(header, m, out); }, message);
}

const char* decode_status_name(DecodeStatus s) {
  switch (s) {
    case DecodeStatus::kOk:
      return "ok";
    case DecodeStatus::kTooShort:
      return "shorter than a header and a footer";
    case DecodeStatus::kBadSync:
      return "bad synchronisation number";
    case DecodeStatus::kSizeMismatch:
      return "size field does not match the datagram";
    case DecodeStatus::kBadCrc:
      return "CRC mismatch";
    case DecodeStatus::kUnknownMessage:
      return "a message not spoken here";
    case DecodeStatus::kBadFields:
      return "fields do not fit the message";
  }
  return "?";
}

DecodeStatus decode(std::span<const std::uint8_t> bytes, Packet& out) {
  if (bytes.size() < kHeaderBytes + kFooterBytes) return DecodeStatus::kTooShort;
  // the sync number as little-endian tells the byte order
  const std::uint16_t sync_le = static_cast<std::uint16_t>(bytes[0] | (bytes[1] << 8));
  bool big = false;
  if (sync_le == kSync) {
    big = false;
  } else if (sync_le == static_cast<std::uint16_t>((kSync >> 8) | ((kSync & 0xFF) << 8))) {
    big = true;
  } else {
    return DecodeStatus::kBadSync;
  }
  Reader h(bytes.first(kHeaderBytes), big);
  std::uint16_t sync = 0, size = 0;
  h.get(sync);
  h.get(out.mgid);
  h.get(size);
  h.get(out.header.timestamp_s);
  h.get(out.header.src);
  h.get(out.header.src_ent);
  h.get(out.header.dst);
  h.get(out.header.dst_ent);
  if (static_cast<std::size_t>(size) + kHeaderBytes + kFooterBytes != bytes.size())
    return DecodeStatus::kSizeMismatch;
  const std::size_t body = kHeaderBytes + size;
  Reader f(bytes.subspan(body), big);
  std::uint16_t crc = 0;
  f.get(crc);
  if (crc != crc16(bytes.first(body))) return DecodeStatus::kBadCrc;

  Reader r(bytes.subspan(kHeaderBytes, size), big);
  switch (out.mgid) {
    case Heartbeat::kId:
      return read_message<Heartbeat>(r, out.message);
    case Announce::kId:
      return read_message<Announce>(r, out.message);
    case SonarData::kId:
      return read_message<SonarData>(r, out.message);
    case EstimatedState::kId:
      return read_message<EstimatedState>(r, out.message);
    case MapFeature::kId:
      return read_message<MapFeature>(r, out.message);
    case CcuEvent::kId:
      return read_message<CcuEvent>(r, out.message);
    default:
      return DecodeStatus::kUnknownMessage;
  }
}

}  // namespace sonarloop::imc
