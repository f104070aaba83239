// SPDX-License-Identifier: GPL-2.0-or-later
// halweb's page: HAL tree (halshow), watch list (halmeter), scope (halscope).
// Talks to the server over one websocket (/ws) with JSON messages; plots
// with dygraphs served by the same server.  window.halweb holds the page's
// state for scripts and tests.
"use strict";

const hw = (window.halweb = {
  connected: false,
  hello: null,
  values: {},          // "kind+name" -> value text (null: gone)
  seq: 0,
  tree: null,
  lastSet: null,
  lastCapture: null,
  scopeStatus: "",
  stats: { updates: 0, latencies: [], first: 0 },
  errors: [],
});

const $ = (id) => document.getElementById(id);
let ws = null;
let watch = [];        // [[kind, name], ...]
let meterHistory = []; // [[Date, v1, v2...], ...]
let meterGraph = null;
let scopeGraph = null;
let rollBuf = null;

function token() {
  const t = new URLSearchParams(location.search).get("token");
  return t ? "?token=" + encodeURIComponent(t) : "";
}

function send(msg) {
  if (ws && ws.readyState === WebSocket.OPEN) ws.send(JSON.stringify(msg));
}

function connect() {
  const proto = location.protocol === "https:" ? "wss:" : "ws:";
  ws = new WebSocket(proto + "//" + location.host + "/ws" + token());
  ws.onopen = () => {
    hw.connected = true;
    $("status").textContent = "connected";
    // at most 2 value updates in flight: the server never queues more than
    // the page can draw, so what is shown stays fresh
    send({ op: "flow", window: 2 });
  };
  ws.onclose = () => {
    hw.connected = false;
    $("status").textContent = "disconnected - retrying";
    setTimeout(connect, 1000);
  };
  ws.onmessage = (ev) => handle(JSON.parse(ev.data));
}

function handle(m) {
  switch (m.type) {
    case "hello": onHello(m); break;
    case "values": onValues(m); break;
    case "tree": onTree(m); break;
    case "set": onSet(m); break;
    case "scope": onCapture(m); break;
    case "scope_chunk": onChunk(m); break;
    case "scope_status": onScopeStatus(m); break;
    case "scope_setup": fillScopeSetup(m.setup); break;
    case "error": hw.errors.push(m.error); $("status").textContent = "error: " + m.error; break;
  }
}

// ---- pages ------------------------------------------------------------------

function showPage(name) {
  for (const p of ["show", "meter", "scope"]) {
    $("page-" + p).classList.toggle("active", p === name);
    $("tab-" + p).classList.toggle("active", p === name);
  }
  if (name === "show") requestTree();
  if (name === "scope" && scopeGraph) scopeGraph.resize();
  if (name === "meter" && meterGraph) meterGraph.resize();
}

function onHello(m) {
  hw.hello = m;
  $("mode").textContent = m.read_only ? "read-only" : "";
  const sel = $("scope-thread");
  sel.innerHTML = "";
  for (const t of m.threads) {
    const o = document.createElement("option");
    o.textContent = t;
    sel.appendChild(o);
  }
  fillScopeSetup(m.scope);
  $("scope-status").textContent = m.scope_running ? "running" : "";
  watch = m.watch.length ? m.watch : watch;
  sendWatch();
  showPage(m.page);
}

// ---- values (halmeter) --------------------------------------------------------

function key(kind, name) { return kind + "+" + name; }

function sendWatch() {
  send({ op: "watch", items: watch });
  renderWatch();
}

function renderWatch() {
  const body = $("watch-list");
  body.innerHTML = "";
  for (const [kind, name] of watch) {
    const tr = document.createElement("tr");
    tr.dataset.key = key(kind, name);
    const cells = [kind, name];
    for (const c of cells) {
      const td = document.createElement("td");
      td.textContent = c;
      tr.appendChild(td);
    }
    const v = document.createElement("td");
    v.className = "watch-value";
    v.dataset.name = name;
    v.textContent = hw.values[key(kind, name)] ?? "";
    tr.appendChild(v);
    const setTd = document.createElement("td");
    if (!(hw.hello && hw.hello.read_only)) {
      const inp = document.createElement("input");
      inp.className = "set-input";
      inp.size = 10;
      const b = document.createElement("button");
      b.className = "set-button";
      b.textContent = "Set";
      const res = document.createElement("span");
      res.className = "set-result";
      b.onclick = () => {
        res.textContent = "";
        send({ op: "set", kind: kind, name: name, value: inp.value });
      };
      inp.onkeydown = (e) => { if (e.key === "Enter") b.click(); };
      setTd.append(inp, b, res);
    }
    tr.appendChild(setTd);
    const rm = document.createElement("td");
    const x = document.createElement("button");
    x.textContent = "remove";
    x.onclick = () => {
      watch = watch.filter(([k, n]) => key(k, n) !== key(kind, name));
      meterHistory = [];
      sendWatch();
    };
    rm.appendChild(x);
    tr.appendChild(rm);
    body.appendChild(tr);
  }
}

