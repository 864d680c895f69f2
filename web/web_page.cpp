#include "web/web_page.h"

namespace sonarloop::web {

const char* const kWebPage = R"PAGE(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>sonarloop live</title>
<style>
  body { margin: 0; background: #11161c; color: #d8dee6; font: 13px/1.35 sans-serif; }
  header { display: flex; gap: 16px; align-items: center; padding: 6px 12px; background: #1b232c; }
  header h1 { font-size: 15px; margin: 0; font-weight: 600; }
  #state { padding: 2px 8px; border-radius: 3px; background: #633; }
  #state.live { background: #264; }
  button { font: inherit; padding: 3px 14px; background: #2d3b4a; color: inherit;
           border: 1px solid #4a5d70; border-radius: 3px; cursor: pointer; }
  main { display: grid; grid-template-columns: minmax(0, 1040px) minmax(360px, 1fr); gap: 12px;
         padding: 10px 12px; }
  section { background: #18202a; border: 1px solid #2a3744; border-radius: 4px; padding: 8px; }
  h2 { font-size: 13px; margin: 0 0 6px; color: #9fb3c8; font-weight: 600; }
  canvas { display: block; background: #000; }
  #waterfall { width: 100%; image-rendering: pixelated; }
  #map { width: 100%; height: 300px; }
  #axis { display: flex; justify-content: space-between; font-size: 11px; color: #9fb3c8; }
  #scale { display: flex; align-items: center; gap: 6px; font-size: 11px; margin-top: 4px; }
  table { border-collapse: collapse; width: 100%; font-size: 12px; }
  th, td { text-align: right; padding: 1px 6px; border-bottom: 1px solid #26313c; }
  th:nth-child(2), td:nth-child(2), th:nth-child(3), td:nth-child(3) { text-align: left; }
  .mine { color: #ff7b6b; } .nonmine { color: #7fd88f; } .none { color: #9aa; }
  dl { display: grid; grid-template-columns: auto auto; gap: 1px 12px; margin: 0; }
  dt { color: #9fb3c8; } dd { margin: 0; text-align: right; font-variant-numeric: tabular-nums; }
  #side { display: flex; flex-direction: column; gap: 12px; }
  #contacts-box { max-height: 230px; overflow-y: auto; }
</style>
</head>
<body>
<header>
  <h1>sonarloop live</h1>
  <span id="state">connecting</span>
  <button id="pause" type="button">Pause</button>
  <span id="held"></span>
</header>
<main>
  <section>
    <h2>Waterfall: port | starboard (slant range), newest at the top</h2>
    <canvas id="waterfall" width="1024" height="560"></canvas>
    <div id="axis"></div>
    <div id="scale"><span id="db0"></span><canvas id="bar" width="256" height="12"></canvas>
      <span id="db1"></span><span>dB re full scale</span></div>
  </section>
  <div id="side">
    <section>
      <h2>Track and contacts (metres, north up)</h2>
      <canvas id="map" width="420" height="300"></canvas>
    </section>
    <section>
      <h2>Statistics</h2>
      <dl id="stats">
        <dt>simulation time</dt><dd id="s-sim">-</dd>
        <dt>pings</dt><dd id="s-pings">-</dd>
        <dt>deadline misses</dt><dd id="s-misses">-</dd>
        <dt>lateness p99</dt><dd id="s-late">-</dd>
        <dt>datagrams lost</dt><dd id="s-lost">-</dd>
        <dt>CPU (one core)</dt><dd id="s-cpu">-</dd>
        <dt>contacts</dt><dd id="s-contacts">-</dd>
        <dt>lines shown / s</dt><dd id="s-rate">-</dd>
        <dt>web: events dropped / pings not shown</dt><dd id="s-web">-</dd>
        <dt>statistics updates</dt><dd id="s-updates">0</dd>
      </dl>
    </section>
    <section id="contacts-box">
      <h2>Contacts</h2>
      <table><thead><tr><th>#</th><th>class</th><th>mine?</th><th>distance</th>
        <th>range m</th><th>side</th><th>N m</th><th>E m</th></tr></thead>
        <tbody id="contacts"></tbody></table>
    </section>
  </div>
</main>
<script>
"use strict";
const $ = (id) => document.getElementById(id);
const wf = $("waterfall"), wctx = wf.getContext("2d");
const map = $("map"), mctx = map.getContext("2d");
const MAX_HELD = 4000;

// colour map: black - deep blue - copper - yellow - white over the display span
const LUT = new Uint8ClampedArray(256 * 3);
for (let i = 0; i < 256; ++i) {
  const u = i / 255;
  LUT[3 * i] = 255 * Math.min(1, Math.max(0, 1.7 * u - 0.25));
  LUT[3 * i + 1] = 255 * Math.min(1, Math.max(0, 1.5 * u - 0.45));
  LUT[3 * i + 2] = 255 * Math.min(1, Math.max(0, 0.5 * Math.sin(Math.PI * u * 1.6) + (u > 0.8 ? 5 * (u - 0.8) : 0)));
}
(function drawBar() {
  const bar = $("bar"), b = bar.getContext("2d"), img = b.createImageData(256, bar.height);
  for (let y = 0; y < bar.height; ++y)
    for (let x = 0; x < 256; ++x) {
      const o = 4 * (y * 256 + x);
      img.data[o] = LUT[3 * x]; img.data[o + 1] = LUT[3 * x + 1]; img.data[o + 2] = LUT[3 * x + 2];
      img.data[o + 3] = 255;
    }
  b.putImageData(img, 0, 0);
})();

let row = null, paused = false, held = [], shown = 0, shownStamp = performance.now(), shownAt = 0;
let range = null;
const track = { n: [], e: [] }, contacts = [];
let vehicle = null, mapDirty = true;

function bytes(b64) {
  const s = atob(b64), a = new Uint8Array(s.length);
  for (let i = 0; i < s.length; ++i) a[i] = s.charCodeAt(i);
  return a;
}

function setAxis(ev) {
  if (range && range[0] === ev.r0_m && range[1] === ev.r1_m) return;
  range = [ev.r0_m, ev.r1_m];
  const f = (r) => r.toFixed(r < 10 ? 1 : 0) + " m";
  const mid = (ev.r0_m + ev.r1_m) / 2;
  $("axis").innerHTML = "<span>port " + f(ev.r1_m) + "</span><span>" + f(mid) + "</span><span>" +
    f(ev.r0_m) + "</span><span>" + f(mid) + "</span><span>" + f(ev.r1_m) + " starboard</span>";
  $("db0").textContent = ev.db0 + " dB";
  $("db1").textContent = ev.db1 + " dB";
}

function drawLine(ev) {
  const port = bytes(ev.port), stbd = bytes(ev.stbd), n = port.length;
  if (wf.width !== 2 * n) { wf.width = 2 * n; row = null; }
  if (!row) row = wctx.createImageData(2 * n, 1);
  const d = row.data;
  for (let i = 0; i < n; ++i) {
    let o = 4 * (n - 1 - i), c = 3 * port[i];  // port: near range at the centre
    d[o] = LUT[c]; d[o + 1] = LUT[c + 1]; d[o + 2] = LUT[c + 2]; d[o + 3] = 255;
    o = 4 * (n + i); c = 3 * stbd[i];
    d[o] = LUT[c]; d[o + 1] = LUT[c + 1]; d[o + 2] = LUT[c + 2]; d[o + 3] = 255;
  }
  wctx.drawImage(wf, 0, 0, wf.width, wf.height - 1, 0, 1, wf.width, wf.height - 1);
  wctx.putImageData(row, 0, 0);
  setAxis(ev);
  document.body.dataset.lines = String(++shown);  // lines drawn (read by tests)
}

function addTrack(n, e) {
  const k = track.n.length;
  if (k && Math.hypot(n - track.n[k - 1], e - track.e[k - 1]) < 1) return;
  track.n.push(n); track.e.push(e); mapDirty = true;
}

function niceStep(span) {
  const raw = span / 6, p = Math.pow(10, Math.floor(Math.log10(raw)));
  for (const m of [1, 2, 5, 10]) if (m * p >= raw) return m * p;
  return 10 * p;
}

function drawMap() {
  // one canvas pixel per CSS pixel, whatever the column's width
  if (map.width !== map.clientWidth && map.clientWidth > 0) { map.width = map.clientWidth; mapDirty = true; }
  if (!mapDirty) return;
  mapDirty = false;
  const W = map.width, H = map.height, pad = 24;
  mctx.fillStyle = "#05080c"; mctx.fillRect(0, 0, W, H);
  const ns = track.n.concat(contacts.map((c) => c.north_m));
  const es = track.e.concat(contacts.map((c) => c.east_m));
  if (!ns.length) return;
  let n0 = Math.min(...ns) - 10, n1 = Math.max(...ns) + 10;
  let e0 = Math.min(...es) - 10, e1 = Math.max(...es) + 10;
  const s = Math.min((W - 2 * pad) / (e1 - e0), (H - 2 * pad) / (n1 - n0));
  const ec = (e0 + e1) / 2, nc = (n0 + n1) / 2;
  const X = (e) => W / 2 + (e - ec) * s, Y = (n) => H / 2 - (n - nc) * s;
  // grid, labelled with its spacing
  const step = niceStep(Math.max((W - 2 * pad) / s, (H - 2 * pad) / s));
  mctx.strokeStyle = "#1c2834"; mctx.lineWidth = 1; mctx.beginPath();
  for (let e = Math.ceil((ec - W / 2 / s) / step) * step; X(e) < W; e += step) {
    mctx.moveTo(X(e), 0); mctx.lineTo(X(e), H);
  }
  for (let n = Math.ceil((nc - H / 2 / s) / step) * step; Y(n) > 0; n += step) {
    mctx.moveTo(0, Y(n)); mctx.lineTo(W, Y(n));
  }
  mctx.stroke();
  mctx.fillStyle = "#9fb3c8"; mctx.font = "11px sans-serif";
  mctx.fillText("grid " + step + " m", 6, H - 6);
  mctx.fillText("N \u2191", W - 30, 14);
  // track
  mctx.strokeStyle = "#4fa3ff"; mctx.lineWidth = 1.5; mctx.beginPath();
  for (let i = 0; i < track.n.length; ++i) {
    if (i) mctx.lineTo(X(track.e[i]), Y(track.n[i])); else mctx.moveTo(X(track.e[i]), Y(track.n[i]));
  }
  mctx.stroke();
  // contacts
  for (const c of contacts) {
    mctx.fillStyle = c.class === null ? "#9aa" : c.mine_like ? "#ff5a46" : "#5fd07a";
    mctx.beginPath(); mctx.arc(X(c.east_m), Y(c.north_m), 4, 0, 2 * Math.PI); mctx.fill();
    mctx.fillText(String(c.contact), X(c.east_m) + 6, Y(c.north_m) - 4);
  }
  // the vehicle, pointing along its heading
  if (vehicle) {
    const h = vehicle.heading_deg * Math.PI / 180, x = X(vehicle.east_m), y = Y(vehicle.north_m);
    mctx.save(); mctx.translate(x, y); mctx.rotate(h);
    mctx.fillStyle = "#fff"; mctx.beginPath();
    mctx.moveTo(0, -8); mctx.lineTo(5, 6); mctx.lineTo(-5, 6); mctx.closePath(); mctx.fill();
    mctx.restore();
  }
}

function cell(text, cls) {
  const td = document.createElement("td");
  td.textContent = text;
  if (cls) td.className = cls;
  return td;
}

function addContact(c) {
  contacts.push(c); mapDirty = true;
  const tr = document.createElement("tr");
  const cls = c.class === null ? "none" : c.mine_like ? "mine" : "nonmine";
  const num = (v, d) => (v === null || v === undefined ? "-" : Number(v).toFixed(d));
  tr.append(cell(c.contact), cell(c.fused_class || c.class || (c.status || "unclassified"), cls),
            cell(c.class === null ? "-" : c.mine_like ? "mine" : "non-mine", cls),
            cell(num(c.distance, 1)), cell(num(c.ground_range_m, 1)), cell(c.side),
            cell(num(c.north_m, 1)), cell(num(c.east_m, 1)));
  $("contacts").prepend(tr);
}

function showStats(s) {
  const num = (v, d, unit) => (v === null || v === undefined ? "n/a" : Number(v).toFixed(d) + (unit || ""));
  $("s-sim").textContent = num(s.sim_time_s, 1, " s");
  $("s-pings").textContent = num(s.pings, 0);
  $("s-misses").textContent = num(s.deadline_misses, 0);
  $("s-late").textContent = num(s.lateness_p99_ms, 3, " ms");
  $("s-lost").textContent = num(s.datagrams_lost, 0);
  $("s-cpu").textContent = num(s.cpu_percent, 1, " %");
  $("s-contacts").textContent = num(s.contacts === null ? contacts.length : s.contacts, 0);
  $("s-web").textContent = s.web.events_dropped + " / " + s.web.pings_not_shown;
  $("s-updates").textContent = String(s.updates);
}

function onLine(ev) {
  vehicle = ev; addTrack(ev.north_m, ev.east_m);
  if (paused) {
    held.push(ev);
    if (held.length > MAX_HELD) held.shift();
    $("held").textContent = held.length + " lines held";
  } else {
    drawLine(ev);
  }
}

$("pause").addEventListener("click", () => {
  paused = !paused;
  $("pause").textContent = paused ? "Resume" : "Pause";
  if (!paused) { for (const ev of held) drawLine(ev); held = []; $("held").textContent = ""; }
});

function connect() {
  const es = new EventSource("/events");
  es.onopen = () => { $("state").textContent = "live"; $("state").className = "live"; };
  es.onerror = () => { $("state").textContent = "disconnected (retrying)"; $("state").className = ""; };
  es.addEventListener("line", (m) => onLine(JSON.parse(m.data)));
  es.addEventListener("track", (m) => {
    const t = JSON.parse(m.data);
    for (let i = 0; i < t.north_m.length; ++i) addTrack(t.north_m[i], t.east_m[i]);
  });
  es.addEventListener("contact", (m) => addContact(JSON.parse(m.data)));
  es.addEventListener("stats", (m) => showStats(JSON.parse(m.data)));
}

setInterval(() => {
  const now = performance.now();
  $("s-rate").textContent = ((shown - shownAt) * 1000 / (now - shownStamp)).toFixed(1);
  shownAt = shown; shownStamp = now;
}, 1000);
(function frame() { drawMap(); requestAnimationFrame(frame); })();
connect();
</script>
</body>
</html>
)PAGE";

}  // namespace sonarloop::web
