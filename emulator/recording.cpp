#include "emulator/recording.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <span>
#include <stdexcept>
#include <system_error>

#include "common/geodesy.h"
#include "units/angles.h"

namespace sonarloop::emulator {
namespace {}  // namespace

Recording::Recording(const std::string& dir, const xtf::XtfFileHeader& header,
                     const std::string& can_channel)
    : dir_(dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) {
    throw std::runtime_error("--record " + dir + ": cannot create the directory (" +
                             (ec ? ec.message() : std::string("not a directory")) + ")");
  }
  const fs::path d(dir);
  xtf_ = std::make_unique<xtf::XtfWriter>((d / "pings.xtf").string(), header);
  nav_log_ = std::make_unique<can::CandumpLogWriter>((d / "nav.log").string(), can_channel);
  truth_ = std::make_unique<io::LineFile>((d / "truth.csv").string(), "truth");
  truth_->append(
      "ping,t_s,time_utc_ns,north_m,east_m,depth_m,heading_deg,pitch_deg,roll_deg,altitude_m,"
      "latitude_deg,longitude_deg,speed_m_s,pose\n");
}

Recording::~Recording() {
  try {
    close();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "warning: closing the recording in %s: %s\n", dir_.c_str(), e.what());
  }
}

void Recording::write_ping(const PingSlot& slot) {
  if (!error_.empty()) return;
  const PingTruth& t = slot.truth;
  const Pose& p = t.pose;
  char altitude[32] = "";
  if (std::isfinite(t.altitude_m)) std::snprintf(altitude, sizeof altitude, "%.4f", t.altitude_m);
  char row[512];
  const int n = std::snprintf(
      row, sizeof row, "%lld,%.9f,%lld,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%s,%.9f,%.9f,%.4f,%s\n",
      static_cast<long long>(slot.index), to_seconds(t.t), static_cast<long long>(t.time_utc_ns),
      p.position_W.x(), p.position_W.y(), p.position_W.z(), heading_deg_from_yaw(p.yaw),
      p.pitch * kDegPerRad, p.roll * kDegPerRad, altitude, t.geo.latitude_deg, t.geo.longitude_deg,
      t.speed_m_s, t.external ? "external" : "trajectory");
  try {
    xtf_->write_packet(std::span<const std::uint8_t>(slot.packet.data(), slot.packet_size));
    truth_->append(std::string_view(row, static_cast<std::size_t>(std::clamp(n, 0, 511))));
  } catch (const std::runtime_error& e) {
    error_ = e.what();
    return;
  }
  ++pings_;
}

void Recording::write_nav(const can::CanFrame& frame, std::int64_t t_ns) {
  if (!error_.empty()) return;
  try {
    nav_log_->write(frame, t_ns);
  } catch (const std::runtime_error& e) {
    error_ = e.what();
  }
}

void Recording::close() {
  std::string errors;
  if (xtf_) {
    try {
      xtf_->close();
    } catch (const std::exception& e) {
      errors += e.what();
    }
  }
  if (nav_log_) {
    try {
      nav_log_->close();
    } catch (const std::exception& e) {
      if (!errors.empty()) errors += "; ";
      errors += e.what();
    }
  }
  if (truth_) {
    try {
      truth_->close();
    } catch (const std::exception& e) {
      if (!errors.empty()) errors += "; ";
      errors += e.what();
    }
  }
  if (!errors.empty()) throw std::runtime_error(errors);
}

}  // namespace sonarloop::emulator
