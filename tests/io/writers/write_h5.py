#!/usr/bin/python3
"""Writes an HDF5 IMU file with h5py (Debian python3-h5py), for the io tests.

usage: write_h5.py OUT.h5 N
Datasets: /imu/gyro float64 [N x 3] (units "rad/s"), /imu/gyro_x float32 [N], /imu/time int64 [N]
(epoch ns, 100 Hz), /counts int16 [N]. Expected values (float64, exact) of gyro, gyro_x and counts
go to OUT.h5.expected as rows [gx, gy, gz, gyro_x, counts].
"""
import sys

import h5py
import numpy as np


def main():
    out, n = sys.argv[1], int(sys.argv[2])
    rng = np.random.default_rng(5)
    gyro = rng.standard_normal((n, 3)) * 1e-3
    gyro_x = (rng.standard_normal(n) * 1e-2).astype(np.float32)
    counts = rng.integers(-30000, 30000, n).astype(np.int16)
    time = 1_600_000_000_000_000_000 + np.arange(n, dtype=np.int64) * 10_000_000
    with h5py.File(out, "w") as f:
        d = f.create_dataset("imu/gyro", data=gyro)
        d.attrs["units"] = "rad/s"
        f.create_dataset("imu/gyro_x", data=gyro_x)
        f.create_dataset("imu/time", data=time)
        f.create_dataset("counts", data=counts)
    expected = np.column_stack([gyro, gyro_x.astype(np.float64), counts.astype(np.float64)])
    expected.astype("<f8").tofile(out + ".expected")


if __name__ == "__main__":
    main()
