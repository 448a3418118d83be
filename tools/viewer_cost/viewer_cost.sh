#!/usr/bin/env bash
# What a live viewer costs a run (docs/decisions/live-viewer.md): alternating pairs of the default
# scene, unpaced, alone and with `--view` and one Foxglove client (tests/foxglove_js/watch.mjs) on
# every topic; prints each run's real-time factor and the viewer's drop count.
#   tools/viewer_cost/viewer_cost.sh [PAIRS (3)] [SIM_SECONDS (40)] [DOMAIN (8)] [PORT (8792)]
set -euo pipefail
pairs="${1:-3}"; seconds="${2:-40}"; domain="${3:-8}"; port="${4:-8792}"
uampc="${UAMPC:-./build/bin/uampc}"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
factor() { grep -o '([0-9.]*x real time)' "$1" | tr -d '()'; }
for i in $(seq "$pairs"); do
  "$uampc" launch config/scenes/default.yaml --set clock.duration="$seconds" --set domain_id="$domain" \
    > "$scratch/alone.log" 2>&1
  "$uampc" launch config/scenes/default.yaml --set clock.duration="$seconds" --set domain_id="$domain" \
    --view --view-port "$port" > "$scratch/viewed.log" 2>&1 &
  run=$!
  until grep -q "uampc view: serving" "$scratch/viewed.log"; do sleep 0.05; done
  node tests/foxglove_js/watch.mjs "ws://127.0.0.1:$port" --topics all --until-closed > /dev/null || true
  wait "$run"
  echo "pair $i: alone $(factor "$scratch/alone.log"), viewed $(factor "$scratch/viewed.log")," \
       "$(grep -o '[0-9]* dropped' "$scratch/viewed.log") for the client"
done
