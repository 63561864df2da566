#!/usr/bin/env bash
# Saves what a user sees from a build: every CLI test's arguments, exit code, standard output and
# written JSON documents (tests/cli/cli_runner.hpp), and the demo's report.json. Two snapshots
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
echo "snapshot in $out: $(ls "$out/cli" | wc -l) CLI runs, demo report.json"
