#!/usr/bin/env bash
# End-to-end: a raw f64 file of N rate samples (default 1e8, 800 MB) through `imunoise dev`
# (oadev, octave taus by default), the default path (noise identification and confidence
# intervals) and `--no-ci` interleaved run by run, so both see the same machine state; reports
# wall time, samples/s and peak memory (GNU time) of each, and their ratio. Run by hand after
# building the default preset:
#   bench/bench_large_file.sh [N] [runs] [extra dev options...]
#   bench/bench_large_file.sh 10000000 7 --estimator mdev
# The file is written once to $TMPDIR and read from the page cache in the timed runs.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
n="${1:-100000000}"
runs="${2:-5}"
shift 2 || shift $# || true
cli="${IMUNOISE_CLI:-$here/build/default/apps/imunoise/imunoise}"
file="${TMPDIR:-/tmp}/imunoise_bench_${n}.f64"
if [ ! -f "$file" ]; then
  /usr/bin/python3 -c "import numpy as np, sys; np.random.default_rng(7).standard_normal(int(sys.argv[1])).astype('<f8').tofile(sys.argv[2])" "$n" "$file"
fi
cat "$file" > /dev/null  # warm the page cache
measure() {  # prints "wall_s rss_kb" (wall from the clock in ns: GNU time rounds to 10 ms)
  local start end rss
  start=$(date +%s%N)
  rss=$( { /usr/bin/time -f "%M" "$cli" dev "$file" --rate 200 --units deg/s --estimator oadev \
      --taus octave "$@" > /dev/null; } 2>&1 | tail -1)
  end=$(date +%s%N)
  echo "$(( (end - start) / 1000 )) $rss" | awk '{ printf "%.3f %s\n", $1 / 1e6, $2 }'
}
echo "| run | default wall (s) | default M samples/s | default peak RSS (MB) | --no-ci wall (s) | --no-ci M samples/s | default / --no-ci |"
echo "|---|---|---|---|---|---|---|"
for run in $(seq 1 "$runs"); do
  read -r wall_ci rss_ci <<< "$(measure "$@")"
  read -r wall_no rss_no <<< "$(measure --no-ci "$@")"
  awk -v r="$run" -v a="$wall_ci" -v k="$rss_ci" -v b="$wall_no" -v n="$n" 'BEGIN {
    printf "| %d | %.3f | %.1f | %.0f | %.3f | %.1f | %.2f |\n", r, a, n / a / 1e6, k / 1024, b,
      n / b / 1e6, a / b }'
done
