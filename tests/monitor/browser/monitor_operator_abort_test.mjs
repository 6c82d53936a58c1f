// An operator aborts a running lock-step test from the page of `rpsd monitor` in Debian's
// chromium: the two-site bridge over DDS (loopback) with its two servo nodes as separate
// processes, operator commands enabled (DDS Security off). Abort asks for no confirmation beyond
// the token; the run ends at once: exit 3, summary.json `operator_abort` naming the monitor as
// sender and no return to start, every step taken recorded in time_history.csv, and the page
// says the run ended by an operator abort (screenshot: monitor-aborted.png).
//   node monitor_operator_abort_test.mjs RPSD SOURCE_DIR OUT_DIR CHROMIUM
import { spawn } from "node:child_process";
import { existsSync, mkdirSync, readFileSync, rmSync } from "node:fs";
import { join } from "node:path";
import { BrowserTest, exited, monitorAddress, openMonitorPage, press, waitFor } from "./page_helpers.mjs";

const [rpsd, src, outDir, chromiumPath] = process.argv.slice(2);
const TEST_ID = "3134", DOMAIN = "227";  // unique to this test on the machine's loopback
const ddsConfig = join(src, "transport", "config", "loopback.xml");
const scenario = join(src, "examples", "scenarios", "two-site-bridge.yaml");
const test = new BrowserTest();
const check = test.check.bind(test);
function start(args, stdio) {
  const child = spawn(rpsd, args, { stdio });
  return test.spawned(child);
}

async function main() {
  const results = join(outDir, "abort-results");
  rmSync(results, { recursive: true, force: true });
  mkdirSync(results, { recursive: true });
  const monitor = start(["monitor", "--test-id", TEST_ID, "--domain", DOMAIN, "--dds-config", ddsConfig, "--listen", "127.0.0.1:0"],
                        ["ignore", "pipe", "inherit"]);
  const [url, token] = await monitorAddress(monitor);
  for (const site of [1, 2]) {
    start(["servo-node", join(src, "examples", "nodes", `bridge-pier-site-${site}.yaml`), "--set", "node.mode=lock_step",
           "--set", `dds.domain_id=${DOMAIN}`, "--set", `node.test_id=${TEST_ID}`], ["ignore", "ignore", "inherit"]);
  }
  const { browser, page, errors } = await openMonitorPage(chromiumPath, url);
  try {
    const out = join(results, "aborted");
    // A 240 s synthetic record (245760 steps): the click happens mid-run at any load. The scenario
    // asks for a return to start, which an abort skips.
    const run = start(["run", scenario, "--out", out, "--telemetry",
                       "--set", "ground_motion={synthetic: {seed: 2026, model: kanai_tajimi, duration_s: 240, target_pga_g: 0.05}}",
                       "--set", "transport.kind=dds", "--set", `transport.test_id=${TEST_ID}`, "--set", `transport.domain_id=${DOMAIN}`,
                       "--set", `transport.dds_config=${ddsConfig}`, "--set", "operator_commands={enabled: true, return_to_start: true, return_velocity_m_per_s: 0.01}"],
                      ["ignore", "ignore", "pipe"]);
    let runErr = "";
    run.stderr.on("data", (d) => { runErr += d; });
    const runCode = exited(run);

    await waitFor(page, () => window.rpsdPage.status && window.rpsdPage.status.state === "running" && window.rpsdPage.status.steps_done > 500);
    const abort = await press(page, "#btn-abort", token);
    check("abort: the page sends it with the token and the run answers done", abort.status === 200 && abort.body.status === "done",
          JSON.stringify(abort));
    const code = await runCode;
    check("the aborted run exits 3", code === 3, `${code}: ${runErr}`);
    await waitFor(page, () => window.rpsdPage.status.state === "ended");
    const ended = await page.evaluate(() => document.getElementById("state").textContent);
    check("the page says the run ended by an operator abort", /operator abort/i.test(ended), ended);
    await page.screenshot({ path: join(outDir, "monitor-aborted.png"), fullPage: true });

    const summary = JSON.parse(readFileSync(join(out, "summary.json"), "utf8"));
    const by = summary.stopped_by;
    check("summary.json: stopped by the monitor's operator abort, mid-run",
          summary.result === "stopped" && by.kind === "operator_abort" && by.operator.action === "abort" && /^monitor@/.test(by.operator.sender) &&
          summary.steps > 500 && summary.steps < summary.steps_planned, JSON.stringify(by));
    check("summary.json: no return to start after an abort, though the scenario asks for one on a stop",
          summary.return_to_start === null && !existsSync(join(out, "return_to_start.csv")), JSON.stringify(summary.return_to_start));
    const rows = readFileSync(join(out, "time_history.csv"), "utf8").split("\n").filter((l) => l.length);
    const steps = rows.slice(1).map((l) => parseInt(l.split(",")[0], 10));
    check("time_history.csv: every step up to the abort, one row each", steps.length === summary.steps && steps.every((s, i) => s === i + 1),
          `${steps.length} rows for ${summary.steps} steps`);
    check("no console errors", errors.length === 0, errors.join(" | "));
  } finally {
    await browser.close();
  }
}

test.run(main);
