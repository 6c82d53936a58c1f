#!/usr/bin/env python3
"""The RTHS benchmark's partitioning cases as a user runs them: a `monte_carlo:` scenario writes
each run, runs.csv and the statistics of every criterion, which must be the sample statistics
of runs.csv (Python's statistics module, not rpsd's); the same seed gives the same runs; and
scripts/rths-benchmark-study.py writes the table of J1-J9 per case with the constraints.

  benchmark_study_test.py CASE RPSD SOURCE_DIR SCRATCH_DIR

Shortened (a few runs, a few seconds of the record) to keep the suite fast."""
import csv
import json
import math
import os
import shutil
import statistics
import subprocess
import sys

import yaml

CASE, RPSD, SOURCE, SCRATCH = sys.argv[1:5]
SCENARIO = os.path.join(SOURCE, "examples/scenarios/rths-benchmark-sample-controller-case-{}.yaml")
SHORT = ["--set", "ground_motion.trim.end_s=2", "--set", "ground_motion.pad_after_s=0"]
problems = []


def check(condition, message):
    if not condition:
        problems.append(message)


def run(folder, *extra):
    shutil.rmtree(folder, ignore_errors=True)
    out = subprocess.run([RPSD, "run", SCENARIO.format(1), "--out", folder, *SHORT, *extra],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=600)
    check(out.returncode == 0, f"rpsd run exited {out.returncode}: {out.stdout[-2000:]}")
    with open(os.path.join(folder, "runs.csv")) as f:
        runs = list(csv.DictReader(f))
    with open(os.path.join(folder, "statistics.csv")) as f:
        stats = {row["quantity"]: row for row in csv.DictReader(f)}
    with open(os.path.join(folder, "summary.json")) as f:
        summary = json.load(f)
    return runs, stats, summary


def monte_carlo_statistics_are_those_of_its_runs():
    folder = os.path.join(SCRATCH, "benchmark-mc")
    runs, stats, summary = run(folder, "--set", "monte_carlo.runs=4")
    check(len(runs) == 4, f"4 runs expected, runs.csv has {len(runs)}")
    check(summary["study"] == "rpsd_test_monte_carlo" and summary["runs_completed"] == 4, "summary: 4 runs completed")
    for name in ["J1_tracking_delay_ms", "J2_rms_tracking_error_percent", "J4_rms_error_floor_1_percent",
                 "J9_peak_error_floor_3_percent", "peak_measured_force_n"]:
        values = [float(r[name]) for r in runs]
        row = stats[name]
        for key, expected in [("mean", statistics.mean(values)), ("standard_deviation", statistics.stdev(values)),
                              ("minimum", min(values)), ("maximum", max(values))]:
            got = float(row[key])
            check(math.isclose(got, expected, rel_tol=1e-12, abs_tol=1e-15), f"{name} {key}: {got} != {expected}")
    # Each run's own folder holds that run, its drawn k_e in its effective scenario: in the plant
    # and in the partition alike (monte_carlo also_keys).
    for r in runs:
        with open(os.path.join(folder, r["folder"], "summary.json")) as f:
            one = json.load(f)
        check(math.isclose(one["benchmark_criteria"]["J2"], float(r["J2_rms_tracking_error_percent"]),
                           rel_tol=1e-8), f"{r['folder']}: J2 differs from runs.csv")
        with open(os.path.join(folder, r["folder"], "effective-scenario.yaml")) as f:
            scenario = yaml.safe_load(f)
        servo = scenario["servo"]
        k = float(r["experimental.0.specimen.stiffness_n_per_m"])
        check(float(servo["rths_benchmark_model"]["specimen_stiffness_n_per_m"]) == k,
              f"{r['folder']}: drawn k_e {k} not in its plant")
        check(float(scenario["experimental"][0]["specimen"]["stiffness_n_per_m"]) == k,
              f"{r['folder']}: drawn k_e {k} not in its partition")
        check(int(servo["converters"]["seed"]) == 2021 + int(r["run"]), f"{r['folder']}: its own noise seed")
    draws = [float(r["servo.rths_benchmark_model.a3_per_s"]) for r in runs]
    check(len(set(draws)) == 4, "every run draws its own a3")
    # The same seed repeats every run; the first runs do not depend on how many follow.
    again, _, _ = run(os.path.join(SCRATCH, "benchmark-mc-again"), "--set", "monte_carlo.runs=2")
    for a, b in zip(runs, again):
        check(a["servo.rths_benchmark_model.a3_per_s"] == b["servo.rths_benchmark_model.a3_per_s"] and
              a["J4_rms_error_floor_1_percent"] == b["J4_rms_error_floor_1_percent"], "the same seed changed a run")
    other, _, _ = run(os.path.join(SCRATCH, "benchmark-mc-seed"), "--set", "monte_carlo.runs=2",
                      "--set", "monte_carlo.seed=99")
    check(other[0]["servo.rths_benchmark_model.a3_per_s"] != runs[0]["servo.rths_benchmark_model.a3_per_s"],
          "another seed drew the same a3")


def the_study_writes_the_benchmark_table_with_its_constraints():
    folder = os.path.join(SCRATCH, "benchmark-study")
    shutil.rmtree(folder, ignore_errors=True)
    out = subprocess.run([sys.executable, os.path.join(SOURCE, "scripts/rths-benchmark-study.py"), "--rpsd", RPSD,
                          "--out", folder, "--runs", "2", "--end-s", "2", "--cases", "1,3"],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=600)
    check(out.returncode == 0, f"study exited {out.returncode}: {out.stdout[-2000:]}")
    with open(os.path.join(folder, "benchmark-table.csv")) as f:
        table = list(csv.DictReader(f))
    check([r["case"] for r in table] == ["1", "3"], "the table has cases 1 and 3")
    check(table[1]["floor_mass_kg"] == "1300" and table[1]["modal_damping"] == "0.03", "case 3 is 1300 kg, 3 %")
    with open(os.path.join(folder, "case-3", "statistics.csv")) as f:
        stats = {row["quantity"]: row for row in csv.DictReader(f)}
    check(math.isclose(float(table[1]["J7_mean"]), float(stats["J7_peak_error_floor_1_percent"]["mean"]),
                       rel_tol=1e-9), "the table's J7 is the case's statistics")
    with open(os.path.join(folder, "constraints.csv")) as f:
        constraints = list(csv.DictReader(f))
    check(len(constraints) == 8, f"4 constraints per case, got {len(constraints)}")
    force = [c for c in constraints if c["constraint"] == "actuator force" and c["case"] == "1"][0]
    with open(os.path.join(folder, "case-1", "runs.csv")) as f:
        worst = max(float(r["peak_measured_force_n"]) for r in csv.DictReader(f))
    check(math.isclose(float(force["worst"]), worst) and float(force["bound"]) == 8900.0, "force constraint")
    markdown = open(os.path.join(folder, "benchmark-table.md")).read()
    check("Shortened study" in markdown, "a shortened study says so")
    check(os.path.getsize(os.path.join(folder, "benchmark-table.png")) > 1000, "the plot")


{"monte_carlo_statistics": monte_carlo_statistics_are_those_of_its_runs,
 "benchmark_study": the_study_writes_the_benchmark_table_with_its_constraints}[CASE]()
for p in problems:
    print("FAIL:", p)
sys.exit(1 if problems else 0)
