#include "atr/contact.h"

#include <cmath>
#include <cstdio>
#include <ctime>

#include "drivers/json/json_writer.h"

namespace sonarloop::atr {
namespace {

constexpr std::int64_t kNsPerS = 1'000'000'000;
constexpr std::int64_t kNsPerHundredth = 10'000'000;
// Significant digits: positions to 0.1 mm (latitude 55.xxxxxxx needs 10), distances to 0.1 mm.
constexpr int kLatLonDigits = 11;
constexpr int kMetreDigits = 7;
constexpr int kScoreDigits = 6;

}  // namespace

std::string format_utc(std::int64_t t_ns) {
  std::int64_t secs = t_ns / kNsPerS;
  std::int64_t rem = t_ns % kNsPerS;
  if (rem < 0) {
    rem += kNsPerS;
    --secs;
  }
  const auto t = static_cast<time_t>(secs);
  tm utc{};
  gmtime_r(&t, &utc);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%S", &utc);
  char out[48];
  std::snprintf(out, sizeof out, "%s.%02dZ", date, static_cast<int>(rem / kNsPerHundredth));
  return out;
}

std::string contact_json(const Contact& c) {
  json::Writer w;
  w.begin_object();
  w.field("contact", c.id);
  if (c.time_utc_ns) {
    w.field("time_utc", format_utc(*c.time_utc_ns));
    w.field("time_utc_ns", *c.time_utc_ns);
  } else {
    w.key("time_utc").null();
    w.key("time_utc_ns").null();
  }
  w.field("ping", static_cast<std::uint64_t>(c.ping_number));
  w.field("side", c.side == 1 ? "starboard" : "port");
  if (c.latitude_deg && c.longitude_deg) {
    w.field("latitude_deg", *c.latitude_deg, kLatLonDigits);
    w.field("longitude_deg", *c.longitude_deg, kLatLonDigits);
  }
  w.field("north_m", c.north_m, kMetreDigits);
  w.field("east_m", c.east_m, kMetreDigits);
  w.field("slant_range_m", c.slant_range_m, kMetreDigits);
  w.field("ground_range_m", c.ground_range_m, kMetreDigits);
  if (c.class_name.empty()) {
    w.key("class").null();
    w.key("mine_like").null();
  } else {
    w.field("class", c.class_name);
    w.field("mine_like", c.mine_like);
    w.field("distance", c.distance, kScoreDigits);
    if (c.runner_up.empty()) {
      w.key("runner_up").null();
    } else {
      w.field("runner_up", c.runner_up);
    }
    w.field("runner_up_distance", c.runner_up_distance, kScoreDigits);
    w.key("scores").begin_object();
    for (const auto& [name, d] : c.scores)
      w.field(name, d, kScoreDigits);
    w.end_object();
    w.field("mine_distance", c.mine_distance, kScoreDigits);
    w.field("non_mine_distance", c.non_mine_distance, kScoreDigits);
    w.key("aspect_sector_deg").begin_array();
    w.value(c.aspect_min_deg, kScoreDigits).value(c.aspect_max_deg, kScoreDigits);
    w.end_array();
    if (c.looks > 1) {
      w.field("looks", c.looks);
      w.field("object", c.object);
      w.field("fused_class", c.fused_class);
      w.field("fused_mine_like", c.fused_mine_like);
    }
    if (c.open_set_score) {
      w.field("unknown", c.unknown);
      w.field("open_set_score", *c.open_set_score, kScoreDigits);
    }
  }
  if (c.clutter_distance) w.field("clutter_distance", *c.clutter_distance, kScoreDigits);
  if (c.target_probability) w.field("target_probability", *c.target_probability, kScoreDigits);
  if (!c.status.empty()) w.field("status", c.status);
  w.key("detection").begin_object();
  w.field("pings", c.pings);
  w.field("along_extent_m", c.along_extent_m, kMetreDigits);
  w.field("height_m", c.height_m, kMetreDigits);
  w.field("shadow_area_m2", c.shadow_area_m2, kMetreDigits);
  w.field("highlight_db", c.highlight_db, kScoreDigits);
  w.field("highlight_above_db", c.highlight_above_db, kScoreDigits);
  w.field("shadow_below_db", c.shadow_below_db, kScoreDigits);
  w.field("highlight_area_m2", c.highlight_area_m2, kScoreDigits);
  w.field("clutter_hits_per_m", c.clutter_hits_per_m, kScoreDigits);
  w.end_object();
  w.key("alignment").begin_object();
  w.field("rows", c.shift_rows).field("cols", c.shift_cols).field("windows", c.windows);
  w.end_object();
  w.end_object();
  return w.str();
}

}  // namespace sonarloop::atr
