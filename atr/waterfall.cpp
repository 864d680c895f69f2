#include "atr/waterfall.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <variant>

#include "units/angles.h"

namespace sonarloop::atr {
namespace {

// One international knot in m/s (1852 m per hour).
constexpr double kMpsPerKnot = 1852.0 / 3600.0;
// Isis' one-way sound velocity, the XTF default when a ping header gives none
// (docs/formats.md 1.5).
constexpr double kDefaultXtfSoundVelocityMps = 750.0;
// Largest samples per channel accepted: a UDP datagram holds at most 65,507 bytes.
constexpr std::size_t kMaxSamples = 65536;

float level_db(double amplitude) {
  return amplitude > 0.0 ? static_cast<float>(20.0 * std::log10(amplitude)) : kNoEchoDb;
}

// A recorder writes latitude and longitude 0, 0 while it has no position fix (the real Iver2
// recording's first ping); it is no position, and must not become the stream's origin.
bool has_fix(const xtf::XtfPingHeader& h) {
  return std::isfinite(h.sensor_y) && std::isfinite(h.sensor_x) && std::fabs(h.sensor_y) <= 90.0 &&
         std::fabs(h.sensor_x) <= 180.0 && !(h.sensor_y == 0.0 && h.sensor_x == 0.0);
}

}  // namespace

double footprint_along_m(const PingRecord& r) {
  const double a = std::isfinite(r.altitude_m) ? r.altitude_m : 0.0;
  return r.along_m + a * std::tan(r.pitch_deg * kRadPerDeg);
}

Waterfall::Waterfall(int capacity, std::optional<GeoPoint> frame_origin) : capacity_(capacity) {
  if (capacity < 2) {
    throw std::invalid_argument("waterfall capacity " + std::to_string(capacity) +
                                " pings: need at least 2");
  }
  if (frame_origin) plane_ = std::make_unique<LocalTangentPlane>(*frame_origin);
}

std::optional<Waterfall::Layout> Waterfall::layout_of(const xtf::XtfFileHeader& header,
                                                      const xtf::XtfPing& ping) const {
  Layout l;
  for (std::size_t i = 0; i < ping.channels.size(); ++i) {
    const xtf::XtfPingChannel& ch = ping.channels[i];
    if (ch.channel_number >= header.chan_info.size()) return std::nullopt;
    const std::uint8_t type = header.chan_info[ch.channel_number].type_of_channel;
    if (type == xtf::kChannelPort && l.port < 0) l.port = static_cast<int>(i);
    if (type == xtf::kChannelStbd && l.stbd < 0) l.stbd = static_cast<int>(i);
  }
  if (l.port < 0 || l.stbd < 0) return std::nullopt;
  const auto& port = ping.channels[static_cast<std::size_t>(l.port)];
  const auto& stbd = ping.channels[static_cast<std::size_t>(l.stbd)];
  const std::size_t n = port.num_samples();
  if (n == 0 || n > kMaxSamples || stbd.num_samples() != n ||
      port.samples.index() != stbd.samples.index()) {
    return std::nullopt;
  }
  if (std::holds_alternative<std::vector<std::uint8_t>>(port.samples)) {
    l.kind = SampleKind::kUint8;
  } else if (std::holds_alternative<std::vector<std::uint16_t>>(port.samples)) {
    l.kind = SampleKind::kUint16;
  } else if (std::holds_alternative<std::vector<float>>(port.samples)) {
    l.kind = SampleKind::kFloat;
  } else {
    return std::nullopt;  // raw 32-bit integers: no known full scale
  }
  const double c = ping.header.sound_velocity_mps > 0.0f ? ping.header.sound_velocity_mps
                                                         : kDefaultXtfSoundVelocityMps;
  l.bins = static_cast<int>(n);
  l.range_start_m = static_cast<double>(port.time_delay_s) * c;
  l.bin_size_m =
      (static_cast<double>(port.slant_range_m) - l.range_start_m) / static_cast<double>(n);
  if (!(l.bin_size_m > 0.0) || !std::isfinite(l.bin_size_m) ||
      port.slant_range_m != stbd.slant_range_m || port.time_delay_s != stbd.time_delay_s) {
    return std::nullopt;
  }
  return l;
}

void Waterfall::configure(const Layout& l) {
  layout_ = l;
  bins_ = l.bins;
  bin_size_m_ = l.bin_size_m;
  range_start_m_ = l.range_start_m;
  levels_.assign(static_cast<std::size_t>(capacity_) * 2 * static_cast<std::size_t>(bins_),
                 kNoEchoDb);
  records_.assign(static_cast<std::size_t>(capacity_), PingRecord{});
  table_.clear();
  if (l.kind == SampleKind::kUint8 || l.kind == SampleKind::kUint16) {
    const int full_scale = l.kind == SampleKind::kUint8 ? 255 : 65535;
    table_.resize(static_cast<std::size_t>(full_scale) + 1);
    for (int s = 0; s <= full_scale; ++s)
      table_[static_cast<std::size_t>(s)] = level_db(static_cast<double>(s) / full_scale);
  }
  count_ = 0;
  configured_ = true;
}

void Waterfall::fill_levels(const xtf::XtfPingChannel& ch, bool reversed, float* out) const {
  const std::size_t n = static_cast<std::size_t>(bins_);
  std::visit(
      [&](const auto& v) {
        using T = typename std::decay_t<decltype(v)>::value_type;
        for (std::size_t k = 0; k < n; ++k) {
          const T s = v[reversed ? n - 1 - k : k];
          if constexpr (std::is_same_v<T, float>) {
            out[k] = std::isfinite(s) ? level_db(s) : kNoEchoDb;
          } else if constexpr (std::is_same_v<T, std::uint8_t> ||
                               std::is_same_v<T, std::uint16_t>) {
            out[k] = table_[s];
          } else {
            out[k] = kNoEchoDb;  // not reached: layout_of refuses raw 32-bit samples
          }
        }
      },
      ch.samples);
}

PingRecord Waterfall::make_record(const xtf::XtfFileHeader& header, const xtf::XtfPing& ping) {
  const xtf::XtfPingHeader& h = ping.header;
  PingRecord r;
  r.seq = next_seq_;
  r.ping_number = h.ping_number;
  r.time_utc_ns = xtf::time_utc_ns(h);
  if (header.nav_units == xtf::kNavUnitsLatLong) {
    geodetic_stream_ = true;
    if (has_fix(h)) {
      if (!plane_) plane_ = std::make_unique<LocalTangentPlane>(GeoPoint{h.sensor_y, h.sensor_x});
      const Vec2 ne = plane_->to_local(GeoPoint{h.sensor_y, h.sensor_x});
      r.north_m = ne.x();
      r.east_m = ne.y();
    } else if (have_last_) {
      // no fix in this ping: where the last one was
      r.north_m = last_.north_m;
      r.east_m = last_.east_m;
    }  // else: before the first fix, at the origin the first fix will set
  } else {
    if (!have_origin_) {
      have_origin_ = true;
      origin_north_m_ = h.sensor_y;
      origin_east_m_ = h.sensor_x;
    }
    r.north_m = h.sensor_y - origin_north_m_;
    r.east_m = h.sensor_x - origin_east_m_;
  }
  r.heading_deg = h.sensor_heading_deg;
  r.pitch_deg = h.sensor_pitch_deg;
  r.roll_deg = h.sensor_roll_deg;
  if (h.sensor_primary_altitude_m > 0.0f) r.altitude_m = h.sensor_primary_altitude_m;
  r.depth_m = h.sensor_depth_m;
  r.speed_m_s = static_cast<double>(h.sensor_speed_kn) * kMpsPerKnot;

  // dead reckoning of the distance travelled
  if (have_last_) {
    double dt = 0.0;
    const auto dn = static_cast<std::int32_t>(r.ping_number - last_.ping_number);
    const float per_ping = ping.channels.empty() ? 0.0f : ping.channels[0].seconds_per_ping_s;
    if (per_ping > 0.0f && dn > 0) {
      dt = dn * static_cast<double>(per_ping);
    } else if (r.time_utc_ns && last_.time_utc_ns) {
      dt = static_cast<double>(*r.time_utc_ns - *last_.time_utc_ns) * 1e-9;
    }
    double step = 0.0;
    if (r.speed_m_s > 0.0 && dt > 0.0) {
      step = r.speed_m_s * dt;
    } else {
      const double psi = r.heading_deg * kRadPerDeg;
      step =
          (r.north_m - last_.north_m) * std::cos(psi) + (r.east_m - last_.east_m) * std::sin(psi);
    }
    r.along_m = last_.along_m + step;
  }
  return r;
}

AddResult Waterfall::add(const xtf::XtfFileHeader& header, const xtf::XtfPing& ping) {
  const std::optional<Layout> l = layout_of(header, ping);
  if (!l) {
    ++unusable_;
    return AddResult::kUnusable;
  }
  AddResult result = AddResult::kAdded;
  if (!configured_ || l->bins != layout_.bins || l->kind != layout_.kind ||
      l->bin_size_m != layout_.bin_size_m || l->range_start_m != layout_.range_start_m) {
    if (configured_) {
      ++resets_;
      result = AddResult::kReset;
    }
    configure(*l);
  }
  layout_.port = l->port;
  layout_.stbd = l->stbd;

  const std::size_t slot = slot_of(next_seq_);
  PingRecord r = make_record(header, ping);
  const std::size_t n = static_cast<std::size_t>(bins_);
  float* base = levels_.data() + slot * 2 * n;
  const auto& port = ping.channels[static_cast<std::size_t>(l->port)];
  const auto& stbd = ping.channels[static_cast<std::size_t>(l->stbd)];
  fill_levels(port, xtf::stored_far_to_near(header.chan_info[port.channel_number]), base);
  fill_levels(stbd, xtf::stored_far_to_near(header.chan_info[stbd.channel_number]), base + n);
  records_[slot] = r;
  last_ = r;
  have_last_ = true;
  ++next_seq_;
  count_ = std::min(count_ + 1, capacity_);
  return result;
}

const PingRecord& Waterfall::record(std::uint64_t seq) const {
  if (!contains(seq)) throw std::out_of_range("waterfall: ping " + std::to_string(seq) + " gone");
  return records_[slot_of(seq)];
}

std::span<const float> Waterfall::levels(std::uint64_t seq, int side) const {
  if (!contains(seq)) throw std::out_of_range("waterfall: ping " + std::to_string(seq) + " gone");
  const std::size_t n = static_cast<std::size_t>(bins_);
  return {levels_.data() + (slot_of(seq) * 2 + static_cast<std::size_t>(side != 0)) * n, n};
}

GeoPoint Waterfall::to_geodetic(double north_m, double east_m) const {
  if (!geodetic_stream_)
    throw std::logic_error("waterfall: the stream gives no latitude/longitude");
  return plane_->to_geodetic(north_m, east_m);
}

}  // namespace sonarloop::atr
