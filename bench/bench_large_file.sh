#!/usr/bin/env bash
# End-to-end: a raw f64 file of N rate samples (default 1e8, 800 MB) through `imunoise dev`
# (oadev, octave taus), reporting wall time, samples/s and peak memory (GNU time). Run by hand
# after building the default preset:  bench/bench_large_file.sh [N] [extra dev options...]
# The file is written once to $TMPDIR and read from the page cache in the timed runs.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
n="${1:-100000000}"
shift || true
cli="$here/build/default/apps/imunoise/imunoise"
file="${TMPDIR:-/tmp}/imunoise_bench_${n}.f64"
if [ ! -f "$file" ]; then
  /usr/bin/python3 -c "import numpy as np, sys; np.random.default_rng(7).standard_normal(int(sys.argv[1])).astype('<f8').tofile(sys.argv[2])" "$n" "$file"
fi
cat "$file" > /dev/null  # warm the page cache
echo "| run | wall (s) | samples/s | ns/sample | input GB/s | peak RSS (MB) |"
echo "|---|---|---|---|---|---|"
for run in 1 2 3 4 5; do
  stats=$( { /usr/bin/time -f "%e %M" "$cli" dev "$file" --rate 200 --units deg/s --estimator oadev --taus octave "$@" > /dev/null; } 2>&1 | tail -1)
  read -r wall rss_kb <<< "$stats"
  awk -v r="$run" -v w="$wall" -v k="$rss_kb" -v n="$n" 'BEGIN {
    printf "| %d | %.2f | %.3g | %.1f | %.2f | %.0f |\n", r, w, n / w, w / n * 1e9, n * 8 / w / 1e9, k / 1024 }'
done
