#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) in their own build dir and runs each for a bounded
# time on a scratch copy of its seed corpus. Exits non-zero on any finding (crash, sanitizer report, leak, timeout,
# out-of-memory); the reproducer and the log stay in test-artifacts/fuzz/.
#
#   tests/fuzz/run.sh                     every target for FUZZ_SECONDS (default 45 s), two at a time
#   FUZZ_RUNS=1000000 tests/fuzz/run.sh   a fixed number of executions per target instead of a time
#   tests/fuzz/run.sh nmea vcu            only these targets
#
# Only the fuzz targets are built with clang (the target fuzz_targets), never the rest of the project.
set -euo pipefail
cd "$(dirname "$0")/../.."

build="${FUZZ_BUILD:-build-fuzz}"
seconds="${FUZZ_SECONDS:-45}"
runs="${FUZZ_RUNS:-}"
jobs="${FUZZ_JOBS:-2}"            # build jobs and targets fuzzed at once (the machine has 2 cores)
out="test-artifacts/fuzz"
targets=("$@")
((${#targets[@]})) || targets=(vlp16_packet vlp16_pcap nmea vcu mcap_reader cone_crop cone_model csv_cloud sensor_csv
                                foxglove_client http_api dds_messages truth_frames)

# Per-target libFuzzer options. NMEA lines are at most 82 characters: 2 KiB holds ~25 sentences (several receiver
# epochs) and keeps the executions fast; the 16 KB seeds are truncated to it, which still covers every sentence type.
declare -A extra=([nmea]="-max_len=2048")

t0=$(date +%s)
if [[ ! -f "$build/build.ninja" ]]; then
  mkdir -p "$build"
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFSD_FUZZ=ON \
    -DFSD_BUILD_TESTS=OFF -DFSD_BUILD_BENCH=OFF "${launcher[@]}" >"$build/configure.log" 2>&1 ||
    { cat "$build/configure.log"; exit 1; }
fi
cmake --build "$build" -j "$jobs" --target fuzz_targets
t_build=$(($(date +%s) - t0))

rm -rf "$out" && mkdir -p "$out"
scratch="$build/fuzz-scratch"
rm -rf "$scratch"

# One target: a fresh copy of the seeds (libFuzzer adds new inputs to the first directory it is given, and the
# committed corpus must not change), artefacts (crash-*, leak-*, timeout-*, oom-*) under test-artifacts/fuzz/NAME/.
fuzz_one() {
  local name="$1" bin="$build/tests/fuzz/${1}_fuzz"
  local corpus="$scratch/$name" art="$out/$name/"
  mkdir -p "$corpus" "$art"
  cp tests/fuzz/corpus/"$name"/* "$corpus"/
  local budget=(-max_total_time="$seconds")
  [[ -n "$runs" ]] && budget=(-runs="$runs")
  local rc=0
  # shellcheck disable=SC2086  # extra options are words on purpose
  "$bin" "${budget[@]}" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$art" \
    ${extra[$name]:-} "$corpus" >"$out/$name.log" 2>&1 || rc=$?
  local execs rate
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$out/$name.log")
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$out/$name.log")
  if ((rc)); then
    echo "fuzz: $name FOUND A BUG (exit $rc) after ${execs:-?} executions; log and input in $out/$name*"
    grep -m1 -E '^(==[0-9]+== ?ERROR|.*runtime error|SUMMARY)' "$out/$name.log" || tail -20 "$out/$name.log"
  else
    echo "fuzz: $name ok, ${execs:-?} executions, ${rate:-?} exec/s, corpus $(ls "$corpus" | wc -l) inputs"
    rmdir "$art" 2>/dev/null || true
  fi
  return "$rc"
}

failed=0
pids=() names=()
for name in "${targets[@]}"; do
  [[ -x "$build/tests/fuzz/${name}_fuzz" ]] || { echo "fuzz: no target ${name}_fuzz" >&2; exit 2; }
  fuzz_one "$name" & pids+=($!) names+=("$name")
  if ((${#pids[@]} >= jobs)); then
    wait "${pids[0]}" || failed=$((failed + 1))
    pids=("${pids[@]:1}") names=("${names[@]:1}")
  fi
done
for p in "${pids[@]}"; do wait "$p" || failed=$((failed + 1)); done
rm -rf "$scratch"

echo "fuzz: ${#targets[@]} targets, build ${t_build} s, total $(($(date +%s) - t0)) s, $failed with a finding"
((failed == 0))
