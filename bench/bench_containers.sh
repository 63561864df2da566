#!/usr/bin/env bash
# Writes a 6 h, 200 Hz IMU record (4.32 M sensor_msgs Imu messages) as a ROS 1 bag (python3-rosbag,
# uncompressed chunks) and as MCAP (@mcap/core, zstd and uncompressed chunks) once, into
# build/bench-data (the writers take many minutes: they are cached), then times reading them.
#   bench/bench_containers.sh [extra benchmark flags]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
data=build/bench-data
mkdir -p "$data"
n=4320000
[ -s "$data/imu_6h_none.bag" ] || /usr/bin/python3 tests/io/writers/write_bag.py "$data/imu_6h_none.bag" none "$n" 200 raw
(cd tests/io/mcap_writer && [ -d node_modules ] || npm ci --no-audit --no-fund --loglevel=error)
[ -s "$data/imu_6h_zstd.mcap" ] || node tests/io/mcap_writer/write_mcap.js "$data/imu_6h_zstd.mcap" zstd "$n"
[ -s "$data/imu_6h_none.mcap" ] || node tests/io/mcap_writer/write_mcap.js "$data/imu_6h_none.mcap" none "$n"
cmake --build --preset default --target bench_containers -j2 >/dev/null
build/default/bench/bench_containers \
  "$data/imu_6h_none.bag" /imu/data "$data/imu_6h_zstd.mcap" /imu "$data/imu_6h_none.mcap" /imu \
  --benchmark_repetitions=3 --benchmark_report_aggregates_only=false --benchmark_counters_tabular=true "$@"
