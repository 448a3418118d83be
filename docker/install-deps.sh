#!/usr/bin/env bash
# The only install step of uampc. README, .ci/run and docker/Dockerfile all call it.
# Installs every build and run dependency from Debian 12's archive. Idempotent: a second run
# finds everything installed and changes nothing.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build ccache pkg-config git
  # middleware: Fast DDS 2.9 and its code generator, tools (fastdds discovery, shm clean)
  libfastrtps-dev libfastcdr-dev fastddsgen fastdds-tools
  # algorithms (libpcl-dev only for pcd_pcl_test, which holds our PCD reader and writer to PCL's;
  # nothing we ship links PCL: docs/decisions/pcd-own-reader.md)
  libeigen3-dev libpcl-dev libceres-dev liboctomap-dev libembree-dev
  # CRC-32 and deflate (MCAP checksums, PNG snapshots)
  zlib1g-dev
  # the live viewer: a Foxglove WebSocket server (libs/foxglove_server)
  libwebsocketpp-dev libasio-dev
  # configuration, JSON files, the command line
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev
  # DDS Security: `uampc security init` runs openssl; the runtime checks certificates with libcrypto
  openssl libssl-dev
  # tests and benchmarks; Cyclone DDS proves our wire format to another vendor
  libgtest-dev libgmock-dev libbenchmark-dev cyclonedds-dev cyclonedds-tools
  # the experiment report is checked in headless Chromium; xmllint checks its SVG figures
  chromium libxml2-utils
  # fuzzing (tests/fuzz, the fuzz preset): clang 14 and its libFuzzer, ASan and UBSan runtimes
  clang libclang-rt-14-dev
  # `uampc experiment --backend slurm` is tested against a real one-node cluster (tests/slurm)
  slurm-wlm munge
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
else
  echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# ---- MCAP recordings ----
# libzstd and liblz4 compress the chunks of uampc's MCAP files; node and npm run the independent
# reader of its test (tests/mcap_js: Foxglove's @mcap/core and @foxglove/rosmsg2-serialization,
# pinned by tests/mcap_js/package-lock.json). node and npm count as present whoever installed them:
# a NodeSource nodejs bundles npm and conflicts with Debian's npm package.
mcap_missing=()
for p in libzstd-dev liblz4-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || mcap_missing+=("$p")
done
command -v node >/dev/null 2>&1 || mcap_missing+=(nodejs)
command -v npm >/dev/null 2>&1 || mcap_missing+=(npm)
if [ ${#mcap_missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${mcap_missing[*]}"
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${mcap_missing[@]}"
fi
# tests/ci_lint checks the CI files with GitHub's workflow parser and GitLab's CI schema,
# pinned the same way by its package-lock.json.
checkout="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
for npm_dir in tests/mcap_js tests/ci_lint tests/foxglove_js; do
  if [ -f "$checkout/$npm_dir/package-lock.json" ]; then
    # npm ci starts from an empty node_modules; skip it when node_modules holds this very lockfile.
    lock_sum="$(sha256sum "$checkout/$npm_dir/package-lock.json" | cut -d' ' -f1)"
    if [ "$(cat "$checkout/$npm_dir/node_modules/.uampc-lock.sha256" 2>/dev/null)" = "$lock_sum" ]; then
      echo "install-deps: $npm_dir already installed from its package-lock.json"
    else
      npm ci --prefix "$checkout/$npm_dir" --no-audit --no-fund
      echo "$lock_sum" >"$checkout/$npm_dir/node_modules/.uampc-lock.sha256"
    fi
  else
    echo "install-deps: no $npm_dir beside this script; in the checkout run: npm ci --prefix $npm_dir"
  fi
done
echo "install-deps: done"
