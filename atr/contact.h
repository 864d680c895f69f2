#pragma once
// Contact reports: what the onboard consumer tells the vehicle (or a log) about each object it
// detects, one JSON object per line (JSON Lines), written as soon as the object is classified.
//
// Example (one line, wrapped here):
//   {"contact":1,"time_utc":"2026-01-01T00:00:08.88Z","time_utc_ns":1767225608880000000,
//    "ping":132,"side":"starboard","latitude_deg":55.8998634,"longitude_deg":-3.19983958,
//    "north_m":-29.91,"east_m":10.07,"slant_range_m":12.31,"ground_range_m":9.98,
//    "class":"manta","mine_like":true,"distance":43.2,"runner_up":"rockan",
//    "runner_up_distance":45.1,"scores":{"cuboid":46.0,"cylinder":47.9,"manta":43.2,"rockan":45.1},
//    "mine_distance":43.2,"non_mine_distance":null,"aspect_sector_deg":[0,45],
//    "detection":{"pings":6,"along_extent_m":0.69,"height_m":0.6,"shadow_area_m2":0.42,
//    "highlight_db":0.0},"alignment":{"rows":-1,"cols":3,"windows":110}}
//
// Fields
//   contact          1, 2, ... in the order reported
//   time_utc(_ns)    the ping time of the ping nearest the object's centre (XTF: 1/100 s)
//   ping             its XTF PingNumber
//   side             "port" or "starboard"
//   latitude_deg, longitude_deg   the object's position (WGS84), when the stream gives
//                    latitude/longitude (NavUnits 3); from the navigation of the pings around
//                    the object (averaged), its side, its ground range and the pitch offset
//   north_m, east_m  the same point in metres: for latitude/longitude streams, in the local
//                    tangent plane of the scenario's origin (OnboardOptions::frame_origin: the
//                    frame of the scenario's scene.json and truth.json; `onboard --origin
//                    first-ping`: the stream's first ping with a fix); for metre streams,
//                    the stream's own northing/easting
//   slant_range_m, ground_range_m   of the object's centre from the sonar at closest approach
//   class            the identified class, null without a model
//   mine_like        the mine / non-mine decision (Section 4.1.2), null without a model
//   distance, runner_up, runner_up_distance, scores: eq. 10 distances (smaller = closer; chips
//                    unrelated to a class lie about sqrt(pixels) = 60 away for 60 x 60 chips);
//                    the target classes only
//   clutter_distance only with a model that has a clutter class (the detector's false alarms,
//                    atr/subspace_classifier.h): its distance
//   mine_distance, non_mine_distance  the group scores (null for a group without classes)
//   aspect_sector_deg  the aspect sector of the nearest subspace of the identified class
//   looks, object, fused_class, fused_mine_like  only when the object was seen before (another
//                    pass or aspect, atr/look_fusion.h): how many looks, the first look's contact
//                    id, and the decision from all the looks' distances
//   unknown, open_set_score  only with a model trained with open-set rejection: the distance
//                    over the identified class's reject distance, and whether it exceeds 1 (an
//                    object unlike every trained type; "class" then names the nearest one)
//   target_probability  only with a model that has a contact gate (atr/contact_gate.h): the
//                    calibrated probability that the object is a target, not clutter
//   detection        the detector's measurements (atr/detector.h): pings, along_extent_m,
//                    height_m, shadow_area_m2, highlight_db (dB re full scale),
//                    highlight_above_db and shadow_below_db (against the local background),
//                    highlight_area_m2, clutter_hits_per_m (the seabed around it)
//   alignment        the chip window's shift from the detector's centre, in pixels, and the
//                    windows classified (atr/aligned_classifier.h)
//   status           present only when the object could not be classified: "no_model", or
//                    why the chip failed (cut: not_yet/gone/gap/outside; chip: constant/...)
//   Non-finite numbers are written as null. Nothing depends on the wall clock: the same stream
//   gives byte-identical reports (timings go to the pipeline's statistics).
//
// Transport. To a file or stdout as JSON Lines; or, with `onboard --contacts udp:HOST:PORT`
// (also `run --classify MODEL --contacts udp:HOST:PORT`), over UDP: one datagram per contact,
// holding exactly one line of JSON as above without the newline (a few hundred bytes, far below
// a datagram's limit), sent as soon as the contact is decided. A missing receiver loses the
// contacts (UDP); readers should skip a datagram that does not parse. The example autonomy agent
// reads this stream (`sonarloop autonomy --contacts udp:HOST:PORT`, docs/autonomy.md).
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sonarloop::atr {

struct Contact {
  std::uint64_t id = 0;
  std::optional<std::int64_t> time_utc_ns;
  std::uint32_t ping_number = 0;
  int side = 1;  // 0 port, 1 starboard
  std::optional<double> latitude_deg;
  std::optional<double> longitude_deg;
  double north_m = 0.0;
  double east_m = 0.0;
  double slant_range_m = 0.0;
  double ground_range_m = 0.0;
  // classification (empty class_name: none)
  std::string class_name;
  bool mine_like = false;
  double distance = 0.0;
  std::string runner_up;
  double runner_up_distance = 0.0;
  std::vector<std::pair<std::string, double>> scores;  // class name, distance
  double mine_distance = 0.0;
  double non_mine_distance = 0.0;
  double aspect_min_deg = 0.0, aspect_max_deg = 360.0;
  // multi-look fusion (atr/look_fusion.h): reported when the object was seen before
  int looks = 1;
  std::uint64_t object = 0;  // the contact id of the object's first look
  std::string fused_class;
  bool fused_mine_like = false;
  // open-set rejection, when the model has it (TrainOptions::reject_quantile)
  std::optional<double> open_set_score;
  bool unknown = false;
  // the contact gate's probability that it is a target (atr/contact_gate.h), when the model has
  // a gate
  std::optional<double> target_probability;
  // the nearest clutter class's distance, when the model has one (scores hold target classes)
  std::optional<double> clutter_distance;
  std::string status;  // empty when classified
  // detection
  int pings = 0;
  double along_extent_m = 0.0;
  double height_m = 0.0;
  double shadow_area_m2 = 0.0;
  double highlight_db = 0.0;
  double highlight_above_db = 0.0;  // the highlight's peak above the local background
  double shadow_below_db = 0.0;     // the shadow's mean depth below it
  double highlight_area_m2 = 0.0;   // the highlight's extent
  double clutter_hits_per_m = 0.0;  // the local seabed's ping detections per metre
  // alignment
  int shift_rows = 0, shift_cols = 0;
  int windows = 0;
};

// "2026-01-01T00:00:08.88Z" (hundredths, as XTF stores them).
std::string format_utc(std::int64_t t_ns);

// The contact as one line of JSON, without the newline.
std::string contact_json(const Contact& c);

}  // namespace sonarloop::atr
