#!/usr/bin/env python3
"""Writes a PX4 ULog test file from the published format specification
(https://docs.px4.io/main/en/dev_log/ulog_file_format.html), independently of imunoise's reader.

    write_ulog.py OUT.ulg N [SEED] [combined|relative|appended]

The log holds, at 200 Hz for N samples: sensor_combined (one instance), sensor_gyro and
sensor_accel (two instances, multi_id 0 and 1, sampled at different instants), vehicle_imu (two
instances; delta angle / velocity over a jittering dt), vehicle_angular_velocity and
vehicle_acceleration (one instance; the latter's format nests another format and ends in a
padding field that is not written, as the specification allows), and vehicle_status (not an
IMU topic). Interleaved: information, parameters, log text ('L', 'C'), sync ('S'), two dropouts
('O', 15 ms and 30 ms) and a removed then re-added subscription. OUT.ulg.json records the
dropouts written. With "combined" (the 4.3 M-message benchmark log) only sensor_combined is
written, with the dropouts. With "relative", sensor_combined's accelerometer is sampled 13 µs
before the gyro (accelerometer_timestamp_relative -13) and every 50th message has no accelerometer
data (RELATIVE_TIMESTAMP_INVALID, 0x7fffffff). With "appended", the log stops in the middle of a
sensor_combined message and 10 more samples follow as appended data (flag bit DATA_APPENDED,
appended_offsets[0] = their start), as a logger that resumed after an interruption writes.
Values are checked in the tests against the reference reader @foxglove/ulog.
"""
import json
import random
import struct
import sys

MAGIC = b"ULog\x01\x12\x35"
SYNC = bytes([0x2F, 0x73, 0x13, 0x20, 0x25, 0x0C, 0xBB, 0x12])


def message(kind, body):
    return struct.pack("<HB", len(body), ord(kind)) + body


def key_value(kind, key, value, prefix=b""):
    k = key.encode()
    return message(kind, prefix + struct.pack("<B", len(k)) + k + value)


FORMATS = {
    "sensor_combined": "uint64_t timestamp;float[3] gyro_rad;uint32_t gyro_integral_dt;"
                       "int32_t accelerometer_timestamp_relative;float[3] accelerometer_m_s2;"
                       "uint32_t accelerometer_integral_dt;uint8_t accelerometer_clipping;uint8_t gyro_clipping;"
                       "uint8_t accel_calibration_count;uint8_t gyro_calibration_count;",
    "sensor_gyro": "uint64_t timestamp;uint64_t timestamp_sample;uint32_t device_id;float x;float y;float z;"
                   "float temperature;uint32_t error_count;uint8_t[3] clip_counter;uint8_t samples;",
    "sensor_accel": "uint64_t timestamp;uint64_t timestamp_sample;uint32_t device_id;float x;float y;float z;"
                    "float temperature;uint32_t error_count;uint8_t[3] clip_counter;uint8_t samples;",
    "vehicle_imu": "uint64_t timestamp;uint64_t timestamp_sample;uint32_t accel_device_id;uint32_t gyro_device_id;"
                   "float[3] delta_angle;float[3] delta_velocity;uint16_t delta_angle_dt;uint16_t delta_velocity_dt;"
                   "uint8_t delta_angle_clipping;uint8_t delta_velocity_clipping;uint8_t accel_calibration_count;"
                   "uint8_t gyro_calibration_count;",
    "vehicle_angular_velocity": "uint64_t timestamp;uint64_t timestamp_sample;float[3] xyz;float[3] xyz_derivative;",
    "pair": "uint64_t timestamp;uint16_t a;int8_t b;",  # @foxglove/ulog needs a timestamp in nested formats
    "vehicle_acceleration": "uint64_t timestamp;uint64_t timestamp_sample;pair[2] pairs;float[3] xyz;uint8_t[5] _padding0;",
    "vehicle_status": "uint64_t timestamp;uint8_t arming_state;uint8_t nav_state;",
}


