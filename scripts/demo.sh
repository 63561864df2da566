#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine (apt packages, Plotly.js from web/package-lock.json),
# builds, and runs the demo: the paper's study on four simulated TG-100 gyros (Table 2, 200 Hz,
# 6 h), written as a report; prints the recovered Table 2, the datasheet verdict and the path
# of the report. Usage: scripts/demo.sh [DIR]  (default build/demo-report, regenerated)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# Only the executable the demo runs (the report needs nothing else that is built); the tests
# and benchmarks are built by scripts/test.sh.
"$here/scripts/setup.sh" default imunoise_cli >&2
cd "$here"
dir="${1:-build/demo-report}"
force=()
# The default directory is the script's own output: regenerate it. A directory the user names
# is never overwritten (imunoise refuses; pass a new name).
[ $# -eq 0 ] && force=(--force)
./build/default/apps/imunoise/imunoise demo -o "$dir" "${force[@]}"
