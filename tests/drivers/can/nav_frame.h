#pragma once
// The CAN frame the transport and protocol tests send: an NMEA 2000 position rapid update
// (PGN 129025, priority 2, source 0x23), 8 bytes, extended identifier.
#include "drivers/can/can_frame.h"

namespace sonarloop::testing {

inline can::CanFrame nav_frame() {
  can::CanFrame f;
  f.id = 0x09F80123;
  f.extended = true;
  f.len = 8;
  f.data = {0x00, 0xE6, 0xB5, 0x23, 0xB1, 0xAC, 0x6A, 0x06};
  return f;
}

}  // namespace sonarloop::testing
