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
import { readHistory, plotted, compare, waitFor, HANG_GUARD_MS } from "./page_helpers.mjs";

const [fixture, replayDir, resultsDir, outDir, chromiumPath] = process.argv.slice(2);
const TOKEN = "0123456789abcdef0123456789abcdef";
let passed = 0, failed = 0;
function check(name, ok, detail) {
  if (ok) { passed++; console.log("ok   " + name); }
  else { failed++; console.log("FAIL " + name + (detail ? ": " + detail : "")); }
}

async function main() {
  mkdirSync(outDir, { recursive: true });
  const commandsLog = join(outDir, "commands.log");
  rmSync(commandsLog, { force: true });
  const history = readHistory(replayDir);
  // The browser and the first page are up before the server starts: its replay starts with
  // it, and the first browser must join within the run's first 10 s (the recent past it is
  // sent). Launched after, on a loaded CI machine chromium once took longer than that.
  const browser = await chromium.launch({ executablePath: chromiumPath, headless: true, args: ["--no-sandbox"] });
  const errors = [];
  const watch = (page, who) => {
    page.on("console", (m) => { if (m.type() === "error") errors.push(`${who}: ${m.text()}`); });
    page.on("pageerror", (e) => errors.push(`${who}: ${e.message}`));
  };
  const context = await browser.newContext({ viewport: { width: 1600, height: 1150 } });
  const first = await context.newPage();
  watch(first, "first browser");
  const server = spawn(fixture, [replayDir, resultsDir, TOKEN, "2048", commandsLog], { stdio: ["pipe", "pipe", "inherit"] });
  const port = await new Promise((resolve, reject) => {
    let out = "";
    server.stdout.on("data", (d) => { out += d; const m = /port (\d+)/.exec(out); if (m) resolve(Number(m[1])); });
    server.on("exit", (code) => reject(new Error("the fixture server ended with " + code)));
  });
  const url = `http://127.0.0.1:${port}/`;
  try {
    await first.goto(url);
    // A second browser joins mid-run, past the first 10 s: it is shown the recent past, then the rest.
    await waitFor(first, () => window.rpsdPage.status && window.rpsdPage.status.steps_done > 12500);
    const joinedAtStep = await first.evaluate(() => window.rpsdPage.status.steps_done);
    const second = await (await browser.newContext({ viewport: { width: 1600, height: 1150 } })).newPage();
    watch(second, "second browser");
    await second.goto(url);
    await waitFor(second, () => window.rpsdShown && window.rpsdShown.step.length > 0);  // its stream has joined
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
    // It joined between these two steps, as the first browser saw them (the server may be a
    // little ahead of what a loaded browser shows): its first step lies at most 10 s of test
    // time (a batch more) before the join, and well before it (the recent past was sent).
    const joinedFromS = history.rows.get(joinedAtStep).time, joinedByS = history.rows.get(joinedByStep).time;
    const fromS = late.time.length ? late.time[0] : NaN;
    check("it was shown the last 10 s before it joined, then the rest to the end",
          late.step[0] > 1 && fromS >= joinedFromS - 10.1 && fromS <= joinedByS - 5.0 &&
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

    // A decimated folder: its rows are every 16th step; the page counts the run's steps.
    const decimated = join(resultsDir, "synthetic-sdof-decimated");
    const summary = JSON.parse(readFileSync(join(decimated, "summary.json"), "utf8"));
    const rows = readHistory(decimated).steps.length;
    await first.evaluate(async (f) => { await window.rpsdOpenFolder(f); }, relative(resultsDir, decimated));
    const shown = await first.evaluate(() => ({ status: window.rpsdPage.status, notice: document.getElementById("notice").textContent }));
    check("a decimated folder holds fewer rows than steps", summary.histories.every_steps === 16 && rows < summary.steps / 10,
          `${rows} rows, ${summary.steps} steps`);
    check("the viewer counts a decimated run's steps, not its rows",
          shown.status.steps_done === summary.steps && shown.status.steps_planned === summary.steps_planned, JSON.stringify(shown.status));
    check("the viewer says the rows are every 16th step", shown.notice.includes(`every 16th recorded (${rows} rows)`), shown.notice);
    check("no console errors after the commands and in the viewer", errors.length === 0, errors.join(" | "));
  } finally {
    await browser.close();
    server.stdin.end();
  }
  console.log(`${passed} passed, ${failed} failed`);
  process.exit(failed === 0 ? 0 : 1);
}

main().catch((e) => { console.log("FAIL " + (e.stack || e)); console.log(`${passed} passed, ${failed + 1} failed`); process.exit(1); });
