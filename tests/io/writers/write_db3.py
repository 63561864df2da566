#!/usr/bin/python3
"""Writes a ROS 2 bag in SQLite3 storage with Python's sqlite3 module and a CDR writer of its
own (written here from the OMG CDR rules, independently of imunoise's decoder), for the io tests.

usage: write_db3.py OUT N [le|be] [split|one] [RATE_HZ] [fast] [zstd]
OUT is a bag directory (metadata.yaml + OUT_0.db3, and OUT_1.db3 with "split": the messages
are divided between two files, as rosbag2 does with --max-bag-size). Tables as rosbag2's
sqlite3 storage (schema version 4): topics(id, name, type, serialization_format,
offered_qos_profiles, type_description_hash), messages(id, topic_id, timestamp, data).
Topic /imu (sensor_msgs/msg/Imu, N messages at RATE_HZ, default 200; CDR little- or
big-endian) and /status (std_msgs/msg/String, 3 messages) and /temperature
(sensor_msgs/msg/Temperature, 5 messages). The IMU values are also saved, as little-endian
float64 rows [stamp_ns - first, gx, gy, gz, ax, ay, az], to OUT/expected.f64. With "fast"
(the 4.3 M-message benchmark bag) every message has frame_id "imu_link" and is packed with one
struct call (the same bytes as the field-by-field writer), and no expected.f64 is written.
With "zstd" every message is compressed by the zstd command-line tool, one frame per message
(rosbag2's --compression-mode message), and metadata.yaml says so.
"""
import os
import random
import sqlite3
import struct
import subprocess
import sys
import tempfile


class Cdr:
    """XCDR1 plain CDR: a 4-byte encapsulation header, then each primitive aligned to its size
    relative to the end of that header."""

    def __init__(self, big):
        self.e = ">" if big else "<"
        self.out = bytearray(b"\x00\x00\x00\x00" if big else b"\x00\x01\x00\x00")

    def align(self, n):
        while (len(self.out) - 4) % n:
            self.out.append(0)

    def put(self, fmt, *values):
        self.align(struct.calcsize(fmt[0]))
        self.out += struct.pack(self.e + fmt, *values)

    def string(self, s):
        b = s.encode() + b"\x00"
        self.put("I", len(b))
        self.out += b


