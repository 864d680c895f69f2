#pragma once
// A synthetic two-channel sidescan stream for the onboard tests: the XTF file header and pings
// (uint16 samples, as the emulator sends them) whose levels per bin the test chooses, with
// navigation along a line, so that the receiver, waterfall, detector and chip cutter can be
// checked against a known answer.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

#include "common/geodesy.h"
#include "common/rng.h"
#include "drivers/xtf/xtf_codec.h"
#include "drivers/xtf/xtf_types.h"

namespace sonarloop::testing {

// The stream's origin (the default scenario's, Edinburgh-ish).
inline const GeoPoint kStreamOrigin{55.9, -3.2};
inline constexpr double kKnotsPerMps = 3600.0 / 1852.0;

// A header of two sidescan channels of uint16 (2), uint8 (1) or float (4) samples: ChanInfo[0]
// port, [1] starboard.
inline xtf::XtfFileHeader make_stream_header(std::uint8_t bytes_per_sample = 2) {
  xtf::XtfFileHeader h;
  h.nav_units = xtf::kNavUnitsLatLong;
  h.number_of_sonar_channels = 2;
  for (int c = 0; c < 2; ++c) {
    xtf::XtfChanInfo ci;
    ci.type_of_channel = c == 0 ? xtf::kChannelPort : xtf::kChannelStbd;
    ci.sub_channel_number = static_cast<std::uint8_t>(c);
    ci.bytes_per_sample = bytes_per_sample;
    ci.sample_format = bytes_per_sample == 4   ? xtf::kSampleFormatIeeeFloat32
                       : bytes_per_sample == 2 ? xtf::kSampleFormatInt16
                                               : xtf::kSampleFormatInt8;
    h.chan_info.push_back(ci);
  }
  return h;
}

// Navigation and timing of one synthetic ping.
struct PingPose {
  std::uint32_t number = 0;
  double north_m = 0.0;  // in the plane of kStreamOrigin
  double east_m = 0.0;
  double heading_deg = 0.0;
  double pitch_deg = 0.0;
  double altitude_m = 7.5;
  double speed_m_s = 2.0;
  double period_s = 0.0675;  // seconds per ping
  std::int64_t t0_utc_ns = 1767225600LL * 1'000'000'000LL;
};

// uint16 sample of a level in dB re full scale (clipped to 0..65535; below -96 dB gives 0).
inline std::uint16_t sample_of_db(double level_db) {
  const double s = std::round(std::pow(10.0, level_db / 20.0) * 65535.0);
  return static_cast<std::uint16_t>(std::clamp(s, 0.0, 65535.0));
}

// A ping with the given levels (near to far, one per bin of bin_m) on each side, in the
// header's sample type.
inline xtf::XtfPing make_ping(const xtf::XtfFileHeader& h, const PingPose& pose,
                              std::span<const float> port_db, std::span<const float> stbd_db,
                              double bin_m) {
  xtf::XtfPing p;
  p.header.ping_number = pose.number;
  xtf::set_time_utc_ns(
      p.header,
      pose.t0_utc_ns + static_cast<std::int64_t>(std::llround(pose.number * pose.period_s * 1e9)));
  const LocalTangentPlane plane(kStreamOrigin);
  const GeoPoint g = plane.to_geodetic(pose.north_m, pose.east_m);
  p.header.sensor_y = g.latitude_deg;
  p.header.sensor_x = g.longitude_deg;
  p.header.ship_y = g.latitude_deg;
  p.header.ship_x = g.longitude_deg;
  p.header.sensor_heading_deg = static_cast<float>(pose.heading_deg);
  p.header.sensor_pitch_deg = static_cast<float>(pose.pitch_deg);
  p.header.sensor_primary_altitude_m = static_cast<float>(pose.altitude_m);
  p.header.sensor_speed_kn = static_cast<float>(pose.speed_m_s * kKnotsPerMps);
  for (int c = 0; c < 2; ++c) {
    const std::span<const float> db = c == 0 ? port_db : stbd_db;
    xtf::XtfPingChannel ch;
    ch.channel_number = static_cast<std::uint16_t>(c);
    ch.slant_range_m = static_cast<float>(static_cast<double>(db.size()) * bin_m);
    ch.time_duration_s = ch.slant_range_m / 750.0f;
    ch.seconds_per_ping_s = static_cast<float>(pose.period_s);
    const xtf::XtfChanInfo& info = h.chan_info[static_cast<std::size_t>(c)];
    if (info.bytes_per_sample == 4) {
      // float samples: amplitudes re full scale, exact
      std::vector<float> near_to_far(db.size());
      for (std::size_t k = 0; k < db.size(); ++k)
        near_to_far[k] = static_cast<float>(std::pow(10.0, db[k] / 20.0));
      xtf::store_samples_near_to_far<float>(ch, info, near_to_far);
    } else {
      std::vector<std::uint16_t> near_to_far(db.size());
      for (std::size_t k = 0; k < db.size(); ++k)
        near_to_far[k] = sample_of_db(db[k]);
      xtf::store_samples_near_to_far<std::uint16_t>(ch, info, near_to_far);
    }
    p.channels.push_back(std::move(ch));
  }
  return p;
}

// A speckled seabed line: level mean_db + 10 log10(E), E exponential of mean 1 (fully developed
// speckle), at slant ranges beyond the altitude; no echo (kNoEcho) before it.
inline std::vector<float> seabed_line(Rng& rng, int bins, double bin_m, double altitude_m,
                                      double mean_db) {
  std::vector<float> v(static_cast<std::size_t>(bins), -150.0f);
  for (int k = 0; k < bins; ++k) {
    if ((k + 0.5) * bin_m < altitude_m) continue;
    v[static_cast<std::size_t>(k)] =
        static_cast<float>(mean_db + 10.0 * std::log10(rng.exponential(1.0)));
  }
  return v;
}

// Something on the seabed of one side: a highlight (full scale) over ground range
// [ground_m - 0.15, ground_m) and the shadow (no echo, -90 dB) that an object height_m tall casts
// behind it, hiding h g / (a - h) of seabed (similar triangles); each may be left out. It shows
// in the pings whose footprint lies within length_m / 2 of along_m.
struct SeabedObject {
  int side = 1;
  double along_m = 0.0;
  double ground_m = 0.0;
  double length_m = 1.0;
  double height_m = 0.4;
  bool highlight = true;
  bool shadow = true;
};

inline int bin_of_ground(double ground_m, double altitude_m, double bin_m) {
  return static_cast<int>(std::floor(std::hypot(ground_m, altitude_m) / bin_m));
}

// Draws `o` into one side's line (near to far, bins of bin_m) of a ping at `altitude_m`.
inline void draw_object(std::vector<float>& line, double bin_m, double altitude_m,
                        const SeabedObject& o) {
  const auto bin = [&](double g) { return bin_of_ground(g, altitude_m, bin_m); };
  if (o.highlight) {
    for (int k = bin(o.ground_m - 0.15); k < bin(o.ground_m); ++k)
      line[static_cast<std::size_t>(k)] = 0.0f;
  }
  if (o.shadow) {
    const double len = o.height_m * o.ground_m / (altitude_m - o.height_m);
    for (int k = bin(o.ground_m); k < bin(o.ground_m + len); ++k)
      line[static_cast<std::size_t>(k)] = -90.0f;
  }
}

// A straight north-going line at 2 m/s, one ping every period_s at `altitude_m`, pitch_deg(k) of
// pitch on ping k, a speckled seabed (-30 dB port, -22 dB starboard) with the objects drawn where
// each ping's footprint falls (north + altitude tan(pitch)). Calls sink(ping) for each.
template <class Pitch, class Sink>
void stream_line(int pings, const std::vector<SeabedObject>& objects, Pitch pitch_deg,
                 const xtf::XtfFileHeader& header, Sink sink, int bins = 1000, double bin_m = 0.05,
                 double altitude_m = 7.5, double period_s = 0.0675) {
  Rng rng(5, RngStream::kTraining, 90);
  constexpr double kSpeed_m_s = 2.0;
  for (int k = 0; k < pings; ++k) {
    PingPose pose;
    pose.number = static_cast<std::uint32_t>(k);
    pose.north_m = k * kSpeed_m_s * period_s;
    pose.speed_m_s = kSpeed_m_s;
    pose.period_s = period_s;
    pose.altitude_m = altitude_m;
    pose.pitch_deg = pitch_deg(k);
    const double footprint =
        pose.north_m + altitude_m * std::tan(pose.pitch_deg * std::numbers::pi / 180.0);
    std::vector<float> port = seabed_line(rng, bins, bin_m, altitude_m, -30.0);
    std::vector<float> stbd = seabed_line(rng, bins, bin_m, altitude_m, -22.0);
    for (const SeabedObject& o : objects) {
      if (std::abs(footprint - o.along_m) <= 0.5 * o.length_m)
        draw_object(o.side ? stbd : port, bin_m, altitude_m, o);
    }
    sink(make_ping(header, pose, port, stbd, bin_m));
  }
}

}  // namespace sonarloop::testing
