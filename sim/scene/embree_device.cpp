#include "sim/scene/embree_device.h"

#include <mutex>
#include <stdexcept>

namespace sonarloop::scene {
namespace {

const char* error_name(RTCError e) {
  switch (e) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
    default:
      return "unknown error";
  }
}

}  // namespace

RTCDevice embree_device() {
  static std::once_flag once;
  static RTCDevice device = nullptr;
  std::call_once(once, [] {
    device = rtcNewDevice(nullptr);
    if (!device) {
      throw std::runtime_error(std::string("cannot create the Embree device: ") +
                               error_name(rtcGetDeviceError(nullptr)));
    }
  });
  return device;
}

void check_embree(const std::string& what) {
  const RTCError e = rtcGetDeviceError(embree_device());
  if (e != RTC_ERROR_NONE) throw std::runtime_error(what + ": Embree " + error_name(e));
}

}  // namespace sonarloop::scene
