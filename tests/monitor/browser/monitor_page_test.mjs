// The monitor's page in Debian's chromium (headless, driven by playwright-core): it loads
// with no console error; what it plots live equals the replayed run's time_history.csv over
// the same steps, in a browser that watched from the start and in one that joined mid-run
// (the recent past); a command without the token is refused and never sent; the STOP button
// asks for the token once and sends stop; the viewer plots a recorded folder exactly; the
// page is photographed (monitor.png, monitor-viewer.png) as the test's artefacts.
//   node monitor_page_test.mjs FIXTURE_SERVER REPLAY_DIR RESULTS_DIR OUT_DIR CHROMIUM
import { spawn } from "node:child_process";
import { readFileSync, mkdirSync, rmSync, existsSync } from "node:fs";
import { join, relative } from "node:path";
import { chromium } from "playwright-core";

const [fixture, replayDir, resultsDir, outDir, chromiumPath] = process.argv.slice(2);
const TOKEN = "0123456789abcdef0123456789abcdef";
const HANG_GUARD_MS = 120000;  // bounds every wait; no time is judged
let passed = 0, failed = 0;
function check(name, ok, detail) {
  if (ok) { passed++; console.log("ok   " + name); }
  else { failed++; console.log("FAIL " + name + (detail ? ": " + detail : "")); }
}

