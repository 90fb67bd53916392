#!/usr/bin/env bash
# Runs the fuzz targets of a fuzz build (-DDSS_BUILD_FUZZ=ON) on their corpora and summarises
# each run: executions, crashes (inputs libFuzzer saved as crash-, leak-, timeout- or oom-
# artifacts), the slowest input's time and the peak memory.
#
#   fuzz/long_run.sh BUILD_DIR [--time SECONDS] [--runs N] [--parallel P] [--seed S] [TARGET...]
#
# Each target runs until SECONDS (default 3600) or N executions (default 10^7), whichever
# comes first, P targets at a time (default 1: the machine may be shared), with libFuzzer's
# random seed S (default: libFuzzer's own, from the clock). Corpora are
# BUILD_DIR/fuzz/corpus/<target> (fuzz/make_corpora.sh builds them; run here when missing) and
# grow with what the run finds; artifacts go to BUILD_DIR/fuzz/artifacts/<target>/, logs to
# BUILD_DIR/fuzz/logs/<target>.log, the summary table (Markdown) to BUILD_DIR/fuzz/summary.md
# and stdout. Exits 1 when any target saved an artifact. A short check, as CI runs it:
#   fuzz/long_run.sh build-fuzz --time 10 --seed 1
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -lt 1 ]; then
  sed -n '2,15p' "$0" >&2
  exit 2
fi
build=$(cd "$1" && pwd)
shift
seconds=3600
runs=10000000
parallel=1
seed=()
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --time) seconds=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --parallel) parallel=$2; shift 2 ;;
    --seed) seed=(-seed="$2"); shift 2 ;;
    -*) echo "unknown option $1" >&2; exit 2 ;;
    *) targets+=("$1"); shift ;;
  esac
done
if [ ${#targets[@]} -eq 0 ]; then
  mapfile -t targets < "$build/fuzz/targets.txt"
fi
[ -d "$build/fuzz/corpus" ] || "$src/fuzz/make_corpora.sh" "$build"
# Leaks inside assimp on malformed files are assimp's (see fuzz/lsan.supp).
export LSAN_OPTIONS=suppressions=$src/fuzz/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}

# Input size bounds: the readers see whole files (the largest seeds are 64 KiB), the core a
# few hundred decoded values.
max_len() {
  case "$1" in
    fuzz_core) echo 4096 ;;
    fuzz_pairs | fuzz_joint_states_csv | fuzz_plan_request | fuzz_srdf) echo 16384 ;;
    *) echo 65536 ;;
  esac
}

run_one() {
  local t=$1
  local corpus=$build/fuzz/corpus/$t artifacts=$build/fuzz/artifacts/$t log=$build/fuzz/logs/$t.log
  mkdir -p "$corpus" "$artifacts" "$(dirname "$log")"
  rm -f "$artifacts"/*
  local start=$SECONDS status=0 TIMEFORMAT='cpu_seconds: %U %S'
  # -timeout: an input taking 25 s is a hang; inputs slower than 10 s are kept as slow-unit
  # artifacts (not counted as crashes). Leak detection stays on (ASan's LeakSanitizer).
  # The CPU time (user and system) is recorded beside the wall time: on a shared machine it
  # says how much of the wall time the target ran.
  { time "$build/fuzz/$t" "$corpus" -artifact_prefix="$artifacts/" -max_total_time="$seconds" \
    -runs="$runs" -max_len="$(max_len "$t")" -timeout=25 -rss_limit_mb=2560 \
    -report_slow_units=10 -print_final_stats=1 "${seed[@]}" > "$log" 2>&1 || status=$?; } 2> "$log.cpu"
  cat "$log.cpu" >> "$log" && rm -f "$log.cpu"
  echo "wall_seconds: $((SECONDS - start))" >> "$log"
  echo "exit_status: $status" >> "$log"
}

# Runs the targets, at most $parallel at a time.
pids=()
for t in "${targets[@]}"; do
  run_one "$t" &
  pids+=($!)
  while [ "$(jobs -rp | wc -l)" -ge "$parallel" ]; do sleep 1; done
done
wait

stat() { grep -m1 "^stat::$2:" "$1" | awk '{print $2}'; }
summary=$build/fuzz/summary.md
{
  echo "| target | executions | crashes | slowest input (s) | peak RSS (MB) | wall (s) | CPU (s) |"
  echo "|---|---|---|---|---|---|---|"
} > "$summary"
failed=0
for t in "${targets[@]}"; do
  log=$build/fuzz/logs/$t.log
  crashes=$(find "$build/fuzz/artifacts/$t" -type f \( -name 'crash-*' -o -name 'leak-*' \
    -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
  [ "$crashes" -eq 0 ] || failed=1
  printf '| %s | %s | %s | %s | %s | %s | %s |\n' "$t" "$(stat "$log" number_of_executed_units)" \
    "$crashes" "$(stat "$log" slowest_unit_time_sec)" "$(stat "$log" peak_rss_mb)" \
    "$(grep -m1 '^wall_seconds:' "$log" | awk '{print $2}')" \
    "$(grep -m1 '^cpu_seconds:' "$log" | awk '{printf "%.0f", $2 + $3}')" >> "$summary"
done
cat "$summary"
if [ "$failed" -ne 0 ]; then
  echo "fuzzing found crashes: see $build/fuzz/artifacts and $build/fuzz/logs" >&2
  exit 1
fi
