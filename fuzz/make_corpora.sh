#!/usr/bin/env bash
# Seed corpora of the fuzz targets, built into BUILD_DIR/fuzz/corpus/<target>/ from the files
# a user would hand the readers: the shared robots and scenes (SHARED_DIR, default ../shared
# next to the checkout; skipped when absent), our own robots (robots/), the small seeds of
# fuzz/seeds/<target>/ and, for the core, deterministic pseudo-random inputs of each scenario.
# Nothing is copied into the repository. Files are named by their SHA-1, as libFuzzer names
# the inputs it adds, so that running the script again adds nothing twice.
#
#   fuzz/make_corpora.sh BUILD_DIR [SHARED_DIR]
set -euo pipefail
if [ $# -lt 1 ]; then
  echo "usage: $0 BUILD_DIR [SHARED_DIR]" >&2
  exit 2
fi
src=$(cd "$(dirname "$0")/.." && pwd)
out=$1/fuzz/corpus
shared=${2:-$src/../shared}
# Inputs above this size slow every mutation down and teach the readers nothing new.
max_bytes=65536

# add TARGET PREFIX FILE...: copies each FILE (at most max_bytes) into the target's corpus,
# after PREFIX bytes (printf format; the mesh target's selector).
add() {
  local target=$1 prefix=$2
  shift 2
  mkdir -p "$out/$target"
  local f tmp sum
  for f in "$@"; do
    [ -f "$f" ] || continue
    [ "$(stat -c %s "$f")" -le "$max_bytes" ] || continue
    tmp=$(mktemp)
    { printf "$prefix"; cat "$f"; } > "$tmp"
    sum=$(sha1sum "$tmp" | cut -d' ' -f1)
    mv "$tmp" "$out/$target/$sum"
  done
}

# find_in DIR ARGS...: find's output, nothing when DIR is missing.
find_in() {
  local dir=$1
  shift
  [ -d "$dir" ] || return 0
  find "$dir" "$@" -print0 | sort -z | xargs -0 -r printf '%s\n'
}

mapfile -t urdfs < <(find_in "$src/robots" -name '*.urdf'; find_in "$shared/robots" -name '*.urdf')
mapfile -t worlds < <(find_in "$shared/scenes" -name '*.urdf')
mapfile -t srdfs < <(find_in "$src/robots" -name '*.srdf'; find_in "$shared/robots" -name '*.srdf'
  find_in "$src/benchmarks/data" -name '*.srdf')
mapfile -t yamls < <(find_in "$src/robots" -name '*.yaml'; find_in "$shared/scenes" -name '*.yaml')
mapfile -t scenes < <(find_in "$shared/scenes" -name '*.scene')
mapfile -t pairs < <(find_in "$shared/testdata" -name '*.jsonl')
mapfile -t stls < <(find_in "$src/robots" -iname '*.stl'; find_in "$shared" -iname '*.stl')
mapfile -t objs < <(find_in "$shared" -iname '*.obj')
mapfile -t daes < <(find_in "$shared" -iname '*.dae')

# PlanningScene YAML and MotionPlanRequest YAML by their top-level keys.
scene_yamls=()
request_yamls=()
for f in "${yamls[@]}"; do
  if grep -qE '^(world|robot_state|allowed_collision_matrix|collision_objects):' "$f"; then
    scene_yamls+=("$f")
  elif grep -qE '^(group_name|goal_constraints|start_state):' "$f"; then
    request_yamls+=("$f")
  fi
done

add fuzz_urdf '' "${urdfs[@]}" "$src"/fuzz/seeds/fuzz_urdf/*
add fuzz_srdf '' "${srdfs[@]}" "$src"/fuzz/seeds/fuzz_srdf/*
add fuzz_urdf_world '' "${worlds[@]}" "${urdfs[@]}" "$src"/fuzz/seeds/fuzz_urdf_world/*
add fuzz_planning_scene_yaml '' "${scene_yamls[@]}" "$src"/fuzz/seeds/fuzz_planning_scene_yaml/*
add fuzz_plan_request '' "${request_yamls[@]}" "$src"/fuzz/seeds/fuzz_plan_request/*
add fuzz_scene_text '' "${scenes[@]}" "$src"/fuzz/seeds/fuzz_scene_text/*
add fuzz_pairs '' "$src"/fuzz/seeds/fuzz_pairs/*
add fuzz_joint_states_csv '' "$src"/fuzz/seeds/fuzz_joint_states_csv/*
add fuzz_decomposition_cache '' "$src"/fuzz/seeds/fuzz_decomposition_cache/*
# The mesh target's first byte chooses the extension (0 .stl, 1 .obj, 2 .dae; 3-5 mirrored).
add fuzz_mesh '\000' "${stls[@]}" "$src"/fuzz/seeds/fuzz_mesh/*.stl
add fuzz_mesh '\003' "$src"/fuzz/seeds/fuzz_mesh/*.stl
add fuzz_mesh '\001' "${objs[@]}" "$src"/fuzz/seeds/fuzz_mesh/*.obj
add fuzz_mesh '\002' "${daes[@]}" "$src"/fuzz/seeds/fuzz_mesh/*.dae

# Pair files hold hundreds of lines: each line is a seed of its own, and so is each file's head.
if [ "${#pairs[@]}" -gt 0 ]; then
  tmpdir=$(mktemp -d)
  for f in "${pairs[@]}"; do
    case "$f" in *.answers.jsonl) continue ;; esac
    split -l 1 -a 4 "$f" "$tmpdir/$(basename "$f" .jsonl)."
    head -n 8 "$f" > "$tmpdir/$(basename "$f" .jsonl).head"
  done
  add fuzz_pairs '' "$tmpdir"/*
  rm -rf "$tmpdir"
fi

# The core target decodes structured values: seeds are deterministic pseudo-random bytes whose
# last byte (the first value FuzzedDataProvider takes) selects each of the four scenarios.
mkdir -p "$out/fuzz_core"
tmpdir=$(mktemp -d)
RANDOM=2024  # bash's generator, seeded: the same seeds on every machine
for scenario in 0 1 2 3; do
  for i in $(seq 0 15); do
    sizes=(64 128 256 512)
    size=${sizes[RANDOM % 4]}
    bytes=""
    for _ in $(seq 2 "$size"); do
      printf -v b '\\%03o' $((RANDOM % 256))
      bytes+=$b
    done
    printf -v b '\\%03o' "$scenario"
    printf "$bytes$b" > "$tmpdir/core_${scenario}_$i"
  done
done
add fuzz_core '' "$tmpdir"/*
rm -rf "$tmpdir"

for d in "$out"/*/; do
  printf '%-28s %5d seeds\n' "$(basename "$d")" "$(find "$d" -type f | wc -l)"
done
