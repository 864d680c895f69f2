#pragma once
// The live operator view's page (docs/web.md): one HTML document with its script and style
// inline, nothing fetched from elsewhere (the machines it runs on are offline). It reads
// GET /events (web/web_events.h) and draws
//   - the waterfall: one row per ping at the line rate, newest at the top, port to the left of
//     the centre line and starboard to the right (near range at the centre), colours over the
//     display span in dB re full scale with its colour bar; "Pause" freezes the scroll while
//     the lines keep arriving (held, up to 4000, and drawn on "Resume"), the run goes on;
//   - the map: the track and the contacts in metres (north up, equal scales, a grid with its
//     spacing), the vehicle's latest position and heading;
//   - the contact table: id, class, mine / non-mine, the classifier's distance, ground range,
//     side, north and east;
//   - the statistics: pings, deadline misses, lateness p99, datagrams lost, CPU, contacts, the
//     line rate and the web view's own drops.

namespace sonarloop::web {

extern const char* const kWebPage;

}  // namespace sonarloop::web
