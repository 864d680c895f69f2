#!/usr/bin/env bash
# The concurrent code under ThreadSanitizer: builds the tests of everything that runs threads
# (render queue, ping producer, emulator, pose sources, socketcand server, UDP, onboard packet
# queue and pipeline, tile cache) with -fsanitize=thread and runs them. (The seabed model's own
# test is left out: its FFTs take 7 minutes under TSan; its cache is the tile cache tested here.)
# Usage: scripts/tsan.sh [BUILD_DIR]   (default build-tsan)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:-$root/build-tsan}
"$root/scripts/setup.sh"
tests=(test_emulator_render_queue test_emulator_ping_producer test_emulator_emulator
       test_emulator_pose_source test_emulator_pacer test_drivers_can_socketcand_server
       test_drivers_can_socketcand_server_faults
       test_drivers_can_can_transport test_drivers_net_udp test_atr_packet_queue
       test_atr_stream_receiver test_atr_onboard_pipeline test_sim_seabed_tile_cache)
gen=()
if command -v ninja >/dev/null 2>&1; then gen=(-G Ninja); fi
# -O1 -g1: line tables for the reports; MPI off (Open MPI's own threads are not instrumented)
cmake -S "$root" -B "$dir" "${gen[@]}" -DSONARLOOP_TSAN=ON -DSONARLOOP_MPI=OFF \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" >/dev/null
# the executables of those tests' folders (one per folder, cmake/SonarloopTests.cmake)
executables=(test_emulator test_drivers_can test_drivers_net test_atr test_sim_seabed)
cmake --build "$dir" -j "$(nproc)" --target "${executables[@]}"
regex=$(IFS='|'; echo "^(${tests[*]})\$")
# halt_on_error: a reported race fails the test; second_deadlock_stack for lock-order reports;
# the suppressions: Embree's and TBB's uninstrumented threads (scripts/tsan.supp)
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 suppressions=$root/scripts/tsan.supp ${TSAN_OPTIONS:-}" \
  ctest --test-dir "$dir" --output-on-failure -j "$(nproc)" -R "$regex"
