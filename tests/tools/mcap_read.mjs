// An independent reader of sonarloop's MCAP recordings (tests/tools/mcap_cli_test.cpp): the MCAP
// library of the npm registry (@mcap/core, its zstd from @mcap/support) reads the file twice,
// once through its index and summary (McapIndexedReader) and once record by record with every
// CRC checked (McapStreamReader); each message is decoded with its own schema
// (@foxglove/rosmsg parses the ros2msg text, @foxglove/rosmsg2-serialization reads the CDR).
// Prints one JSON object per line: a summary, then one line per message (in log-time order, as
// the index gives them) with what the test compares against the XTF and candump recordings.
//
// usage: node mcap_read.mjs FILE.mcap
import { readFileSync } from "node:fs";

import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { loadDecompressHandlers } from "@mcap/support";
import { parse } from "@foxglove/rosmsg";
import { MessageReader } from "@foxglove/rosmsg2-serialization";

const path = process.argv[2];
const bytes = readFileSync(path);
const decompressHandlers = await loadDecompressHandlers();

// 1. record by record, every CRC checked
const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true });
stream.append(new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength));
const streamCounts = {};
let streamMessages = 0;
let footer = false;
for (let r; (r = stream.nextRecord()); ) {
  if (r.type === "Message") ++streamMessages;
  if (r.type === "Footer") footer = true;
  streamCounts[r.type] = (streamCounts[r.type] ?? 0) + 1;
}
if (!stream.done()) throw new Error("stream reader: the file did not end where the format says");

// 2. through the index
const readable = {
  size: async () => BigInt(bytes.byteLength),
  read: async (offset, size) =>
    new Uint8Array(bytes.buffer, bytes.byteOffset + Number(offset), Number(size)),
};
const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
const readers = new Map();
const topics = {};
for (const [id, channel] of reader.channelsById) {
  const schema = reader.schemasById.get(channel.schemaId);
  if (schema.encoding !== "ros2msg" || channel.messageEncoding !== "cdr")
    throw new Error(`channel ${channel.topic}: ${schema.encoding} / ${channel.messageEncoding}`);
  const text = new TextDecoder().decode(schema.data);
  readers.set(id, { topic: channel.topic, type: schema.name, reader: new MessageReader(parse(text, { ros2: true })) });
  topics[channel.topic] = schema.name;
}

const lines = [];
let indexed = 0;
let ordered = true;
let last = -1n;
const sum = (a) => a.reduce((s, v) => s + Number(v), 0);
for await (const m of reader.readMessages()) {
  ++indexed;
  if (m.logTime < last) ordered = false;
  last = m.logTime;
  const { topic, type, reader: r } = readers.get(m.channelId);
  const msg = r.readMessage(m.data);
  const stamp = `${msg.header?.stamp?.sec ?? 0}.${String(msg.header?.stamp?.nanosec ?? 0).padStart(9, "0")}`;
  const base = { topic, log_time: m.logTime.toString(), stamp };
  if (type === "marine_acoustic_msgs/msg/RawSonarImage") {
    const d = msg.image.data;
    const dtype = msg.image.dtype;
    const view = new DataView(d.buffer, d.byteOffset, d.byteLength);
    const size = dtype === 0 ? 1 : dtype === 2 ? 2 : 4;
    const samples = [];
    for (let k = 0; k < d.byteLength; k += size)
      samples.push(size === 1 ? view.getUint8(k) : size === 2 ? view.getUint16(k, true) : view.getFloat32(k, true));
    lines.push({ ...base, kind: "ping", samples: samples.length, samples_per_beam: msg.samples_per_beam,
      dtype, beams: msg.image.beam_count, sum: sum(samples), first: samples[0], last: samples[samples.length - 1],
      rx_angle: msg.rx_angles[0], frequency: msg.ping_info.frequency, sample_rate: msg.sample_rate });
  } else if (type === "sensor_msgs/msg/NavSatFix") {
    lines.push({ ...base, kind: "fix", latitude: msg.latitude, longitude: msg.longitude, altitude: msg.altitude });
  } else if (type === "geometry_msgs/msg/PoseStamped") {
    const p = msg.pose;
    lines.push({ ...base, kind: "pose", x: p.position.x, y: p.position.y, z: p.position.z,
      qx: p.orientation.x, qy: p.orientation.y, qz: p.orientation.z, qw: p.orientation.w });
  } else if (type === "sensor_msgs/msg/Image") {
    lines.push({ ...base, kind: "image", height: msg.height, width: msg.width, encoding: msg.encoding,
      step: msg.step, bytes: msg.data.byteLength });
  } else if (type === "std_msgs/msg/String") {
    lines.push({ ...base, kind: "string", data: msg.data });
  } else {
    lines.push({ ...base, kind: "other", type });
  }
}
const stats = reader.statistics;
console.log(JSON.stringify({
  kind: "summary", topics, footer, stream_messages: streamMessages, indexed_messages: indexed,
  ordered, chunks: reader.chunkIndexes.length, statistics_messages: Number(stats?.messageCount ?? -1),
  profile: reader.header.profile, library: reader.header.library,
}));
for (const l of lines) console.log(JSON.stringify(l));
