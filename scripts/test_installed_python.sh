#!/usr/bin/env bash
# Installs the Python package with pip into a fresh virtual environment (Debian's python3 with
# its NumPy and pytest, --system-site-packages; offline: --no-build-isolation --no-index) from a
# configured build, then runs the Python tests against the installed package, from outside the
# source tree and without PYTHONPATH, so `import imunoise` must find the installed one.
# Usage: scripts/test_installed_python.sh [BUILD_DIR]   (default build/default)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(cd "${1:-$here/build/default}" && pwd)"
venv="$build/python-venv"
rm -rf "$venv"
/usr/bin/python3 -m venv --system-site-packages "$venv"
IMUNOISE_BUILD_DIR="$build" "$venv/bin/pip" install --quiet --no-build-isolation --no-index "$here"
rm -rf "$here/imunoise.egg-info"
cd "$build"
unset PYTHONPATH
location="$("$venv/bin/python" -c 'import imunoise, imunoise.allantools; print(imunoise.__file__)')"
case "$location" in
  "$venv"/*) echo "installed package: $location" ;;
  *) echo "test_installed_python: imunoise imported from $location, not the virtual environment" >&2; exit 1 ;;
esac
IMUNOISE_TEST_DATA_DIR="$here/tests/data" "$venv/bin/python" -m pytest -q -p no:cacheprovider "$here/python/tests"
