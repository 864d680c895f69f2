#include "emulator/recording.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <span>
#include <stdexcept>
#include <system_error>

#include "sim/core/geodesy.h"

namespace sonarloop::emulator {
namespace {
constexpr double kDegPerRad = 180.0 / std::numbers::pi;
}  // namespace

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
  truth_path_ = (d / "truth.csv").string();
  truth_ = std::fopen(truth_path_.c_str(), "w");
  if (!truth_) {
    throw std::runtime_error(truth_path_ + ": cannot create (" + std::strerror(errno) + ")");
  }
  std::fputs(
      "ping,t_s,time_utc_ns,north_m,east_m,depth_m,heading_deg,pitch_deg,roll_deg,altitude_m,"
      "latitude_deg,longitude_deg,speed_m_s,pose\n",
      truth_);
}

Recording::~Recording() {
  try {
    close();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "warning: closing the recording in %s: %s\n", dir_.c_str(), e.what());
  }
}

void Recording::write_ping(const PingSlot& slot) {
  xtf_->write_packet(std::span<const std::uint8_t>(slot.packet.data(), slot.packet_size));
  const PingTruth& t = slot.truth;
  const Pose& p = t.pose;
  char altitude[32] = "";
  if (std::isfinite(t.altitude_m)) std::snprintf(altitude, sizeof altitude, "%.4f", t.altitude_m);
  std::fprintf(truth_, "%lld,%.9f,%lld,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%s,%.9f,%.9f,%.4f,%s\n",
               static_cast<long long>(slot.index), to_seconds(t.t),
               static_cast<long long>(t.time_utc_ns), p.position_W.x(), p.position_W.y(),
               p.position_W.z(), heading_deg_from_yaw(p.yaw), p.pitch * kDegPerRad,
               p.roll * kDegPerRad, altitude, t.geo.latitude_deg, t.geo.longitude_deg, t.speed_m_s,
               t.external ? "external" : "trajectory");
  ++pings_;
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
    const bool bad = std::fflush(truth_) != 0 || std::ferror(truth_);
    std::fclose(truth_);
    truth_ = nullptr;
    if (bad) {
      if (!errors.empty()) errors += "; ";
      errors += truth_path_ + ": write error";
    }
  }
  if (!errors.empty()) throw std::runtime_error(errors);
}

}  // namespace sonarloop::emulator
