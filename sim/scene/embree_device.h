#pragma once
// The process-wide Embree device (created on first use; Embree devices are thread-safe and
// meant to be shared). Embree errors become exceptions.
#include <embree3/rtcore.h>

#include <string>

namespace sonarloop::scene {

RTCDevice embree_device();

// Throws std::runtime_error("<what>: <Embree error>") if the device has a pending error.
void check_embree(const std::string& what);

}  // namespace sonarloop::scene
