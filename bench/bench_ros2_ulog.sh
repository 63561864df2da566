#!/usr/bin/env bash
# Writes a 6 h, 200 Hz IMU record (4.32 M messages) as a ROS 2 SQLite bag (Python's sqlite3 with
# the tests' CDR writer, sensor_msgs/msg/Imu) and as a PX4 ULog (sensor_combined, the tests'
# spec-following writer) once, into build/bench-data (the writers take minutes: they are
# cached), then times reading them with bench_containers (target < 3 s each).
#   bench/bench_ros2_ulog.sh [extra benchmark flags]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
data=build/bench-data
mkdir -p "$data"
n=4320000
[ -s "$data/imu_6h_db3/imu_6h_db3_0.db3" ] ||
  /usr/bin/python3 tests/io/writers/write_db3.py "$data/imu_6h_db3" "$n" le one 200 fast
[ -s "$data/imu_6h.ulg" ] || /usr/bin/python3 tests/io/writers/write_ulog.py "$data/imu_6h.ulg" "$n" 7 combined
cmake --build --preset default --target bench_containers -j1 >/dev/null
build/default/bench/bench_containers \
  "$data/imu_6h_db3/imu_6h_db3_0.db3" /imu "$data/imu_6h.ulg" sensor_combined \
  --benchmark_repetitions=3 --benchmark_report_aggregates_only=false --benchmark_counters_tabular=true "$@"
