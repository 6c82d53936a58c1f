// What the monitor's browser tests share: the record as the page should plot it, the page's
// plotted series read back from uPlot (window.rpsdPlots), their comparison step by step.
import { readFileSync } from "node:fs";
import { join } from "node:path";
import { chromium } from "playwright-core";

export const HANG_GUARD_MS = 120000;  // bounds every wait; no time is judged

export function readHistory(dir) {
  const lines = readFileSync(join(dir, "time_history.csv"), "utf8").split("\n").filter((l) => l.length);
  const header = lines[0].split(",");
  const col = Object.fromEntries(header.map((h, i) => [h, i]));
  const rows = new Map();
  const steps = [];
  for (let r = 1; r < lines.length; r++) {
    const v = lines[r].split(",");
    const step = parseInt(v[col.step], 10);
    steps.push(step);
    rows.set(step, { time: parseFloat(v[col.time_s]), target: parseFloat(v[col.target_m_ch0]), command: parseFloat(v[col.command_m_ch0]),
                     measured: parseFloat(v[col.measured_m_ch0]), force: parseFloat(v[col.measured_force_n_ch0]),
                     roundTrip: parseFloat(v[col.round_trip_s_ch0]), age: parseInt(v[col.feedback_age_periods], 10),
                     lateness: parseFloat(v[col.cycle_lateness_s]) });
  }
  return { rows, steps };
}

// What the page plots, read back from uPlot's own data (window.rpsdPlots).
export async function plotted(page) {
  return page.evaluate(() => {
    const p = window.rpsdPlots;
    return { step: window.rpsdShown.step, time: p.displacement.data[0], target: p.displacement.data[1],
             command: p.displacement.data[2], measured: p.displacement.data[3], force: p.force.data[1],
             error: p.error.data[1], loopFrom: window.rpsdShown.loopFrom, hx: p.hysteresis.data[1][0], hy: p.hysteresis.data[1][1],
             age: p.timing.data[1], roundTrip: p.timing.data[2], lateness: p.lateness.data[1] };
  });
}

// Every plotted value equals the record's at the same step (and the steps follow each other
// unless the telemetry is decimated); returns the first difference, or "". time_history.csv
// holds 10 significant digits (%.10g): a value that came through it (a replay, the viewer)
// must be equal; one that came over the telemetry, the double itself, must be equal when
// written as the recorder writes it (digits: 10).
export function compare(shown, history, { consecutive = true, digits = 0 } = {}) {
  if (!shown.step.length) return "nothing plotted";
  if (shown.hx.length !== shown.step.length - shown.loopFrom) return `the loop has ${shown.hx.length} points for ${shown.step.length - shown.loopFrom} steps`;
  const asRecorded = (v) => (digits && v !== null && isFinite(v) ? Number(v.toPrecision(digits)) : v);
  for (let i = 0; i < shown.step.length; i++) {
    const r = history.rows.get(shown.step[i]);
    if (!r) return `step ${shown.step[i]} is not in the record`;
    const loop = i >= shown.loopFrom;
    const pairs = [["time", shown.time[i], r.time], ["target", shown.target[i], r.target], ["command", shown.command[i], r.command],
                   ["measured", shown.measured[i], r.measured], ["force", shown.force[i], r.force],
                   ["hysteresis x", loop ? shown.hx[i - shown.loopFrom] : shown.measured[i], r.measured],
                   ["hysteresis y", loop ? shown.hy[i - shown.loopFrom] : shown.force[i], r.force], ["feedback age", shown.age[i], r.age],
                   ["round trip", shown.roundTrip[i], r.roundTrip], ["lateness", shown.lateness[i], r.lateness]];
    for (const [name, got, want] of pairs) {
      if (asRecorded(got) !== want) return `step ${shown.step[i]}: ${name} plotted ${got}, recorded ${want}`;
    }
    // The tracking error is the page's own difference of what it plots.
    if (shown.error[i] !== shown.measured[i] - shown.target[i]) return `step ${shown.step[i]}: tracking error ${shown.error[i]}`;
    if (!digits && shown.error[i] !== r.measured - r.target) return `step ${shown.step[i]}: tracking error ${shown.error[i]} differs from the record's`;
    if (consecutive && i > 0 && shown.step[i] !== shown.step[i - 1] + 1) return `steps ${shown.step[i - 1]} and ${shown.step[i]} are not consecutive`;
  }
  return "";
}

export async function waitFor(page, fn, arg) {
  return page.waitForFunction(fn, arg, { timeout: HANG_GUARD_MS, polling: 50 });
}

// Clicks an operator button, giving the token when the page asks for it, and waits for the reply.
export async function press(page, button, token) {
  await page.evaluate(() => { window.rpsdLastCommand = null; });
  await page.click(button);
  if (await page.isVisible("#token-dialog")) {
    await page.fill("#token-input", token);
    await page.click("#token-ok");
  }
  await waitFor(page, () => window.rpsdLastCommand !== null);
  return page.evaluate(() => window.rpsdLastCommand);
}

// The page's address and the operator token `rpsd monitor` (a child with piped stdout) prints at start.
export function monitorAddress(monitor) {
  let printed = "";
  return new Promise((resolve, reject) => {
    monitor.stdout.on("data", (d) => {
      printed += d;
      const m = /page: +(http:\/\/127\.0\.0\.1:\d+\/)/.exec(printed), t = /token: +([0-9a-f]+)/.exec(printed);
      if (m && t) resolve([m[1], t[1]]);
    });
    monitor.on("exit", (code) => reject(new Error("rpsd monitor ended with " + code + ": " + printed)));
  });
}

// What a browser test that starts processes shares: its checks counted and printed, every
// process it started (spawned) ended however it ends, exit 0 only when every check passed.
export class BrowserTest {
  constructor() { this.passed = 0; this.failed = 0; this.children = []; }
  check(name, ok, detail) {
    if (ok) { this.passed++; console.log("ok   " + name); }
    else { this.failed++; console.log("FAIL " + name + (detail ? ": " + detail : "")); }
  }
  spawned(child) { this.children.push(child); return child; }
  // Runs main, then ends: an exception out of it counts as one more failure.
  run(main) {
    main().catch((e) => { this.failed++; console.log("FAIL " + (e.stack || e)); }).finally(() => {
      for (const child of this.children) if (child.exitCode === null) child.kill("SIGTERM");
      console.log(`${this.passed} passed, ${this.failed} failed`);
      process.exit(this.failed === 0 ? 0 : 1);
    });
  }
}

export const exited = (child) => new Promise((resolve) => (child.exitCode !== null ? resolve(child.exitCode) : child.on("exit", resolve)));

// Debian's chromium, headless, with one page at `url` once it streams; the page's console
// errors (but those `ignore` matches) and uncaught exceptions collected in `errors`. The
// caller closes `browser`; on a failure here it is closed before the error goes on.
export async function openMonitorPage(chromiumPath, url, { ignore = null } = {}) {
  const browser = await chromium.launch({ executablePath: chromiumPath, headless: true, args: ["--no-sandbox"] });
  const errors = [];
  try {
    const page = await (await browser.newContext({ viewport: { width: 1600, height: 1150 } })).newPage();
    page.on("console", (m) => { if (m.type() === "error" && !(ignore && ignore.test(m.text()))) errors.push(m.text()); });
    page.on("pageerror", (e) => errors.push(e.message));
    await page.goto(url);
    await waitFor(page, () => window.rpsdPage.link !== null);  // the page streams
    return { browser, page, errors };
  } catch (e) {
    await browser.close();
    throw e;
  }
}
