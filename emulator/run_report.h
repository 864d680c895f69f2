#pragma once
// `sonarloop run`'s console report (tools/cmd_run.cpp runs the emulator): the run's set-up before
// it starts (sonar, timing, duration, outputs) and its final statistics (pings, deadlines,
// lateness and latency, navigation, UDP, rendering, CPU), on stderr.
#include "emulator/emulator.h"
#include "emulator/run_stats.h"

namespace sonarloop::emulator {

// The sonar, the ping timing, the duration and every output, one line each.
void print_run_setup(const emulator::Emulator& emu, const emulator::EmulatorOptions& o);

// The final statistics; `how` says how the run ended ("done", "stopped by SIGINT", ...).
void print_run_summary(const emulator::RunStats& s, const char* how);

}  // namespace sonarloop::emulator
