#!/usr/bin/env bash
# Coverage-guided fuzzing of every parser that reads outside data (tests/fuzz/*_fuzz.cpp) with
# libFuzzer, AddressSanitizer and UndefinedBehaviorSanitizer (clang from Debian).
#
# usage: scripts/fuzz.sh [--build DIR] [SECONDS | --runs N] [HARNESS ...]
#   SECONDS      per harness (default 60); CI runs 10
#   --runs N     instead: N executions per harness (issue 11 asks 1000000 of each; the slowest
#                harnesses, scenario YAML, whole XTF files and chip images, need 5-16 minutes)
#   --build DIR  use the harnesses of an existing sanitizer build (scripts/test.sh's build-test:
#                there the libraries that parse outside data carry the coverage, the simulator
#                does not) instead of building build-fuzz/; what CI does, to save a build
#   HARNESS      xtf_decode xtf_file candump_line socketcand n2k_decode pose_message imc_decode
#                model_file scenario_yaml stream_receiver png_chip (default: all)
# By default builds build-fuzz/ (clang, -DSONARLOOP_FUZZ=ON: every library instrumented for
# coverage; only the harnesses and the libraries they link). Copies the seed corpus of
# tests/fuzz/corpus/NAME into DIR/fuzz/corpus/NAME (the fuzzer grows it there, never in the source
# tree) and runs each harness with: inputs up to 64 KB (1 MB for whole files), 1 s per input at
# most (a slower input is a hang), 2 GB of memory at most. Prints per harness the executions and
# the coverage (edges, features); a crash, leak, hang or memory overrun stops with its reproducer
# saved as DIR/fuzz/findings/NAME-*, and the script exits 1. Harnesses run one per core at a time.
# Reproduce a finding with:
#   DIR/tests/fuzz/fuzz_NAME DIR/fuzz/findings/FILE
set -euo pipefail
cd "$(dirname "$0")/.."
build=""
if [ "${1:-}" = "--build" ]; then
  build="${2:?--build needs a build directory}"
  shift 2
fi
seconds="${1:-60}"
shift || true
runs=""
if [ "$seconds" = "--runs" ]; then
  runs="${1:?--runs needs a number}"
  shift
  seconds=86400  # the runs end it
fi
all=(xtf_decode xtf_file candump_line socketcand n2k_decode pose_message imc_decode model_file
     scenario_yaml stream_receiver png_chip contact_line http_request)
harnesses=("$@")
if [ ${#harnesses[@]} -eq 0 ]; then harnesses=("${all[@]}"); fi

scripts/install_clang.sh
jobs="$(nproc 2>/dev/null || echo 2)"
targets=()
for h in "${harnesses[@]}"; do targets+=("fuzz_$h"); done
if [ -z "$build" ]; then
  build=build-fuzz
  mkdir -p "$build"
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DSONARLOOP_FUZZ=ON \
    -DSONARLOOP_BUILD_TESTS=OFF > "$build/configure.log"
elif [ ! -f "$build/CMakeCache.txt" ]; then
  echo "fuzz.sh: $build is not a build directory (scripts/test.sh makes build-test)" >&2
  exit 2
fi
if ! cmake --build "$build" -j "$jobs" --target "${targets[@]}"; then
  echo "fuzz.sh: could not build the harnesses in $build (a sanitizer build with clang has them:" \
    "scripts/test.sh)" >&2
  exit 2
fi
out="$build/fuzz"

mkdir -p "$out/findings"
# fuzz_one NAME: runs one harness for $seconds, its log in $out/NAME.log and its exit code in
# $out/NAME.rc
fuzz_one() {
  local h=$1 corpus="$out/corpus/$1" max_len=65536 rc=0
  mkdir -p "$corpus"
  cp -n tests/fuzz/corpus/"$h"/* "$corpus"/ 2>/dev/null || true
  case "$h" in xtf_file | png_chip | scenario_yaml) max_len=1048576 ;; esac
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 \
    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$build/tests/fuzz/fuzz_$h" "$corpus" -max_total_time="$seconds" ${runs:+-runs="$runs"} \
    -timeout=1 -rss_limit_mb=2048 -max_len="$max_len" -print_final_stats=1 \
    -artifact_prefix="$out/findings/$h-" > "$out/$h.log" 2>&1 || rc=$?
  echo "$rc" > "$out/$h.rc"
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
  log="$out/$h.log"
  rc=$(cat "$out/$h.rc")
  execs="$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)"
  cov="$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || true)"
  ft="$(grep -o 'ft: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || true)"
  if [ "$rc" -eq 0 ]; then
    result=ok
  else
    result="FINDING (exit $rc): see $log and $out/findings/$h-*"
    status=1
  fi
  printf '%-16s %12s %8s %8s  %s\n' "$h" "${execs:-?}" "${cov:-?}" "${ft:-?}" "$result"
done
exit "$status"
