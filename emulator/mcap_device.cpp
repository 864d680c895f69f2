#include "emulator/mcap_device.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "drivers/ros2/ros2_messages.h"

namespace sonarloop::emulator {
namespace {

// The pixel (0..255) of an amplitude re full scale: 60 dB below full scale to full scale.
std::uint8_t pixel_of(double amplitude) {
  if (!(amplitude > 0.0)) return 0;
  const double db = 20.0 * std::log10(amplitude);
  return static_cast<std::uint8_t>(std::clamp(std::lround(255.0 * (db + 60.0) / 60.0), 0L, 255L));
}

template <class T>
double full_scale() {
  if constexpr (std::is_floating_point_v<T>) {
    return 1.0;
  } else {
    return static_cast<double>(std::numeric_limits<T>::max());
  }
}

// The samples of an XTF channel near to far, little-endian, into out; the ROS dtype.
std::uint32_t samples_near_to_far(const xtf::XtfPingChannel& c, bool stored_far_to_near,
                                  std::vector<std::uint8_t>& out) {
  out.clear();
  std::uint32_t dtype = ros2::RawSonarImage::kDtypeUint16;
  std::visit(
      [&](const auto& v) {
        using T = typename std::decay_t<decltype(v)>::value_type;
        if constexpr (std::is_same_v<T, std::uint8_t>) {
          dtype = ros2::RawSonarImage::kDtypeUint8;
        } else if constexpr (std::is_same_v<T, std::uint16_t>) {
          dtype = ros2::RawSonarImage::kDtypeUint16;
        } else if constexpr (std::is_same_v<T, float>) {
          dtype = ros2::RawSonarImage::kDtypeFloat32;
        } else {
          dtype = 4;  // DTYPE_UINT32
        }
        const std::size_t n = v.size();
        out.resize(n * sizeof(T));
        for (std::size_t k = 0; k < n; ++k) {
          const T s = v[stored_far_to_near ? n - 1 - k : k];
          std::memcpy(out.data() + k * sizeof(T), &s, sizeof(T));  // little-endian hosts
        }
      },
      c.samples);
  return dtype;
}

}  // namespace

std::array<double, 4> enu_flu_quaternion(double yaw, double pitch, double roll) {
  // REP 103: yaw about up from east = pi/2 - heading; pitch about left = -pitch (nose up is a
  // negative rotation about the left axis); roll about forward unchanged (starboard down is
  // positive about forward in both). Quaternion of Rz(y) Ry(p) Rx(r).
  const double y = 0.5 * (0.5 * std::numbers::pi - yaw);
  const double p = 0.5 * -pitch;
  const double r = 0.5 * roll;
  const double cy = std::cos(y), sy = std::sin(y), cp = std::cos(p), sp = std::sin(p),
               cr = std::cos(r), sr = std::sin(r);
  return {sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
          cr * cp * cy + sr * sp * sy};
}

McapDevice::McapDevice(const std::string& path, const LocalTangentPlane& origin,
                       const McapSonarInfo& sonar, mcap::WriterOptions options)
    : origin_(origin), sonar_(sonar), writer_(std::make_unique<mcap::Writer>(path, options)) {
  const auto schema = [&](const ros2::MessageSchema& s) { return add_schema(s); };
  const std::uint16_t sonar_schema = schema(ros2::raw_sonar_image_schema());
  const std::uint16_t image_schema = schema(ros2::image_schema());
  fix_schema_ = schema(ros2::nav_sat_fix_schema());
  const std::uint16_t pose_schema = schema(ros2::pose_stamped_schema());
  port_ = writer_->add_channel(sonar_schema, "/sidescan/port", "cdr");
  stbd_ = writer_->add_channel(sonar_schema, "/sidescan/starboard", "cdr");
  waterfall_ = writer_->add_channel(image_schema, "/sidescan/waterfall", "cdr");
  fix_ = writer_->add_channel(fix_schema_, "/nav/fix", "cdr");
  nav_pose_ = writer_->add_channel(pose_schema, "/nav/pose", "cdr");
  truth_ = writer_->add_channel(pose_schema, "/truth/pose", "cdr");
}

template <class F>
void McapDevice::guarded(F&& write) {
  if (!writer_ || !error_.empty()) return;
  try {
    write();
  } catch (const std::exception& e) {
    error_ = e.what();
    std::fprintf(stderr, "warning: MCAP recording stopped: %s\n", error_.c_str());
  }
}

void McapDevice::ping(const PingSlot& slot, std::span<const std::uint8_t>) {
  if (slot.xtf.channels.size() != 2) return;
  guarded([&] {
    const std::int64_t t = slot.truth.time_utc_ns;
    last_ping_utc_ns_ = t;
    const auto stamp = static_cast<std::uint64_t>(t);
    for (int side = 0; side < 2; ++side) {
      ros2::RawSonarImage m;
      m.header = {t, "sonar"};
      m.frequency_hz = static_cast<float>(sonar_.frequency_hz);
      m.sound_speed_m_s = static_cast<float>(sonar_.sound_speed_m_s);
      m.sample_rate_hz = static_cast<float>(sonar_.sound_speed_m_s / (2.0 * sonar_.bin_size_m));
      m.rx_angle_rad = static_cast<float>((side == 0 ? -0.5 : 0.5) * std::numbers::pi);
      const xtf::XtfPingChannel& c = slot.xtf.channels[static_cast<std::size_t>(side)];
      m.dtype = samples_near_to_far(c, side == 0, samples_);
      m.samples = static_cast<std::uint32_t>(c.num_samples());
      m.data = samples_;
      ros2::encode(m, buffer_);
      writer_->write(side == 0 ? port_ : stbd_, seq_++, stamp, stamp, buffer_);
    }
    const Pose& p = slot.truth.pose;
    write_pose(truth_, t, p.position_W.x(), p.position_W.y(), p.position_W.z(), p.yaw, p.pitch,
               p.roll);
    waterfall_row(slot.xtf);
    if (++pings_ % kMcapWaterfallEvery == 0) write_waterfall(t);
  });
}

void McapDevice::waterfall_row(const xtf::XtfPing& ping) {
  const std::size_t n = ping.channels[0].num_samples();
  if (n == 0 || ping.channels[1].num_samples() != n) return;
  const std::size_t line = 2 * n;
  const std::size_t step = (line + kMcapWaterfallWidth - 1) / kMcapWaterfallWidth;
  if (width_ == 0) {
    width_ = static_cast<int>((line + step - 1) / step);
    rows_.assign(static_cast<std::size_t>(width_) * kMcapWaterfallRows, 0);
  }
  std::uint8_t* row = rows_.data() + static_cast<std::size_t>(next_row_) * width_;
  // the line across: port as stored (far to near), then starboard (near to far)
  std::size_t col = 0, in_col = 0;
  double sum = 0.0;
  for (int side = 0; side < 2; ++side) {
    std::visit(
        [&](const auto& v) {
          using T = typename std::decay_t<decltype(v)>::value_type;
          const double scale = 1.0 / full_scale<T>();
          for (const T s : v) {
            sum += static_cast<double>(s) * scale;
            if (++in_col == step) {
              if (col < static_cast<std::size_t>(width_))
                row[col++] = pixel_of(sum / static_cast<double>(step));
              sum = 0.0;
              in_col = 0;
            }
          }
        },
        ping.channels[static_cast<std::size_t>(side)].samples);
  }
  if (in_col > 0 && col < static_cast<std::size_t>(width_))
    row[col++] = pixel_of(sum / static_cast<double>(in_col));
  next_row_ = (next_row_ + 1) % kMcapWaterfallRows;
  rows_filled_ = std::min(rows_filled_ + 1, kMcapWaterfallRows);
}

void McapDevice::write_waterfall(std::int64_t utc_ns) {
  if (width_ == 0) return;
  const auto w = static_cast<std::size_t>(width_);
  image_.resize(w * static_cast<std::size_t>(rows_filled_));
  // newest row on top
  for (int r = 0; r < rows_filled_; ++r) {
    const int src = (next_row_ - 1 - r + kMcapWaterfallRows) % kMcapWaterfallRows;
    std::copy_n(rows_.data() + static_cast<std::size_t>(src) * w, w,
                image_.data() + static_cast<std::size_t>(r) * w);
  }
  ros2::Image m;
  m.header = {utc_ns, "sonar"};
  m.height = static_cast<std::uint32_t>(rows_filled_);
  m.width = static_cast<std::uint32_t>(width_);
  m.encoding = "mono8";
  m.step = static_cast<std::uint32_t>(width_);
  m.data = image_;
  ros2::encode(m, buffer_);
  const auto stamp = static_cast<std::uint64_t>(utc_ns);
  writer_->write(waterfall_, seq_++, stamp, stamp, buffer_);
}

void McapDevice::write_pose(std::uint16_t channel, std::int64_t utc_ns, double north_m,
                            double east_m, double depth_m, double yaw, double pitch, double roll) {
  ros2::PoseStamped m;
  m.header = {utc_ns, "map"};
  m.x = east_m;
  m.y = north_m;
  m.z = -depth_m;
  const auto q = enu_flu_quaternion(yaw, pitch, roll);
  m.qx = q[0];
  m.qy = q[1];
  m.qz = q[2];
  m.qw = q[3];
  ros2::encode(m, buffer_);
  const auto stamp = static_cast<std::uint64_t>(utc_ns);
  writer_->write(channel, seq_++, stamp, stamp, buffer_);
}

void McapDevice::write_fix(std::uint16_t channel, std::int64_t utc_ns, double north_m,
                           double east_m, double altitude_m) {
  const GeoPoint g = origin_.to_geodetic(north_m, east_m);
  ros2::NavSatFix fix;
  fix.header = {utc_ns, "map"};
  fix.latitude_deg = g.latitude_deg;
  fix.longitude_deg = g.longitude_deg;
  fix.altitude_m = altitude_m;
  ros2::encode(fix, buffer_);
  const auto stamp = static_cast<std::uint64_t>(utc_ns);
  writer_->write(channel, seq_++, stamp, stamp, buffer_);
}

void McapDevice::nav_solution(const vehicle::NavSolution& s, std::int64_t utc_ns) {
  guarded([&] {
    write_fix(fix_, utc_ns, s.north_m, s.east_m, -s.depth_m);
    write_pose(nav_pose_, utc_ns, s.north_m, s.east_m, s.depth_m, s.heading, s.pitch, s.roll);
  });
}

void McapDevice::add_stats(RunStats& stats) const {
  stats.mcap_messages = writer_ ? writer_->messages() : 0;
  stats.mcap_error = error_;
}

std::vector<std::string> McapDevice::describe() const {
  return {writer_->path() + ": MCAP for ROS 2 (sidescan, waterfall image, navigation, truth)"};
}

std::uint16_t McapDevice::add_schema(const ros2::MessageSchema& s) {
  return writer_->add_schema(
      s.name, "ros2msg",
      {reinterpret_cast<const std::uint8_t*>(s.definition.data()), s.definition.size()});
}

void McapDevice::record_contacts() {
  if (record_contacts_) return;
  record_contacts_ = true;
  contacts_ = writer_->add_channel(add_schema(ros2::string_schema()), "/contacts", "cdr");
  // the NavSatFix schema the navigation's channel already has
  contact_fix_ = writer_->add_channel(fix_schema_, "/contacts/fix", "cdr");
}

void McapDevice::add_contact(McapContact contact) {
  if (!record_contacts_) throw std::logic_error("McapDevice::add_contact before record_contacts");
  const std::lock_guard lock(contacts_mutex_);
  pending_.push_back(std::move(contact));
}

void McapDevice::write_contacts() {
  std::vector<McapContact> contacts;
  {
    const std::lock_guard lock(contacts_mutex_);
    contacts.swap(pending_);
  }
  for (McapContact& c : contacts)
    if (!c.time_utc_ns) c.time_utc_ns = last_ping_utc_ns_;
  std::stable_sort(contacts.begin(), contacts.end(), [](const auto& a, const auto& b) {
    return std::pair(*a.time_utc_ns, a.id) < std::pair(*b.time_utc_ns, b.id);
  });
  for (const McapContact& c : contacts) {
    const std::int64_t t = *c.time_utc_ns;
    const auto stamp = static_cast<std::uint64_t>(t);
    ros2::encode_string(c.json, buffer_);
    writer_->write(contacts_, seq_++, stamp, stamp, buffer_);
    write_fix(contact_fix_, t, c.north_m, c.east_m, std::numeric_limits<double>::quiet_NaN());
  }
}

void McapDevice::close() {
  if (!writer_) return;
  guarded([&] {
    if (record_contacts_) write_contacts();
    writer_->close();
  });
}

}  // namespace sonarloop::emulator
