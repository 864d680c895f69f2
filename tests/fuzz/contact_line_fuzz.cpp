// The agent's contact decoder (autonomy/contact_decision.h) on one UDP datagram: every line it
// accepts is within the documented bounds (ids whole numbers from 1 to 2^53, a finite position
// within 1000 km, finite numbers, 1 to 1000 looks), and an Agent takes it twice as one look.
#include <cmath>
#include <cstdlib>
#include <string_view>

#include "autonomy/agent.h"
#include "autonomy/contact_decision.h"
#include "tests/fuzz/fuzz_support.h"

using namespace sonarloop;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string error;
  const auto c = autonomy::contact_from_json(
      std::string_view(reinterpret_cast<const char*>(data), size), error);
  if (!c) return 0;
  if (c->id < 1 || static_cast<double>(c->id) > autonomy::kMaxContactId) std::abort();
  if (!std::isfinite(c->north_m) || !std::isfinite(c->east_m) ||
      std::abs(c->north_m) > autonomy::kMaxContactOffset_m ||
      std::abs(c->east_m) > autonomy::kMaxContactOffset_m) {
    std::abort();
  }
  if (c->looks < 1 || c->looks > autonomy::kMaxContactLooks) std::abort();
  autonomy::AgentParams p;
  p.relooks = false;
  autonomy::Agent agent(p, {autonomy::Leg{{0, 0}, {100, 0}}}, autonomy::VehicleState{});
  agent.on_contact(*c);
  agent.on_contact(*c);
  if (agent.objects().size() != 1 || agent.objects()[0].looks.size() != 1 ||
      agent.duplicate_contacts() != 1) {
    std::abort();
  }
  return 0;
}
