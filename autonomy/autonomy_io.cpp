#include "autonomy/autonomy_io.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "drivers/can/socketcand_client.h"
#include "drivers/json/json_writer.h"
#include "drivers/n2k/messages.h"
#include "drivers/pose/pose_message.h"

namespace sonarloop::autonomy {
namespace {

constexpr int kPollMs = 50;
constexpr std::size_t kMaxDatagramBytes = 65536;
constexpr const char* kSocketcandPrefix = "socketcand:";
// Between connection attempts to a socketcand server that is not up yet.
constexpr auto kRetryInterval = std::chrono::milliseconds(250);

// socketcand:HOST:PORT[:CHANNEL], retried until the deadline (the emulator opens its server
// after building the scene).
std::unique_ptr<can::CanTransport> connect_socketcand(const std::string& rest, double timeout_s) {
  std::string address = rest;
  can::SocketcandClientOptions o;
  // a trailing :CHANNEL that is not a port number
  const auto last = rest.rfind(':');
  if (last != std::string::npos && rest.find(':') != last &&
      rest.find_first_not_of("0123456789", last + 1) != std::string::npos) {
    o.channel = rest.substr(last + 1);
    address = rest.substr(0, last);
  }
  const net::HostPort hp = net::parse_host_port(address);
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(timeout_s));
  for (;;) {
    try {
      return std::make_unique<can::SocketcandClient>(hp, o);
    } catch (const std::runtime_error&) {
      if (std::chrono::steady_clock::now() >= deadline) throw;
      std::this_thread::sleep_for(kRetryInterval);
    }
  }
}

}  // namespace

NavListener::NavListener(const std::string& spec, const LocalTangentPlane& ltp,
                         double connect_timeout_s)
    : ltp_(ltp) {
  if (spec.rfind(kSocketcandPrefix, 0) == 0) {
    bus_ = connect_socketcand(spec.substr(std::strlen(kSocketcandPrefix)), connect_timeout_s);
  } else {
    bus_ = can::open_can_transport(spec);
    if (!bus_->can_receive()) {
      throw std::runtime_error("--nav " + spec + ": cannot receive from " + bus_->describe());
    }
  }
  describe_ = bus_->describe();
  thread_ = std::thread([this] { run(); });
}

NavListener::~NavListener() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

NavFix NavListener::latest() const {
  std::lock_guard lock(mu_);
  return fix_;
}

void NavListener::run() {
  try {
    while (!stop_.load()) {
      const auto frame = bus_->receive(kPollMs);
      if (!frame) continue;
      const auto m = n2k::decode_any(*frame);
      std::lock_guard lock(mu_);
      ++fix_.frames;
      if (!m) continue;
      ++fix_.decoded;
      if (const auto* p = std::get_if<n2k::PositionRapidUpdate>(&*m)) {
        if (p->latitude_deg && p->longitude_deg) {
          const Vec2 ne = ltp_.to_local(GeoPoint{*p->latitude_deg, *p->longitude_deg});
          fix_.position = autonomy::Point2{ne.x(), ne.y()};
          ++fix_.position_updates;
        }
      } else if (const auto* h = std::get_if<n2k::VesselHeading>(&*m)) {
        if (h->heading_rad) fix_.heading_rad = wrap_to_pi(*h->heading_rad);
      } else if (const auto* d = std::get_if<n2k::WaterDepth>(&*m)) {
        if (d->depth_m) {
          fix_.altitude_m = *d->depth_m;
          if (d->offset_m && *d->offset_m >= 0.0) {
            fix_.seabed_depth_m = *d->offset_m + *d->depth_m;
            ++fix_.depth_updates;
          }
        }
      }
    }
  } catch (const std::exception& e) {
    // the emulator went away (end of the mission): keep the last fix
    std::lock_guard lock(mu_);
    error_ = e.what();
  }
}

ContactListener::ContactListener(const net::HostPort& address) : rx_(address, 1 << 20) {
  thread_ = std::thread([this] { run(); });
}

ContactListener::~ContactListener() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

void ContactListener::run() {
  std::vector<std::uint8_t> buf(kMaxDatagramBytes);
  while (!stop_.load()) {
    std::optional<net::ReceivedDatagram> d;
    try {
      d = rx_.receive(buf, kPollMs);
    } catch (const std::exception&) {
      ++malformed_;
      continue;
    }
    if (!d) continue;
    std::string error;
    auto c = autonomy::contact_from_json(
        std::string_view(reinterpret_cast<const char*>(buf.data()), d->size), error);
    if (!c) {
      ++malformed_;
      continue;
    }
    ++received_;
    std::lock_guard lock(mu_);
    if (queue_.size() >= kMaxQueuedContacts) {
      ++dropped_;
      continue;
    }
    queue_.push_back(std::move(*c));
  }
}

std::deque<atr::Contact> ContactListener::take(std::size_t max) {
  std::lock_guard lock(mu_);
  std::deque<atr::Contact> out;
  while (!queue_.empty() && out.size() < max) {
    out.push_back(std::move(queue_.front()));
    queue_.pop_front();
  }
  return out;
}

PosePublisher::PosePublisher(const net::HostPort& destination, const LocalTangentPlane& ltp)
    : tx_(destination), ltp_(ltp) {}

void PosePublisher::publish(const autonomy::VehicleState& s, std::int64_t time_unix_ns) {
  pose::PoseMessage m;
  m.sequence = ++sequence_;
  m.time_unix_ns = time_unix_ns;
  const GeoPoint g = ltp_.to_geodetic(s.position.north_m, s.position.east_m);
  m.latitude_deg = g.latitude_deg;
  m.longitude_deg = g.longitude_deg;
  m.depth_m = s.depth_m;
  m.heading_rad = s.heading_rad;
  m.pitch_rad = s.pitch_rad;
  m.roll_rad = 0.0;
  const auto bytes = pose::encode_pose_message(m);
  tx_.send(bytes);
}