function onValues(m) {
  const now = Date.now() / 1000;
  hw.seq = m.seq;
  const row = [new Date()];
  m.names.forEach(([kind, name], i) => {
    const v = m.values[i];
    hw.values[key(kind, name)] = v;
    row.push(v === null || isNaN(Number(v)) ? (v === "TRUE" ? 1 : v === "FALSE" ? 0 : null) : Number(v));
  });
  for (const td of document.querySelectorAll("#watch-list tr")) {
    const v = hw.values[td.dataset.key];
    const cell = td.querySelector(".watch-value");
    const text = v === null ? "removed" : v ?? "";
    if (cell.textContent !== text) cell.textContent = text;
  }
  if ($("page-show").classList.contains("active")) {
    for (const el of document.querySelectorAll("#tree .val[data-key]")) {
      const v = hw.values[el.dataset.key];
      const text = v === null ? "removed" : v;
      if (v !== undefined && el.textContent !== text) el.textContent = text;
    }
  }
  $("haltime").textContent = "t = " + (m.hal_time / 1e9).toFixed(6) + " s";
  // latency: HAL read on the server to the page's next frame (same machine clock)
  requestAnimationFrame(() => {
    send({ op: "ack", seq: m.seq });
    const st = hw.stats;
    if (!st.first) st.first = now;
    st.updates += 1;
    st.latencies.push(Date.now() / 1000 - m.t_read);
    if (st.latencies.length > 5000) st.latencies.shift();
  });
  if (m.names.length && $("page-meter").classList.contains("active")) {
    const plotted = row.slice(0, METER_PLOT_MAX + 1);
    if (meterHistory.length && meterHistory[0].length !== plotted.length) meterHistory = [];
    meterHistory.push(plotted);
    if (meterHistory.length > 600) meterHistory.shift();
    // the plot is redrawn at most 5 times a second; the table every update
    if (Date.now() - lastMeterDraw > 200) {
      lastMeterDraw = Date.now();
      drawMeter(m.names);
    }
  }
}

let lastMeterDraw = 0;
const METER_PLOT_MAX = 8; // series in the history plot (the table shows all)

function drawMeter(names) {
  const labels = ["time"].concat(names.slice(0, METER_PLOT_MAX).map(([k, n]) => n));
  if (!meterHistory.length || meterHistory[0].length !== labels.length) return;
  if (!meterGraph || meterGraph.getLabels().length !== labels.length) {
    if (meterGraph) meterGraph.destroy();
    meterGraph = new Dygraph($("meter-plot"), meterHistory, { labels: labels, legend: "always" });
  } else {
    meterGraph.updateOptions({ file: meterHistory });
  }
}

function addWatch(kind, name) {
  if (!watch.some(([k, n]) => k === kind && n === name)) {
    watch.push([kind, name]);
    sendWatch();
  }
}

function onSet(m) {
  hw.lastSet = m;
  const text = m.ok ? "set: " + m.value : m.error;
  for (const tr of document.querySelectorAll("#watch-list tr")) {
    if (tr.dataset.key === key(m.kind, m.name)) {
      const res = tr.querySelector(".set-result");
      if (res) { res.textContent = " " + text; res.className = "set-result " + (m.ok ? "ok" : "error"); }
    }
  }
  const tres = document.querySelector(`#tree .set-result[data-key="${CSS.escape(key(m.kind, m.name))}"]`);
  if (tres) { tres.textContent = " " + text; tres.className = "set-result " + (m.ok ? "ok" : "error"); }
  if (m.ok) hw.values[key(m.kind, m.name)] = m.value;
}

// ---- tree (halshow) -------------------------------------------------------------

const SECTIONS = [["comp", "Components"], ["pin", "Pins"], ["param", "Parameters"],
                  ["sig", "Signals"], ["funct", "Functions"], ["thread", "Threads"]];
