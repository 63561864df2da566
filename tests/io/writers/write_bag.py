#!/usr/bin/python3
"""Writes a ROS 1 bag with the real rosbag library (Debian python3-rosbag), for the io tests.

usage: write_bag.py OUT.bag COMPRESSION N [RATE_HZ] [raw]
COMPRESSION: none | bz2 | lz4. Topic /imu/data (sensor_msgs/Imu, N messages at RATE_HZ,
default 200) and /status (std_msgs/String, 3 messages). The IMU values written are also
saved, as little-endian float64 rows [stamp_ns, gx, gy, gz, ax, ay, az], to OUT.bag.expected,
so the reader can be checked bit for bit. With "raw", each Imu message is serialized here
with struct (the same bytes genpy writes) and handed to Bag.write(raw=True): several times faster,
for the 4.3 M-message benchmark file.
"""
import struct
import sys

import numpy as np
import rosbag
import rospy
from sensor_msgs.msg import Imu
from std_msgs.msg import String


def main():
    out, compression, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
    rate = float(sys.argv[4]) if len(sys.argv) > 4 else 200.0
    raw = len(sys.argv) > 5 and sys.argv[5] == "raw"
    frame = b"imu_link"
    zeros9 = (0.0,) * 9
    rng = np.random.default_rng(16)
    values = rng.standard_normal((n, 6)) * [1e-3, 1e-3, 1e-3, 0.05, 0.05, 0.05] + [0, 0, 0, 0, 0, 9.81]
    start_ns = 1_700_000_000_123_456_789
    period_ns = int(round(1e9 / rate))
    with rosbag.Bag(out, "w", compression=compression, chunk_threshold=64 * 1024) as bag, \
            open(out + ".expected", "wb") as expected:
        for i in range(n):
            stamp_ns = start_ns + i * period_ns
            g = values[i]
            stamp = rospy.Time(stamp_ns // 1_000_000_000, stamp_ns % 1_000_000_000)
            if raw:
                data = struct.pack("<3II", i, stamp.secs, stamp.nsecs, len(frame)) + frame + struct.pack(
                    "<4d9d3d9d3d9d", 0.0, 0.0, 0.0, 1.0, *zeros9, g[0], g[1], g[2], *zeros9, g[3], g[4], g[5], *zeros9)
                bag.write("/imu/data", ("sensor_msgs/Imu", data, Imu._md5sum, Imu), stamp, raw=True)
            else:
                msg = Imu()
                msg.header.seq = i
                msg.header.stamp = stamp
                msg.header.frame_id = "imu_link"
                msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z = g[0], g[1], g[2]
                msg.linear_acceleration.x, msg.linear_acceleration.y, msg.linear_acceleration.z = g[3], g[4], g[5]
                msg.orientation.w = 1.0
                bag.write("/imu/data", msg, stamp)
            expected.write(struct.pack("<7d", float(stamp_ns - start_ns), *g))
            if i % (n // 3 + 1) == 0:
                bag.write("/status", String(data="ok %d" % i), stamp)


if __name__ == "__main__":
    main()
