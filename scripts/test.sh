#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine (apt packages), builds the default preset (everything:
# library, CLI, tests, benchmarks, Python module) and runs every test but the slow Monte-Carlo
# studies (C++ unit and CLI tests, Python module tests, the find_package consumer), then the
# Python package installed with pip into a virtual environment and tested there.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh" default
cd "$here"
# The Monte-Carlo acceptance studies (label slow, ~5 min on 2 cores) run outside CI:
# scripts/test_slow.sh.
ctest --preset default -LE slow
# The Python package as a user installs it: pip into a virtual environment, tests against it.
scripts/test_installed_python.sh build/default
