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
  # algorithms
  libeigen3-dev libpcl-dev libceres-dev liboctomap-dev libembree-dev
  # configuration, JSON files, the command line
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev
  # tests and benchmarks; Cyclone DDS proves our wire format to another vendor
  libgtest-dev libgmock-dev libbenchmark-dev cyclonedds-dev cyclonedds-tools
  # the experiment report is checked in headless Chromium; xmllint checks its SVG figures
  chromium libxml2-utils
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi

SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "install-deps: done"
