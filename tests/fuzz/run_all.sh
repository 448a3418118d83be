#!/usr/bin/env bash
# A short run of every fuzz target over its committed corpus (CI, from .ci/run; docs/dev/testing.md).
# Builds the `fuzz` preset (build-fuzz/, only the fuzz targets and what they load), then runs each
# target for FUZZ_RUNS inputs (default 3000) from random seed FUZZ_SEED (default 1), at most
# FUZZ_SECONDS (default 30), starting from a copy of tests/fuzz/<name>/corpus (the committed seeds
# are not changed; new inputs are thrown away). A fixed seed and count make CI's run the same
# inputs every time, so that it passes or fails with the code, not with luck (a time limit that
# cuts it short only leaves out the sequence's tail). Longer, random runs are for finding bugs
# (docs/dev/testing.md, "Fuzzing"). Exits non-zero at the first crash, leak, timeout or
# out-of-memory; the input that did it is left in build-fuzz/fuzz/artifacts/<name>/.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
seconds="${FUZZ_SECONDS:-30}"
runs="${FUZZ_RUNS:-3000}"
seed="${FUZZ_SEED:-1}"
lock=(flock /tmp/uampc-build.lock)
command -v flock >/dev/null 2>&1 || lock=()

# As in the asan test presets: GCC 12's sanitizer runtime can misread a dynamic TLS block (the
# component plugins the fuzzers load have them) and crash LeakSanitizer's tracer (docs/dev/testing.md,
# "Sanitizers and CI"). Options the caller set are kept; this one is added.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}intercept_tls_get_addr=0"

cd "$root"
"${lock[@]}" cmake --preset fuzz >/dev/null
"${lock[@]}" cmake --build --preset fuzz

# name max_len dictionary
targets=(
  "scene_yaml 8192 scene_yaml/scene.dict"
  "experiment_yaml 4096 experiment_yaml/experiment.dict"
  "set_override 1024 set_override/set.dict"
  "trajectory 8192 -"
  "pcd 4096 pcd/pcd.dict"
  "ply 4096 ply/ply.dict"
  "pointcloud2 4096 -"
  "panorama 16384 -"
  "mcap 16384 mcap/mcap.dict"
  "idl 4096 idl/idl.dict"
  "foxglove_request 4096 foxglove_request/request.dict"
)
bin="$root/build-fuzz/fuzz"
work="$(mktemp -d "${TMPDIR:-/tmp}/uampc-fuzz-run.XXXXXX")"
trap 'rm -rf "$work"' EXIT
start=$(date +%s)
for entry in "${targets[@]}"; do
  read -r name max_len dict <<<"$entry"
  mkdir -p "$work/$name" "$bin/artifacts/$name"
  cp "$here/$name/corpus/"* "$work/$name/"
  options=(-rss_limit_mb=2048 -max_len="$max_len" -timeout=10 -max_total_time="$seconds" -runs="$runs" -seed="$seed"
           -print_final_stats=1 -artifact_prefix="$bin/artifacts/$name/")
  [ "$dict" != "-" ] && options+=(-dict="$here/$dict")
  echo "fuzz: $name ($runs inputs from seed $seed, at most $seconds s)"
  if ! "$bin/fuzz_$name" "${options[@]}" "$work/$name" >"$work/$name.log" 2>&1; then
    tail -n 60 "$work/$name.log"
    echo "fuzz: $name FAILED; the input is in $bin/artifacts/$name/"
    exit 1
  fi
  grep -E "^#[0-9]+.*DONE|stat::number_of_executed_units|stat::peak_rss_mb" "$work/$name.log" | tr '\n' ' '
  echo
done
echo "fuzz: all ${#targets[@]} targets clean in $(( $(date +%s) - start )) s"