const open = new Set(["pin", "param", "sig"]);

function requestTree() { send({ op: "tree", pattern: $("filter").value.trim() }); }

function meta(it) {
  switch (it.kind) {
    case "comp": return `${it.type} id ${it.extra.id}` + (it.extra.ready === "1" ? " ready" : "");
    case "pin": return `${it.type} ${it.dir}` + (it.links.length ? ` [${it.links[0]}]` : "");
    case "param": return `${it.type} ${it.dir}`;
    case "sig": return it.type + (it.links.length ? ` [${it.links.join(" ")}]` : "");
    case "funct": return `owner ${it.extra.owner_id}, ${it.extra.users} thread(s)`;
    case "thread": return `${it.extra.period} ns: ${it.links.join(", ")}`;
  }
  return "";
}

// what halcmd's setp/sets would accept: unlinked IN or I/O pins, RW
// parameters, signals without a writer
function writable(it) {
  if (it.kind === "pin") return it.dir !== "OUT" && it.links.length === 0;
  if (it.kind === "param") return it.dir === "RW";
  if (it.kind === "sig") return it.extra.writers === "0";
  return false;
}

function leaf(it, label) {
  const d = document.createElement("div");
  d.className = "leaf";
  d.dataset.kind = it.kind;
  d.dataset.name = it.name;
  const n = document.createElement("span");
  n.className = "name";
  n.textContent = label;
  d.appendChild(n);
  if (["pin", "param", "sig"].includes(it.kind)) {
    const v = document.createElement("span");
    v.className = "val";
    v.dataset.key = key(it.kind, it.name);
    v.textContent = hw.values[key(it.kind, it.name)] ?? it.value;
    d.appendChild(v);
  }
  const mt = document.createElement("span");
  mt.className = "meta";
  mt.textContent = meta(it);
  d.appendChild(mt);
  if (["pin", "param", "sig"].includes(it.kind)) {
    const w = document.createElement("button");
    w.textContent = "watch";
    w.className = "watch-button";
    w.onclick = () => addWatch(it.kind, it.name);
    d.appendChild(w);
    if (!(hw.hello && hw.hello.read_only) && writable(it)) {
      const inp = document.createElement("input");
      inp.size = 8;
      inp.className = "tree-set-input";
      const b = document.createElement("button");
      b.textContent = "set";
      b.className = "tree-set-button";
      const res = document.createElement("span");
      res.className = "set-result";
      res.dataset.key = key(it.kind, it.name);
      b.onclick = () => send({ op: "set", kind: it.kind, name: it.name, value: inp.value });
      inp.onkeydown = (e) => { if (e.key === "Enter") b.click(); };
      d.append(inp, b, res);
    }
  }
  return d;
}

// The tree is rebuilt only when its set of objects changed; otherwise the
// values and facts are updated in place, so a value being typed into a set
// field survives the periodic refresh.
let treeSignature = "";

function updateTreeInPlace(m) {
  const leaves = new Map();
  for (const d of document.querySelectorAll("#tree .leaf")) leaves.set(d.dataset.kind + "+" + d.dataset.name, d);
  for (const [kind] of SECTIONS) {
    for (const it of m.items[kind] || []) {
      const d = leaves.get(kind + "+" + it.name);
      if (!d) continue;
      const v = d.querySelector(".val");
      if (v) v.textContent = hw.values[key(it.kind, it.name)] ?? it.value;
      d.querySelector(".meta").textContent = meta(it);
    }
  }
}

// An existing leaf is kept if it offers the same controls (a set field only
// where halcmd would accept a set); its value and facts are refreshed.
function reuseLeaf(d, it) {
  if (!d) return null;
  const settable = ["pin", "param", "sig"].includes(it.kind) && !(hw.hello && hw.hello.read_only) && writable(it);
  if (!!d.querySelector(".tree-set-input") !== settable) return null;
  const v = d.querySelector(".val");
  if (v) v.textContent = hw.values[key(it.kind, it.name)] ?? it.value;
  d.querySelector(".meta").textContent = meta(it);
  return d;
}

