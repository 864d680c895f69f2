#include "tools/mission_report.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include "autonomy/json_line.h"
#include "drivers/json/json_writer.h"
#include "sim/targets/target_type.h"

namespace sonarloop::tools {
namespace {

struct Object {
  double north_m = 0, east_m = 0;
  std::string state, cls;
  bool mine_like = false;
  int looks = 0;
  bool relooked = false;
  int target = -1;
};

std::vector<Object> read_objects(const autonomy::JsonLine& report) {
  std::vector<Object> out;
  for (const autonomy::JsonLine& j : report.objects("objects")) {
    Object o;
    o.north_m = j.number("north_m").value_or(0.0);
    o.east_m = j.number("east_m").value_or(0.0);
    o.state = j.string("state").value_or("");
    o.cls = j.string("class").value_or("");
    o.mine_like = j.boolean("mine_like").value_or(false);
    o.looks = static_cast<int>(j.number("looks").value_or(0));
    o.relooked = j.boolean("relooked").value_or(false);
    out.push_back(o);
  }
  return out;
}

// Each target's nearest unmatched object within the radius (targets in order).
std::vector<int> match(const config::Scenario& sc, std::vector<Object>& objects) {
  std::vector<int> of_target(sc.scene.targets.size(), -1);
  for (std::size_t t = 0; t < sc.scene.targets.size(); ++t) {
    const Vec2 p = sc.scene.targets[t].position_m;
    double best = kTargetMatchRadius_m;
    for (std::size_t i = 0; i < objects.size(); ++i) {
      if (objects[i].target >= 0) continue;
      const double d = std::hypot(objects[i].north_m - p.x(), objects[i].east_m - p.y());
      if (d <= best) {
        best = d;
        of_target[t] = static_cast<int>(i);
      }
    }
    if (of_target[t] >= 0) objects[of_target[t]].target = static_cast<int>(t);
  }
  return of_target;
}

void summarise_relooks(const autonomy::JsonLine& report, MissionSummary& s) {
  double latency = 0, aspect = 0, range = 0;
  for (const autonomy::JsonLine& r : report.objects("relooks")) {
    ++s.relooks;
    const double l = r.number("latency_s").value_or(0.0);
    latency += l;
    s.latency_max_s = std::max(s.latency_max_s, l);
    if (r.boolean("passed").value_or(false)) {
      ++s.relooks_passed;
      aspect += r.number("aspect_change_deg").value_or(0.0);
      range += r.number("pass_range_m").value_or(0.0);
    }
    s.relooks_second_look += r.boolean("second_look").value_or(false);
  }
  if (s.relooks) s.latency_mean_s = latency / s.relooks;
  if (s.relooks_passed) {
    s.aspect_change_mean_deg = aspect / s.relooks_passed;
    s.pass_range_mean_m = range / s.relooks_passed;
  }
}

double fraction(int n, int d) {
  return d ? static_cast<double>(n) / d : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

std::string mission_report_json(const std::string& agent_report, const config::Scenario& sc,
                                const std::string& extra_fields_json, MissionSummary* summary) {
  std::string error;
  const auto report = autonomy::JsonLine::parse(agent_report, error);
  if (!report) throw std::runtime_error("the agent's report does not parse: " + error);
  MissionSummary s;
  std::vector<Object> objects = read_objects(*report);
  const std::vector<int> of_target = match(sc, objects);
  s.targets = static_cast<int>(sc.scene.targets.size());
  s.objects = static_cast<int>(objects.size());
  json::Writer w(true);
  w.begin_object();
  w.key("targets").begin_array();
  for (std::size_t t = 0; t < sc.scene.targets.size(); ++t) {
    const auto& info = targets::target_type_info(sc.scene.targets[t].type);
    w.begin_object();
    w.field("type", info.key).field("mine_like", info.mine_like);
    w.field("north_m", sc.scene.targets[t].position_m.x(), 8);
    w.field("east_m", sc.scene.targets[t].position_m.y(), 8);
    const int i = of_target[t];
    w.field("detected", i >= 0);
    if (i >= 0) {
      const Object& o = objects[i];
      const bool identified = o.cls == info.key;
      const bool mine_ok = !o.cls.empty() && o.mine_like == info.mine_like;
      ++s.detected;
      s.identified += identified;
      s.mine_correct += mine_ok;
      s.confirmed_correct += identified && o.state == "confirmed";
      w.field("class", o.cls).field("state", o.state).field("looks", o.looks);
      w.field("relooked", o.relooked).field("identified", identified);
      w.field("mine_correct", mine_ok);
    }
    w.end_object();
  }
  w.end_array();
  for (const Object& o : objects) {
    s.confirmed += o.state == "confirmed";
    s.false_contacts += o.target < 0;
  }
  summarise_relooks(*report, s);
  s.mission_time_s = report->number("sim_time_s").value_or(0.0);
  s.wall_time_s = report->number("wall_time_s").value_or(0.0);
  s.distance_m = report->number("distance_m").value_or(0.0);
  s.relook_distance_m = report->number("relook_distance_m").value_or(0.0);
  s.relook_time_s = report->number("relook_time_s").value_or(0.0);
  s.mission_done = report->boolean("mission_done").value_or(false);
  w.key("summary").begin_object();
  w.field("targets", s.targets).field("detected", s.detected).field("identified", s.identified);
  w.field("mine_correct", s.mine_correct);
  w.field("detected_fraction", fraction(s.detected, s.targets), 4);
  w.field("identified_fraction", fraction(s.identified, s.targets), 4);
  w.field("mine_correct_fraction", fraction(s.mine_correct, s.targets), 4);
  w.field("objects", s.objects).field("confirmed", s.confirmed);
  w.field("confirmed_correct", s.confirmed_correct).field("false_contacts", s.false_contacts);
  w.field("relooks", s.relooks).field("relooks_passed", s.relooks_passed);
  w.field("relooks_second_look", s.relooks_second_look);
  w.field("aspect_change_mean_deg", s.aspect_change_mean_deg, 6);
  w.field("pass_range_mean_m", s.pass_range_mean_m, 6);
  w.field("mission_time_s", s.mission_time_s, 8).field("wall_time_s", s.wall_time_s, 6);
  w.field("distance_m", s.distance_m, 8);
  w.field("relook_distance_m", s.relook_distance_m, 8);
  w.field("relook_time_s", s.relook_time_s, 8);
  w.field("latency_mean_s", s.latency_mean_s, 6).field("latency_max_s", s.latency_max_s, 6);
  w.field("mission_done", s.mission_done);
  w.end_object();
  w.end_object();
  // the run's settings and the agent's own report, spliced in as they are
  std::string out = w.str();
  out.pop_back();  // the closing brace
  while (!out.empty() && (out.back() == '\n' || out.back() == ' '))
    out.pop_back();
  out += ",\n  " + extra_fields_json + ",\n  \"agent\": " + agent_report + "}\n";
  if (summary) *summary = s;
  return out;
}

void print_mission_summary(const MissionSummary& s) {
  std::fprintf(stderr,
               "mission: %d targets: %d detected, %d identified, %d mine / non-mine right; %d "
               "objects, %d confirmed (%d right), %d false contacts\n",
               s.targets, s.detected, s.identified, s.mine_correct, s.objects, s.confirmed,
               s.confirmed_correct, s.false_contacts);
  std::fprintf(stderr,
               "mission: %.0f s of mission (%.1f s wall), %.0f m; re-looks: %d (%d passed, %d "
               "seen again), %.0f m and %.0f s extra, aspect change %.1f deg, pass range %.1f "
               "m, latency mean %.1f s max %.1f s (mission time)%s\n",
               s.mission_time_s, s.wall_time_s, s.distance_m, s.relooks, s.relooks_passed,
               s.relooks_second_look, s.relook_distance_m, s.relook_time_s,
               s.aspect_change_mean_deg, s.pass_range_mean_m, s.latency_mean_s, s.latency_max_s,
               s.mission_done ? "" : " [mission not finished]");
}

}  // namespace sonarloop::tools
