// An operator holds, resumes and stops a running lock-step test from the page of `rpsd monitor`
// in Debian's chromium: the two-site bridge over DDS (loopback) with its two servo nodes as
// separate processes, its scenario enabling operator commands (DDS Security off). The page asks
// for the token printed at the monitor's start; Hold shows the run held with its steps standing
// still (screenshot: monitor-held.png), Resume lets them advance again, STOP ends the run: exit
// 3, summary.json `operator_stop` naming the monitor as sender, the held interval and the three
// commands, every step in time_history.csv, and that history equal byte for byte to the same
// scenario's unheld in-process run over the same steps (all but the wall-clock columns).
//   node monitor_operator_test.mjs RPSD SOURCE_DIR OUT_DIR CHROMIUM
import { spawn } from "node:child_process";
import { mkdirSync, readFileSync, rmSync } from "node:fs";
import { join } from "node:path";
import { BrowserTest, exited, monitorAddress, openMonitorPage, press, waitFor } from "./page_helpers.mjs";

const [rpsd, src, outDir, chromiumPath] = process.argv.slice(2);
const TEST_ID = "3133", DOMAIN = "226";  // unique to this test on the machine's loopback
const ddsConfig = join(src, "transport", "config", "loopback.xml");
const scenario = join(src, "examples", "scenarios", "two-site-bridge.yaml");
// A synthetic record long enough (240 s, 245760 steps) that the clicks happen mid-run even when
// the browser is starved (CI compiling beside it: 90 s once ran out between Resume and STOP).
const common = ["--set", "ground_motion={synthetic: {seed: 2026, model: kanai_tajimi, duration_s: 240, target_pga_g: 0.05}}"];
const test = new BrowserTest();
const check = test.check.bind(test);
function start(args, stdio) {
  const child = spawn(rpsd, args, { stdio });
  return test.spawned(child);
}

// Waits until the page has taken `count` more of the link notices the monitor sends every
// browser twice a second (a held run publishes no new steps, so its status stays as it was).
async function linkNotices(page, count) {
  await page.evaluate(() => { window.opSeen = { last: window.rpsdPage.link, n: 0 }; });
  await waitFor(page, (n) => {
    const s = window.opSeen;
    if (window.rpsdPage.link !== s.last) { s.last = window.rpsdPage.link; s.n++; }
    return s.n >= n;
  }, count);
}

