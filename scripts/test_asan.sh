#!/usr/bin/env bash
# Every test program under AddressSanitizer + UBSan (the asan preset: UBSan on the modules that
# turn input into numbers, ASan everywhere), every test but the slow and statistics ones. CI
# runs a part of it (the asan-ci presets: the engine, the readers, the simulator, the spec files,
# the exports and the CLI, whose tests run every command and so every module under ASan); this
# is the whole, outside CI for time (about 25 min on 2 cores), after a change of the numerics.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh" asan
cd "$here"
ctest --preset asan
