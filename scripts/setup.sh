#!/usr/bin/env bash
# Installs every Debian package imunoise needs on a fresh Debian 12 machine, then builds.
# Usage: scripts/setup.sh [preset [target...]]   (default preset: default; no target: all)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
preset="${1:-default}"
shift $(( $# > 0 ? 1 : 0 ))
targets=("$@")

packages=(
  build-essential cmake ninja-build pkg-config
  libgtest-dev libgmock-dev libbenchmark-dev
  libfast-float-dev libcli11-dev libfmt-dev nlohmann-json3-dev
  libboost-dev libeigen3-dev libyaml-cpp-dev libfftw3-dev
  clang libclang-rt-14-dev
  python3-dev python3-numpy python3-pytest pybind11-dev python3-setuptools python3-venv python3-wheel python3-pip
  gnuplot-nox chromium fonts-dejavu-core
  libhdf5-dev libbz2-dev liblz4-dev libzstd-dev zstd libsqlite3-dev python3-h5py python3-rosbag python3-sensor-msgs
  libopenmpi-dev openmpi-bin
  libopencv-dev
)
# The report's Plotly.js comes from npm (web/package-lock.json); Debian's npm only when none is
# installed (a NodeSource node ships its own npm and conflicts with Debian's).
command -v npm >/dev/null 2>&1 || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update -qq
  $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

cd "$here"
# Plotly.js for the interactive HTML report, pinned by web/package-lock.json.
if [ ! -f web/node_modules/plotly.js-basic-dist-min/plotly-basic.min.js ]; then
  (cd web && npm ci --no-audit --no-fund --loglevel=error)
fi
# The MCAP reader's tests write files with the reference TypeScript writer (node 20 + npm): only
# for a whole build, which includes the tests.
if ((${#targets[@]} == 0)) && command -v npm >/dev/null; then
  (cd tests/io/mcap_writer && npm ci --no-audit --no-fund --loglevel=error)
  # The ULog reader's tests check values against the reference reader @foxglove/ulog.
  (cd tests/io/ulog_reader && npm ci --no-audit --no-fund --loglevel=error)
fi
cmake --preset "$preset" >/dev/null
# Named targets only (the demo needs the CLI, not the ~150 test and benchmark programs).
target_flags=()
((${#targets[@]})) && target_flags=(--target "${targets[@]}")
cmake --build --preset "$preset" -j "$(nproc)" "${target_flags[@]}"
