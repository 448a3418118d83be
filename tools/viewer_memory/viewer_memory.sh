#!/usr/bin/env bash
# What clients cost the live viewer's memory (docs/user/viewing.md, "What clients cost"): a
# `uampc view` beside the default scene paced at real time, and Foxglove's client
# (tests/foxglove_js/watch.mjs) in the hostile cases: one client with 500 subscription ids on
# /lidar/points that never reads, 100 clients on every topic that never read, 100 that read. Prints
# per case, each in a viewer of its own, the viewer's resident memory before, at its peak while the
# clients are there, and once they have left.
#   tools/viewer_memory/viewer_memory.sh [SECONDS_PER_CASE (15)] [DOMAIN (9)] [PORT (8793)] [-- VIEW_OPTIONS]
# UAMPC=path/to/uampc measures another build (an older one, to compare).
set -euo pipefail
seconds="${1:-15}"; domain="${2:-9}"; port="${3:-8793}"
shift $(( $# < 3 ? $# : 3 )); [ "${1:-}" = "--" ] && shift
uampc="${UAMPC:-./build/bin/uampc}"
scratch="$(mktemp -d)"
view=""; run=""
trap '[ -n "$view" ] && kill "$view" 2>/dev/null; [ -n "$run" ] && kill "$run" 2>/dev/null; rm -rf "$scratch"' EXIT
mib() { awk -v k="$1" 'BEGIN { printf "%.0f", k / 1024 }'; }
field() { awk -v f="$1:" '$1 == f { print $2 }' "/proc/$view/status"; }

startView() {
  "$uampc" view --domain "$domain" --port "$port" "${view_options[@]}" > "$scratch/view.log" 2>&1 &
  view=$!
  until grep -q "uampc view: serving" "$scratch/view.log"; do sleep 0.1; done
}
stopView() { kill "$view"; wait "$view" || true; view=""; }
view_options=("$@")
# Long enough for every case; paced, so that it publishes as a rig does.
"$uampc" launch config/scenes/default.yaml --set clock.real_time_factor=1 --set clock.duration=$((3 * seconds + 90)) \
  --set domain_id="$domain" > "$scratch/run.log" 2>&1 &
run=$!
sleep 8  # the run's topics discovered and publishing
watch() { node tests/foxglove_js/watch.mjs "ws://127.0.0.1:$port" "$@" > "$scratch/watch.json" || true; }
# What the server did to the clients, from watch.mjs's line.
verdict() {
  node -e 'const r = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"));
    const held = r.held_clients ? `, ${r.held_clients.closed_by_server} held one(s) disconnected` : "";
    console.log(`first client disconnected: ${r.closed_by_server}${held}`);' "$scratch/watch.json" 2>/dev/null || echo "?"
}

measure() {  # NAME WATCH_ARGS...: in a viewer of its own
  local name="$1"; shift
  startView
  sleep 2
  local before; before="$(field VmRSS)"
  watch "$@" --seconds "$seconds"
  local peak; peak="$(field VmHWM)"
  sleep 3  # the clients' leaving seen, and malloc_trim'd
  echo "$name: before $(mib "$before") MiB, peak $(mib "$peak") MiB, after they left $(mib "$(field VmRSS)") MiB;" \
       "$(verdict)"
  stopView
}

measure "1 client, 500 subscription ids on /lidar/points, never reading" \
  --topics /lidar/points --subscriptions-per-topic 500 --stop-reading
measure "100 clients on every topic, never reading" --topics all --stop-reading --hold-clients 99 --held-subscribe
measure "100 clients on every topic, reading" --topics all --hold-clients 99 --held-subscribe --held-reading
