#pragma once
// The events of the live operator view (docs/web.md), as Server-Sent Events: "event: NAME\n"
// "data: JSON\n\n". Pure functions, no threads.
//
//   line     one ping: {"seq","ping","t_utc_ns","north_m","east_m","heading_deg","r0_m","r1_m",
//            "db0","db1","port","stbd"}; port and stbd are base64 of line_pixels bytes each,
//            near to far range, a byte b standing for the level db0 + b/255 x (db1 - db0) dB re
//            full scale (db0 = kDisplayMinDb, db1 = kDisplayMaxDb); r0_m..r1_m the slant range
//            they span; north_m/east_m the sonar's position in the stream's metres
//   track    {"north_m":[...],"east_m":[...]}: the track so far (catch-up of a new client)
//   contact  a contact report as `onboard` writes it (atr/contact.h)
//   stats    the latest statistics (WebHub::stats_json)
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace sonarloop::web {

// The displayed span of levels, dB re full scale: the span chips are cut from
// (atr/chip_preprocess.h maps -60..0 dB), and a 60 dB span is what a sidescan display shows.
inline constexpr float kDisplayMinDb = -60.0f;
inline constexpr float kDisplayMaxDb = 0.0f;
// The track keeps a point per this many metres travelled (a 20 m/s dash at 15 pings/s still
// gets a point per ping).
inline constexpr double kTrackStepM = 1.0;

// A level in dB as a display byte (0 at or below kDisplayMinDb, 255 at or above kDisplayMaxDb).
std::uint8_t level_byte(float level_db);

// Reduces `levels` (dB, near to far) to out.size() pixels: each pixel is the mean power of the
// samples it covers, 10 log10(mean(10^(L/10))), as a display byte; with fewer samples than
// pixels, each pixel takes the sample under its centre.
void reduce_line(std::span<const float> levels, std::span<std::uint8_t> out);

// RFC 4648 base64 with padding.
std::string base64(std::span<const std::uint8_t> bytes);

// "event: NAME\ndata: DATA\n\n" (data must be one line).
std::string sse_event(std::string_view name, std::string_view data);

}  // namespace sonarloop::web
