#!/usr/bin/env python3
"""`rpsd site-server` against scripted genericClients on loopback (generic_client.py): it stops
on SIGINT or SIGTERM whatever the client does, serves only the clients it may, refuses a trial
time that runs backwards, and is not ended by a stray connection.

  site_server_cli_test.py CASE RPSD SOURCE_DIR SCRATCH_DIR

Cases:
  flooding_sigint, flooding_sigterm  a client sending steps back to back: the signal ends the
                        run (exit 6, result interrupted) with at most one more step commanded
  stalled_sigint        a client that sent half a request and then nothing: SIGINT ends the run
  non_reading_sigint    a client that sends requests and never reads a reply (the server
                        blocked writing): SIGINT ends the run
  non_reading_idle      the same without a signal: listen.idle_timeout_s ends it (exit 3)
  backwards_time        trials at t = -k dt are refused, named, never commanded (exit 3)
  connect_and_close     a connection that closes before its setup does not end the session:
                        the client after it is served to its end (exit 0)
  unprotected_listen    listen.address 0.0.0.0 without listen.allowed_clients, or an allowed
                        client that is no host's address, is refused when the file is read (exit 2)
  allow_list            listen.allowed_clients [127.0.0.2]: a client from 127.0.0.1 is closed
                        before any command, one from 127.0.0.2 is served

Counts are in steps and exit codes; times only bound a hang. Every check that fails is printed;
the exit code is 1 if any did."""
import json
import math
import re
import os
import shutil
import signal
import socket
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from generic_client import DIE, DT, GenericClient, request_bytes, setup_bytes, start_server, SET_TRIAL  # noqa: E402

CASE, RPSD, SOURCE, SCRATCH = sys.argv[1:5]
SITE = os.path.join(SOURCE, "examples/opensees/sdof-site-perfect.yaml")
HANG_GUARD_S = 60  # only so that a server that never ends fails the test instead of hanging it
problems = []


def check(condition, message):
    if not condition:
        problems.append(message)
    return condition


def fresh():
    folder = os.path.join(SCRATCH, CASE)
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    return folder


def server(folder, *sets):
    return start_server(RPSD, SITE, os.path.join(folder, "site"), sets=("listen.port=0", *sets),
                        log_path=os.path.join(folder, "site.log"))


def end_of(process, folder):
    """The server's exit code (None if the hang guard killed it) and its log."""
    try:
        rc = process.wait(timeout=HANG_GUARD_S)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()
        rc = None
        problems.append(f"rpsd site-server did not end within {HANG_GUARD_S} s (hang guard); killed")
    with open(os.path.join(folder, "site.log"), errors="replace") as f:
        return rc, f.read()


def summary(folder):
    try:
        with open(os.path.join(folder, "site", "summary.json")) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        problems.append(f"summary.json: {e}")
        return {}


def rows(folder):
    with open(os.path.join(folder, "site", "time_history.csv")) as f:
        return sum(1 for _ in f) - 1


def wait_for_line(folder, text, process):
    end = time.monotonic() + HANG_GUARD_S
    while time.monotonic() < end and process.poll() is None:
        with open(os.path.join(folder, "site.log"), errors="replace") as f:
            if text in f.read():
                return True
        time.sleep(0.02)
    return check(False, f"the server never printed {text!r}")


def expect_end(rc, log, s, code, result, kind=None):
    check(rc == code, f"exit code {rc}, expected {code}: {log[-1500:]}")
    check(s.get("result") == result, f"summary result {s.get('result')!r}, expected {result!r}")
    if kind:
        got = s.get("stopped_by", {}).get("kind")
        check(got == kind, f"stopped_by.kind {got!r}, expected {kind!r}")


