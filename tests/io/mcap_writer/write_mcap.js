#!/usr/bin/env node
// Writes an MCAP file with the reference TypeScript writer (@mcap/core) and CDR messages
// serialized by @foxglove/cdr, for the io tests (dependencies pinned in package-lock.json;
// `npm ci` in this folder installs them).
//
// usage: node write_mcap.js OUT.mcap COMPRESSION N [RATE_HZ] [summary|nosummary]
// COMPRESSION: none | zstd | lz4. Topic /imu (sensor_msgs/msg/Imu, N messages) and /status
// (std_msgs/msg/String). The IMU values are also written, as little-endian float64 rows
// [stamp_ns - first, gx, gy, gz, ax, ay, az], to OUT.mcap.expected for a bit-exact check.
"use strict";
const fs = require("fs");
const { McapWriter } = require("@mcap/core");
const { CdrWriter } = require("@foxglove/cdr");
const zstd = require("@foxglove/wasm-zstd");
const lz4 = require("lz4js");

class FileSink {
  constructor(path) { this.fd = fs.openSync(path, "w"); this.pos = 0n; }
  async write(buffer) { fs.writeSync(this.fd, buffer); this.pos += BigInt(buffer.byteLength); }
  position() { return this.pos; }
  close() { fs.closeSync(this.fd); }
}

// Deterministic values: a 32-bit LCG mapped to [-0.5, 0.5) (no dependency on Math.random).
let state = 12345;
function uniform() { state = (Math.imul(state, 1664525) + 1013904223) >>> 0; return state / 4294967296 - 0.5; }

async function main() {
  const [out, compression, nText, rateText, summaryText] = process.argv.slice(2);
  const n = Number(nText);
  const rate = rateText ? Number(rateText) : 200;
  const summary = summaryText !== "nosummary";
  await zstd.isLoaded;
  const compressChunk = compression === "zstd"
    ? (data) => ({ compression: "zstd", compressedData: zstd.compress(data, 3) })
    : compression === "lz4"
      ? (data) => ({ compression: "lz4", compressedData: lz4.compress(data) })
      : undefined;
  const sink = new FileSink(out);
  const writer = new McapWriter({
    writable: sink, chunkSize: 256 * 1024, compressChunk,
    useStatistics: summary, useSummaryOffsets: summary, useChunkIndex: summary,
    useMessageIndex: summary, repeatSchemas: summary, repeatChannels: summary,
  });
  await writer.start({ profile: "ros2", library: "imunoise tests" });
  const imuSchema = await writer.registerSchema({ name: "sensor_msgs/msg/Imu", encoding: "ros2msg",
    data: new TextEncoder().encode("std_msgs/Header header\n...") });
  const strSchema = await writer.registerSchema({ name: "std_msgs/msg/String", encoding: "ros2msg",
    data: new TextEncoder().encode("string data") });
  const imu = await writer.registerChannel({ topic: "/imu", schemaId: imuSchema, messageEncoding: "cdr", metadata: new Map() });
  const status = await writer.registerChannel({ topic: "/status", schemaId: strSchema, messageEncoding: "cdr", metadata: new Map() });
  const expected = Buffer.alloc(n * 7 * 8);
  const start = 1700000000123456789n;
  const period = BigInt(Math.round(1e9 / rate));
  for (let i = 0; i < n; i++) {
    const stamp = start + BigInt(i) * period;
    const g = [uniform() * 2e-3, uniform() * 2e-3, uniform() * 2e-3, uniform() * 0.1, uniform() * 0.1, 9.81 + uniform() * 0.1];
    const w = new CdrWriter();
    w.int32(Number(stamp / 1000000000n)); w.uint32(Number(stamp % 1000000000n)); w.string("imu_link");
    for (const q of [0, 0, 0, 1]) w.float64(q);
    for (let k = 0; k < 9; k++) w.float64(0);
    for (let k = 0; k < 3; k++) w.float64(g[k]);
    for (let k = 0; k < 9; k++) w.float64(0);
    for (let k = 3; k < 6; k++) w.float64(g[k]);
    for (let k = 0; k < 9; k++) w.float64(0);
    await writer.addMessage({ channelId: imu, sequence: i, logTime: stamp, publishTime: stamp, data: w.data });
    expected.writeDoubleLE(Number(stamp - start), i * 56);
    for (let k = 0; k < 6; k++) expected.writeDoubleLE(g[k], i * 56 + 8 * (k + 1));
    if (i % Math.floor(n / 3 + 1) === 0) {
      const s = new CdrWriter(); s.string("ok " + i);
      await writer.addMessage({ channelId: status, sequence: i, logTime: stamp, publishTime: stamp, data: s.data });
    }
  }
  await writer.end();
  sink.close();
  fs.writeFileSync(out + ".expected", expected);
}

main().catch((e) => { console.error(e); process.exit(1); });
