#!/usr/bin/env bash
# Saves what a user sees from a build: every CLI test's arguments, exit code, standard output and
# written JSON documents (tests/cli/cli_runner.hpp), the demo's report.json, and a fleet run
# (fleet.json, fleet.csv) over simulated sensors, one of them an outlier and one a bad file. Two snapshots
# diffed (diff -r A B) show whether a change of the code changed any output.
# Usage: scripts/snapshot_outputs.sh BUILD_DIR OUT_DIR   (OUT_DIR must not exist)
set -euo pipefail
build="${1:?usage: scripts/snapshot_outputs.sh BUILD_DIR OUT_DIR}"
out="${2:?usage: scripts/snapshot_outputs.sh BUILD_DIR OUT_DIR}"
[ -e "$out" ] && { echo "snapshot_outputs: $out exists; name a new directory" >&2; exit 1; }
mkdir -p "$out/cli"
out="$(cd "$out" && pwd)"
IMUNOISE_CLI_SNAPSHOT_DIR="$out/cli" ctest --test-dir "$build" -L 'cli|nav|redundant' -LE slow \
  -j "$(nproc)" --output-on-failure >"$out/ctest.log" 2>&1 || echo "snapshot_outputs: some tests failed (see $out/ctest.log)" >&2
"$build/apps/imunoise/imunoise" demo -o "$out/demo" >"$out/demo.stdout" 2>"$out/demo.stderr"
# Relative paths, so that two snapshots' documents name the same files.
cli="$(cd "$build" && pwd)/apps/imunoise/imunoise"
(
  cd "$out"
  mkdir -p fleet-in fleet
  for seed in 1 2 3 4 5 6; do
    n=1.5e-3; [ "$seed" = 6 ] && n=6e-3
    "$cli" simulate --rate 200 --duration 1800 --N "$n" --B 3e-4 --K 2e-5 --seed "$seed" -o "fleet-in/g$seed.txt"
  done
  printf '1.0\nnot-a-number\n' >fleet-in/bad.txt
  "$cli" fleet fleet-in/*.txt --rate 200 --units deg/s --spec tg100 --nav -q -o fleet-run \
    >fleet/stdout 2>fleet/stderr || true
  mv fleet-run/fleet.json fleet-run/fleet.csv fleet/
  rm -rf fleet-in fleet-run
)
echo "snapshot in $out: $(ls "$out/cli" | wc -l) CLI runs, demo report.json, fleet.json and fleet.csv"