def flooding(sig):
    folder = fresh()
    process, port, start_line = server(folder)
    check("clients allowed: loopback only" in start_line, f"the start line does not say who may connect: {start_line}")
    client = GenericClient("127.0.0.1", port)
    client.send(setup_bytes())
    before = 200
    for n in range(1, before + 1):
        force = client.step(1e-4 * math.sin(n / 10), n * DT)  # every step moves: a command each
        if not check(force is not None and math.isfinite(force), f"step {n} before the signal got {force}"):
            break
    os.kill(process.pid, sig)
    # Back to back after the signal: every force that comes back is a step the server commanded.
    answered_after = 0
    for n in range(before + 1, before + 5001):
        force = client.step(1e-4 * math.sin(n / 10), n * DT)
        if force is None or math.isnan(force):
            break
        answered_after += 1
    client.send(request_bytes(DIE))
    client.close()
    rc, log = end_of(process, folder)
    s = summary(folder)
    expect_end(rc, log, s, 6, "interrupted", "interrupted")
    check(answered_after <= 1, f"{answered_after} steps answered after the signal (at most the one under way)")
    exchanges = s.get("exchanges", -1)
    check(before <= exchanges <= before + 1, f"{exchanges} steps commanded, {before} before the signal")
    check(rows(folder) == exchanges, f"time_history.csv has {rows(folder)} rows for {exchanges} steps")


def stalled():
    folder = fresh()
    # With the old per-message wait the half request would hold the server for a minute.
    process, port, _ = server(folder, "listen.message_timeout_s=120", "listen.idle_timeout_s=120")
    client = GenericClient("127.0.0.1", port)
    client.send(setup_bytes())
    for n in range(1, 4):
        client.step(1e-5 * n, n * DT)
    wait_for_line(folder, "OpenSees connected from", process)
    client.send(request_bytes(SET_TRIAL, 4e-5, 0.0, 0.0, 4 * DT)[:1000])  # half a request, then nothing
    time.sleep(0.2)  # not needed for the check: the server is then inside the half request
    os.kill(process.pid, signal.SIGINT)
    rc, log = end_of(process, folder)
    client.close()
    s = summary(folder)
    expect_end(rc, log, s, 6, "interrupted", "interrupted")
    check(s.get("exchanges") == 3, f"{s.get('exchanges')} steps commanded, expected the 3 whole ones")


def non_reading(by_signal):
    folder = fresh()
    sets = ["listen.idle_timeout_s=120"] if by_signal else ["listen.idle_timeout_s=2"]
    process, port, _ = server(folder, *sets)
    client = GenericClient("127.0.0.1", port)
    client.send(setup_bytes())
    wait_for_line(folder, "OpenSees connected from", process)
    sent = client.fill_without_reading(quiet_s=1.0)
    # The server took nothing for a second: it is writing replies nobody reads.
    check(process.poll() is None or not by_signal, "the server ended before the client had filled the connection")
    if by_signal:
        os.kill(process.pid, signal.SIGINT)
    rc, log = end_of(process, folder)
    client.close()
    s = summary(folder)
    if by_signal:
        expect_end(rc, log, s, 6, "interrupted", "interrupted")
    else:
        expect_end(rc, log, s, 3, "stopped", "client_idle")
        reason = s.get("stopped_by", {}).get("reason", "")
        check("took no reply" in reason, f"the reason does not say the client read no reply: {reason!r}")
    exchanges = s.get("exchanges", -1)
    check(0 < exchanges <= sent, f"{exchanges} steps commanded of the {sent} sent")


def backwards_time():
    folder = fresh()
    process, port, _ = server(folder)
    client = GenericClient("127.0.0.1", port)
    client.send(setup_bytes())
    forces = [client.step(1e-4 * k, -k * DT) for k in range(1, 6)]
    client.send(request_bytes(DIE))
    client.close()
    rc, log = end_of(process, folder)
    s = summary(folder)
    expect_end(rc, log, s, 3, "stopped", "site_stopped")
    check(all(f is not None and math.isnan(f) for f in forces), f"the client got forces {forces}, not NaN")
    check(s.get("exchanges") == 0, f"{s.get('exchanges')} trials commanded, expected none")
    reason = s.get("stopped_by", {}).get("reason", "")
    check("went back" in reason and "t = 0 s to -0.0009765625 s" in reason, f"the reason does not name it: {reason!r}")
    check("went back" in log, "the log does not name the refused trial time")
    check(s.get("channels", [{}])[0].get("peak_measured_m") == 0.0, "the actuator moved")


