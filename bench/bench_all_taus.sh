#!/usr/bin/env bash
# End-to-end: every tau (`--taus all`) of oadev and ohdev on a raw f64 file of N white rate
# samples (default 1e6: 499,999 and 333,333 taus), the default path (noise identification and
# intervals at every tau) and `--no-ci` interleaved run by run; wall time (ns clock) and peak
# RSS (GNU time). Issue 28's target: <= 10 s each on 2 cores. Run by hand after building:
#   bench/bench_all_taus.sh [N] [runs]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
n="${1:-1000000}"
runs="${2:-3}"
cli="${IMUNOISE_CLI:-$here/build/default/apps/imunoise/imunoise}"
file="${TMPDIR:-/tmp}/imunoise_bench_${n}.f64"
if [ ! -f "$file" ]; then
  /usr/bin/python3 -c "import numpy as np, sys; np.random.default_rng(7).standard_normal(int(sys.argv[1])).astype('<f8').tofile(sys.argv[2])" "$n" "$file"
fi
cat "$file" > /dev/null  # warm the page cache
measure() {  # prints "wall_s rss_kb"
  local start end rss
  start=$(date +%s%N)
  rss=$( { /usr/bin/time -f "%M" "$cli" dev "$file" --binary f64 --rate 100 --estimator "$@" \
      --taus all > /dev/null; } 2>&1 | tail -1)
  end=$(date +%s%N)
  echo "$(( (end - start) / 1000 )) $rss" | awk '{ printf "%.3f %s\n", $1 / 1e6, $2 }'
}
echo "| estimator | run | default wall (s) | default peak RSS (MB) | --no-ci wall (s) | default / --no-ci |"
echo "|---|---|---|---|---|---|"
for estimator in oadev ohdev; do
  for run in $(seq 1 "$runs"); do
    read -r wall_ci rss_ci <<< "$(measure "$estimator")"
    read -r wall_no rss_no <<< "$(measure "$estimator" --no-ci)"
    awk -v e="$estimator" -v r="$run" -v a="$wall_ci" -v k="$rss_ci" -v b="$wall_no" 'BEGIN {
      printf "| %s | %d | %.3f | %.0f | %.3f | %.2f |\n", e, r, a, k / 1024, b, a / b }'
  done
done
