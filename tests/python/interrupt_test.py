"""Ctrl-C in Python stops a run as SIGINT does on the command line: in order, its summary says
interrupted, and KeyboardInterrupt is raised once it has ended."""
import json
import os
import signal
import subprocess
import sys
import time

from conftest import SCENARIO

CHILD = r"""
import signal, sys
import rpsd
signal.signal(signal.SIGINT, signal.default_int_handler)  # as an interactive Python has it
try:
    rpsd.run(sys.argv[1], out=sys.argv[2],
             overrides={"ground_motion.trim.end_s": 2, "ground_motion.pad_after_s": 3600})
except KeyboardInterrupt:
    print("KeyboardInterrupt")
    sys.exit(42)
print("completed")
"""


def test_sigint_interrupts_a_run_in_order_and_raises_keyboard_interrupt(scratch):
    out = scratch / "out"
    child = subprocess.Popen([sys.executable, "-c", CHILD, str(SCENARIO), str(out)],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=os.environ)
    try:
        # Wait until the run has begun (its summary.json says "running" from the start); hang guard only.
        deadline = time.monotonic() + 120
        summary = out / "summary.json"
        while not (summary.exists() and json.loads(summary.read_text()).get("result") == "running"):
            assert child.poll() is None, child.stderr.read()
            assert time.monotonic() < deadline, "the run did not start"
            time.sleep(0.05)
        child.send_signal(signal.SIGINT)
        stdout, stderr = child.communicate(timeout=300)
    finally:
        if child.poll() is None:
            child.kill()
    assert child.returncode == 42, stdout + stderr
    assert stdout.strip() == "KeyboardInterrupt"
    written = json.loads(summary.read_text())
    assert written["result"] == "interrupted"
    assert 0 < written["steps"] < written["steps_planned"]
