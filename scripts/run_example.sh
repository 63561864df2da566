#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds, and runs the main job on the bundled example:
# the overlapping Allan, modified Allan and overlapping Hadamard deviations, with confidence
# bounds, of a simulated TG-100 gyro (paper's Table 2, gyro 1; 200 Hz, 30 minutes) shipped in
# data/, then its fitted noise terms compared with the TG-100 datasheet.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh" default >&2
cd "$here"
./build/default/apps/imunoise/imunoise dev data/tg100_gyro1_30min.f32 --rate 200 --units deg/s \
  --estimator oadev,mdev,ohdev --taus octave
echo
# The noise terms of eq. 5 with 95 % intervals, and the datasheet comparison of the paper's Table 1.
./build/default/apps/imunoise/imunoise fit data/tg100_gyro1_30min.f32 --rate 200 --units deg/s \
  --format table --spec tg100
