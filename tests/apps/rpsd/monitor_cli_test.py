#!/usr/bin/env python3
"""`rpsd monitor` as a user meets it, on loopback with no test running: it prints the page's
address and a token, serves the page and the status (no run, no live publisher), refuses a
command without the token, sends one with it (no coordinator answers: 504), lists and guards
the recorded folders, and ends in order on SIGINT (exit 0). Bad options are exit 2.

  monitor_cli_test.py RPSD SOURCE_DIR OUT_DIR"""
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import urllib.error
import urllib.request

HANG_GUARD_S = 60


def request(url, body=None):
    data = json.dumps(body).encode() if body is not None else None
    req = urllib.request.Request(url, data=data, headers={"Content-Type": "application/json"} if data else {})
    try:
        with urllib.request.urlopen(req, timeout=HANG_GUARD_S) as res:
            return res.status, res.read().decode()
    except urllib.error.HTTPError as e:
        return e.code, e.read().decode()


def main():
    rpsd, src, out = sys.argv[1:4]
    problems = []

    def check(ok, what):
        print(("ok   " if ok else "FAIL ") + what)
        if not ok:
            problems.append(what)

    results = os.path.join(out, "monitor-results")
    shutil.rmtree(results, ignore_errors=True)
    os.makedirs(os.path.join(results, "test-1"))
    with open(os.path.join(results, "test-1", "summary.json"), "w") as f:
        f.write('{"study":"rpsd_test","result":"completed"}')
    with open(os.path.join(results, "test-1", "time_history.csv"), "w") as f:
        f.write("step,time_s\n1,0.001\n")

    bad = subprocess.run([rpsd, "monitor", "--test-id", "31", "--listen", "127.0.0.1"], capture_output=True, text=True,
                         timeout=HANG_GUARD_S)
    check(bad.returncode == 2 and "expected HOST:PORT" in bad.stderr, f"a --listen without a port is exit 2 ({bad.returncode})")
    bad = subprocess.run([rpsd, "monitor", "--test-id", "31", "--results", os.path.join(results, "missing")],
                         capture_output=True, text=True, timeout=HANG_GUARD_S)
    check(bad.returncode == 2 and "not a folder" in bad.stderr, f"a --results that is no folder is exit 2 ({bad.returncode})")

    cmd = [rpsd, "monitor", "--test-id", "3131", "--domain", "223", "--dds-config",
           os.path.join(src, "transport", "config", "loopback.xml"), "--listen", "127.0.0.1:0", "--results", results,
           "--reply-timeout", "0.5"]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    printed = ""
    while "the primary stop" not in printed:
        line = proc.stdout.readline()
        if not line:
            break
        printed += line
    page = re.search(r"page: +(http://127\.0\.0\.1:\d+/)", printed)
    token = re.search(r"token: +([0-9a-f]{32})\b", printed)
    check(page is not None and token is not None, "it prints the page's address and a 32-digit token")
    check(re.search(r"operator: +http://127\.0\.0\.1:\d+/#token=[0-9a-f]{32}", printed) is not None,
          "and the operator's address with the token after '#'")
    if page and token:
        url, token = page.group(1), token.group(1)
        code, body = request(url)
        check(code == 200 and "<title>rpsd monitor</title>" in body, "the page is served")
        code, body = request(url + "api/status")
        status = json.loads(body)
        check(code == 200 and status["telemetry"] and status["alive"] is False and status["run"] is None,
              f"the status says no run is published yet: {body}")
        code, _ = request(url + "api/operator", {"action": "stop"})
        check(code == 403, f"a stop without the token is refused ({code})")
        code, _ = request(url + "api/operator", {"action": "stop", "token": "0" * 32})
        check(code == 403, f"a stop with a wrong token is refused ({code})")
        code, body = request(url + "api/operator", {"action": "stop", "token": token})
        check(code == 504 and "no reply from the coordinator" in body, f"a stop with the token goes out, unanswered ({code})")
        code, body = request(url + "api/results")
        check(code == 200 and json.loads(body)["folders"][0]["path"] == "test-1", "the viewer lists the folder")
        code, _ = request(url + "api/results/file?folder=..&name=CMakeCache.txt")
        check(code == 404, f"a path out of --results is refused ({code})")
    proc.send_signal(signal.SIGINT)
    try:
        rest, err = proc.communicate(timeout=HANG_GUARD_S)
    except subprocess.TimeoutExpired:
        proc.kill()
        rest, err = proc.communicate()
    printed += rest
    check(proc.returncode == 0 and "rpsd monitor: stopped" in printed, f"SIGINT ends it in order (exit {proc.returncode})")
    check(re.search(r"operator stop from 127\.0\.0\.1:\d+: refused, wrong or missing token", printed) is not None,
          "the refused command is logged with where it came from")
    check(re.search(r"operator stop from 127\.0\.0\.1:\d+: no reply from the coordinator", printed) is not None,
          "the unanswered command is logged")
    if problems:
        print(err)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
