#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine (apt packages), builds the default preset (everything:
# library, CLI, tests, benchmarks, Python module) and runs every test (C++ unit and CLI tests,
# Python module tests, the find_package consumer), then the Python package installed with pip
# into a virtual environment and tested there.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh" default
cd "$here"
ctest --preset default
# The Python package as a user installs it: pip into a virtual environment, tests against it.
scripts/test_installed_python.sh build/default
