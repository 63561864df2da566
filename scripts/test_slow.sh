#!/usr/bin/env bash
# The slow tests (label slow): the Monte-Carlo acceptance studies of the fit, the confidence
# intervals and the navigation models, minutes on 2 cores; outside CI, run before a release or
# after a change of the estimators, the fit or the simulator. Builds like scripts/test.sh.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh" default
cd "$here"
ctest --preset default -L slow
