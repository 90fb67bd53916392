#!/usr/bin/env bash
# Regenerates every narrow-phase figure from fresh benchmark output.
#
#   benchmarks/plots/regenerate.sh [--quick] [--long] [--tradeoff] [--build DIR] [--out DIR]
#
# Runs `dss_bench narrowphase` (with the vertex-count sweep) and a `dss_bench failure-rate`
# density scan, writing CSV/JSON into OUT/data/, then draws the PNGs into OUT with
# plot_narrowphase.py. The long failure-rate run (1e8 pairs, minutes to tens of minutes) is
# only rerun with --long; otherwise its committed result OUT/failure_rate.json is drawn.
#
#   --quick      seconds-long runs (what CI calls, so the scripts cannot rot); output goes to
#                BUILD/figures-quick unless --out is given, so committed figures stay intact
#   --long       also rerun the 1e8-pair failure-rate run (nice -n 19)
#   --tradeoff   also rerun the full `dss_bench tradeoff` grid (about 30-40 min on 2 cores;
#                otherwise the committed OUT/data/tradeoff.csv is drawn; --quick always runs
#                its seconds-long version)
#   --build DIR  build folder holding benchmarks/dss_bench (default: $DSS_BUILD_DIR or build)
#   --out DIR    figure folder (default: docs/figures)
#
# Needs python3 with matplotlib (Debian: python3-matplotlib); no display (Agg backend).
# Exits non-zero if any step fails.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
quick=0
long=0
tradeoff=0
build="${DSS_BUILD_DIR:-$root/build}"
out=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --quick) quick=1 ;;
    --long) long=1 ;;
    --tradeoff) tradeoff=1 ;;
    --build) build="$2"; shift ;;
    --out) out="$2"; shift ;;
    -h|--help) sed -n '2,22p' "${BASH_SOURCE[0]}"; exit 0 ;;
    *) echo "regenerate.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done

bench="$build/benchmarks/dss_bench"
if [[ ! -x "$bench" ]]; then
  echo "regenerate.sh: $bench not found; build it first (cmake --build $build --target dss_bench)" >&2
  exit 1
fi
if [[ -z "$out" ]]; then
  if [[ $quick == 1 ]]; then out="$build/figures-quick"; else out="$root/docs/figures"; fi
fi
data="$out/data"
mkdir -p "$data"

# A python3 that has matplotlib (a pyenv shim may shadow the Debian one).
python="${PYTHON:-}"
if [[ -z "$python" ]]; then
  for p in python3 /usr/bin/python3; do
    if command -v "$p" >/dev/null && "$p" -c "import matplotlib" 2>/dev/null; then python="$p"; break; fi
  done
fi
if [[ -z "$python" ]]; then
  echo "regenerate.sh: no python3 with matplotlib (apt-get install python3-matplotlib)" >&2
  exit 1
fi

rel() { realpath --relative-to="$root" "$1"; }
commit="$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
note="commit $commit, $(date -u +%Y-%m-%d), $(nproc) cores, load average at start $(cut -d' ' -f1-3 /proc/loadavg)"
if [[ $quick == 1 ]]; then
  np_args=(--quick --sweep)
  fr_args=(--pairs 2e4 --sigmas 1,2,4 --double)
else
  np_args=(--reps 9 --sweep --sweep-vertices 4,8,12,16,24,32,48,64,96,128,256,512,1024)
  fr_args=(--pairs 5e6 --sigmas 0.5,1,1.5,2,2.5,3,4,6,10 --double)
fi
np_csv="$data/narrowphase.csv"
np_json="$data/narrowphase.json"
fr_scan="$data/failure_rate_scan.jsonl"
np_cmd="dss_bench narrowphase ${np_args[*]} --csv $(rel "$np_csv") --json $(rel "$np_json")"

cd "$root"  # relative paths from here on, so that the commands recorded in the data are portable
echo "== $np_cmd"
nice -n 10 "$bench" narrowphase "${np_args[@]}" --csv "$(rel "$np_csv")" --json "$(rel "$np_json")" > "$data/narrowphase.txt"
echo "== dss_bench failure-rate ${fr_args[*]} --json $(rel "$fr_scan")"
nice -n 10 "$bench" failure-rate "${fr_args[@]}" --note "$note" --json "$(rel "$fr_scan")" > "$data/failure_rate_scan.txt"

fr_long="$out/failure_rate.json"
if [[ $long == 1 ]]; then
  echo "== dss_bench failure-rate --pairs 1e8 --sigma 2 --double --json $(rel "$fr_long")  (long)"
  nice -n 19 "$bench" failure-rate --pairs 1e8 --sigma 2 --double --note "$note" --json "$(rel "$fr_long")" > "$data/failure_rate_long.txt"
fi
long_args=()
if [[ -s "$fr_long" ]]; then
  long_args=(--failure-long "$fr_long")
elif [[ -s "$root/docs/figures/failure_rate.json" ]]; then
  long_args=(--failure-long "$root/docs/figures/failure_rate.json")
fi

{
  echo "# commands that produced the data in this folder ($note)"
  echo "$np_cmd"
  echo "dss_bench failure-rate ${fr_args[*]} --json $(rel "$fr_scan")"
} > "$data/commands.txt"

# Speed/accuracy trade of checking settings on the shared robots (plot_tradeoff.py). Without
# ../shared the run skips every robot and writes a header-only CSV; nothing is drawn then.
to_csv="$data/tradeoff.csv"
if [[ $quick == 1 ]]; then
  to_args=(--quick)
else
  to_args=(--states 50000 --motions 2000)
fi
to_cmd="dss_bench tradeoff ${to_args[*]} --csv $(rel "$to_csv")"
if [[ $quick == 1 || $tradeoff == 1 ]]; then
  echo "== $to_cmd"
  # Exit 77: the shared robots are absent, nothing measured (the header-only CSV draws nothing).
  rc=0
  nice -n 5 "$bench" tradeoff "${to_args[@]}" --csv "$(rel "$to_csv")" > "$data/tradeoff.txt" || rc=$?
  if [[ $rc != 0 && $rc != 77 ]]; then exit $rc; fi
  echo "$to_cmd" >> "$data/commands.txt"
fi
if [[ -s "$to_csv" ]]; then
  "$python" "$here/plot_tradeoff.py" --data "$to_csv" --out "$out" --note "$note" --summary "$data/tradeoff_summary.md"
fi

"$python" "$here/plot_narrowphase.py" --data "$np_csv" --command "$np_cmd" \
  --failure-scan "$fr_scan" "${long_args[@]}" --note "$note" --out "$out" --summary "$data/summary.md"
echo "figures in $(rel "$out")"
