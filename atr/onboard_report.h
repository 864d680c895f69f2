#pragma once
// The onboard consumer's end-of-run statistics as `onboard` and `run --classify` print them and
// write them (--stats-json).
#include <string>

#include "atr/onboard_pipeline.h"
#include "atr/packet_queue.h"

namespace sonarloop::atr {

// The end-of-run statistics on stderr, a few lines (`who` prefixes the first).
void print_onboard_stats(const char* who, const OnboardStats& s, const PacketQueue* queue);

// The statistics as one JSON object.
std::string onboard_stats_json(const OnboardStats& s, const PacketQueue* queue);

}  // namespace sonarloop::atr
