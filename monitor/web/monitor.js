// rpsd monitor's page: the live test from /api/stream (Server-Sent Events), or a recorded
// folder from /api/results; the same plots for both. Values stay in SI in the plots' data
// (the axes show mm, kN, ms), so that window.rpsdPlots[name].data is what was measured.
"use strict";

(function () {
  const $ = (id) => document.getElementById(id);
  const NODE_BITS = [[1, "limit active"], [2, "fault"], [4, "holding"], [8, "end stop"], [16, "valve saturated"]];
  const LIMIT_BITS = [[1, "stroke"], [2, "velocity"], [4, "force"], [8, "increment"], [16, "acceleration"]];
  const COLORS = { target: "#7fb0e6", command: "#8a8f96", measured: "#c8102e", force: "#1b7f3b", error: "#6b2fa0",
                   age: "#b26a00", roundTrip: "#2b6cb0", lateness: "#c8102e" };
  const MAX_SAMPLES = 400000;  // a live run keeps at most this many steps in the browser

  const page = { mode: "live", channel: 0, windowS: 30, dirty: true, status: null, link: null,
                 streamOpen: false, lastMessageAt: 0, folder: null, progressHistory: [], droppedUpdates: 0 };
  let store = emptyStore(0);

  function emptyStore(channels) {
    const perChannel = () => Array.from({ length: channels }, () => []);
    return { channels, runId: null, step: [], time: [], target: perChannel(), command: perChannel(),
             measured: perChannel(), force: perChannel(), roundTrip: perChannel(), age: [], lateness: [],
             nodeStatus: [], limitFlags: [] };
  }

  // ---------- plots ----------
  function decimals(step) { return Math.max(0, Math.min(6, -Math.floor(Math.log10(step) + 1e-9))); }
  function scaledValues(factor) {
    return (u, splits, axisIdx, space, incr) => splits.map((v) => v == null ? "" : (v * factor).toFixed(decimals(Math.abs(incr * factor) || 1)));
  }
  function axis(label, factor, side) {
    const a = { label, labelSize: 22, size: 64, font: "14px DejaVu Sans, Arial, sans-serif", labelFont: "bold 15px DejaVu Sans, Arial, sans-serif",
                stroke: "#15202b", grid: { stroke: "#e3e7ec", width: 1 }, ticks: { stroke: "#c0c6cc", width: 1 } };
    if (factor !== 1) a.values = scaledValues(factor);
    if (side !== undefined) { a.side = side; a.grid = { show: false }; }
    return a;
  }
  const timeAxis = () => axis("test time [s]", 1);
  function plotWidth(id) { return Math.max(420, $(id).parentElement.clientWidth - 20); }
  const PLOT_HEIGHT = 300;
  function line(label, stroke, extra) { return Object.assign({ label, stroke, width: 2, points: { show: false } }, extra || {}); }
  function siValue(factor, unit, digits) { return (u, v) => v == null ? "—" : (v * factor).toFixed(digits) + " " + unit; }

  // A line through the points in their order (the hysteresis loop), for uPlot's mode 2.
  function loopPath(u, seriesIdx) {
    const [xs, ys] = u.data[seriesIdx];
    const p = new Path2D();
    let started = false;
    for (let i = 0; i < xs.length; i++) {
      if (xs[i] == null || ys[i] == null) { started = false; continue; }
      const x = u.valToPos(xs[i], "x", true), y = u.valToPos(ys[i], "y", true);
      if (started) p.lineTo(x, y); else { p.moveTo(x, y); started = true; }
    }
    return { stroke: p, fill: null, clip: null, band: null, gaps: null, flags: 0 };
  }

  function makePlots() {
    const plots = {};
    const common = (id) => ({ width: plotWidth(id), height: PLOT_HEIGHT, scales: { x: { time: false } },
                              cursor: { drag: { x: true, y: false } }, legend: { live: true } });
    plots.displacement = new uPlot(Object.assign(common("p-displacement"), {
      // The target wide and pale beneath, the measurement narrow on top: both stay visible.
      series: [{ label: "t [s]" }, line("target", COLORS.target, { width: 5, value: siValue(1000, "mm", 3) }),
               line("command", COLORS.command, { dash: [6, 4], width: 1.5, value: siValue(1000, "mm", 3) }),
               line("measured", COLORS.measured, { width: 1.5, value: siValue(1000, "mm", 3) })],
      axes: [timeAxis(), axis("displacement [mm]", 1000)] }), [[], [], [], []], $("p-displacement"));
    plots.force = new uPlot(Object.assign(common("p-force"), {
      series: [{ label: "t [s]" }, line("measured force", COLORS.force, { value: siValue(1e-3, "kN", 3) })],
      axes: [timeAxis(), axis("force [kN]", 1e-3)] }), [[], []], $("p-force"));
    plots.error = new uPlot(Object.assign(common("p-error"), {
      series: [{ label: "t [s]" }, line("measured − target", COLORS.error, { value: siValue(1000, "mm", 3) })],
      axes: [timeAxis(), axis("tracking error [mm]", 1000)] }), [[], []], $("p-error"));
    plots.hysteresis = new uPlot({ mode: 2, width: plotWidth("p-hysteresis"), height: PLOT_HEIGHT,
      scales: { x: { time: false, auto: true }, y: { auto: true } }, legend: { show: false }, cursor: { show: false },
      series: [{}, { label: "force against displacement", stroke: COLORS.force, width: 2, paths: loopPath, points: { show: false } }],
      axes: [axis("measured displacement [mm]", 1000), axis("measured force [kN]", 1e-3)] }, [null, [[], []]], $("p-hysteresis"));
    plots.timing = new uPlot(Object.assign(common("p-timing"), {
      scales: { x: { time: false }, periods: { auto: true, range: (u, lo, hi) => [0, Math.max(2, hi + 1)] }, s: { auto: true, range: (u, lo, hi) => [0, Math.max(hi * 1.1, 1e-3)] } },
      series: [{ label: "t [s]" }, line("feedback age", COLORS.age, { scale: "periods", paths: uPlot.paths.stepped({ align: 1 }), value: (u, v) => v == null ? "—" : v + " periods" }),
               line("round trip", COLORS.roundTrip, { scale: "s", value: siValue(1000, "ms", 3) })],
      axes: [timeAxis(), Object.assign(axis("feedback age [periods]", 1), { scale: "periods" }), Object.assign(axis("round trip [ms]", 1000, 1), { scale: "s" })] }),
      [[], [], []], $("p-timing"));
    plots.lateness = new uPlot(Object.assign(common("p-lateness"), {
      scales: { x: { time: false }, y: { auto: true, range: (u, lo, hi) => [Math.min(0, lo), Math.max(hi * 1.1, 1e-3)] } },
      series: [{ label: "t [s]" }, line("cycle lateness", COLORS.lateness, { value: siValue(1000, "ms", 3) })],
      axes: [timeAxis(), axis("lateness [ms]", 1000)] }), [[], []], $("p-lateness"));
    return plots;
  }
  const plots = makePlots();
  window.rpsdPlots = plots;
  window.rpsdPage = page;

  function firstShown() {
    if (!page.windowS || store.time.length === 0) return 0;
    const from = store.time[store.time.length - 1] - page.windowS;
    let lo = 0, hi = store.time.length - 1;  // first index at or after `from`
    while (lo < hi) { const mid = (lo + hi) >> 1; if (store.time[mid] < from) lo = mid + 1; else hi = mid; }
    return lo;
  }

  const LOOP_S = 5;
  function countSince(t, seconds) {  // samples within the last `seconds` of t
    let n = 0;
    while (n < t.length && t[t.length - 1 - n] >= t[t.length - 1] - seconds) n++;
    return n;
  }

  function draw() {
    if (!page.dirty) return;
    page.dirty = false;
    const c = Math.min(page.channel, Math.max(0, store.channels - 1));
    const i0 = firstShown();
    const cut = (a) => (a ? a.slice(i0) : []);
    const t = cut(store.time);
    const target = cut(store.target[c]), command = cut(store.command[c]), measured = cut(store.measured[c]);
    const force = cut(store.force[c]);
    const error = measured.map((m, i) => (m == null || target[i] == null ? null : m - target[i]));
    plots.displacement.setData([t, target, command, measured]);
    plots.force.setData([t, force]);
    plots.error.setData([t, error]);
    // The loop of the last few seconds (the whole run when the whole run is asked for).
    const h0 = page.windowS ? Math.max(0, t.length - countSince(t, LOOP_S)) : 0;
    plots.hysteresis.setData([null, [measured.slice(h0), force.slice(h0)]]);
    $("loop-caption").textContent = page.windowS ? `last ${LOOP_S} s` : "whole run";
    plots.timing.setData([t, cut(store.age), cut(store.roundTrip[c])]);
    plots.lateness.setData([t, cut(store.lateness)]);
    window.rpsdShown = { channel: c, step: cut(store.step), loopFrom: h0 };
  }
  setInterval(draw, 40);  // 25 frames per second at most, only when something came
  window.addEventListener("resize", () => {
    for (const [name, u] of Object.entries(plots)) u.setSize({ width: plotWidth("p-" + name), height: PLOT_HEIGHT });
  });

  // ---------- the data ----------
  function setChannels(n) {
    const box = $("channels");
    if (box.childElementCount === n) return;
    box.textContent = "";
    for (let c = 0; c < n; c++) {
      const b = document.createElement("button");
      b.type = "button";
      b.textContent = "ch" + c;
      b.onclick = () => { page.channel = c; markChannel(); page.dirty = true; };
      box.appendChild(b);
    }
    markChannel();
  }
  function markChannel() {
    [...$("channels").children].forEach((b, i) => b.classList.toggle("active", i === page.channel));
  }

  function appendBatch(m) {
    const s = m.samples;
    // A new run starts afresh; a run's channels never change, but a batch of no samples (its
    // last, with the status) may say none.
    if (store.runId !== m.run_id || (s.step.length && store.channels !== s.channels)) {
      store = emptyStore(s.channels);
      store.runId = m.run_id;
      setChannels(s.channels);
    }
    for (let i = 0; i < s.step.length; i++) {
      // A batch that repeats steps already shown (a browser that joined sees the recent past) adds nothing.
      if (store.step.length && s.step[i] <= store.step[store.step.length - 1]) continue;
      store.step.push(s.step[i]); store.time.push(s.time_s[i]);
      for (let c = 0; c < s.channels; c++) {
        store.target[c].push(s.target_m[c][i]); store.command[c].push(s.command_m[c][i]);
        store.measured[c].push(s.measured_m[c][i]); store.force[c].push(s.measured_force_n[c][i]);
        store.roundTrip[c].push(s.round_trip_s[c][i]);
      }
      store.age.push(s.feedback_age_periods[i]); store.lateness.push(s.cycle_lateness_s[i]);
      store.nodeStatus.push(s.node_status[i]); store.limitFlags.push(s.limit_flags[i]);
    }
    const excess = store.step.length - MAX_SAMPLES;
    if (excess > 0) {
      for (const k of ["step", "time", "age", "lateness", "nodeStatus", "limitFlags"]) store[k].splice(0, excess);
      for (const k of ["target", "command", "measured", "force", "roundTrip"]) store[k].forEach((a) => a.splice(0, excess));
    }
    page.dirty = true;
    showStatus(m.status);
  }

  function bits(value, table) {
    const names = table.filter(([bit]) => value & bit).map(([, name]) => name);
    return names.length ? names.join(", ") : "ok";
  }
  function duration(s) {
    if (!isFinite(s) || s < 0) return "—";
    if (s < 60) return Math.round(s) + " s";
    const m = Math.floor(s / 60), r = Math.round(s - 60 * m);
    return m < 60 ? `${m} min ${r} s` : `${Math.floor(m / 60)} h ${m % 60} min`;
  }
  function percent(v) { return v == null ? "—" : (100 * v).toFixed(2) + " %"; }

  function showStatus(st) {
    page.status = st;
    $("subtitle").textContent = page.mode === "results" ? "recorded: " + st.test_name
      : `test ${st.test_id} · ${st.test_name || "run " + st.run_id} · ${st.real_time ? "real time" : "lock-step"}`;
    const state = page.mode === "results" ? "recorded" : st.state;
    $("state").textContent = state === "ended" && st.stopped_by ? "ENDED: " + st.stopped_by
      : state === "recorded" && page.result ? "RECORDED: " + page.result : state.toUpperCase();
    $("state").className = "state state-" + state;
    const done = st.steps_done, planned = st.steps_planned;
    $("progress-text").textContent = `step ${done} of ${planned}` + (store.time.length ? ` · t = ${store.time[store.time.length - 1].toFixed(2)} s` : "");
    $("progress-fill").style.width = (planned > 0 ? Math.min(100, (100 * done) / planned) : 0) + "%";
    $("progress-left").textContent = "time left " + timeLeft(st);
    $("f-overruns").textContent = st.overruns; $("f-overruns").classList.toggle("bad", st.overruns > 0);
    $("f-late").textContent = st.late_feedback;
    $("f-age").textContent = st.worst_feedback_age_periods + " periods";
    $("f-zeta-p").textContent = percent(st.predicted_effective_damping);
    $("f-zeta-i").textContent = percent(st.identified_effective_damping);
    const last = store.nodeStatus.length - 1;
    if (last >= 0) {
      const flags = store.limitFlags[last];
      $("f-node").textContent = bits(store.nodeStatus[last], NODE_BITS) + (flags ? " · limit: " + bits(flags, LIMIT_BITS) : "");
      $("f-node").classList.toggle("bad", store.nodeStatus[last] !== 0 || flags !== 0);
    }
    const lockStep = !st.real_time;
    $("btn-hold").classList.toggle("hidden", !lockStep);
    $("btn-resume").classList.toggle("hidden", !lockStep);
    $("btn-hold").disabled = st.state !== "running";
    $("btn-resume").disabled = st.state !== "held";
  }

  function timeLeft(st) {
    if (st.state === "ended" || page.mode === "results") return "—";
    // Held: no time passes for the test; the pace starts afresh on resuming.
    if (st.state === "held") { page.progressHistory.length = 0; return "— (held)"; }
    const left = st.steps_planned - st.steps_done;
    if (st.real_time && st.control_rate_hz > 0) return duration(left / st.control_rate_hz);
    // Lock-step: from the pace of the last ten seconds on this clock.
    const now = performance.now(), h = page.progressHistory;
    h.push([now, st.steps_done]);
    while (h.length > 2 && now - h[0][0] > 10000) h.shift();
    const rate = h.length > 1 ? (h[h.length - 1][1] - h[0][1]) / ((h[h.length - 1][0] - h[0][0]) / 1000) : 0;
    return rate > 0 ? "≈ " + duration(left / rate) : "—";
  }

  const seenEvents = new Set();
  function addEvent(e) {
    // A reconnected stream repeats the recent events: each is listed once.
    const key = [e.run_id, e.kind, e.step, e.wall_clock_unix_ns, e.text].join("|");
    if (e.wall_clock_unix_ns !== undefined) {
      if (seenEvents.has(key)) return;
      seenEvents.add(key);
    }
    if (e.kind === "run_started") $("events").textContent = "";  // a new run: its own events
    const li = document.createElement("li");
    li.className = e.kind + (e.kind === "run_ended" && !/completed/.test(e.text) ? " bad" : "");
    const when = document.createElement("span");
    when.className = "when";
    when.textContent = e.step >= 0 ? `step ${e.step} · ${Number(e.time_s).toFixed(3)} s` : "before the first step";
    li.appendChild(when);
    const label = e.kind.replace("_", " ");
    li.appendChild(document.createTextNode(" " + (e.text.startsWith(label) ? e.text : label + ": " + e.text)));
    $("events").prepend(li);
  }

  // ---------- the live link ----------
  function showBanner() {
    const b = $("banner");
    const quiet = performance.now() - page.lastMessageAt > 3000;
    let text = "";
    let lost = false;
    if (page.mode !== "live") text = "";
    else if (!page.streamOpen || quiet) { text = "LINK TO THE MONITOR LOST — the plots are not live"; lost = true; }
    else if (page.link && page.link.link_lost) { text = "TELEMETRY LINK LOST — the test's publisher is gone; the plots show the last data received"; lost = true; }
    else if (page.link && page.link.stale) {
      const age = page.link.last_batch_age_s;
      text = "DATA STALE — no new samples for " + (age == null ? "a while" : age.toFixed(1) + " s");
    }
    b.textContent = text;
    b.classList.toggle("hidden", text === "");
    b.classList.toggle("lost", lost);
    window.rpsdBanner = text;
  }
  setInterval(showBanner, 500);

  let source = null;
  function connect() {
    source = new EventSource("/api/stream");
    source.onopen = () => { page.streamOpen = true; page.lastMessageAt = performance.now(); };
    source.onerror = () => { page.streamOpen = false; };
    source.onmessage = (ev) => {
      page.lastMessageAt = performance.now();
      const m = JSON.parse(ev.data);
      if (page.mode !== "live") return;
      if (m.type === "batch") appendBatch(m);
      else if (m.type === "event") addEvent(m);
      else if (m.type === "link") {
        page.link = m;
        $("f-lost").textContent = m.batches_lost;
        if (!page.status) $("subtitle").textContent = `test ${m.test_id}: waiting for its run to publish`;
      }
      else if (m.type === "dropped") {
        page.droppedUpdates = m.count;  // what this browser was never sent: its own queue overflowed
        notice(`${m.count} updates were not shown: this browser kept up too slowly`, true);
      }
    };
  }

  // ---------- operator commands ----------
  function notice(text, bad) {
    const n = $("notice");
    n.textContent = text;
    n.classList.toggle("hidden", !text);
    n.classList.toggle("bad", !!bad);
  }
  function askToken() {
    return new Promise((resolve) => {
      const d = $("token-dialog");
      $("token-input").value = "";
      d.onclose = () => resolve(d.returnValue === "ok" && $("token-input").value ? $("token-input").value.trim() : null);
      d.showModal();
      $("token-input").focus();
    });
  }
  async function command(action) {
    let token = sessionStorage.getItem("rpsd-token");
    if (!token) {
      token = await askToken();
      if (!token) return;
    }
    notice(`${action}: sending…`);
    let res, body;
    try {
      res = await fetch("/api/operator", { method: "POST", headers: { "Content-Type": "application/json" },
                                           body: JSON.stringify({ action, token }) });
      body = await res.json();
    } catch (err) {
      notice(`${action}: not sent, the monitor does not answer (${err})`, true);
      return;
    }
    if (res.status === 403) sessionStorage.removeItem("rpsd-token");
    else sessionStorage.setItem("rpsd-token", token);
    if (res.ok) notice(`${action}: done — ${body.text}`);
    else notice(`${action}: ${body.error || body.text || "refused"}`, true);
    window.rpsdLastCommand = { action, status: res.status, body };
  }
  for (const a of ["stop", "abort", "hold", "resume"]) $("btn-" + a).onclick = () => command(a);
  // The operator's own link may carry the token after '#': kept for this tab, taken off the address bar.
  const fromHash = /(?:^#|&)token=([0-9a-f]+)/.exec(location.hash);
  if (fromHash) { sessionStorage.setItem("rpsd-token", fromHash[1]); history.replaceState(null, "", location.pathname); }

  // ---------- recorded results ----------
  async function listResults() {
    const tbody = $("results-table").querySelector("tbody");
    const res = await fetch("/api/results");
    const body = await res.json();
    tbody.textContent = "";
    if (!res.ok) { $("results-root").textContent = body.error; return; }
    for (const f of body.folders) {
      const tr = document.createElement("tr");
      for (const text of [f.path || "(the results folder)", f.kind, f.result, f.scenario]) {
        const td = document.createElement("td"); td.textContent = text; tr.appendChild(td);
      }
      if (f.has_time_history) { tr.className = "openable"; tr.onclick = () => openFolder(f.path, tr); }
      tbody.appendChild(tr);
    }
    window.rpsdResults = body.folders;
  }

  function parseHistory(text) {
    const lines = text.split("\n").filter((l) => l.length);
    const header = lines[0].split(",");
    const col = Object.fromEntries(header.map((h, i) => [h, i]));
    let channels = 0;
    while (("target_m_ch" + channels) in col) channels++;
    const s = emptyStore(channels);
    for (let r = 1; r < lines.length; r++) {
      const v = lines[r].split(",");
      const num = (name) => parseFloat(v[col[name]]);
      s.step.push(parseInt(v[col.step], 10)); s.time.push(num("time_s"));
      for (let c = 0; c < channels; c++) {
        s.target[c].push(num("target_m_ch" + c)); s.command[c].push(num("command_m_ch" + c));
        s.measured[c].push(num("measured_m_ch" + c)); s.force[c].push(num("measured_force_n_ch" + c));
        s.roundTrip[c].push(num("round_trip_s_ch" + c));
      }
      s.age.push(parseInt(v[col.feedback_age_periods], 10)); s.lateness.push(num("cycle_lateness_s"));
      s.nodeStatus.push(parseInt(v[col.node_status], 10)); s.limitFlags.push(parseInt(v[col.limit_flags], 10));
    }
    return s;
  }

  async function openFolder(path, row) {
    document.querySelectorAll("#results-table tr.open").forEach((r) => r.classList.remove("open"));
    if (row) row.classList.add("open");
    notice(`opening ${path || "the results folder"}…`);
    const q = "/api/results/file?folder=" + encodeURIComponent(path) + "&name=";
    const [csv, summary] = await Promise.all([fetch(q + "time_history.csv"), fetch(q + "summary.json")]);
    if (!csv.ok) { notice(`${path}: no time history (${csv.status})`, true); return; }
    store = parseHistory(await csv.text());
    const sum = summary.ok ? await summary.json() : {};
    page.folder = path;
    page.channel = 0;
    setChannels(store.channels);
    $("events").textContent = "";
    let overruns = 0, late = 0, worst = 0;
    for (let i = 0; i < store.step.length; i++) {
      if (store.lateness[i] > 0) overruns++;
      if (store.age[i] > 0) late++;
      worst = Math.max(worst, store.age[i]);
      if (store.limitFlags[i] && (i === 0 || store.limitFlags[i] !== store.limitFlags[i - 1])) {
        addEvent({ kind: "limit", step: store.step[i], time_s: store.time[i], text: bits(store.limitFlags[i], LIMIT_BITS) });
      }
    }
    const stopped = sum.stopped_by && sum.stopped_by.reason ? sum.stopped_by.reason : (sum.result || "");
    if (stopped) addEvent({ kind: "run_ended", step: store.step[store.step.length - 1], time_s: store.time[store.time.length - 1], text: stopped });
    const n = store.step.length;
    // A decimated history (output.histories) holds every k-th step: the counts are the run's,
    // from summary.json, not the rows'.
    const every = sum.histories && sum.histories.kept === "decimated" ? sum.histories.every_steps : 1;
    const steps = every > 1 && Number.isFinite(sum.steps) ? sum.steps : n;
    const planned = every > 1 && Number.isFinite(sum.steps_planned) ? sum.steps_planned : steps;
    if (every > 1) {
      if (Number.isFinite(sum.overruns)) overruns = sum.overruns;
      if (sum.timing && Number.isFinite(sum.timing.late_feedback)) late = sum.timing.late_feedback;
    }
    page.result = sum.result || "";
    showStatus({ test_id: "—", test_name: (path || "the results folder") + (sum.scenario ? " · " + sum.scenario : ""), run_id: 0, state: "ended",
                 stopped_by: stopped, steps_done: steps, steps_planned: planned, real_time: false, overruns, late_feedback: late,
                 worst_feedback_age_periods: worst, predicted_effective_damping: null, identified_effective_damping: null });
    $("btn-hold").classList.add("hidden"); $("btn-resume").classList.add("hidden");
    $("window").value = "0"; page.windowS = 0;
    page.dirty = true;
    notice(`${path || "the results folder"}: ` + (every > 1 ? `${steps} steps, every ${every}th recorded (${n} rows)` : `${n} steps`) +
           (sum.result ? ` · ${sum.result}` : ""));
    window.rpsdOpened = path;
  }

  // ---------- modes ----------
  function setMode(mode) {
    page.mode = mode;
    $("mode-live").classList.toggle("active", mode === "live");
    $("mode-results").classList.toggle("active", mode === "results");
    $("results-panel").classList.toggle("hidden", mode !== "results");
    store = emptyStore(0); page.dirty = true; $("events").textContent = ""; seenEvents.clear();
    if (mode === "results") listResults();
    else if (source) { source.close(); page.status = null; connect(); }  // a new stream starts with the recent past
    showBanner();
  }
  $("mode-live").onclick = () => setMode("live");
  $("mode-results").onclick = () => setMode("results");
  $("window").onchange = () => { page.windowS = Number($("window").value); page.dirty = true; };
  window.rpsdOpenFolder = async (path) => { setMode("results"); await listResults(); await openFolder(path, null); };

  connect();
})();
