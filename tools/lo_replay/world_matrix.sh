#!/usr/bin/env bash
# world_matrix.sh [--jobs N] [--only REGEX] [LO_REPLAY_FLAGS ...]
#
# Runs build/bench/lo_replay over the worlds on which the LO's parameters are decided (whole MCD
# trajectories, the indoor worlds, the density worlds, the LiDAR-inertial campus loop;
# docs/results/lo-degenerate-geometry.md, "A registration budget"), every run at a constant motor speed
# and with the scenes' 2 cm range noise, and prints one line per run: its name, then lo_replay's summary.
# REPLAY=PATH runs another lo_replay binary (e.g. a copy of an older build). LO_REPLAY_FLAGS are added to every run (e.g. --set lo.max_registration_points=2000). --only keeps the runs
# whose name matches REGEX (grep -E). N runs at a time (default: the number of cores); the lines come in
# the order of the list below whatever order the runs finish in, and stderr says each as it ends.
set -euo pipefail
cd "$(dirname "$0")/../.."
replay=${REPLAY:-build/bench/lo_replay}
[ -x "$replay" ] || { echo "world_matrix: $replay not built (cmake --workflow --preset build)" >&2; exit 1; }

jobs=$(nproc)
only=""
while [ $# -gt 0 ]; do
  case "$1" in
    --jobs|--only)
      [ $# -ge 2 ] || { echo "world_matrix: $1 needs a value" >&2; exit 2; }
      if [ "$1" = --jobs ]; then jobs="$2"; else only="$2"; fi
      shift 2 ;;
    -h|--help) sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) break ;;
  esac
done
export EXTRA_FLAGS="$*"

noise="--set lidar.range_noise=0.02"
indoor="--set lo.scan_voxel_size=0.15 --set lo.map_voxel_size=0.15"
# name|arguments
runs=(
  "kth-1.8-s1|data/mcd/kth_day06.csv --duration 1e6 --motor 1.8 --seed 1 $noise"
  "kth-1.8-s2|data/mcd/kth_day06.csv --duration 1e6 --motor 1.8 --seed 2 $noise"
  "kth-3.6|data/mcd/kth_day06.csv --duration 1e6 --motor 3.6 $noise"
  "ntu-3.6|data/mcd/ntu_day01.csv --duration 1e6 --motor 3.6 $noise"
  "tuhh-3.6|data/mcd/tuhh_day03.csv --duration 1e6 --motor 3.6 $noise"
  "corridor-doors|corridor --set world.corridor_door_spacing=8 --duration 1e6 $indoor $noise"
  "corridor-plain|corridor --duration 1e6 $indoor $noise"
  "multilevel|multilevel --duration 1e6 $indoor $noise"
)
for site in kth:kth_day06 ntu:ntu_day01 tuhh:tuhh_day03; do
  for profile in mixed poor; do
    for seed in 1 2; do
      runs+=("${site%%:*}-$profile-s$seed|data/mcd/${site#*:}.csv --duration 180 --set world.density_profile=$profile --seed $seed $noise")
    done
  done
done
for seed in 1 2 3; do
  runs+=("campus-imu-3.6-s$seed|campus --duration 1e6 --seed $seed --set lo.use_imu=true $noise")
done
runs+=("kth-imu-3.6|data/mcd/kth_day06.csv --duration 1e6 --motor 3.6 --set lo.use_imu=true $noise")

# Each run's line goes to its own file, and the lines are printed in the order above once all
# have run (parallel runs finish in any order); stderr says each run as it finishes.
results=$(mktemp -d)
trap 'rm -rf "$results"' EXIT
export results

run_one() {
  local index="${1%%|*}" run="${1#*|}"
  local name="${run%%|*}" args="${run#*|}"
  local summary
  # shellcheck disable=SC2086  # both are lists of words by construction
  summary=$("$replay" $args $EXTRA_FLAGS | grep '^summary:' || echo "summary: lo_replay failed")
  printf '%-18s %s\n' "$name" "${summary#summary: }" > "$results/$index"
  echo "world_matrix: $name done" >&2
}
export -f run_one
export replay

count=0
for run in "${runs[@]}"; do
  if [ -z "$only" ] || [[ "${run%%|*}" =~ $only ]]; then
    printf '%s|%s\0' "$count" "$run"
    count=$((count + 1))
  fi
done | xargs -0 -n 1 -P "$jobs" bash -c 'run_one "$1"' _
# By index (numerically), whatever ran: a run whose file is missing cannot stop the others' lines.
find "$results" -type f -printf '%f\n' | sort -n | while read -r i; do cat "$results/$i"; done