def main():
    out, n = sys.argv[1], int(sys.argv[2])
    rng = random.Random(int(sys.argv[3]) if len(sys.argv) > 3 else 7)
    combined_only = len(sys.argv) > 4 and sys.argv[4] == "combined"
    relative = len(sys.argv) > 4 and sys.argv[4] == "relative"
    appended = len(sys.argv) > 4 and sys.argv[4] == "appended"
    combined = struct.Struct("<HBHQ3fIi3fI4B")
    f32 = lambda x: struct.unpack("<f", struct.pack("<f", x))[0]
    data = bytearray(MAGIC + bytes([1]) + struct.pack("<Q", 1_000_000))
    data += message("B", bytes(8) + bytes(8) + struct.pack("<3Q", 0, 0, 0))
    data += key_value("I", "char[12] sys_name", b"PX4 imunoise")
    data += key_value("M", "char[5] hw", b"fmu-v", prefix=b"\x00")
    for name, fields in FORMATS.items():
        data += message("F", (name + ":" + fields).encode())
    data += key_value("P", "float IMU_GYRO_CUTOFF", struct.pack("<f", 40.0))
    data += key_value("Q", "int32_t SYS_AUTOSTART", struct.pack("<i", 4001), prefix=b"\x01")
    subs = [("sensor_combined", 0), ("sensor_gyro", 0), ("sensor_gyro", 1), ("sensor_accel", 0), ("sensor_accel", 1),
            ("vehicle_imu", 0), ("vehicle_imu", 1), ("vehicle_angular_velocity", 0), ("vehicle_acceleration", 0),
            ("vehicle_status", 0)]
    ids = {}
    for msg_id, (name, multi) in enumerate(subs):
        msg_id = 3 * msg_id + 2  # ids need not be consecutive
        ids[(name, multi)] = msg_id
        data += message("A", struct.pack("<BH", multi, msg_id) + name.encode())
    dropouts = []

    def d(name, multi, body):
        return message("D", struct.pack("<H", ids[(name, multi)]) + body)

    v = lambda scale: [f32(rng.gauss(0.0, scale)) for _ in range(3)]
    t0 = 5_000_000
    for i in range(n):
        t = t0 + 5000 * i
        if i == n // 3 or i == 2 * n // 3:
            ms = 15 if i == n // 3 else 30
            data += message("O", struct.pack("<H", ms))
            dropouts.append(ms)
        if i % 100 == 0:
            data += message("S", SYNC)
            data += message("L", struct.pack("<BQ", ord("6"), t) + b"sample text")
            data += message("C", struct.pack("<BHQ", ord("4"), 3, t) + b"tagged text")
            data += key_value("P", "float IMU_GYRO_CUTOFF", struct.pack("<f", 40.0 + i))
        if i == n // 2:
            # Removed and subscribed again under the same id: data goes on.
            data += message("R", struct.pack("<H", ids[("vehicle_status", 0)]))
            data += message("A", struct.pack("<BH", 0, ids[("vehicle_status", 0)]) + b"vehicle_status")
        g, a = v(0.01), v(0.05)
        if combined_only:
            data += combined.pack(combined.size - 3, ord("D"), ids[("sensor_combined", 0)], t, *g, 5000, 0, *a, 5000,
                                  0, 0, 1, 1)
            continue
        rel = (0x7FFFFFFF if i % 50 == 0 else -13) if relative else 0
        data += d("sensor_combined", 0, struct.pack("<Q3fIi3fI4B", t, *g, 5000, rel, *a, 5000, 0, 0, 1, 1))
        for multi, phase in ((0, 0), (1, 1234)):
            ts = t + phase - 300
            data += d("sensor_gyro", multi, struct.pack("<QQI4fI3BB", t + phase, ts, 0x2100 + multi, *v(0.01),
                                                        45.5, 0, 0, 0, 0, 4))
            data += d("sensor_accel", multi, struct.pack("<QQI4fI3BB", t + phase + 10, ts + 10, 0x1100 + multi,
                                                         *v(0.05), 45.5, 0, 0, 0, 0, 4))
            dt_a = 5000 + rng.randint(-7, 7)
            dt_v = 5000 + rng.randint(-7, 7)
            data += d("vehicle_imu", multi, struct.pack("<QQII3f3fHH4B", t + phase + 20, ts + 20, 0x1100 + multi,
                                                        0x2100 + multi, *v(5e-5), *v(2.5e-4), dt_a, dt_v, 0, 0, 1, 1))
        data += d("vehicle_angular_velocity", 0, struct.pack("<QQ3f3f", t + 40, t - 100, *v(0.01), 0, 0, 0))
        # Trailing _padding0 not written: the message is shorter than its format.
        data += d("vehicle_acceleration", 0, struct.pack("<QQQHbQHb3f", t + 50, t - 90, t, 1, -1, t, 2, -2, *v(0.05)))
        if i % 20 == 0:
            data += d("vehicle_status", 0, struct.pack("<QBB", t, 2, 14))
    if appended:
        g, a = v(0.01), v(0.05)
        cut = d("sensor_combined", 0, struct.pack("<Q3fIi3fI4B", t0 + 5000 * n, *g, 5000, 0, *a, 5000, 0, 0, 1, 1))
        data += cut[:len(cut) // 2]
        offset = len(data)
        data[16 + 3 + 8] |= 1                               # incompat_flags[0] bit 0: DATA_APPENDED
        data[16 + 3 + 16:16 + 3 + 24] = struct.pack("<Q", offset)  # appended_offsets[0]
        for i in range(n, n + 10):
            g, a = v(0.01), v(0.05)
            data += d("sensor_combined", 0, struct.pack("<Q3fIi3fI4B", t0 + 5000 * i, *g, 5000, 0, *a, 5000, 0, 0, 1, 1))
    with open(out, "wb") as f:
        f.write(data)
    with open(out + ".json", "w") as f:
        json.dump({"dropouts": len(dropouts), "dropout_ms": sum(dropouts), "samples": n}, f)


if __name__ == "__main__":
    main()
