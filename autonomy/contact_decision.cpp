#include "autonomy/contact_decision.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "autonomy/json_line.h"

namespace sonarloop::autonomy {
namespace {

constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();

bool classified(const atr::Contact& c) {
  return !c.class_name.empty() && !c.scores.empty();
}

// The look's mean class distance (the normalisation of the fusion), NaN when unusable.
double mean_distance(const atr::Contact& c) {
  double sum = 0.0;
  for (const auto& s : c.scores)
    sum += s.second;
  const double mean = sum / static_cast<double>(c.scores.size());
  return mean > 0.0 && std::isfinite(mean) ? mean : kMissing;
}

// Every number of the line is finite (strtod reads 1e999 as infinity; the contact format writes
// a non-finite value as null) and the ids are positive integers a double holds exactly; the
// position is on Earth. "" when it is, else what is wrong.
std::string out_of_range(const JsonLine& j) {
  for (const auto& [key, text] : j.members()) {
    const auto v = j.number(key);
    if (v && !std::isfinite(*v)) return "field " + key + " is not a finite number";
  }
  if (const auto scores = j.object("scores")) {
    for (const auto& [name, text] : scores->members()) {
      const auto v = scores->number(name);
      if (v && !std::isfinite(*v)) return "score " + name + " is not a finite number";
    }
  }
  for (const char* key : {"contact", "object"}) {
    const auto v = j.number(key);
    if (!v) continue;
    if (*v != std::floor(*v) || *v < (std::string(key) == "contact" ? 1.0 : 0.0) ||
        *v > kMaxContactId) {
      return std::string("field ") + key + " is not an id (a whole number from 1 to 2^53)";
    }
  }
  for (const char* key : {"north_m", "east_m"}) {
    if (std::abs(j.number(key).value_or(0.0)) > kMaxContactOffset_m) {
      return std::string("field ") + key + " is more than 1000 km from the origin";
    }
  }
  const double t = j.number("time_utc_ns").value_or(0.0);
  if (t < 0.0 || t > kMaxContactTimeNs) return "field time_utc_ns is not from 0 to 2^62";
  const double ping = j.number("ping").value_or(0.0);
  if (ping < 0.0 || ping > 4294967295.0 || ping != std::floor(ping)) {
    return "field ping is not a whole number from 0 to 2^32 - 1";
  }
  const double looks = j.number("looks").value_or(1.0);
  if (looks < 1.0 || looks > kMaxContactLooks || looks != std::floor(looks)) {
    return "field looks is not a whole number from 1 to 1000";
  }
  return "";
}

void read_scores(const JsonLine& j, atr::Contact& c) {
  const auto scores = j.object("scores");
  if (!scores) return;
  for (const auto& [name, text] : scores->members()) {
    if (const auto v = scores->number(name)) c.scores.emplace_back(name, *v);
  }
}

}  // namespace

std::optional<atr::Contact> contact_from_json(std::string_view line, std::string& error) {
  const auto j = JsonLine::parse(line, error);
  if (!j) return std::nullopt;
  const auto id = j->number("contact");
  const auto north = j->number("north_m");
  const auto east = j->number("east_m");
  if (!id || !north || !east) {
    error = "a contact needs the fields contact, north_m and east_m";
    return std::nullopt;
  }
  if (const std::string wrong = out_of_range(*j); !wrong.empty()) {
    error = wrong;
    return std::nullopt;
  }
  atr::Contact c;
  c.id = static_cast<std::uint64_t>(*id);
  c.north_m = *north;
  c.east_m = *east;
  if (const auto t = j->number("time_utc_ns")) c.time_utc_ns = static_cast<std::int64_t>(*t);
  c.ping_number = static_cast<std::uint32_t>(j->number("ping").value_or(0));
  c.side = j->string("side").value_or("starboard") == "port" ? 0 : 1;
  c.slant_range_m = j->number("slant_range_m").value_or(kMissing);
  c.ground_range_m = j->number("ground_range_m").value_or(kMissing);
  c.class_name = j->string("class").value_or("");
  c.mine_like = j->boolean("mine_like").value_or(false);
  c.distance = j->number("distance").value_or(kMissing);
  c.runner_up = j->string("runner_up").value_or("");
  c.runner_up_distance = j->number("runner_up_distance").value_or(kMissing);
  read_scores(*j, c);
  c.mine_distance = j->number("mine_distance").value_or(kMissing);
  c.non_mine_distance = j->number("non_mine_distance").value_or(kMissing);
  c.looks = static_cast<int>(j->number("looks").value_or(1));
  c.object = static_cast<std::uint64_t>(j->number("object").value_or(0));
  c.fused_class = j->string("fused_class").value_or("");
  c.fused_mine_like = j->boolean("fused_mine_like").value_or(false);
  if (const auto s = j->number("open_set_score")) c.open_set_score = *s;
  if (const auto p = j->number("target_probability")) c.target_probability = *p;
  if (const auto d = j->number("clutter_distance")) c.clutter_distance = *d;
  c.unknown = j->boolean("unknown").value_or(false);
  c.status = j->string("status").value_or("");
  return c;
}

double decision_margin(const atr::Contact& c) {
  if (c.class_name.empty() || !(c.distance > 0.0) || !std::isfinite(c.runner_up_distance)) {
    return 0.0;
  }
  double m = (c.runner_up_distance - c.distance) / c.distance;
  if (c.open_set_score && std::isfinite(*c.open_set_score))
    m = std::min(m, 1.0 - *c.open_set_score);
  return std::max(m, 0.0);
}

namespace {
// The relative gap between two group distances: (far - near) / near.
double group_gap(double a, double b) {
  const double lo = std::min(a, b), hi = std::max(a, b);
  return lo > 0.0 ? (hi - lo) / lo : 0.0;
}
}  // namespace

FusedDecision fuse_looks(const std::vector<atr::Contact>& looks) {
  FusedDecision f;
  // the target probability: the mean log-odds of the looks that have one
  double logit_sum = 0.0;
  int with_p = 0;
  for (const atr::Contact& c : looks) {
    if (!c.target_probability || !std::isfinite(*c.target_probability)) continue;
    const double p = std::clamp(*c.target_probability, 1e-9, 1.0 - 1e-9);
    logit_sum += std::log(p / (1.0 - p));
    ++with_p;
  }
  if (with_p > 0) f.target_probability = 1.0 / (1.0 + std::exp(-logit_sum / with_p));
  std::map<std::string, double> sum;  // D_c
  std::map<std::string, bool> mine_like_of;
  double mine_sum = 0.0, non_mine_sum = 0.0;
  bool groups = true;
  for (const atr::Contact& c : looks) {
    if (!classified(c)) continue;
    const double mean = mean_distance(c);
    if (!std::isfinite(mean)) continue;
    ++f.looks;
    for (const auto& s : c.scores)
      sum[s.first] += s.second / mean;
    mine_like_of[c.class_name] = c.mine_like;
    if (std::isfinite(c.mine_distance) && std::isfinite(c.non_mine_distance)) {
      mine_sum += c.mine_distance / mean;
      non_mine_sum += c.non_mine_distance / mean;
    } else {
      groups = false;
    }
  }
  if (f.looks == 0) return f;
  // argmin and runner-up of D_c
  std::string best, second;
  for (const auto& [name, d] : sum) {
    if (best.empty() || d < sum[best]) {
      second = best;
      best = name;
    } else if (second.empty() || d < sum[second]) {
      second = name;
    }
  }
  f.class_name = best;
  f.margin = second.empty() ? 0.0 : (sum[second] - sum[best]) / sum[best];
  f.mine_margin = groups ? group_gap(mine_sum, non_mine_sum) : kMissing;
  if (groups) {
    f.mine_like = mine_sum < non_mine_sum;
  } else {
    const auto it = mine_like_of.find(best);
    f.mine_like = it != mine_like_of.end() && it->second;
  }
  // the onboard consumer's own fusion, when the latest look has it
  const atr::Contact& last = looks.back();
  if (last.looks >= 2 && !last.fused_class.empty()) {
    f.class_name = last.fused_class;
    f.mine_like = last.fused_mine_like;
    f.from_onboard = true;
  }
  return f;
}

const char* to_string(FinalState s) {
  return s == FinalState::kConfirmed ? "confirmed" : "uncertain";
}

ObjectDecision decide(const std::vector<atr::Contact>& looks, double threshold,
                      double confirm_probability) {
  ObjectDecision d;
  d.fused = fuse_looks(looks);
  if (d.fused.class_name.empty()) return d;
  const bool unsure_target =
      std::isfinite(d.fused.target_probability) && d.fused.target_probability < confirm_probability;
  if (d.fused.looks == 1) {
    // the one classified look's own margin
    for (const atr::Contact& c : looks) {
      if (!classified(c)) continue;
      d.fused.margin = decision_margin(c);
      d.fused.class_name = c.class_name;
      d.fused.mine_like = c.mine_like;
      d.fused.mine_margin = std::isfinite(c.mine_distance) && std::isfinite(c.non_mine_distance)
                                ? group_gap(c.mine_distance, c.non_mine_distance)
                                : kMissing;
    }
    d.state = d.fused.margin >= threshold && !unsure_target ? FinalState::kConfirmed
                                                            : FinalState::kUncertain;
    return d;
  }
  // a majority of at least two classified looks name the fused class
  int classified_looks = 0, votes = 0;
  for (const atr::Contact& c : looks) {
    if (!classified(c)) continue;
    ++classified_looks;
    votes += c.class_name == d.fused.class_name;
  }
  const bool agree = votes >= 2 && 2 * votes > classified_looks;
  d.state = (d.fused.margin >= threshold || agree) && !unsure_target ? FinalState::kConfirmed
                                                                     : FinalState::kUncertain;
  return d;
}

}  // namespace sonarloop::autonomy
