#!/usr/bin/env bash
# Coverage-guided fuzzing of every parser that reads outside data (tests/fuzz/*_fuzz.cpp) with
# libFuzzer, AddressSanitizer and UndefinedBehaviorSanitizer (clang from Debian).
#
# usage: scripts/fuzz.sh [SECONDS | --runs N] [HARNESS ...]
#   SECONDS   per harness (default 60); CI runs 10
#   --runs N  instead: N executions per harness (issue 11 asks 1000000 of each; the slowest
#             harnesses, scenario YAML, whole XTF files and chip images, need 5-16 minutes)
#   HARNESS   xtf_decode xtf_file candump_line socketcand n2k_decode pose_message model_file
#             scenario_yaml stream_receiver png_chip (default: all)
# Builds build-fuzz/ (clang, -DSONARLOOP_FUZZ=ON, only the harnesses and the libraries they
# link), copies the seed corpus of tests/fuzz/corpus/NAME into build-fuzz/corpus/NAME (the
# fuzzer grows it there, never in the source tree) and runs each harness with: inputs up to 64 KB
# (1 MB for whole files), 1 s per input at most (a slower input is a hang), 2 GB of memory at
# most. Prints per harness the executions and the coverage (edges, features); a crash, leak,
# hang or memory overrun stops with its reproducer saved as build-fuzz/findings/NAME-*, and the
# script exits 1. Harnesses run one per core at a time. Reproduce a finding with:
#   build-fuzz/tests/fuzz/fuzz_NAME build-fuzz/findings/FILE
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
runs=""
if [ "$seconds" = "--runs" ]; then
  runs="${1:?--runs needs a number}"
  shift
  seconds=86400  # the runs end it
fi
all=(xtf_decode xtf_file candump_line socketcand n2k_decode pose_message model_file scenario_yaml
     stream_receiver png_chip)
harnesses=("$@")
if [ ${#harnesses[@]} -eq 0 ]; then harnesses=("${all[@]}"); fi

scripts/install_clang.sh
jobs="$(nproc 2>/dev/null || echo 2)"
mkdir -p build-fuzz
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DSONARLOOP_FUZZ=ON \
  -DSONARLOOP_BUILD_TESTS=OFF > build-fuzz/configure.log
targets=()
for h in "${harnesses[@]}"; do targets+=("fuzz_$h"); done
cmake --build build-fuzz -j "$jobs" --target "${targets[@]}"

mkdir -p build-fuzz/findings
# fuzz_one NAME: runs one harness for $seconds, its log in build-fuzz/NAME.log and its exit code
# in build-fuzz/NAME.rc
fuzz_one() {
  local h=$1 corpus="build-fuzz/corpus/$1" max_len=65536 rc=0
  mkdir -p "$corpus"
  cp -n tests/fuzz/corpus/"$h"/* "$corpus"/ 2>/dev/null || true
  case "$h" in xtf_file | png_chip | scenario_yaml) max_len=1048576 ;; esac
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 \
    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    build-fuzz/tests/fuzz/fuzz_"$h" "$corpus" -max_total_time="$seconds" ${runs:+-runs="$runs"} -timeout=1 \
    -rss_limit_mb=2048 -max_len="$max_len" -print_final_stats=1 \
    -artifact_prefix="build-fuzz/findings/$h-" > "build-fuzz/$h.log" 2>&1 || rc=$?
  echo "$rc" > "build-fuzz/$h.rc"
}

# one harness per core at a time (each fuzzer is single-threaded)
running=0
for h in "${harnesses[@]}"; do
  fuzz_one "$h" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait

status=0
printf '%-16s %12s %8s %8s  %s\n' harness executions edges features result
for h in "${harnesses[@]}"; do
  log="build-fuzz/$h.log"
  rc=$(cat "build-fuzz/$h.rc")
  execs="$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)"
  cov="$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || true)"
  ft="$(grep -o 'ft: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || true)"
  if [ "$rc" -eq 0 ]; then
    result=ok
  else
    result="FINDING (exit $rc): see $log and build-fuzz/findings/$h-*"
    status=1
  fi
  printf '%-16s %12s %8s %8s  %s\n' "$h" "${execs:-?}" "${cov:-?}" "${ft:-?}" "$result"
done
exit "$status"
