// Reads the IMU topic of a ULog file with the reference reader @foxglove/ulog (pinned in
// package-lock.json) and writes what imunoise's reader must return, as JSON:
//   node read_ulog.js FILE.ulg TOPIC OUT.json
// {"channels": {"gyro0_x": {"time_ns": ["..."], "values": [...]}, ...}}: per instance (multi_id),
// in file order, time from timestamp_sample when the topic has it (else timestamp), values as
// doubles (float32 widened exactly), vehicle_imu's deltas divided by their dt in µs,
// sensor_combined's accelerometer at timestamp + accelerometer_timestamp_relative. Channel
// names: gyro_x.. for one instance multi_id 0, else gyro<multi_id>_x.
"use strict";
const fs = require("fs");
const { ULog, MessageType } = require("@foxglove/ulog");
const { FileReader } = require("@foxglove/ulog/node");

async function main() {
  const [file, topic, out] = process.argv.slice(2);
  const ulog = new ULog(new FileReader(file));
  await ulog.open();
  const ids = new Map();
  for (const [id, sub] of ulog.subscriptions) {
    if (sub.name === topic) ids.set(id, sub.multiId);
  }
  const instances = new Set(ids.values());
  const several = instances.size > 1 || !instances.has(0);
  const series = new Map();  // name -> {time_ns, values}
  const push = (name, t, value) => {
    if (!series.has(name)) series.set(name, { time_ns: [], values: [] });
    const s = series.get(name);
    s.time_ns.push(t.toString());
    s.values.push(value);
  };
  const msgs = [];
  for await (const msg of ulog.readMessages({ msgIds: new Set(ids.keys()), includeLogs: false })) {
    if (msg.type === MessageType.Data) msgs.push(msg);
  }
  // readMessages yields in timestamp order; imunoise keeps file order per instance, which the
  // test files have in time order within an instance.
  for (const msg of msgs) {
    const m = msg.value;
    const multi = ids.get(msg.msgId);
    const k = several ? String(multi) : "";
    const t = (m.timestamp_sample !== undefined ? BigInt(m.timestamp_sample) : BigInt(m.timestamp)) * 1000n;
    const put = (prefix, values, scale, time) => {
      ["x", "y", "z"].forEach((axis, i) => push(`${prefix}${k}_${axis}`, time, Number(values[i]) * scale));
    };
    if (topic === "sensor_combined") {
      put("gyro", m.gyro_rad, 1, t);
      // RELATIVE_TIMESTAMP_INVALID (0x7fffffff): no accelerometer data in this message.
      if (m.accelerometer_timestamp_relative !== 0x7fffffff) {
        put("accel", m.accelerometer_m_s2, 1, t + BigInt(m.accelerometer_timestamp_relative) * 1000n);
      }
    } else if (topic === "vehicle_imu") {
      put("gyro", m.delta_angle, 1e6 / Number(m.delta_angle_dt), t);
      put("accel", m.delta_velocity, 1e6 / Number(m.delta_velocity_dt), t);
    } else if (topic === "sensor_gyro" || topic === "sensor_accel") {
      put(topic === "sensor_gyro" ? "gyro" : "accel", [m.x, m.y, m.z], 1, t);
    } else {
      put(topic === "vehicle_angular_velocity" ? "gyro" : "accel", m.xyz, 1, t);
    }
  }
  fs.writeFileSync(out, JSON.stringify({ channels: Object.fromEntries(series) }));
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