def connect_and_close():
    folder = fresh()
    process, port, _ = server(folder)
    socket.create_connection(("127.0.0.1", port), timeout=10).close()
    wait_for_line(folder, "ended before a genericClient's setup", process)
    client = GenericClient("127.0.0.1", port)
    client.send(setup_bytes())
    forces = [client.step(1e-5 * n, n * DT) for n in range(1, 11)]
    client.send(request_bytes(DIE))
    client.close()
    rc, log = end_of(process, folder)
    s = summary(folder)
    expect_end(rc, log, s, 0, "completed")
    check(all(f is not None and math.isfinite(f) for f in forces), f"the real client got {forces}")
    check(s.get("exchanges") == 10, f"{s.get('exchanges')} steps, expected 10")
    check(s.get("listen", {}).get("connections_without_setup") == 1, f"listen: {s.get('listen')}")


def unprotected_listen():
    folder = fresh()
    cases = [(["listen.address=0.0.0.0", "listen.accept_timeout_s=1"],
              r"listen\.address: 0\.0\.0\.0 is not a loopback address"),
             (["listen.allowed_clients=[0.0.0.0]", "listen.accept_timeout_s=1"],
              r"listen\.allowed_clients: 0\.0\.0\.0 is no host's address"),
             (["listen.address=localhost", "listen.accept_timeout_s=1"],
              r"listen\.address: expected an IPv4 address such as 127\.0\.0\.1")]
    for i, (sets, pattern) in enumerate(cases):
        out = os.path.join(folder, f"run{i}")
        run = subprocess.run([RPSD, "site-server", SITE, "--out", out, "--set", "listen.port=0",
                              *[a for s in sets for a in ("--set", s)]],
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=HANG_GUARD_S)
        check(run.returncode == 2, f"{sets}: exit code {run.returncode}, expected 2: {run.stdout[-800:]}")
        check(re.search(pattern, run.stdout), f"{sets}: the output does not match {pattern!r}: {run.stdout[-800:]}")
        check(not os.path.exists(out), f"{sets}: {out} was created for a file that was refused")


def allow_list():
    folder = fresh()
    process, port, start_line = server(folder, "listen.allowed_clients=[127.0.0.2]")
    check("clients allowed: 127.0.0.2" in start_line, f"the start line does not say who may connect: {start_line}")
    intruder = GenericClient("127.0.0.1", port, source="127.0.0.1")
    intruder.send(setup_bytes())
    refused = intruder.step(0.05, DT)
    check(refused is None, f"the intruder got an answer: {refused}")
    intruder.close()
    client = GenericClient("127.0.0.1", port, source="127.0.0.2")
    client.send(setup_bytes())
    forces = [client.step(1e-5 * n, n * DT) for n in range(1, 11)]
    client.send(request_bytes(DIE))
    client.close()
    rc, log = end_of(process, folder)
    s = summary(folder)
    expect_end(rc, log, s, 0, "completed")
    check(all(f is not None and math.isfinite(f) for f in forces), f"the allowed client got {forces}")
    check(s.get("exchanges") == 10, f"{s.get('exchanges')} steps, expected the allowed client's 10")
    listen = s.get("listen", {})
    check(listen.get("allowed_clients") == "127.0.0.2", f"listen: {listen}")
    check(listen.get("refused_connections") == 1 and str(listen.get("refused_peers", [""])[0]).startswith("127.0.0.1:"),
          f"listen: {listen}")
    check(str(s.get("client", {}).get("peer", "")).startswith("127.0.0.2:"), f"client: {s.get('client')}")
    check("refused a connection from 127.0.0.1:" in log, "the log does not name the refused peer")


CASES = {
    "flooding_sigint": lambda: flooding(signal.SIGINT),
    "flooding_sigterm": lambda: flooding(signal.SIGTERM),
    "stalled_sigint": stalled,
    "non_reading_sigint": lambda: non_reading(True),
    "non_reading_idle": lambda: non_reading(False),
    "backwards_time": backwards_time,
    "connect_and_close": connect_and_close,
    "unprotected_listen": unprotected_listen,
    "allow_list": allow_list,
}

if __name__ == "__main__":
    try:
        CASES[CASE]()
    except Exception as e:  # a failed step of the script is a failed test, said plainly
        problems.append(f"{type(e).__name__}: {e}")
    for p in problems:
        print("FAILED: " + p)
    if not problems:
        print(f"PASS: {CASE}")
    sys.exit(1 if problems else 0)
