#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine (apt packages), builds the default preset (everything:
# library, CLI, tests, benchmarks, Python module) and runs every test (C++ unit and CLI tests,
# Python module tests, the find_package consumer).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh" default
cd "$here"
ctest --preset default
