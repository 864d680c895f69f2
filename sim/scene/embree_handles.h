#pragma once
// Embree's opaque handles, declared exactly as Embree 3 declares them (rtcore_device.h,
// rtcore_geometry.h; the Debian build has no API namespace), so that a header of the simulator can
// hold one without including Embree: Embree stays inside the .cpp files of the renderers and the
// scene that call it, and the layers above sim/ never see its headers (scripts/check_layers.sh).
// (Repeating an identical typedef is allowed in C++.)
typedef struct RTCDeviceTy* RTCDevice;
typedef struct RTCSceneTy* RTCScene;
struct RTCRayHit;