def imu(stamp_ns, frame, g, a, big):
    c = Cdr(big)
    c.put("i", stamp_ns // 1_000_000_000)
    c.put("I", stamp_ns % 1_000_000_000)
    c.string(frame)
    for x in (0.0, 0.0, 0.0, 1.0) + (0.0,) * 9:   # orientation, its covariance
        c.put("d", x)
    for x in tuple(g) + (0.01,) * 9:               # angular_velocity, covariance
        c.put("d", x)
    for x in tuple(a) + (0.02,) * 9:               # linear_acceleration, covariance
        c.put("d", x)
    return bytes(c.out)


def imu_fixed(big):
    """One struct for an Imu with frame_id "imu_link": sec, nanosec, length 9, the 9 bytes,
    3 bytes of padding to the 8-aligned orientation, then 37 doubles."""
    e = ">" if big else "<"
    head = b"\x00\x00\x00\x00" if big else b"\x00\x01\x00\x00"
    body = struct.Struct(e + "iII9s3x4d9d3d9d3d9d")
    zeros9, c1, c2 = (0.0,) * 9, (0.01,) * 9, (0.02,) * 9

    def pack(stamp_ns, g, a):
        return head + body.pack(stamp_ns // 1_000_000_000, stamp_ns % 1_000_000_000, 9, b"imu_link\x00",
                                0.0, 0.0, 0.0, 1.0, *zeros9, *g, *c1, *a, *c2)
    return pack


def string_msg(text):
    c = Cdr(False)
    c.string(text)
    return bytes(c.out)


def temperature(stamp_ns):
    c = Cdr(False)
    c.put("i", stamp_ns // 1_000_000_000)
    c.put("I", stamp_ns % 1_000_000_000)
    c.string("imu_link")
    c.put("d", 41.5)
    c.put("d", 0.1)
    return bytes(c.out)


SCHEMA = """
CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);
CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL, metadata TEXT NOT NULL);
CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,
                    serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL,
                    type_description_hash TEXT NOT NULL);
CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL,
                      data BLOB NOT NULL);
CREATE INDEX timestamp_idx ON messages (timestamp ASC);
"""
TOPICS = [(1, "/status", "std_msgs/msg/String"), (2, "/imu", "sensor_msgs/msg/Imu"),
          (3, "/temperature", "sensor_msgs/msg/Temperature")]


def open_db(path):
    if os.path.exists(path):
        os.remove(path)
    db = sqlite3.connect(path)
    db.executescript(SCHEMA)
    db.execute("INSERT INTO schema VALUES (4, 'jazzy')")
    db.executemany("INSERT INTO topics VALUES (?, ?, ?, 'cdr', '', '')", TOPICS)
    return db


def main():
    out, n = sys.argv[1], int(sys.argv[2])
    big = len(sys.argv) > 3 and sys.argv[3] == "be"
    split = len(sys.argv) > 4 and sys.argv[4] == "split"
    rate = float(sys.argv[5]) if len(sys.argv) > 5 else 200.0
    fast = "fast" in sys.argv[6:]
    zstd = "zstd" in sys.argv[6:]
    pack_fixed = imu_fixed(big)
    os.makedirs(out, exist_ok=True)
    base = os.path.basename(os.path.normpath(out))
    names = [f"{base}_0.db3"] + ([f"{base}_1.db3"] if split else [])
    dbs = [open_db(os.path.join(out, name)) for name in names]
    rng = random.Random(25)
    start_ns = 1_700_000_000_987_654_321
    period_ns = int(round(1e9 / rate))
    rows = [[] for _ in dbs]
    with open(os.path.join(out, "expected.f64") if not fast else os.devnull, "wb") as expected:
        for i in range(n):
            stamp = start_ns + i * period_ns
            g = [rng.gauss(0.0, 1e-3) for _ in range(3)]
            a = [rng.gauss(0.0, 0.05), rng.gauss(0.0, 0.05), 9.81 + rng.gauss(0.0, 0.05)]
            k = 0 if i < n // 2 or not split else 1
            # Received a little after the stamp (the bag's own timestamp is not the sample time).
            data = pack_fixed(stamp, g, a) if fast else imu(stamp, "imu_link" * (i % 3), g, a, big)
            rows[k].append((2, stamp + 700_000 + rng.randint(0, 100_000), data))
            if i % (n // 3 + 1) == 0:
                rows[k].append((1, stamp, string_msg("ok %d" % i)))
            if i % (n // 5 + 1) == 0:
                rows[k].append((3, stamp, temperature(stamp)))
            if not fast:
                expected.write(struct.pack("<7d", float(stamp - start_ns), *g, *a))
    if zstd:
        # One zstd run over every message: each file becomes one frame (with its content size).
        with tempfile.TemporaryDirectory() as tmp:
            for k, r in enumerate(rows):
                for j, (_, _, data) in enumerate(r):
                    with open(os.path.join(tmp, "%d_%d" % (k, j)), "wb") as f:
                        f.write(data)
            subprocess.run(["zstd", "-q", "-19", "--rm"] + [os.path.join(tmp, x) for x in os.listdir(tmp)], check=True)
            for k, r in enumerate(rows):
                for j, (topic, stamp, _) in enumerate(r):
                    with open(os.path.join(tmp, "%d_%d.zst" % (k, j)), "rb") as f:
                        r[j] = (topic, stamp, f.read())
    for db, r in zip(dbs, rows):
        db.executemany("INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)", r)
        db.commit()
        db.close()
    with open(os.path.join(out, "metadata.yaml"), "w") as f:
        f.write("rosbag2_bagfile_information:\n  version: 9\n  storage_identifier: sqlite3\n"
                "  duration:\n    nanoseconds: %d\n  message_count: %d\n  relative_file_paths:\n" % (n * period_ns, n))
        for name in names:
            f.write("    - %s\n" % name)
        f.write("  compression_format: %s\n  compression_mode: %s\n" % (("zstd", "MESSAGE") if zstd else ('""', '""')))


if __name__ == "__main__":
    main()
