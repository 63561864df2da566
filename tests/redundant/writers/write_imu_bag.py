#!/usr/bin/python3
"""Writes a ROS 1 bag of several sensor_msgs/Imu topics with the real rosbag library (Debian
python3-rosbag), for the in-motion tests of a multi-IMU bag.

usage: write_imu_bag.py OUT.bag IN.bin TOPIC[,TOPIC...] N
IN.bin holds, topic after topic, N little-endian rows of struct "<q6d": the header stamp (int64
ns) and gx gy gz (rad/s) ax ay az (m/s^2). Each message is serialized here with struct (the bytes
genpy writes for sensor_msgs/Imu) and handed to Bag.write(raw=True).
"""
import struct
import sys

import rosbag
import rospy
from sensor_msgs.msg import Imu


def main():
    out, src, topics, n = sys.argv[1], sys.argv[2], sys.argv[3].split(","), int(sys.argv[4])
    row = struct.Struct("<q6d")
    frame = b"imu_link"
    zeros9 = (0.0,) * 9
    with open(src, "rb") as f:
        data = f.read()
    if len(data) != row.size * n * len(topics):
        raise SystemExit("IN.bin has %d bytes, expected %d" % (len(data), row.size * n * len(topics)))
    with rosbag.Bag(out, "w", chunk_threshold=256 * 1024) as bag:
        for k, topic in enumerate(topics):
            for i in range(n):
                stamp_ns, gx, gy, gz, ax, ay, az = row.unpack_from(data, row.size * (k * n + i))
                stamp = rospy.Time(stamp_ns // 1_000_000_000, stamp_ns % 1_000_000_000)
                msg = struct.pack("<3II", i, stamp.secs, stamp.nsecs, len(frame)) + frame + struct.pack(
                    "<4d9d3d9d3d9d", 0.0, 0.0, 0.0, 1.0, *zeros9, gx, gy, gz, *zeros9, ax, ay, az, *zeros9)
                bag.write(topic, ("sensor_msgs/Imu", msg, Imu._md5sum, Imu), stamp, raw=True)


if __name__ == "__main__":
    main()