namespace {

void write_object(json::Writer& w, const autonomy::AgentObject& o) {
  const autonomy::ObjectDecision& d = o.decision;
  w.begin_object();
  w.field("object", o.id).field("north_m", o.position.north_m, 8);
  w.field("east_m", o.position.east_m, 8);
  w.field("state", autonomy::to_string(d.state));
  w.key("class");
  if (d.fused.class_name.empty())
    w.null();
  else
    w.value(d.fused.class_name);
  w.key("mine_like");
  if (d.fused.class_name.empty())
    w.null();
  else
    w.value(d.fused.mine_like);
  w.field("margin", d.fused.margin, 6).field("looks", static_cast<int>(o.looks.size()));
  w.field("classified_looks", d.fused.looks).field("relooked", o.relooks > 0);
  if (std::isfinite(d.fused.target_probability))
    w.field("target_probability", d.fused.target_probability, 6);
  if (o.relook_over_budget) w.field("relook_over_budget", true);
  w.field("first_margin", autonomy::decision_margin(o.looks.front()), 6);
  w.key("first_class");
  if (o.looks.front().class_name.empty())
    w.null();
  else
    w.value(o.looks.front().class_name);
  w.key("look_contacts").begin_array();
  for (const auto& c : o.looks)
    w.value(c.id);
  w.end_array();
  w.key("look_headings_deg").begin_array();
  for (const double h : o.look_headings_rad)
    w.value(autonomy::degrees(h), 6);
  w.end_array();
  w.end_object();
}

// rate <= 0: lock-step (no wall time)
void write_relook(json::Writer& w, const autonomy::RelookRecord& r, double rate) {
  using autonomy::degrees;
  w.begin_object();
  w.field("object", r.object);
  w.field("first_heading_deg", degrees(r.first_heading_rad), 6);
  w.field("planned_heading_deg", degrees(r.plan.heading_rad), 6);
  w.field("side", r.plan.side == 1 ? "starboard" : "port");
  w.field("passed", r.passed);
  w.field("pass_heading_deg", degrees(r.pass_heading_rad), 6);
  w.field("aspect_change_deg",
          r.passed
              ? degrees(autonomy::heading_difference_rad(r.pass_heading_rad, r.first_heading_rad))
              : std::nan(""),
          6);
  w.field("pass_range_m", r.passed ? r.pass_range_m : std::nan(""), 6);
  w.field("second_look", r.second_look);
  w.field("look_t_s", r.look_t_s, 8).field("received_t_s", r.received_t_s, 8);
  w.field("inserted_t_s", r.inserted_t_s, 8);
  w.field("latency_s", r.inserted_t_s - r.look_t_s, 6);
  if (rate > 0) w.field("latency_wall_s", (r.inserted_t_s - r.look_t_s) / rate, 6);
  w.end_object();
}

}  // namespace

std::string agent_report_json(const autonomy::Agent& agent, const AgentRunInfo& info) {
  json::Writer w(true);
  w.begin_object();
  if (info.lockstep) {
    w.field("mode", "lockstep");
  } else {
    w.field("mode", "realtime").field("rate", info.rate, 6);
  }
  w.field("threshold", info.threshold, 6);
  w.field("relooks_enabled", info.relooks).field("stopped", info.stopped);
  w.field("relook_timing", autonomy::to_string(agent.params().relook_timing));
  if (std::isfinite(agent.params().relook_budget_s))
    w.field("relook_budget_s", agent.params().relook_budget_s, 8);
  w.field("mission_done", agent.mission_done());
  w.field("sim_time_s", agent.state().t_s, 8);
  if (!info.lockstep) w.field("wall_time_s", info.wall_time_s, 6);
  w.field("distance_m", agent.travelled_m(), 8).field("survey_plan_m", info.survey_plan_m, 8);
  w.field("relook_distance_m", agent.detour_distance_m(), 8);
  w.field("relook_time_s", agent.detour_time_s(), 8);
  w.field("contacts_received", info.contacts_received);
  // ignored repeats of an id (agent.h), only when there were some
  if (agent.duplicate_contacts() + agent.conflicting_contacts() > 0) {
    w.field("contacts_duplicated", agent.duplicate_contacts());
    w.field("contacts_conflicting", agent.conflicting_contacts());
  }
  if (!info.lockstep) {
    w.field("contacts_malformed", info.contacts_malformed);
    if (info.contacts_dropped) w.field("contacts_dropped", info.contacts_dropped);
    w.field("poses_sent", info.poses_sent);
    w.key("nav").begin_object();
    w.field("frames", info.nav.frames).field("decoded", info.nav.decoded);
    w.field("position_updates", info.nav.position_updates);
    w.field("depth_updates", info.nav.depth_updates);
    w.field("offset_mean_m", info.nav_offset_mean_m, 6);
    w.field("offset_max_m", info.nav_offset_max_m, 6);
    w.end_object();
  }
  w.key("objects").begin_array();
  for (const auto& o : agent.objects())
    write_object(w, o);
  w.end_array();
  w.key("relooks").begin_array();
  for (const auto& r : agent.relooks())
    write_relook(w, r, info.lockstep ? 0.0 : info.rate);
  w.end_array();
  w.end_object();
  return w.str();
}

}  // namespace sonarloop::autonomy
