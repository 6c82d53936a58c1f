#!/usr/bin/env python3
"""`rpsd host-check --json` as a lab runs it, briefly: every field is there with a sane value
(counts whole and not negative, percentiles in order, the cycle count the rate and duration
give), never a time threshold.

  host_check_test.py RPSD"""
import json
import subprocess
import sys

RATES = [1024, 4096]
SECONDS = 0.5


def main():
    rpsd = sys.argv[1]
    run = subprocess.run([rpsd, "host-check", "--rates", ",".join(map(str, RATES)), "--seconds", str(SECONDS), "--json"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=300)
    problems = []

    def check(ok, what):
        if not ok:
            problems.append(what)

    if run.returncode != 0:
        print(f"exit code {run.returncode}, expected 0\n{run.stderr}")
        return 1
    report = json.loads(run.stdout)
    check(report["rates_hz"] == RATES, f"rates_hz {report['rates_hz']}")
    check(report["seconds_per_rate"] == SECONDS, f"seconds_per_rate {report['seconds_per_rate']}")
    granted = report["granted"]
    for key in ("sched_fifo", "mlockall"):
        check(isinstance(granted[key], bool), f"granted.{key} is not a boolean")
    check(granted["fifo_priority"] == 80, "granted.fifo_priority")
    check(isinstance(granted["refused"], list), "granted.refused is not a list")
    # A refusal is said, and only a refusal.
    check((not granted["refused"]) == (granted["sched_fifo"] and granted["mlockall"]), "granted.refused disagrees")
    kernel = report["kernel"]
    check(kernel["preemption"] in ("unknown", "none", "voluntary", "full", "lazy", "rt"),
          f"kernel.preemption {kernel['preemption']}")
    check(isinstance(kernel["source"], str) and kernel["source"], "kernel.source")
    check(kernel["preempts_for_real_time"] == (kernel["preemption"] in ("full", "lazy", "rt")),
          "kernel.preempts_for_real_time disagrees with kernel.preemption")
    idle = report["cpu_idle"]
    check(isinstance(idle["driver"], str), "cpu_idle.driver")
    check(isinstance(idle["cpus"], int) and idle["cpus"] >= 0, "cpu_idle.cpus")
    for s in idle["states"]:
        check(isinstance(s["name"], str) and s["name"], "a state without a name")
        check(isinstance(s["exit_latency_us"], int) and s["exit_latency_us"] >= -1, f"{s['name']}: exit_latency_us")
        check(isinstance(s["disabled"], bool) and isinstance(s["can_be_disabled"], bool), f"{s['name']}: flags")
    check(isinstance(idle["can_keep_cpus_awake"], bool), "cpu_idle.can_keep_cpus_awake")
    check(idle["can_keep_cpus_awake"] == (idle["keep_awake_refused"] == ""), "keep_awake_refused disagrees")
    check(isinstance(idle["wake_latency_limit_us"], int), "cpu_idle.wake_latency_limit_us")

    # Every rate free to idle, then every rate kept awake when the CPUs could be kept awake.
    settings = [False, True] if idle["can_keep_cpus_awake"] else [False]
    expected = [(rate, awake) for awake in settings for rate in RATES]
    loops = report["loops"]
    check([(l["rate_hz"], l["cpus_kept_awake"]) for l in loops] == expected,
          f"loops {[(l['rate_hz'], l['cpus_kept_awake']) for l in loops]}, expected {expected}")
    for l in loops:
        name = f"{l['rate_hz']} Hz{' awake' if l['cpus_kept_awake'] else ''}"
        cycles = l["cycles"]
        check(cycles == int(SECONDS * l["rate_hz"]), f"{name}: {cycles} cycles")
        check(isinstance(l["overruns"], int) and 0 <= l["overruns"] <= cycles, f"{name}: overruns {l['overruns']}")
        check(isinstance(l["skipped_deadlines"], int) and l["skipped_deadlines"] >= 0, f"{name}: skipped_deadlines")
        check(abs(l["overruns_percent"] - 100.0 * l["overruns"] / cycles) < 1e-9, f"{name}: overruns_percent")
        w = l["wakeup"]
        check(w["count"] == cycles, f"{name}: wakeup.count {w['count']}")
        check(0 <= w["p50_s"] <= w["p99_s"] <= w["p99_9_s"] <= w["max_s"], f"{name}: wake-up percentiles out of order {w}")
        check(0 <= w["mean_s"] <= w["max_s"], f"{name}: wakeup.mean_s")
        check(0.0 <= l["steal_percent"] <= 100.0, f"{name}: steal_percent {l['steal_percent']}")
    for p in problems:
        print("host-check:", p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
