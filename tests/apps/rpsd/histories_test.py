#!/usr/bin/env python3
"""What a run keeps of its histories (output.histories, docs/results-format.md), as a user runs
it: criteria_only writes no history and the same criteria, bit for bit, as a run that keeps every
step; decimated keeps exactly the rows of the steps n with n % k == 0, as the full run wrote them;
and the RTHS benchmark's batch with its defaults writes at most a tenth of the bytes of the same
batch keeping every step, with the same runs.csv and statistics.

  histories_test.py CASE RPSD SOURCE_DIR SCRATCH_DIR"""
import csv
import json
import os
import shutil
import subprocess
import sys

CASE, RPSD, SOURCE, SCRATCH = sys.argv[1:5]
SDOF = os.path.join(SOURCE, "examples/scenarios/synthetic-sdof.yaml")  # 20 s at 1024 Hz
BENCHMARK = os.path.join(SOURCE, "examples/scenarios/rths-benchmark-sample-controller-case-1.yaml")
# What summary.json says of the criteria: computed from every step whatever is kept.
CRITERIA = ["channels", "dofs", "benchmark_criteria", "energy_error_j", "steps", "steps_planned"]
problems = []


def check(condition, message):
    if not condition:
        problems.append(message)


def run(folder, scenario, *extra):
    shutil.rmtree(folder, ignore_errors=True)
    out = subprocess.run([RPSD, "run", scenario, "--out", folder, *extra],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=900)
    if out.returncode != 0:
        sys.exit(f"rpsd run {scenario} {' '.join(extra)} exited {out.returncode}: {out.stdout[-2000:]}")
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


def lines(path):
    with open(path) as f:
        return f.read().splitlines()


def full_run():
    folder = os.path.join(SCRATCH, f"histories-all-for-{CASE}")  # one per case: ctest may run them at once
    return folder, run(folder, SDOF)


def criteria_only_keeps_no_history_and_the_same_criteria():
    full, full_summary = full_run()
    folder = os.path.join(SCRATCH, "histories-criteria-only")
    summary = run(folder, SDOF, "--histories", "criteria_only")
    for name in ["time_history.csv", "reference_history.csv", "plot.json", "test.png", "plot_time_history.csv"]:
        check(not os.path.exists(os.path.join(folder, name)), f"criteria_only wrote {name}")
    check(os.path.exists(os.path.join(full, "time_history.csv")), "the full run wrote no time_history.csv")
    # JSON numbers are written to round-trip: equal floats are equal bits.
    for key in CRITERIA:
        check(summary[key] == full_summary[key], f"criteria_only: {key} differs from the full run's")
    check(summary["completed"] is True, "criteria_only: not completed")
    check(summary.get("histories") == {"kept": "criteria_only"}, f"histories: {summary.get('histories')}")
    check("histories" not in full_summary, "a run keeping every step says histories in summary.json")


def decimated_keeps_every_kth_step_exactly():
    full, full_summary = full_run()
    folder = os.path.join(SCRATCH, "histories-decimated")
    summary = run(folder, SDOF, "--histories", "decimated", "--history-rate-hz", "128")  # 1024 / 8
    for key in CRITERIA:
        check(summary[key] == full_summary[key], f"decimated: {key} differs from the full run's")
    check(summary.get("histories") == {"kept": "decimated", "rate_hz": 128.0, "every_steps": 8},
          f"histories: {summary.get('histories')}")
    for table in ["time_history.csv", "reference_history.csv"]:
        every = lines(os.path.join(full, table))
        kept = lines(os.path.join(folder, table))
        check(kept[0] == every[0], f"{table}: another header")
        steps = [int(row.split(",", 1)[0]) for row in kept[1:]]
        last = int(every[-1].split(",", 1)[0])
        check(steps == list(range(8, last + 1, 8)), f"{table}: steps {steps[:4]}... not 8, 16, ... {last}")
        # Each kept row is the full run's row of that step, character for character: nothing filtered.
        wanted = [row for row in every[1:] if int(row.split(",", 1)[0]) % 8 == 0]
        check(kept[1:] == wanted, f"{table}: a kept row differs from the full run's")
    # Its plots are drawn from the kept rows, not from a second thinning of them.
    check(os.path.exists(os.path.join(folder, "test.png")), "decimated: no test.png")
    check(not os.path.exists(os.path.join(folder, "plot_time_history.csv")), "decimated: plot_time_history.csv")


def benchmark_batch_fits_a_tenth():
    # Two runs of 20 s of the record: every step (--histories all) against the file's defaults.
    short = ["--set", "monte_carlo.runs=2", "--set", "ground_motion.trim.end_s=20",
             "--set", "ground_motion.pad_after_s=0"]
    every = os.path.join(SCRATCH, "histories-benchmark-all")
    default = os.path.join(SCRATCH, "histories-benchmark-default")
    run(every, BENCHMARK, *short, "--histories", "all")
    summary = run(default, BENCHMARK, *short)

    def size(folder):
        return sum(os.path.getsize(os.path.join(d, f)) for d, _, files in os.walk(folder) for f in files)

    ratio = size(default) / size(every)
    print(f"bytes: default {size(default)}, every step {size(every)}, ratio {ratio:.4f}")
    check(ratio <= 0.1, f"the default batch writes {ratio:.3f} of the bytes of every step's, above 0.1")
    for name in ["runs.csv", "statistics.csv", "statistics.md"]:
        check(lines(os.path.join(default, name)) == lines(os.path.join(every, name)), f"{name} differs")
    check(summary["runs_completed"] == 2, "the default batch did not complete its runs")
    with open(os.path.join(default, "run_001", "summary.json")) as f:
        one = json.load(f)
    check(one.get("histories", {}).get("every_steps") == 16, f"run_001 kept {one.get('histories')}")
    with open(os.path.join(default, "run_001", "time_history.csv")) as f:
        rows = list(csv.reader(f))[1:]
    check(rows and all(int(r[0]) % 16 == 0 for r in rows), "run_001: a row of a step not kept at 256 Hz")


CASES = {
    "criteria_only": criteria_only_keeps_no_history_and_the_same_criteria,
    "decimated": decimated_keeps_every_kth_step_exactly,
    "benchmark_bytes": benchmark_batch_fits_a_tenth,
}

if __name__ == "__main__":
    CASES[CASE]()
    for p in problems:
        print("FAIL:", p)
    sys.exit(1 if problems else 0)
