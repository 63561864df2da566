#!/usr/bin/env bash
# The fleet on this machine: F simulated gyro records (default 24, 100 Hz x 1200 s = 1.2e5
# samples each) through `imunoise fleet`, serial (the baseline) and under mpirun -np P
# (P - 1 workers; rank 0 only hands out files), reporting files/s; then one record of N samples
# (default 2^24) through `dev --mpi` on 1..P ranks. Run by hand after building the default
# preset:  bench/bench_fleet.sh [F] [P_max] [N]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
files="${1:-24}"
pmax="${2:-3}"
n="${3:-16777216}"
cli="$here/build/default/apps/imunoise/imunoise"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mpi=(mpirun --oversubscribe --allow-run-as-root)
list=()
for i in $(seq 1 "$files"); do
  "$cli" simulate --rate 100 --duration 1200 --N 7e-4 --B 3e-4 --K 2e-6 --seed "$i" \
    -o "$work/s$i.txt" > /dev/null 2>&1
  list+=("$work/s$i.txt")
done
echo "fleet of $files records (1.2e5 samples each), $(nproc) cores"
echo "| run | ranks | wall (s) | files/s |"
echo "|---|---|---|---|"
for p in serial $(seq 2 "$pmax"); do
  rm -rf "$work/out"
  start=$(date +%s.%N)
  if [ "$p" = serial ]; then
    "$cli" fleet "${list[@]}" --units deg/s -o "$work/out" > /dev/null 2>&1
  else
    "${mpi[@]}" -np "$p" "$cli" fleet "${list[@]}" --units deg/s -o "$work/out" > /dev/null 2>&1
  fi
  end=$(date +%s.%N)
  awk -v p="$p" -v s="$start" -v e="$end" -v f="$files" 'BEGIN {
    printf "| fleet | %s | %.2f | %.2f |\n", p, e - s, f / (e - s) }'
done
/usr/bin/python3 -c "import numpy as np, sys; np.random.default_rng(7).standard_normal(int(sys.argv[1])).astype('<f8').tofile(sys.argv[2])" "$n" "$work/big.f64"
cat "$work/big.f64" > /dev/null
echo
echo "one record of $n samples, dev --mpi --estimator oadev,mdev,ohdev (octave taus)"
echo "| run | ranks | wall (s) | samples/s |"
echo "|---|---|---|---|"
for p in plain $(seq 1 "$pmax"); do
  start=$(date +%s.%N)
  if [ "$p" = plain ]; then
    "$cli" dev "$work/big.f64" --rate 200 --estimator oadev,mdev,ohdev --no-ci > /dev/null
  else
    "${mpi[@]}" -np "$p" "$cli" dev "$work/big.f64" --rate 200 --estimator oadev,mdev,ohdev --mpi > /dev/null
  fi
  end=$(date +%s.%N)
  awk -v p="$p" -v s="$start" -v e="$end" -v n="$n" 'BEGIN {
    printf "| dev | %s | %.2f | %.3g |\n", (p == "plain" ? "serial (no --mpi)" : p), e - s, n / (e - s) }'
done
