#!/usr/bin/env bash
# A long run of the default scene, sampled: every uampc process's resident memory, open file
# descriptors and the /dev/shm entries every 10 s of wall time, into OUT/samples.csv; then a run
# of half the length, whose outputs must be the first half of the long run's
# (docs/results/soak.md).
#   tools/soak/soak.sh OUT [SIM_SECONDS (3600)] [DOMAIN (6)]
# UAMPC (default build/bin/uampc) names the binary: copy build/ elsewhere and point UAMPC and
# LD_LIBRARY_PATH there if you rebuild while it runs.
set -euo pipefail
out="${1:?usage: soak.sh OUT [SIM_SECONDS] [DOMAIN]}"
seconds="${2:-3600}"
domain="${3:-6}"
uampc="${UAMPC:-./build/bin/uampc}"
mkdir -p "$out"
"$uampc" launch config/scenes/default.yaml --set clock.duration="$seconds" --set domain_id="$domain" \
  --out "$out/long" > "$out/long.log" 2>&1 &
launcher=$!
echo "t_s,pid,process,rss_kb,fds,shm_entries" > "$out/samples.csv"
start=$(date +%s)
while kill -0 "$launcher" 2>/dev/null; do
  for pid in $(pgrep -f "uampc (launch|run-process) config/scenes/default.yaml.*domain_id=$domain" || true); do
    rss=$(awk '/VmRSS/ {print $2}' "/proc/$pid/status" 2>/dev/null || true)
    [ -n "$rss" ] || continue
    what=$(tr '\0' ' ' < "/proc/$pid/cmdline" | awk '{print $2 ($3 == "" ? "" : "")}')
    echo "$(( $(date +%s) - start )),$pid,$what,$rss,$(ls "/proc/$pid/fd" | wc -l),$(ls /dev/shm | wc -l)" >> "$out/samples.csv"
  done
  sleep 10
done
wait "$launcher"
"$uampc" launch config/scenes/default.yaml --set clock.duration=$(( seconds / 2 )) --set domain_id="$domain" \
  --out "$out/half" > "$out/half.log" 2>&1
echo "samples: $out/samples.csv; long run: $out/long; half: $out/half"
