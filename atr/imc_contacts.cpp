#include "atr/imc_contacts.h"

#include "units/angles.h"

namespace sonarloop::atr {

std::optional<imc::CcuEvent> contact_map_event(const Contact& c) {
  if (!c.latitude_deg || !c.longitude_deg) return std::nullopt;
  const std::uint64_t object = c.object != 0 ? c.object : c.id;
  const std::string& cls = c.fused_class.empty() ? c.class_name : c.fused_class;
  const bool mine = c.fused_class.empty() ? c.mine_like : c.fused_mine_like;
  imc::MapFeature f;
  f.id = "c" + std::to_string(object) + (cls.empty() ? "" : " " + cls) + (mine ? " mine-like" : "");
  f.feature_type = imc::MapFeature::kPointOfInterest;
  if (cls.empty()) {
    f.rgb_red = f.rgb_green = f.rgb_blue = 128;
  } else if (mine) {
    f.rgb_red = 255;
  } else {
    f.rgb_red = 255;
    f.rgb_green = 200;
  }
  f.feature.push_back({*c.latitude_deg * kRadPerDeg, *c.longitude_deg * kRadPerDeg, 0.0f});
  imc::CcuEvent e;
  e.type = imc::CcuEvent::kMapFeatureAdded;
  e.id = f.id;
  e.arg = std::move(f);
  return e;
}

ImcContactSender::ImcContactSender(const net::HostPort& destination, std::uint16_t system)
    : udp_(destination), system_(system) {}

bool ImcContactSender::send(const Contact& c) {
  const std::optional<imc::CcuEvent> e = contact_map_event(c);
  if (!e) {
    ++without_position_;
    return false;
  }
  imc::Header h;
  h.timestamp_s = c.time_utc_ns ? static_cast<double>(*c.time_utc_ns) * 1e-9 : 0.0;
  h.src = system_;
  h.src_ent = imc::kImcEntityAtr;
  imc::encode(h, *e, buffer_);
  ++sent_;
  return udp_.send(buffer_);
}

std::string ImcContactSender::describe() const {
  return "imc " + udp_.describe();
}

}  // namespace sonarloop::atr
