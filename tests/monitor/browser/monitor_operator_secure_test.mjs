// Under DDS Security a monitor holding only the lab's monitor identity (a read-only grant)
// watches the test but cannot stop it: STOP on its page is refused, the page says so, and the
// run goes on to complete, having heard no operator command. The two-site bridge lock-step over
// loopback with its nodes and coordinator under the lab's identities (scripts/make-lab-ca.sh).
// Exit 77 (skipped) without openssl or Cyclone's security plugins.
//   node monitor_operator_secure_test.mjs RPSD SOURCE_DIR OUT_DIR CHROMIUM
import { spawn, spawnSync } from "node:child_process";
import { existsSync, mkdirSync, readFileSync, rmSync } from "node:fs";
import { join } from "node:path";
import { BrowserTest, exited, monitorAddress, openMonitorPage, waitFor } from "./page_helpers.mjs";

const [rpsd, src, outDir, chromiumPath] = process.argv.slice(2);
const TEST_ID = "3134", DOMAIN = "225";  // unique to this test on the machine's loopback
const secure = join(src, "transport", "config", "security", "loopback-secure.xml");
const scenario = join(src, "examples", "scenarios", "two-site-bridge.yaml");
const test = new BrowserTest();
const check = test.check.bind(test);
function start(args, identity, lab, stdio) {
  const env = { ...process.env, RPSD_DDS_SECURITY_DIR: lab, RPSD_DDS_IDENTITY: identity };
  const child = spawn(rpsd, args, { stdio, env });
  return test.spawned(child);
}

async function main() {
  const plugins = spawnSync("sh", ["-c", "ls /usr/lib/*/libddsc0debian/libdds_security_crypto.so || ldconfig -p | grep -q libdds_security_crypto.so"]);
  if (spawnSync("sh", ["-c", "command -v openssl"]).status !== 0 || plugins.status !== 0) {
    console.log("SKIP: openssl or Cyclone DDS's security plugins not installed");
    process.exit(77);
  }
  const results = join(outDir, "operator-secure-results");
  rmSync(results, { recursive: true, force: true });
  mkdirSync(results, { recursive: true });
  const lab = join(results, "lab");
  const ca = spawnSync("bash", [join(src, "scripts", "make-lab-ca.sh"), lab], { encoding: "utf8" });
  if (ca.status !== 0 || !existsSync(join(lab, "identities", "monitor"))) throw new Error("make-lab-ca.sh: " + ca.stderr);

  const monitor = start(["monitor", "--test-id", TEST_ID, "--domain", DOMAIN, "--dds-config", secure, "--listen", "127.0.0.1:0"],
                        "monitor", lab, ["ignore", "pipe", "inherit"]);
  const [url, token] = await monitorAddress(monitor);
  for (const site of [1, 2]) {
    start(["servo-node", join(src, "examples", "nodes", `bridge-pier-site-${site}.yaml`), "--set", "node.mode=lock_step",
           "--set", `dds.domain_id=${DOMAIN}`, "--set", `node.test_id=${TEST_ID}`, "--set", `dds.config=${secure}`],
          `node-site-${site}`, lab, ["ignore", "ignore", "inherit"]);
  }
  // The operator's own link: the token kept for the tab.
  const { browser, page, errors } = await openMonitorPage(chromiumPath, url + "#token=" + token, { ignore: /status of 503/ });
  try {
    const out = join(results, "run");
    const run = start(["run", scenario, "--out", out, "--telemetry", "--set", "ground_motion.trim={end_s: 30}", "--set", "transport.kind=dds",
                       "--set", `transport.test_id=${TEST_ID}`, "--set", `transport.domain_id=${DOMAIN}`, "--set", `transport.dds_config=${secure}`],
                      "coordinator", lab, ["ignore", "ignore", "pipe"]);
    let runErr = "";
    run.stderr.on("data", (d) => { runErr += d; });
    const runCode = exited(run);

    await waitFor(page, () => window.rpsdPage.status && window.rpsdPage.status.state === "running" && window.rpsdPage.status.steps_done > 200);
    await page.evaluate(() => { window.rpsdLastCommand = null; });
    await page.click("#btn-stop");
    await waitFor(page, () => window.rpsdLastCommand !== null);
    const stop = await page.evaluate(() => window.rpsdLastCommand);
    const shown = await page.evaluate(() => ({ text: document.getElementById("notice").textContent,
                                               bad: document.getElementById("notice").classList.contains("bad") }));
    check("STOP from the monitor's identity is refused", stop.status === 503 && /DDS Security/.test(stop.body.error), JSON.stringify(stop));
    check("the page says so, as an error", shown.bad && /^stop: refused: .*DDS Security/.test(shown.text), JSON.stringify(shown));
    await page.screenshot({ path: join(outDir, "monitor-secure-refused.png"), fullPage: true });
    const code = await runCode;
    check("the run goes on to complete (exit 0)", code === 0, `${code}: ${runErr}`);
    const summary = JSON.parse(readFileSync(join(out, "summary.json"), "utf8"));
    check("summary.json: completed, no operator command heard", summary.result === "completed" && summary.steps === summary.steps_planned &&
          summary.operator_commands.length === 0, JSON.stringify([summary.result, summary.steps, summary.operator_commands]));
    await waitFor(page, () => window.rpsdPage.status.state === "ended");
    check("the page shows the run ended, completed", await page.evaluate(() => window.rpsdPage.status.stopped_by === "completed"));
    check("no console errors", errors.length === 0, errors.join(" | "));
  } finally {
    await browser.close();
  }
}

test.run(main);