function readHistory(dir) {
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
async function plotted(page) {
  return page.evaluate(() => {
    const p = window.rpsdPlots;
    return { step: window.rpsdShown.step, time: p.displacement.data[0], target: p.displacement.data[1],
             command: p.displacement.data[2], measured: p.displacement.data[3], force: p.force.data[1],
             error: p.error.data[1], loopFrom: window.rpsdShown.loopFrom, hx: p.hysteresis.data[1][0], hy: p.hysteresis.data[1][1],
             age: p.timing.data[1], roundTrip: p.timing.data[2], lateness: p.lateness.data[1] };
  });
}

// Every plotted value equals the record's at the same step; returns the first difference.
function compare(shown, history) {
  if (!shown.step.length) return "nothing plotted";
  if (shown.hx.length !== shown.step.length - shown.loopFrom) return `the loop has ${shown.hx.length} points for ${shown.step.length - shown.loopFrom} steps`;
  for (let i = 0; i < shown.step.length; i++) {
    const r = history.rows.get(shown.step[i]);
    if (!r) return `step ${shown.step[i]} is not in the record`;
    const pairs = [["time", shown.time[i], r.time], ["target", shown.target[i], r.target], ["command", shown.command[i], r.command],
                   ["measured", shown.measured[i], r.measured], ["force", shown.force[i], r.force],
                   ["tracking error", shown.error[i], r.measured - r.target],
                   ["hysteresis x", i >= shown.loopFrom ? shown.hx[i - shown.loopFrom] : r.measured, r.measured],
                   ["hysteresis y", i >= shown.loopFrom ? shown.hy[i - shown.loopFrom] : r.force, r.force], ["feedback age", shown.age[i], r.age],
                   ["round trip", shown.roundTrip[i], r.roundTrip], ["lateness", shown.lateness[i], r.lateness]];
    for (const [name, got, want] of pairs) {
      if (got !== want) return `step ${shown.step[i]}: ${name} plotted ${got}, recorded ${want}`;
    }
    if (i > 0 && shown.step[i] !== shown.step[i - 1] + 1) return `steps ${shown.step[i - 1]} and ${shown.step[i]} are not consecutive`;
  }
  return "";
}

async function waitFor(page, fn, arg) {
  return page.waitForFunction(fn, arg, { timeout: HANG_GUARD_MS, polling: 50 });
}

async function main() {
  mkdirSync(outDir, { recursive: true });
  const commandsLog = join(outDir, "commands.log");
  rmSync(commandsLog, { force: true });
  const history = readHistory(replayDir);
  const server = spawn(fixture, [replayDir, resultsDir, TOKEN, "2048", commandsLog], { stdio: ["pipe", "pipe", "inherit"] });
  const port = await new Promise((resolve, reject) => {
    let out = "";
    server.stdout.on("data", (d) => { out += d; const m = /port (\d+)/.exec(out); if (m) resolve(Number(m[1])); });
    server.on("exit", (code) => reject(new Error("the fixture server ended with " + code)));
  });
  const url = `http://127.0.0.1:${port}/`;
  const browser = await chromium.launch({ executablePath: chromiumPath, headless: true, args: ["--no-sandbox"] });
  const errors = [];
  const watch = (page, who) => {
    page.on("console", (m) => { if (m.type() === "error") errors.push(`${who}: ${m.text()}`); });
    page.on("pageerror", (e) => errors.push(`${who}: ${e.message}`));
  };
  try {
    const context = await browser.newContext({ viewport: { width: 1600, height: 1150 } });
    const first = await context.newPage();
    watch(first, "first browser");
    await first.goto(url);
    // A second browser joins mid-run, past the first 10 s: it is shown the recent past, then the rest.
    await waitFor(first, () => window.rpsdPage.status && window.rpsdPage.status.steps_done > 12500);
    const joinedAtStep = await first.evaluate(() => window.rpsdPage.status.steps_done);
    const second = await (await browser.newContext({ viewport: { width: 1600, height: 1150 } })).newPage();
    watch(second, "second browser");
    await second.goto(url);
    const joinedByStep = await first.evaluate(() => window.rpsdPage.status.steps_done);
    await waitFor(first, () => window.rpsdPage.status && window.rpsdPage.status.steps_done > 16000);
    await first.screenshot({ path: join(outDir, "monitor.png"), fullPage: true });
    for (const page of [first, second]) {
      await waitFor(page, () => window.rpsdPage.status && window.rpsdPage.status.state === "ended");
      await page.selectOption("#window", "0");
      await page.waitForTimeout(200);  // a frame or two
    }
    const all = await plotted(first);
    check("the first browser plots every step of the run", all.step.length === history.steps.length,
          `${all.step.length} of ${history.steps.length}`);
    const diff = compare(all, history);
    check("the live plots equal time_history.csv at every step", diff === "", diff);
    const late = await plotted(second);
    const lateDiff = compare(late, history);
    check("a browser that joined mid-run plots the recorded values", lateDiff === "", lateDiff);
    // It joined between these two steps: its first step lies 10 s of test time (a batch more
    // or less) before the join.
    const joinedFromS = history.rows.get(joinedAtStep).time, joinedByS = history.rows.get(joinedByStep).time;
    const fromS = late.time.length ? late.time[0] : NaN;
    check("it was shown the last 10 s before it joined, then the rest to the end",
          late.step[0] > 1 && fromS >= joinedFromS - 10.1 && fromS <= joinedByS - 9.9 &&
          late.step[late.step.length - 1] === history.steps[history.steps.length - 1],
          `joined between ${joinedFromS.toFixed(2)} s and ${joinedByS.toFixed(2)} s, shown from ${fromS.toFixed(3)} s`);
    const banner = await first.evaluate(() => window.rpsdBanner);
    check("the ended run is not reported as a lost link", banner === "" || banner.startsWith("TELEMETRY"), banner);

    check("the page loads and runs with no console errors", errors.length === 0, errors.join(" | "));
    errors.length = 0;

    // Commands: refused without the token, never sent (the browser logs each refusal).
    const refused = await first.evaluate(async () => {
      const codes = [];
      for (const body of [{ action: "stop" }, { action: "stop", token: "nope" }, { action: "stop", token: "0123456789abcdef0123456789abcdee" }]) {
        codes.push((await fetch("/api/operator", { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body) })).status);
      }
      return codes;
    });
    check("a POST without the right token is refused (403)", refused.every((c) => c === 403), refused.join(","));
    const refusals = errors.splice(0).filter((e) => !/status of 403/.test(e));
    check("the refusals are the only console errors", refusals.length === 0, refusals.join(" | "));
    check("and nothing reached the command sink", !existsSync(commandsLog) || readFileSync(commandsLog, "utf8") === "");

    // The STOP button: always in view, asks for the token once, sends stop.
    const stop = first.locator("#btn-stop");
    check("the STOP button is visible", await stop.isVisible());
    await stop.click();
    await first.fill("#token-input", TOKEN);
    await first.click("#token-ok");
    await waitFor(first, () => window.rpsdLastCommand && window.rpsdLastCommand.action === "stop");
    const sent = await first.evaluate(() => window.rpsdLastCommand);
    check("STOP with the token is answered (200)", sent.status === 200, JSON.stringify(sent));
    const log = existsSync(commandsLog) ? readFileSync(commandsLog, "utf8").trim().split("\n") : [];
    check("stop reached the command sink once, from the browser", log.length === 1 && /^stop 127\.0\.0\.1:\d+$/.test(log[0]), log.join("|"));
    await first.click("#btn-abort");  // the token is asked once per tab
    await waitFor(first, () => window.rpsdLastCommand && window.rpsdLastCommand.action === "abort");
    check("abort goes without asking again", (await first.evaluate(() => window.rpsdLastCommand.status)) === 200);

    // The viewer: the same plots from the recorded folder.
    const folder = relative(resultsDir, replayDir);
    const listed = await first.evaluate(async (f) => { await window.rpsdOpenFolder(f); return window.rpsdResults.map((r) => r.path); }, folder);
    check("the viewer lists the recorded folder", listed.includes(folder), listed.join(","));
    await first.waitForTimeout(200);
    const viewed = await plotted(first);
    check("the viewer plots every step", viewed.step.length === history.steps.length, `${viewed.step.length}`);
    const viewDiff = compare(viewed, history);
    check("the viewer's plots equal time_history.csv", viewDiff === "", viewDiff);
    await first.screenshot({ path: join(outDir, "monitor-viewer.png"), fullPage: true });
    check("no console errors after the commands and in the viewer", errors.length === 0, errors.join(" | "));
  } finally {
    await browser.close();
    server.stdin.end();
  }
  console.log(`${passed} passed, ${failed} failed`);
  process.exit(failed === 0 ? 0 : 1);
}

main().catch((e) => { console.log("FAIL " + (e.stack || e)); console.log(`${passed} passed, ${failed + 1} failed`); process.exit(1); });
