#!/usr/bin/env bash
# Fingerprints of every shipped scene's lockstep outputs, to check that a refactoring changes no
# behaviour: run it before and after, and diff the two listings.
#
#   tools/scene_fingerprints/scene_fingerprints.sh [SECONDS] > before.txt   (default 20 s of sim time)
#
# Each scene runs for SECONDS of simulated time with --out; every output file is hashed, except the
# values of timings.csv (wall-clock processing times, the one part of a run that is not
# deterministic): of it only the time, source and name columns are hashed, and of the run's record
# only what does not change from run to run (see below). The runs use a DDS domain
# of their own (UAMPC_FINGERPRINT_DOMAIN, default 150 + PID % 50), so that another run on the
# machine cannot feed them.
set -euo pipefail
shopt -s nullglob
cd "$(dirname "$0")/../.."
seconds="${1:-20}"
uampc="${UAMPC:-./build/bin/uampc}"
domain="${UAMPC_FINGERPRINT_DOMAIN:-$((150 + $$ % 50))}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for scene in config/scenes/*.yaml; do
  name="$(basename "$scene" .yaml)"
  if ! "$uampc" launch "$scene" --set clock.duration="$seconds" --set domain_id="$domain" --out "$work/$name" >"$work/$name.log" 2>&1; then
    echo "$name: FAILED (log follows)"; tail -5 "$work/$name.log"; continue
  fi
  files=("$work/$name"/*)
  [ ${#files[@]} -gt 0 ] || echo "$name: (no output files)"
  for file in "${files[@]}"; do
    case "$(basename "$file")" in
      timings.csv) hash="$(cut -d, -f1-3 "$file" | sha256sum | cut -c1-16)" ;;
      # What the run was (start time, version, paths, domain): metrics.json's figures without its
      # last key "run", printed as the evaluator printed them before it had one; the resolved
      # scene without its domain; run_info.json not at all.
      metrics.json)
        if grep -q '^  "run": {$' "$file"; then
          hash="$({ sed '/^  "run": {$/,$d' "$file" | sed '$ s/^  },$/  }/'; echo "}"; } | sha256sum | cut -c1-16)"
        else
          hash="$(sha256sum "$file" | cut -c1-16)"  # no run record (the evaluator said why)
        fi ;;
      scene.yaml) hash="$(grep -v '^domain_id: ' "$file" | sha256sum | cut -c1-16)" ;;
      run_info.json) continue ;;
      *) hash="$(sha256sum "$file" | cut -c1-16)" ;;
    esac
    echo "$name/$(basename "$file") $hash"
  done
done
