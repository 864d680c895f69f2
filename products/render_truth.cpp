// `sonarloop render`'s target truth (render_truth.h).
#include "products/render_truth.h"

#include <fstream>

#include "drivers/json/json_writer.h"
#include "sim/targets/target_type.h"

namespace sonarloop::products {
namespace {

void extend(int& lo, int& hi, int v) {
  if (v < 0) return;
  if (lo < 0 || v < lo) lo = v;
  if (hi < 0 || v > hi) hi = v;
}

}  // namespace

void add_ping_traces(std::vector<TargetTruth>& truth, std::size_t k,
                     std::span<const render::TargetTrace> traces) {
  for (const auto& tr : traces) {
    TargetTruth& t = truth[static_cast<std::size_t>(tr.target)];
    t.side = tr.side;
    const int p = static_cast<int>(k);
    if (tr.highlight_first >= 0) {
      extend(t.ping_first, t.ping_last, p);
      extend(t.sample_first, t.sample_last, tr.highlight_first);
      extend(t.sample_first, t.sample_last, tr.highlight_last);
      t.energy += tr.energy;
      t.energy_ping += tr.energy * p;
      t.energy_sample += tr.energy * 0.5 * (tr.highlight_first + tr.highlight_last);
    }
    if (tr.shadow_first >= 0) {
      extend(t.shadow_ping_first, t.shadow_ping_last, p);
      extend(t.shadow_first, t.shadow_last, tr.shadow_first);
      extend(t.shadow_first, t.shadow_last, tr.shadow_last);
    }
  }
}

void write_render_truth_json(const std::string& path, const RenderedLine& line,
                             const scene::Scene& sc, const std::vector<TargetTruth>& truth) {
  json::Writer w(true);
  w.begin_object().field("scenario", line.scenario).field("seed", line.seed);
  w.field("sonar", line.sonar);
  w.field("pings", static_cast<std::uint64_t>(line.pings))
      .field("bins_per_side", line.bins_per_side);
  w.field("bin_size_m", line.bin_size_m)
      .field("ping_spacing_m", line.ping_spacing_m)
      .field("altitude_m", line.altitude_m);
  w.field("frame",
          "track_m and position_m are [north, east] in metres from the scenario origin (the frame "
          "of scene.json and of the onboard consumer's contacts, north_m / east_m)");
  w.key("origin")
      .begin_object()
      .field("latitude_deg", line.latitude_deg, 9)
      .field("longitude_deg", line.longitude_deg, 9)
      .end_object();
  w.key("track_m").begin_array();
  w.begin_array().value(line.track_start.x()).value(line.track_start.y()).end_array();
  w.begin_array().value(line.track_end.x()).value(line.track_end.y()).end_array();
  w.end_array();
  w.field(
      "indexing",
      "ping = XTF PingNumber (0 = first, at track start); sample = slant-range bin of that side "
      "counted from nadir (bin k covers [k, k+1) * bin_size_m); in waterfall.png a port sample "
      "is at column bins-1-sample, a starboard one at bins+sample, and ping p at row pings-1-p");
  w.key("targets").begin_array();
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const auto& t = truth[i];
    const auto& pt = sc.targets()[i];
    w.begin_object()
        .field("name", pt.desc.name)
        .field("type", std::string(targets::target_type_info(pt.desc.type).key));
    w.key("position_m")
        .begin_array()
        .value(pt.desc.position_m.x())
        .value(pt.desc.position_m.y())
        .end_array();
    w.field("seen", t.ping_first >= 0);
    if (t.ping_first >= 0) {
      w.field("side", t.side == 0 ? "port" : "starboard");
      w.key("highlight")
          .begin_object()
          .field("ping_first", t.ping_first)
          .field("ping_last", t.ping_last)
          .field("sample_first", t.sample_first)
          .field("sample_last", t.sample_last)
          .field("centroid_ping", t.energy_ping / t.energy, 6)
          .field("centroid_sample", t.energy_sample / t.energy, 6)
          .end_object();
      w.key("shadow").begin_object();
      if (t.shadow_first >= 0) {
        w.field("ping_first", t.shadow_ping_first)
            .field("ping_last", t.shadow_ping_last)
            .field("sample_first", t.shadow_first)
            .field("sample_last", t.shadow_last);
      }
      w.end_object();
    }
    w.end_object();
  }
  w.end_array();
  w.field("renderer", line.renderer);
  w.field("render_s", line.render_s, 4).field("threads", line.threads);
  w.end_object();
  std::ofstream(path) << w.str() << '\n';
}

}  // namespace sonarloop::products
