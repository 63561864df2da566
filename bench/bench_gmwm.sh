#!/usr/bin/env bash
# GMWM speed (issue: a 3 h, 100 Hz record with --terms auto in < 2 s on 2 cores; the parametric
# bootstrap with R = 100 in < 30 s). The record: white rate noise, rate random walk and a
# Gauss-Markov term, made once by `imunoise simulate` (raw f64) and read from the page cache.
# Each case is the whole `imunoise fit` process, best of RUNS, beside the default wls fit of the
# same file in the same script (the baseline). Prints a Markdown table.
#   bench/bench_gmwm.sh [HOURS] [RUNS]      (default 3 h, 3 runs)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
hours="${1:-3}"
runs="${2:-3}"
cli="${IMUNOISE_CLI:-$here/build/default/apps/imunoise/imunoise}"
file="${TMPDIR:-/tmp}/imunoise_bench_gmwm_${hours}h.f64"
if [ ! -f "$file" ]; then
  "$cli" simulate --rate 100 --duration "$(awk -v h="$hours" 'BEGIN { print h * 3600 }')" --units deg/s \
    --N 0.01 --K 1e-4 --gm-sigma 0.01 --gm-tau 20 --seed 5 --format f64 -o "$file" >/dev/null
fi
cat "$file" >/dev/null
best() {  # best wall time (s) of $runs runs of `imunoise fit FILE ...`
  local best_ns="" start end
  for _ in $(seq "$runs"); do
    start=$(date +%s%N)
    "$cli" fit "$file" --binary f64 --rate 100 --units deg/s --format json "$@" >/dev/null
    end=$(date +%s%N)
    if [ -z "$best_ns" ] || [ $((end - start)) -lt "$best_ns" ]; then best_ns=$((end - start)); fi
  done
  awk -v ns="$best_ns" 'BEGIN { printf "%.3f", ns / 1e9 }'
}
wls=$(best)
auto=$(best --method gmwm --terms auto)
boot=$(best --method gmwm --terms N,K,GM --bootstrap 100 --seed 1)
echo "| case | seconds | baseline | baseline seconds | target |"
echo "|---|---|---|---|---|"
echo "| fit --method gmwm --terms auto, ${hours} h 100 Hz | $auto | fit (wls) | $wls | < 2 s |"
echo "| fit --method gmwm --terms N,K,GM --bootstrap 100, ${hours} h 100 Hz | $boot | fit (wls) | $wls | < 30 s |"
