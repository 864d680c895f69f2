#pragma once
// What the autonomy agent makes of the onboard consumer's contacts (ours): each look's decision
// margin, the fusion of several looks of one object, and the object's final state.
//
// Decision margin of one look. With d1 the distance of the identified class and d2 the runner-up's
// (eq. 10 of Pailhas et al. 2010; atr/contact.h "distance", "runner_up_distance"):
//     margin = (d2 - d1) / d1
// the runner-up's gap relative to the distance itself (0: a tie; 0.05: the runner-up is 5 %
// farther). Normalised so that one threshold serves chips of any contrast and models of any chip
// size (the distances scale with sqrt(pixels)). With an open-set model (contact field
// open_set_score s = distance / the class's reject distance) the margin is min((d2 - d1) / d1,
// 1 - s): an object near its class's reject distance is uncertain however far its runner-up.
// An unclassified contact (no class, or no runner-up) has margin 0.
//
// Fusion of looks (when the onboard consumer's fused fields are absent, and always for the fused
// margin): each look's class distances are normalised by that look's mean over the classes,
// n_c = d_c / mean_k(d_k), and summed over the looks: D_c = sum n_c. The fused class is argmin D_c,
// the fused margin (D_2nd - D_1st) / D_1st. Mine / non-mine: the same sum over the looks'
// normalised mine_distance and non_mine_distance when every look has both, else the mine-likeness
// the onboard reported for the fused class. When the latest look carries the onboard's own fusion
// (fields looks >= 2, fused_class, fused_mine_like: atr/look_fusion.h), its class and mine-likeness
// are used, the margin still from the sum above.
//
// Target probability: with a model that has a contact gate, each look carries the probability
// that it is a target rather than clutter (atr/contact_gate.h, Contact::target_probability). The
// looks' probabilities are fused by the mean of their log-odds (a look's gate already weighs its
// evidence; several looks of one object are not independent enough to add them).
//
// Final state of an object, for a margin threshold T and a confirm probability P:
//   one look:    confirmed when margin >= T, else uncertain (a re-look is due)
//   more looks:  confirmed when the fused margin >= T, or when the looks agree: at least two
//                classified looks, and more than half of them, name the fused class as their
//                own (independent aspects agree); else uncertain
//   either way, uncertain while the fused target probability (when the looks have one) is
//   below P: not sure it is a target at all
//
// Mine margin: the same relative gap between the mine-like and non-mine group distances
// (mine_distance, non_mine_distance; summed normalised over the looks as above): how sure the
// mine / non-mine decision is, whatever the class. NaN when a look lacks either group.
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "atr/contact.h"

namespace sonarloop::autonomy {

// Bounds of an acceptable contact: ids a double holds exactly, positions within 1000 km of the
// frame's origin, at most 1000 looks.
inline constexpr double kMaxContactId = 9007199254740992.0;  // 2^53
inline constexpr double kMaxContactOffset_m = 1e6;
inline constexpr double kMaxContactLooks = 1000.0;
inline constexpr double kMaxContactTimeNs = 4611686018427387904.0;  // 2^62 ns: year 2116

// The contact of one JSON line of the onboard consumer (atr/contact.h). nullopt with `error`
// on malformed input, a missing required field (contact, north_m, east_m), or a value out of
// range: any number not finite (1e999), an id that is not a whole number from 1 (contact) or 0
// (object) to 2^53, a position beyond kMaxContactOffset_m, a time outside 0..2^62 ns, a ping
// number outside 0..2^32 - 1, looks outside 1..1000.
// The line is untrusted input (it arrives over UDP).
std::optional<atr::Contact> contact_from_json(std::string_view line, std::string& error);

double decision_margin(const atr::Contact& c);

struct FusedDecision {
  std::string class_name;  // empty when no look was classified
  bool mine_like = false;
  double margin = 0.0;
  double mine_margin = 0.0;   // (d_far - d_near) / d_near of the two groups; NaN: no groups
  int looks = 0;              // classified looks used
  bool from_onboard = false;  // class and mine-likeness from the onboard's fused fields
  double target_probability = std::numeric_limits<double>::quiet_NaN();  // NaN: no gate
};

FusedDecision fuse_looks(const std::vector<atr::Contact>& looks);

enum class FinalState { kConfirmed, kUncertain };
const char* to_string(FinalState s);

struct ObjectDecision {
  FinalState state = FinalState::kUncertain;
  FusedDecision fused;
};

ObjectDecision decide(const std::vector<atr::Contact>& looks, double threshold,
                      double confirm_probability = 0.5);

}  // namespace sonarloop::autonomy
