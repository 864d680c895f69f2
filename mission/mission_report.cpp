#include "mission/mission_report.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include "autonomy/json_line.h"
#include "drivers/json/json_writer.h"
#include "sim/targets/target_type.h"

namespace sonarloop::mission {
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
std::vector<int> match(const Scenario& sc, std::vector<Object>& objects, double radius_m) {
  std::vector<int> of_target(sc.scene.targets.size(), -1);
  for (std::size_t t = 0; t < sc.scene.targets.size(); ++t) {
    const Vec2 p = sc.scene.targets[t].position_m;
    double best = radius_m;
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

std::string mission_report_json(const std::string& agent_report, const Scenario& sc,
                                const std::string& extra_fields_json, MissionSummary* summary,
                                double match_radius_m) {
  std::string error;
  const auto report = autonomy::JsonLine::parse(agent_report, error);
  if (!report) throw std::runtime_error("the agent's report does not parse: " + error);
  MissionSummary s;
  std::vector<Object> objects = read_objects(*report);
  const std::vector<int> of_target = match(sc, objects, match_radius_m);
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
  w.end_object();
  // the summary, the run's settings and the agent's own report, spliced in as they are
  std::string out = w.str();
  out.pop_back();  // the closing brace
  while (!out.empty() && (out.back() == '\n' || out.back() == ' '))
    out.pop_back();
  out += ",\n  \"summary\": " + mission_summary_json(s) + ",\n  " + extra_fields_json +
         ",\n  \"agent\": " + agent_report + "}\n";
  if (summary) *summary = s;
  return out;
}

std::string mission_summary_json(const MissionSummary& s) {
  json::Writer w(true);
  w.begin_object();
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
  return w.str();
}

MissionSummary add_summaries(const MissionSummary& a, const MissionSummary& b) {
  MissionSummary s = a;
  s.targets += b.targets;
  s.detected += b.detected;
  s.identified += b.identified;
  s.mine_correct += b.mine_correct;
  s.objects += b.objects;
  s.confirmed += b.confirmed;
  s.confirmed_correct += b.confirmed_correct;
  s.false_contacts += b.false_contacts;
  const auto weighted = [](double x, int n, double y, int m) {
    return n + m > 0 ? (x * n + y * m) / (n + m) : 0.0;
  };
  s.aspect_change_mean_deg = weighted(a.aspect_change_mean_deg, a.relooks_passed,
                                      b.aspect_change_mean_deg, b.relooks_passed);
  s.pass_range_mean_m =
      weighted(a.pass_range_mean_m, a.relooks_passed, b.pass_range_mean_m, b.relooks_passed);
  s.latency_mean_s = weighted(a.latency_mean_s, a.relooks, b.latency_mean_s, b.relooks);
  s.latency_max_s = std::max(a.latency_max_s, b.latency_max_s);
  s.relooks += b.relooks;
  s.relooks_passed += b.relooks_passed;
  s.relooks_second_look += b.relooks_second_look;
  s.mission_time_s += b.mission_time_s;
  s.wall_time_s += b.wall_time_s;
  s.distance_m += b.distance_m;
  s.relook_distance_m += b.relook_distance_m;
  s.relook_time_s += b.relook_time_s;
  s.mission_done = a.mission_done && b.mission_done;
  return s;
}

void print_mission_summary(const MissionSummary& s) {
  std::fprintf(stderr,
               "mission: %d targets: %d detected, %d identified, %d mine / non-mine right; %d "
               "objects, %d confirmed (%d right), %d false contacts\n",
               s.targets, s.detected, s.identified, s.mine_correct, s.objects, s.confirmed,
               s.confirmed_correct, s.false_contacts);
  std::fprintf(stderr,
               "mission: %.0f s of mission, %.0f m; re-looks: %d (%d passed, %d "
               "seen again), %.0f m and %.0f s extra, aspect change %.1f deg, pass range %.1f "
               "m, latency mean %.1f s max %.1f s (mission time)%s\n",
               s.mission_time_s, s.distance_m, s.relooks, s.relooks_passed, s.relooks_second_look,
               s.relook_distance_m, s.relook_time_s, s.aspect_change_mean_deg, s.pass_range_mean_m,
               s.latency_mean_s, s.latency_max_s, s.mission_done ? "" : " [mission not finished]");
}

std::string survey_score_json(const study::SurveyScore& s) {
  json::Writer w(true);
  w.begin_object();
  w.field("objects", s.objects).field("area_km2", s.area_km2, 6);
  w.key("area_km2_by_seabed").begin_object();
  for (const auto& [kind, a] : s.area_km2_by_kind)
    w.field(kind, a, 6);
  w.end_object();
  w.key("targets").begin_array();
  for (const study::TargetOutcome& t : s.targets) {
    w.begin_object();
    w.field("name", t.name).field("type", t.type).field("seabed", t.seabed);
    w.field("mine_like", t.mine_like);
    w.field("covered", t.covered).field("detected", t.detected);
    if (t.detected) {
      w.field("class", t.class_name).field("identified", t.identified);
      w.field("mine_correct", t.mine_correct).field("looks", t.looks);
      w.field("error_m", t.error_m, 4);
    }
    w.end_object();
  }
  w.end_array();
  w.key("false_contacts").begin_array();
  for (const study::FalseContact& f : s.false_contacts) {
    w.begin_object();
    w.field("object", f.object).field("north_m", f.north_m, 8).field("east_m", f.east_m, 8);
    w.field("seabed", f.seabed).field("class", f.class_name).field("mine_like", f.mine_like);
    w.field("looks", f.looks).field("rock_diameter_m", f.rock_diameter_m, 4);
    w.end_object();
  }
  w.end_array();
  w.end_object();
  return w.str();
}

std::string survey_rows_json(std::span<const study::SurveyRow> rows) {
  json::Writer w(true);
  w.begin_array();
  for (const study::SurveyRow& r : rows) {
    w.begin_object();
    w.field("scope", r.scope).field("surveys", r.c.surveys).field("targets", r.c.targets);
    w.field("covered", r.c.covered).field("detected", r.c.detected);
    w.field("pd", r.pd, 6).field("pd_lo", r.pd_ci.lo, 6).field("pd_hi", r.pd_ci.hi, 6);
    w.field("identified", r.c.identified).field("identified_rate", r.identified, 6);
    w.field("identified_lo", r.identified_ci.lo, 6).field("identified_hi", r.identified_ci.hi, 6);
    w.field("mine_wrong", r.c.mine_wrong).field("mine_error", r.mine_error, 6);
    w.field("mine_error_lo", r.mine_error_ci.lo, 6).field("mine_error_hi", r.mine_error_ci.hi, 6);
    w.field("false_contacts", r.c.false_contacts).field("area_km2", r.c.area_km2, 6);
    w.field("false_per_km2", r.false_per_km2, 6).field("false_per_target", r.false_per_target, 6);
    w.end_object();
  }
  w.end_array();
  return w.str();
}

void print_survey_rows(std::span<const study::SurveyRow> rows) {
  for (const study::SurveyRow& r : rows) {
    if (r.scope.rfind("type:", 0) == 0) continue;
    std::fprintf(stderr,
                 "survey %-24s Pd %d/%d = %.1f %% [%.1f, %.1f]; identified %.1f %% [%.1f, "
                 "%.1f]; mine/non-mine error %.1f %% [%.1f, %.1f]; false contacts %d: %.1f "
                 "per km2, %.2f per target\n",
                 r.scope.c_str(), r.c.detected, r.c.covered, 100 * r.pd, 100 * r.pd_ci.lo,
                 100 * r.pd_ci.hi, 100 * r.identified, 100 * r.identified_ci.lo,
                 100 * r.identified_ci.hi, 100 * r.mine_error, 100 * r.mine_error_ci.lo,
                 100 * r.mine_error_ci.hi, r.c.false_contacts, r.false_per_km2, r.false_per_target);
  }
}

std::string candidates_csv(std::span<const atr::CandidateReport> candidates) {
  std::string out =
      "contact,ping,side,north_m,east_m,ground_range_m,score,fate,reported,failed_gates,pings,"
      "along_extent_m,height_m,shadow_area_m2,highlight_db,highlight_above_db,shadow_below_db,"
      "highlight_area_m2,highlight_mean_above_db,clutter_hits_per_m,"
      "class,mine_like,distance,runner_up_distance,status,p_detection,p_classification,scores\n";
  char line[512];
  for (const atr::CandidateReport& r : candidates) {
    const atr::Contact& c = r.contact;
    const atr::Detection& d = r.candidate.detection;
    std::snprintf(line, sizeof line,
                  "%llu,%u,%s,%.3f,%.3f,%.3f,%.4f,%s,%d,%u,%d,%.3f,%.3f,%.4f,%.2f,%.2f,%.2f,%.4f,%"
                  ".2f,%.3f,%s,%d,%.4f,%.4f,%s,%.5g,%.5g,",
                  static_cast<unsigned long long>(c.id), c.ping_number,
                  d.side == 1 ? "starboard" : "port", c.north_m, c.east_m, c.ground_range_m,
                  d.score, atr::candidate_fate_name(r.candidate.fate), r.reported ? 1 : 0,
                  static_cast<unsigned>(r.candidate.failed_gates), d.pings, d.along_extent_m,
                  d.height_m, d.shadow_area_m2, d.highlight_db, d.highlight_above_db,
                  d.shadow_below_db, d.highlight_area_m2, d.highlight_mean_above_db,
                  d.clutter_hits_per_m, c.class_name.c_str(), c.mine_like ? 1 : 0, c.distance,
                  c.runner_up_distance, c.status.c_str(), r.p_detection, r.p_classification);
    out += line;
    // every class's distance, NAME=D separated by ';'
    for (std::size_t i = 0; i < c.scores.size(); ++i) {
      std::snprintf(line, sizeof line, "%s%s=%.4f", i ? ";" : "", c.scores[i].first.c_str(),
                    c.scores[i].second);
      out += line;
    }
    out += "\n";
  }
  return out;
}

std::string survey_targets_csv(std::span<const std::pair<std::uint64_t, study::SurveyScore>> s) {
  std::string out =
      "seed,name,type,seabed,mine_like,north_m,east_m,covered,detected,class,identified,"
      "mine_correct,looks,error_m\n";
  char line[512];
  for (const auto& [seed, score] : s) {
    for (const study::TargetOutcome& t : score.targets) {
      std::snprintf(line, sizeof line, "%llu,%s,%s,%s,%d,%.3f,%.3f,%d,%d,%s,%d,%d,%d,%.3f\n",
                    static_cast<unsigned long long>(seed), t.name.c_str(), t.type.c_str(),
                    t.seabed.c_str(), t.mine_like, t.north_m, t.east_m, t.covered, t.detected,
                    t.class_name.c_str(), t.identified, t.mine_correct, t.looks, t.error_m);
      out += line;
    }
  }
  return out;
}

std::string survey_false_contacts_csv(
    std::span<const std::pair<std::uint64_t, study::SurveyScore>> s) {
  std::string out = "seed,object,north_m,east_m,seabed,class,mine_like,looks,rock_diameter_m\n";
  char line[512];
  for (const auto& [seed, score] : s) {
    for (const study::FalseContact& f : score.false_contacts) {
      std::snprintf(line, sizeof line, "%llu,%llu,%.3f,%.3f,%s,%s,%d,%d,%.3f\n",
                    static_cast<unsigned long long>(seed),
                    static_cast<unsigned long long>(f.object), f.north_m, f.east_m,
                    f.seabed.c_str(), f.class_name.c_str(), f.mine_like, f.looks,
                    f.rock_diameter_m);
      out += line;
    }
  }
  return out;
}

}  // namespace sonarloop::mission