function onTree(m) {
  hw.tree = m.items;
  const sig = SECTIONS.map(([k]) => k + ":" + (m.items[k] || []).map((it) =>
    it.name + (writable(it) ? "+w" : "")).join(",")).join(";");
  if (sig === treeSignature && $("tree").childElementCount) {
    updateTreeInPlace(m);
    return;
  }
  treeSignature = sig;
  // Leaves that still exist are moved into the new tree, not recreated: what
  // the user typed, the last set results, and a click whose press and release
  // straddle the rebuild (another halcmd coming and going changes the
  // component list) all stay with the same elements.
  const old = new Map();
  for (const d of document.querySelectorAll("#tree .leaf")) old.set(d.dataset.kind + "+" + d.dataset.name, d);
  const focused = document.activeElement;
  const root = $("tree");
  root.innerHTML = "";
  let total = 0;
  for (const [kind, title] of SECTIONS) {
    const items = m.items[kind] || [];
    total += items.length;
    const sec = document.createElement("details");
    sec.className = "section";
    sec.id = "section-" + kind;
    sec.open = open.has(kind) || $("filter").value.trim() !== "";
    sec.ontoggle = () => (sec.open ? open.add(kind) : open.delete(kind));
    const s = document.createElement("summary");
    s.textContent = `${title} (${items.length})`;
    sec.appendChild(s);
    // dotted names become levels for pins and parameters, as halshow shows them
    const nodes = { "": sec };
    for (const it of items) {
      const parts = ["pin", "param"].includes(kind) ? it.name.split(".") : [it.name];
      let path = "";
      let parent = sec;
      for (const p of parts.slice(0, -1)) {
        path = path ? path + "." + p : p;
        if (!nodes[path]) {
          const d = document.createElement("details");
          d.open = true;
          const sm = document.createElement("summary");
          sm.textContent = p;
          d.appendChild(sm);
          parent.appendChild(d);
          nodes[path] = d;
        }
        parent = nodes[path];
      }
      parent.appendChild(reuseLeaf(old.get(kind + "+" + it.name), it) || leaf(it, parts[parts.length - 1]));
    }
    root.appendChild(sec);
  }
  if (focused && focused !== document.activeElement && root.contains(focused)) focused.focus();
  $("tree-count").textContent = total + " objects";
}

// ---- scope (halscope) -----------------------------------------------------------

function scopeSetup() {
  const chans = $("scope-channels").value.split(",").map((s) => s.trim()).filter((s) => s);
  // a loaded setup's scales and offsets stay with their channels
  const known = new Map(((hw.scopeSetup && hw.scopeSetup.channels) || []).map((c) => [c.name, c]));
  return {
    channels: chans.map((c) => ({ name: c, scale: known.get(c)?.scale ?? 1, offset: known.get(c)?.offset ?? 0 })),
    thread: $("scope-thread").value,
    samples: Number($("scope-samples").value),
    mult: Number($("scope-mult").value),
    mode: $("scope-mode").value,
    trigger: $("scope-trigger").value,
    edge: $("scope-edge").value,
    level: Number($("scope-level").value),
    position: Number($("scope-position").value),
  };
}

function fillTriggerChoices(names, chosen) {
  const sel = $("scope-trigger");
  sel.innerHTML = "";
  const none = document.createElement("option");
  none.value = "";
  none.textContent = "none";
  sel.appendChild(none);
  for (const n of names) {
    const o = document.createElement("option");
    o.value = n;
    o.textContent = n;
    sel.appendChild(o);
  }
  sel.value = chosen || "";
}

function fillScopeSetup(s) {
  if (!s) return;
  hw.scopeSetup = s;
  const names = s.channels.map((c) => c.name);
  $("scope-channels").value = names.join(", ");
  if (s.thread) $("scope-thread").value = s.thread;
  $("scope-samples").value = s.samples;
  $("scope-mult").value = s.mult;
  $("scope-mode").value = s.mode;
  fillTriggerChoices(names, s.trigger);
  $("scope-edge").value = s.edge;
  $("scope-level").value = s.level;
  $("scope-position").value = s.position;
}

function onScopeStatus(m) {
  hw.scopeStatus = m.text;
  $("scope-status").textContent = m.text;
  $("scope-status").className = "status " + (m.error ? "error" : "");
}

function plotCapture(m, data) {
  hw.plotted = { labels: ["time (ms)"].concat(m.names), rows: data.length, first: data[0], last: data[data.length - 1] };
  const labels = ["time (ms)"].concat(m.names);
  const opts = { labels: labels, legend: "always", xlabel: m.trigger === null ? "ms" : "ms from the trigger",
                 stepPlot: false, animatedZooms: false };
  if (!scopeGraph || scopeGraph.getLabels().join() !== labels.join()) {
    if (scopeGraph) scopeGraph.destroy();
    scopeGraph = new Dygraph($("scope-plot"), data, opts);
  } else {
    scopeGraph.updateOptions({ file: data, xlabel: opts.xlabel });
  }
}

