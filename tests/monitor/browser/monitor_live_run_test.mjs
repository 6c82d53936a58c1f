// `rpsd monitor` watching a real `rpsd run --telemetry` in Debian's chromium: the run's
// telemetry goes over DDS (loopback) to the monitor, the monitor's stream to the page, and
// what the page plots equals the run's time_history.csv at every step it was sent (the
// publisher keeps every k-th step); the page shows the run ended, completed, with no console
// error and no stale or lost banner while it ran. Screenshot: monitor-live-run.png.
// Telemetry may lose batches by design (docs/telemetry.md: a keep-last writer never waits; a
// run as fast as possible sends the writer's 80 batches of history in milliseconds, so a
// loaded monitor can match the publisher after its first batches or fall behind): every
// step missing from the page must then be shown lost, on the "batches lost" tile or as updates
// this browser was not sent; a gap the page does not own up to fails.
//   node monitor_live_run_test.mjs RPSD SOURCE_DIR OUT_DIR CHROMIUM
import { spawn } from "node:child_process";
import { mkdirSync, rmSync } from "node:fs";
import { join } from "node:path";
import { readHistory, plotted, compare, openMonitorPage, waitFor } from "./page_helpers.mjs";

const [rpsd, src, outDir, chromiumPath] = process.argv.slice(2);
// The test id is this process's own: two runs of this test at once (two checkouts on one
// machine) never read each other's telemetry; the domain is one no other test uses.
const TEST_ID = String(1000000 + process.pid), DOMAIN = "228";
const ddsConfig = join(src, "transport", "config", "loopback.xml");
let passed = 0, failed = 0;
function check(name, ok, detail) {
  if (ok) { passed++; console.log("ok   " + name); }
  else { failed++; console.log("FAIL " + name + (detail ? ": " + detail : "")); }
}

async function main() {
  const results = join(outDir, "live-run-results");
  rmSync(results, { recursive: true, force: true });
  mkdirSync(results, { recursive: true });
  const monitor = spawn(rpsd, ["monitor", "--test-id", TEST_ID, "--domain", DOMAIN, "--dds-config", ddsConfig,
                               "--listen", "127.0.0.1:0", "--results", results], { stdio: ["ignore", "pipe", "inherit"] });
  let printed = "";
  const url = await new Promise((resolve, reject) => {
    monitor.stdout.on("data", (d) => { printed += d; const m = /page: +(http:\/\/127\.0\.0\.1:\d+\/)/.exec(printed); if (m) resolve(m[1]); });
    monitor.on("exit", (code) => reject(new Error("rpsd monitor ended with " + code + ": " + printed)));
  });
  const { browser, page, errors } = await openMonitorPage(chromiumPath, url).catch((e) => { monitor.kill("SIGINT"); throw e; });
  try {
    const banners = [];
    const sampler = setInterval(async () => {
      try { const b = await page.evaluate(() => window.rpsdBanner); if (b) banners.push(b); } catch { /* closing */ }
    }, 100);
    const out = join(results, "synthetic-sdof");
    // Not spawnSync: the page is sampled while the run goes on.
    const run = spawn(rpsd, ["run", join(src, "examples", "scenarios", "synthetic-sdof.yaml"), "--out", out, "--telemetry",
                             "--set", "transport.kind=in_process", "--set", `transport.test_id=${TEST_ID}`, "--set", `transport.domain_id=${DOMAIN}`,
                             "--set", `transport.dds_config=${ddsConfig}`], { stdio: ["ignore", "ignore", "pipe"] });
    let runErr = "";
    run.stderr.on("data", (d) => { runErr += d; });
    const code = await new Promise((resolve) => run.on("exit", resolve));
    check("the run completes (exit 0)", code === 0, `${code}: ${runErr}`);
    await waitFor(page, () => window.rpsdPage.status && window.rpsdPage.status.state === "ended");
    clearInterval(sampler);
    await page.selectOption("#window", "0");
    await page.waitForTimeout(200);
    const history = readHistory(out);
    const shown = await plotted(page);
    const diff = compare(shown, history, { consecutive: false, digits: 10 });
    check("the page plots the run's time_history.csv at every step it was sent", diff === "", diff);
    const last = history.steps[history.steps.length - 1];
    const everyK = Math.round(1024 / 256);  // synthetic-sdof at 1024 Hz, telemetry at 256 samples/s
    // The stretches of every-k-th steps the page lacks, from the start of the run to its end.
    const missing = [];
    [0, ...shown.step, last - (last % everyK) + everyK].forEach((s, i, a) => {
      if (i > 0 && s - a[i - 1] > everyK) missing.push([a[i - 1] + everyK, s - everyK]);
    });
    const missingSamples = missing.reduce((n, [a, b]) => n + (b - a) / everyK + 1, 0);
    // What the page says it lost, once it has the server's final count (a hang guard bounds the wait).
    const server = await (await fetch(new URL("api/status", url))).json();
    await waitFor(page, (n) => document.getElementById("f-lost").textContent === String(n), server.batches_lost);
    const lost = Number(await page.textContent("#f-lost")) + await page.evaluate(() => window.rpsdPage.droppedUpdates);
    check("every k-th step from the start of the run to its end, but for the batches the page shows lost",
          shown.step.every((s, i) => s % everyK === 0 && (i === 0 || s > shown.step[i - 1])) &&
          missing.length <= lost && missingSamples <= 32 * lost,
          `steps ${shown.step[0]}..${shown.step[shown.step.length - 1]} of ${last}, every ${everyK}; ` +
          `missing ${JSON.stringify(missing)} (${missingSamples} samples); the page shows ${lost} batches or updates lost`);
    if (missing.length) console.log(`note: ${missingSamples} samples in ${missing.length} stretch(es) not received; the page shows ${lost} lost`);
    const status = await page.evaluate(() => window.rpsdPage.status);
    check("the page says the run ended, completed", status.state === "ended" && status.stopped_by === "completed", JSON.stringify(status));
    check("no stale or lost banner while the run went on", banners.filter((b) => !b.startsWith("TELEMETRY")).length === 0, banners.join(" | "));
    await page.screenshot({ path: join(outDir, "monitor-live-run.png"), fullPage: true });
    check("no console errors", errors.length === 0, errors.join(" | "));
  } finally {
    await browser.close();
    monitor.kill("SIGINT");
  }
  console.log(`${passed} passed, ${failed} failed`);
  process.exit(failed === 0 ? 0 : 1);
}

main().catch((e) => { console.log("FAIL " + (e.stack || e)); console.log(`${passed} passed, ${failed + 1} failed`); process.exit(1); });
