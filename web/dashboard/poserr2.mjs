import { McapIndexedReader } from "@mcap/core";
import { decompress } from "fzstd";
import { open } from "node:fs/promises";
const fh = await open(process.argv[2]);
const readable = { size: async () => BigInt((await fh.stat()).size),
  read: async (off, len) => { const b = Buffer.alloc(Number(len)); await fh.read(b, 0, Number(len), Number(off)); return new Uint8Array(b); } };
const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers: { zstd: (d, n) => decompress(d, new Uint8Array(Number(n))) } });
const topics = new Map(); for (const [id, c] of reader.channelsById) topics.set(id, c.topic);
const truth = [], est = [];
for await (const m of reader.readMessages({ topics: ["/raw/truth_state", "/vehicle/state"] })) {
  const t = topics.get(m.channelId);
  if (t === "/raw/truth_state") {
    const d = m.data; const dv = new DataView(d.buffer, d.byteOffset + d.length - 87, 87);
    const f = (i) => dv.getFloat64(2 + 8 * i, true);
    truth.push({ t: f(0), x: f(1), y: f(2), yaw: f(3), vx: f(4), vy: f(5), r: f(6) });
  } else { est.push(JSON.parse(new TextDecoder().decode(m.data))); }
}
let j = 0; const from = Number(process.argv[3] || 0), to = Number(process.argv[4] || 1e9), every = Number(process.argv[5] || 1);
est.forEach((e, i) => {
  const t = e.timestamp.sec + e.timestamp.nsec*1e-9; if (t < from || t > to || i % every) return;
  while (j + 1 < truth.length && truth[j + 1].t <= t) j++;
  const g = truth[j];
  console.log(t.toFixed(2), "vx", g.vx.toFixed(2), e.vx.toFixed(2), "vy", g.vy.toFixed(2), e.vy.toFixed(2), "r", g.r.toFixed(3), e.yaw_rate.toFixed(3));
});
