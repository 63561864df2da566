#!/usr/bin/env bash
# Every test program under AddressSanitizer + UBSan (the asan preset: ASan everywhere, UBSan
# but in the numerics, IMUNOISE_NO_UBSAN_MODULES), every test but the slow and statistics ones.
# CI runs a part of it (the asan-ci presets: the engine, readers, simulator, spec files, exports,
# preprocessing, threads and CLI, whose tests run every command and so every module under ASan);
# this is the whole, outside CI for time (about 23 min on 2 cores from nothing: build ~930 s, tests ~450 s), after a change of the
# numerics. (`ctest --preset asan` needs this whole build: an asan-ci build lacks six programs.)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh" asan
cd "$here"
ctest --preset asan
