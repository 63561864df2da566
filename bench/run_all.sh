#!/usr/bin/env bash
# Runs every benchmark in bench/ (the Google Benchmark programs and the .sh/.py scripts) and
# writes one JSON file: machine (nproc, CPU model, kernel), date, load average before and after,
# the load of other processes during each program, each benchmark's time and its ratio against
# its baseline in the same process or script. A run whose load exceeded 1.5 is marked
# "unreliable": true (and stays out of docs/performance.md). Needs no network.
#   bench/run_all.sh [--quick] [--only bench_total,bench_fleet.sh] [--output FILE]
#                    [--build-dir DIR] [--settle SECONDS] [--no-build]
# --quick: smaller inputs, the whole run in under 10 minutes on 2 cores (a full run takes longer).
# Default output: build/bench/run_all.json, the programs' output in run_all.json.log.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
build=build/default
build_first=1
args=()
while (($#)); do
  case "$1" in
    --no-build) build_first=0 ;;
    --build-dir) build="$2"; args+=("$1" "$2"); shift ;;
    --build-dir=*) build="${1#*=}"; args+=("$1") ;;
    *) args+=("$1") ;;
  esac
  shift
done
if ((build_first)); then
  # The benchmark programs, the executables the scripts run and the Python module; the build's
  # own load is waited out by run_all.py (--settle) before anything is timed.
  [ -f "$build/build.ninja" ] || cmake --preset default >/dev/null
  targets=(imunoise_cli)
  for source in bench/*.cpp; do targets+=("$(basename "$source" .cpp)"); done
  grep -q '^build imunoise_cli_mpi:' "$build/build.ninja" && targets+=(imunoise_cli_mpi)
  grep -q '^build _imunoise:' "$build/build.ninja" && targets+=(_imunoise)
  cmake --build "$build" -j 2 --target "${targets[@]}" >&2
fi
exec /usr/bin/python3 bench/run_all.py "${args[@]}"
