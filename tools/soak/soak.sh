#!/usr/bin/env bash
# A long run of the default scene, sampled: every uampc process's resident memory (VmRSS, and its
# parts RssAnon, RssFile, RssShmem), open file descriptors and the /dev/shm entries every 10 s of
# wall time, into OUT/samples.csv (column process: "launcher" or the process group's name); then a
# run of half the length, whose outputs must be the first half of the long run's
# (docs/results/soak.md).
#   tools/soak/soak.sh OUT [SIM_SECONDS (3600)] [DOMAIN (6)]
# UAMPC (default build/bin/uampc) names the binary: copy build/ elsewhere and point UAMPC and
# LD_LIBRARY_PATH there if you rebuild while it runs. SCENE (default config/scenes/default.yaml)
# names the scene: tools/soak/default_per_component.yaml is the default scene with each component
# in a process group of its own, so that each one's memory is sampled apart. HALF=0 skips the
# half-length run.
set -euo pipefail
out="${1:?usage: soak.sh OUT [SIM_SECONDS] [DOMAIN]}"
seconds="${2:-3600}"
domain="${3:-6}"
uampc="${UAMPC:-./build/bin/uampc}"
scene="${SCENE:-config/scenes/default.yaml}"
mkdir -p "$out"
"$uampc" launch "$scene" --set clock.duration="$seconds" --set domain_id="$domain" \
  --out "$out/long" > "$out/long.log" 2>&1 &
launcher=$!
echo "t_s,pid,process,rss_kb,rss_anon_kb,rss_file_kb,rss_shmem_kb,fds,shm_entries" > "$out/samples.csv"
start=$(date +%s)
while kill -0 "$launcher" 2>/dev/null; do
  for pid in $(pgrep -f "uampc (launch|run-process) $scene.*domain_id=$domain" || true); do
    # VmRSS, and its parts: the heap and stacks (RssAnon), mapped files such as the shared
    # libraries (RssFile) and shared memory such as Fast DDS's segments (RssShmem).
    rss=$(awk '/^(VmRSS|RssAnon|RssFile|RssShmem):/ {printf "%s%s", sep, $2; sep = ","}' \
      "/proc/$pid/status" 2>/dev/null || true)
    [ -n "$rss" ] || continue
    # "launcher", or the group's name: `uampc run-process SCENE --process NAME ...`
    what=$(tr '\0' '\n' < "/proc/$pid/cmdline" 2>/dev/null |
      awk 'NR == 2 && $0 == "launch" {print "launcher"; exit} previous == "--process" {print; exit} {previous = $0}')
    [ -n "$what" ] || continue
    echo "$(( $(date +%s) - start )),$pid,$what,$rss,$(ls "/proc/$pid/fd" | wc -l),$(ls /dev/shm | wc -l)" >> "$out/samples.csv"
  done
  sleep 10
done
wait "$launcher"
if [ "${HALF:-1}" = 0 ]; then
  echo "samples: $out/samples.csv; long run: $out/long"
  exit 0
fi
"$uampc" launch "$scene" --set clock.duration=$(( seconds / 2 )) --set domain_id="$domain" \
  --out "$out/half" > "$out/half.log" 2>&1
echo "samples: $out/samples.csv; long run: $out/long; half: $out/half"
