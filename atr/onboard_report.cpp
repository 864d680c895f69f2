#include "atr/onboard_report.h"

#include <cstdint>
#include <cstdio>

#include "drivers/json/json_writer.h"

namespace sonarloop::atr {
namespace {

unsigned long long ull(std::uint64_t v) {
  return static_cast<unsigned long long>(v);
}

}  // namespace

void print_onboard_stats(const char* who, const OnboardStats& s, const PacketQueue* queue) {
  const ReceiverStats& r = s.receiver;
  std::fprintf(stderr,
               "%s: %llu datagrams (%llu file headers), %llu pings; lost %llu, late %llu, "
               "duplicated %llu, reordered %llu, malformed %llu, before a header %llu\n",
               who, ull(r.datagrams), ull(r.file_headers), ull(r.pings), ull(r.lost), ull(r.late),
               ull(r.duplicates), ull(r.reordered), ull(r.malformed), ull(r.before_header));
  if (r.other_packets || r.restarts || r.header_changes || r.unconfirmed || s.waterfall_unusable) {
    std::fprintf(stderr,
                 "  also: %llu other XTF packets, %llu stream restarts, %llu header changes, "
                 "%llu unconfirmed ping-number jumps (junk), %llu unusable pings\n",
                 ull(r.other_packets), ull(r.restarts), ull(r.header_changes), ull(r.unconfirmed),
                 ull(s.waterfall_unusable));
  }
  if (queue) {
    std::fprintf(stderr,
                 "  queue: %llu datagrams, %llu dropped (queue full), %llu oversize; high water "
                 "%zu of %zu\n",
                 ull(queue->pushed()), ull(queue->dropped_full()), ull(queue->dropped_oversize()),
                 queue->high_water(), queue->capacity());
  }
  const DetectorStats& d = s.detector;
  std::fprintf(stderr,
               "  detector: %llu ping detections, %llu objects, %llu rejected by the gates, %llu "
               "suppressed, %llu reported\n",
               ull(d.ping_detections), ull(d.objects), ull(d.rejected), ull(d.suppressed),
               ull(d.reported));
  std::fprintf(stderr, "  contacts: %llu (%llu classified, %llu not)", ull(s.contacts),
               ull(s.classified), ull(s.unclassified));
  if (s.windows) {
    std::fprintf(stderr,
                 "; %llu chips classified in %.3f s: %.3f ms per chip, %.1f ms per contact "
                 "(max %.1f ms)",
                 ull(s.windows), s.classify_total_s, s.seconds_per_chip() * 1e3,
                 s.seconds_per_contact() * 1e3, s.classify_max_s * 1e3);
  }
  std::fprintf(stderr, "\n");
}

std::string onboard_stats_json(const OnboardStats& s, const PacketQueue* queue) {
  const ReceiverStats& r = s.receiver;
  json::Writer w;
  w.begin_object();
  w.key("receiver").begin_object();
  w.field("datagrams", r.datagrams).field("bytes", r.bytes).field("file_headers", r.file_headers);
  w.field("header_changes", r.header_changes).field("pings", r.pings).field("lost", r.lost);
  w.field("late", r.late).field("duplicates", r.duplicates).field("reordered", r.reordered);
  w.field("malformed", r.malformed).field("before_header", r.before_header);
  w.field("other_packets", r.other_packets).field("restarts", r.restarts);
  w.field("unconfirmed", r.unconfirmed);
  w.end_object();
  if (queue) {
    w.key("queue").begin_object();
    w.field("pushed", queue->pushed()).field("dropped_full", queue->dropped_full());
    w.field("dropped_oversize", queue->dropped_oversize());
    w.field("high_water", static_cast<std::uint64_t>(queue->high_water()));
    w.end_object();
  }
  w.field("unusable_pings", s.waterfall_unusable).field("waterfall_resets", s.waterfall_resets);
  const DetectorStats& d = s.detector;
  w.key("detector").begin_object();
  w.field("pings", d.pings).field("pings_no_altitude", d.pings_no_altitude);
  w.field("ping_detections", d.ping_detections).field("objects", d.objects);
  w.field("rejected", d.rejected).field("suppressed", d.suppressed);
  w.field("reported", d.reported).field("overflows", d.overflows);
  w.end_object();
  w.field("contacts", s.contacts).field("classified", s.classified);
  w.field("unclassified", s.unclassified).field("chips", s.windows);
  w.field("classify_total_s", s.classify_total_s, 6);
  w.field("ms_per_chip", s.seconds_per_chip() * 1e3, 6);
  w.field("ms_per_contact", s.seconds_per_contact() * 1e3, 6);
  w.field("ms_max_contact", s.classify_max_s * 1e3, 6);
  w.end_object();
  return w.str();
}

}  // namespace sonarloop::atr
