#!/usr/bin/env bash
# `imunoise redundant --in-motion` as a user runs it, from files: a tetrahedral unit of four
# gyros (TG-100 noise) under the 200 deg/s tumble, H hours at 200 Hz (default 6: the issue's
# four 6 h recordings, 4.3e6 samples each, about 100 MB of text per sensor), written by
# `imunoise simulate --unit`, then read, checked and analysed (parity, leakage regression, Allan
# covariances, mean level) with the wall time printed. The in-memory part alone is
# bench_in_motion.cpp. Run by hand after building the default preset, on a quiet machine
# (uptime load < 1.5):  bench/bench_in_motion.sh [H] [GEOMETRY]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
hours="${1:-6}"
geometry="${2:-tetra}"
cli="$here/build/default/apps/imunoise/imunoise"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
duration=$(awk "BEGIN { print $hours * 3600 }")
"$cli" simulate --unit "$geometry" --motion tumble:200 --rate 200 --duration "$duration" \
  --N 8.9e-4 --B 5.9e-4 --K 1.5e-5 --units deg/s --seed 1 -o "$work/unit" > /dev/null 2>&1
files=("$work"/unit/sensor*.txt)
echo "in-motion analysis of ${#files[@]} recordings ($geometry), $hours h at 200 Hz, $(nproc) cores, load $(cut -d' ' -f1 /proc/loadavg)"
start=$(date +%s.%N)
"$cli" redundant --geometry "$geometry" --in-motion "${files[@]}" --rate 200 --units deg/s \
  --json "$work/out.json" 2> /dev/null
end=$(date +%s.%N)
echo "| recordings | samples each | wall (s) |"
echo "|---|---|---|"
echo "| ${#files[@]} | $(awk "BEGIN { print $duration * 200 }") | $(awk "BEGIN { printf \"%.2f\", $end - $start }") |"