async function main() {
  const results = join(outDir, "operator-results");
  rmSync(results, { recursive: true, force: true });
  mkdirSync(results, { recursive: true });
  const monitor = start(["monitor", "--test-id", TEST_ID, "--domain", DOMAIN, "--dds-config", ddsConfig, "--listen", "127.0.0.1:0",
                         "--results", results], ["ignore", "pipe", "inherit"]);
  const [url, token] = await monitorAddress(monitor);
  const nodes = [1, 2].map((site) => start(["servo-node", join(src, "examples", "nodes", `bridge-pier-site-${site}.yaml`), "--set", "node.mode=lock_step",
                                            "--set", `dds.domain_id=${DOMAIN}`, "--set", `node.test_id=${TEST_ID}`], ["ignore", "ignore", "inherit"]));
  // The plain page: no token in its address, so it asks for one.
  const { browser, page, errors } = await openMonitorPage(chromiumPath, url);
  try {
    const out = join(results, "held");
    const run = start(["run", scenario, "--out", out, "--telemetry", ...common, "--set", "transport.kind=dds", "--set", `transport.test_id=${TEST_ID}`,
                       "--set", `transport.domain_id=${DOMAIN}`, "--set", `transport.dds_config=${ddsConfig}`,
                       "--set", "operator_commands={enabled: true}"], ["ignore", "ignore", "pipe"]);
    let runErr = "";
    run.stderr.on("data", (d) => { runErr += d; });
    const runCode = exited(run);

    await waitFor(page, () => window.rpsdPage.status && window.rpsdPage.status.state === "running" && window.rpsdPage.status.steps_done > 500);
    const hold = await press(page, "#btn-hold", token);
    check("hold: the page sends it with the token and the run answers done", hold.status === 200 && hold.body.status === "done", JSON.stringify(hold));
    await waitFor(page, () => window.rpsdPage.status.state === "held" && document.getElementById("state").textContent === "HELD");
    // The step under way when the hold came may still be on its way to the page; then none:
    // the steps shown across two seconds of link notices stay the same (a few tries, on a loaded machine).
    let heldAt = -1, stillAt = null;
    for (let tries = 0; tries < 5 && !(stillAt && stillAt.steps_done === heldAt); tries++) {
      heldAt = await page.evaluate(() => window.rpsdPage.status.steps_done);
      await linkNotices(page, 4);
      stillAt = await page.evaluate(() => window.rpsdPage.status);
    }
    check("while held the page shows HELD and the steps stand still", stillAt.state === "held" && stillAt.steps_done === heldAt,
          `${heldAt} then ${JSON.stringify(stillAt)}`);
    check("while held only Resume is offered of hold and resume",
          await page.isDisabled("#btn-hold") && await page.isEnabled("#btn-resume") && await page.isEnabled("#btn-stop"));
    const left = await page.evaluate(() => document.getElementById("progress-left").textContent);
    check("while held the time left stands still and says so", /held/.test(left), left);
    // The hold is listed at the step it came after (the page was past step 500), not at step 0.
    const holdAt = await page.evaluate(() => {
      const li = [...document.querySelectorAll("#events li")].find((l) => /hold from/.test(l.textContent));
      const m = li && /step (\d+)/.exec(li.textContent);
      return m ? parseInt(m[1], 10) : -1;
    });
    check("the hold's event names the step it came at", holdAt > 500 && holdAt <= heldAt + 1, `${holdAt}, held at ${heldAt}`);
    await page.screenshot({ path: join(outDir, "monitor-held.png"), fullPage: true });

    const resume = await press(page, "#btn-resume", token);
    check("resume: done", resume.status === 200 && resume.body.status === "done", JSON.stringify(resume));
    await waitFor(page, (at) => window.rpsdPage.status.state === "running" && window.rpsdPage.status.steps_done > at + 100, heldAt);
    const stop = await press(page, "#btn-stop", token);
    check("stop: done", stop.status === 200 && stop.body.status === "done", JSON.stringify(stop));
    const code = await runCode;
    check("the stopped run exits 3", code === 3, `${code}: ${runErr}`);
    await waitFor(page, () => window.rpsdPage.status.state === "ended");
    const ended = await page.evaluate(() => document.getElementById("state").textContent);
    check("the page says the run ended by an operator stop", /operator stop/i.test(ended), ended);

    const summary = JSON.parse(readFileSync(join(out, "summary.json"), "utf8"));
    const sender = summary.stopped_by.operator && summary.stopped_by.operator.sender;
    check("summary.json: stopped by the monitor's operator stop",
          summary.result === "stopped" && summary.stopped_by.kind === "operator_stop" && summary.stopped_by.operator.action === "stop" &&
          /^monitor@/.test(sender) && summary.steps < summary.steps_planned, JSON.stringify(summary.stopped_by));
    const held = summary.held;
    check("summary.json: the held interval, after the step the page showed, held and resumed by the monitor",
          held.length === 1 && held[0].after_step === heldAt && held[0].held_s > 0 && held[0].held_by === sender && held[0].resumed_by === sender,
          JSON.stringify(held) + " shown " + heldAt);
    const commands = summary.operator_commands.map((c) => [c.action, c.status, c.sender === sender]);
    check("summary.json: hold, resume and stop, each done and from the monitor",
          JSON.stringify(commands) === JSON.stringify([["hold", "done", true], ["resume", "done", true], ["stop", "done", true]]),
          JSON.stringify(summary.operator_commands));
    const rows = readFileSync(join(out, "time_history.csv"), "utf8").split("\n").filter((l) => l.length);
    const steps = rows.slice(1).map((l) => parseInt(l.split(",")[0], 10));
    check("time_history.csv: every step up to the stop, one row each", rows[0].startsWith("step,") && steps.length === summary.steps &&
          steps.every((s, i) => s === i + 1), `${steps.length} rows for ${summary.steps} steps`);

    // The same scenario never held, in process: the same history, byte for byte, over the same steps.
    const local = join(results, "unheld");
    const ref = start(["run", scenario, "--out", local, ...common], ["ignore", "ignore", "inherit"]);
    check("the unheld run completes", (await exited(ref)) === 0);
    const unheld = readFileSync(join(local, "time_history.csv"), "utf8").split("\n").slice(0, rows.length);
    // Every column but those the wall clock measured (round trips, the cycle's lateness).
    const header = rows[0].split(",");
    const kept = header.map((h, i) => (/^(round_trip_s_|cycle_lateness_s)/.test(h) ? -1 : i)).filter((i) => i >= 0);
    const same = (l) => { const v = l.split(","); return kept.map((i) => v[i]).join(","); };
    const first = unheld[0] !== rows[0] ? 0 : rows.findIndex((l, i) => unheld[i] === undefined || same(l) !== same(unheld[i]));
    check(`the held-and-resumed history equals the unheld run's byte for byte (${kept.length} of ${header.length} columns, ${rows.length - 1} steps)`,
          first === -1, `row ${first}:\n  held   ${rows[first]}\n  unheld ${unheld[first]}`);
    check("no console errors", errors.length === 0, errors.join(" | "));
  } finally {
    await browser.close();
  }
}

test.run(main);