function rows(m, ref) {
  const data = [];
  for (let r = 0; r < m.index.length; r++) {
    const row = [((m.index[r] - ref) * m.interval) / 1e6];
    for (let c = 0; c < m.columns.length; c++) {
      const v = m.columns[c][r];
      row.push(v === null ? null : v * m.scales[c] + m.offsets[c]);
    }
    data.push(row);
  }
  return data;
}

function onCapture(m) {
  hw.lastCapture = m;
  hw.captures = (hw.captures || 0) + 1;
  const ref = m.trigger === null ? 0 : m.trigger;
  plotCapture(m, rows(m, ref));
  $("scope-info").textContent =
    `${m.index.length} samples every ${m.interval} ns in ${m.thread}, ${m.mode}` +
    (m.trigger === null ? "" : `, trigger at sample ${m.trigger}${m.forced ? " (forced)" : ""}`) +
    `, t0 = ${(m.t0 / 1e9).toFixed(6)} s`;
}

function onChunk(m) {
  const keep = Number($("scope-samples").value) || 1000;
  if (!rollBuf || rollBuf.names.join() !== m.names.join()) rollBuf = { m: m, rows: [] };
  const t0 = rollBuf.m.t0;
  const shifted = Object.assign({}, m, { index: m.index.map((i) => i + (m.t0 - t0) / m.interval) });
  rollBuf.rows = rollBuf.rows.concat(rows(shifted, 0)).slice(-keep);
  hw.lastChunk = m;
  plotCapture(Object.assign({}, m, { trigger: null }), rollBuf.rows);
  $("scope-info").textContent = `rolling: ${rollBuf.rows.length} samples shown, ${m.lost} lost`;
}

function saveSetup() {
  const s = scopeSetup();
  const lines = ["# halscope setup (docs/halscope.md)", "thread " + s.thread, "mult " + s.mult,
                 "samples " + s.samples, "mode " + s.mode,
                 s.trigger ? `trigger ${s.trigger} ${s.edge} ${s.level} position ${s.position}` : "trigger none"];
  for (const c of s.channels) lines.push(`chan auto ${c.name} scale ${c.scale} offset ${c.offset}`);
  const blob = new Blob([lines.join("\n") + "\n"], { type: "text/plain" });
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob);
  a.download = "scope.halscope";
  a.click();
}

// ---- wiring ---------------------------------------------------------------------

function init() {
  for (const b of document.querySelectorAll("nav .tab")) b.onclick = () => showPage(b.dataset.page);
  $("refresh").onclick = requestTree;
  let ft = null;
  $("filter").oninput = () => { clearTimeout(ft); ft = setTimeout(requestTree, 200); };
  $("watch-add-button").onclick = () => {
    const n = $("watch-add").value.trim();
    if (!n) return;
    let kind = "pin", name = n;
    for (const sep of ["+", ":"]) {
      const i = n.indexOf(sep);
      if (i > 0 && ["pin", "sig", "param"].includes(n.slice(0, i))) { kind = n.slice(0, i); name = n.slice(i + 1); }
    }
    if (kind === "pin" && hw.tree) {
      const found = ["pin", "sig", "param"].find((k) => (hw.tree[k] || []).some((it) => it.name === name));
      if (found) kind = found;
    }
    addWatch(kind, name);
  };
  $("scope-channels").onchange = () => {
    const names = $("scope-channels").value.split(",").map((s) => s.trim()).filter((s) => s);
    fillTriggerChoices(names, $("scope-trigger").value);
  };
  $("scope-run").onclick = () => {
    rollBuf = null;
    send({ op: "scope_run", setup: scopeSetup() });
  };
  $("scope-stop").onclick = () => send({ op: "scope_stop" });
  $("scope-save").onclick = saveSetup;
  $("scope-load").onchange = (e) => {
    const f = e.target.files[0];
    if (f) f.text().then((t) => send({ op: "scope_load", text: t }));
  };
  setInterval(() => { if ($("page-show").classList.contains("active")) requestTree(); }, 2000);
  connect();
}

document.addEventListener("DOMContentLoaded", init);
