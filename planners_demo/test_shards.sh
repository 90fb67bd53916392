#!/usr/bin/env bash
# dss_plan --shard: shards of one problem folder, run side by side with GNU parallel, give
# exactly the problems and results of one run over the whole folder (planning times aside),
# and dss_plan --summarize merges their lines into that run's solved count. Reported skipped
# (exit 77) without GNU parallel (Debian package parallel).
#   test_shards.sh DSS_PLAN SOURCE_DIR WORK_DIR
set -euo pipefail
plan=$1 src=$2 work=$3
command -v parallel > /dev/null || { echo "skipped: GNU parallel not installed (package parallel)"; exit 77; }
rm -rf "$work" && mkdir -p "$work/problems"
arm="$src/robots/dss_arm7"
# Five problems of our arm in its shelf scene with different goals for joint 1, so that each
# problem's result is its own.
i=0
for goal in -0.19 -0.05 0.1 -0.3 0.0; do
  i=$((i + 1)); n=$(printf '%04d' $i)
  cp "$arm/scenes/shelf.yaml" "$work/problems/scene$n.yaml"
  awk -v g="$goal" '/joint_name: joint1$/ {print; getline; sub(/position: .*/, "position: " g)} {print}' \
    "$arm/scenes/shelf_request.yaml" > "$work/problems/request$n.yaml"
done
common=(--robot "$arm/dss_arm7.urdf" --srdf "$arm/dss_arm7.srdf" --problems "$work/problems" --time 20)
"$plan" "${common[@]}" > "$work/all.jsonl" 2> "$work/all.err"
export plan work
parallel -j2 '"$plan" --robot {2}/dss_arm7.urdf --srdf {2}/dss_arm7.srdf --problems "$work/problems" --time 20 --shard {1}/3 > "$work/shard{1}.jsonl" 2> "$work/shard{1}.err"' ::: 1 2 3 ::: "$arm"
python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
def load(paths):
    rows = []
    for p in paths:
        for line in open(p):
            if line.strip():
                j = json.loads(line)
                for k in ("planning_time_s", "planning_cpu_s", "setup_s"):
                    j.pop(k)
                rows.append(json.dumps(j, sort_keys=True))
    return sorted(rows)
whole = load([work + "/all.jsonl"])
shards = load([work + "/shard%d.jsonl" % k for k in (1, 2, 3)])
if len(whole) != 5:
    sys.exit("FAIL: the whole run has %d problems, expected 5" % len(whole))
if whole != shards:
    sys.exit("FAIL: the shards differ from the whole run:\n" + "\n".join(sorted(set(whole) ^ set(shards))))
if len(set(json.loads(r)["validity_checks"] for r in whole)) < 2:
    sys.exit("FAIL: every problem gave the same result: the goals do not differ")
print("shards agree with the whole run on %d problems" % len(whole))
PY
"$plan" --summarize "$work"/shard1.jsonl "$work"/shard2.jsonl "$work"/shard3.jsonl > "$work/merged.txt"
whole_solved=$(grep -o 'solved [0-9]* of [0-9]*' "$work/all.err")
merged_solved=$(grep -o 'solved [0-9]* of [0-9]*' "$work/merged.txt")
[ "$whole_solved" = "$merged_solved" ] || { echo "FAIL: summary '$merged_solved' against '$whole_solved'"; exit 1; }
# Mixing runs of different seeds is refused.
sed 's/"seed":1/"seed":2/' "$work/shard1.jsonl" > "$work/other_seed.jsonl"
if "$plan" --summarize "$work/other_seed.jsonl" "$work/shard2.jsonl" > /dev/null 2> "$work/mixed.err"; then
  echo "FAIL: runs of different seeds were merged"; exit 1
fi
grep -q "differ from the first line" "$work/mixed.err" || { echo "FAIL: $(cat "$work/mixed.err")"; exit 1; }
echo "summary of the shards: $merged_solved"
