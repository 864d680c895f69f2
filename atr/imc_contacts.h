#pragma once
// Contacts as IMC (`onboard --imc udp:HOST:PORT`, `run --classify --imc ...`; docs/formats.md
// §7.4): each contact report as a CcuEvent of type MAP_FEATURE_ADDED (606) carrying a MapFeature
// (603) point of interest at the contact's latitude and longitude. That is the message the
// Neptus console's contact marker takes from other systems to put a mark on its map (its
// operator accepts it); MapFeature's own description says a point of interest "should appear as
// a point with a label in the map". The feature's id, the mark's name, is
// "c<object> <class>[ mine-like]" (the object's first contact id, so every look of an object
// names one mark); red for mine-like, yellow for other classes, grey when unclassified. The
// point's altitude is 0 (on the seabed below the contact: IMC gives no seabed depth here).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "atr/contact.h"
#include "drivers/imc/imc_codec.h"
#include "drivers/net/host_port.h"
#include "drivers/net/udp_sender.h"

namespace sonarloop::atr {

// The event of one contact; nullopt when it has no latitude and longitude (a stream in local
// metres only).
std::optional<imc::CcuEvent> contact_map_event(const Contact& c);

class ImcContactSender {
 public:
  // Throws std::runtime_error when the socket cannot be opened.
  ImcContactSender(const net::HostPort& destination, std::uint16_t system);
  // Sends the contact's event; false when it has no position (counted) or the kernel dropped it.
  bool send(const Contact& c);
  std::string describe() const;  // "imc udp to HOST:PORT"
  std::uint64_t sent() const { return sent_; }
  std::uint64_t without_position() const { return without_position_; }

 private:
  net::UdpSender udp_;
  std::uint16_t system_;
  std::vector<std::uint8_t> buffer_;
  std::uint64_t sent_ = 0, without_position_ = 0;
};

}  // namespace sonarloop::atr
