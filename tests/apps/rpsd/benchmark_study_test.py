#!/usr/bin/env python3
"""The RTHS benchmark's partitioning cases as a user runs them: a `monte_carlo:` scenario writes
each run, runs.csv and the statistics of every criterion, which must be the sample statistics
of runs.csv (Python's statistics module, not rpsd's); the same seed gives the same runs; and
scripts/rths-benchmark-study.py writes the table of J1-J9 per case with the constraints, for the
sample controller and for any other controller's scenarios beside it.

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
    check({r["controller"] for r in table} == {"sample controller"}, "the sample controller by default")
    check(table[1]["floor_mass_kg"] == "1300" and table[1]["modal_damping"] == "0.03", "case 3 is 1300 kg, 3 %")
    with open(os.path.join(folder, "sample-controller", "case-3", "statistics.csv")) as f:
        stats = {row["quantity"]: row for row in csv.DictReader(f)}
    check(math.isclose(float(table[1]["J7_mean"]), float(stats["J7_peak_error_floor_1_percent"]["mean"]),
                       rel_tol=1e-9), "the table's J7 is the case's statistics")
    with open(os.path.join(folder, "constraints.csv")) as f:
        constraints = list(csv.DictReader(f))
    check(len(constraints) == 8, f"4 constraints per case, got {len(constraints)}")
    force = [c for c in constraints if c["constraint"] == "actuator force" and c["case"] == "1"][0]
    with open(os.path.join(folder, "sample-controller", "case-1", "runs.csv")) as f:
        worst = max(float(r["peak_measured_force_n"]) for r in csv.DictReader(f))
    check(math.isclose(float(force["worst"]), worst) and float(force["bound"]) == 8900.0, "force constraint")
    markdown = open(os.path.join(folder, "benchmark-table.md")).read()
    check("Shortened study" in markdown, "a shortened study says so")
    check(os.path.getsize(os.path.join(folder, "benchmark-table.png")) > 1000, "the plot")


def a_participants_controller_is_tabled_beside_another():
    """Two controllers, two small cases each, written here from the sample controller's files
    (a 4 s synthetic record, its motion from 2 s on, 2 runs): one without the phase-lead feedforward, one with a
    stiffer PI. The table's numbers must be the mean and sample standard deviation of each
    case's runs.csv over its completed runs, and the constraints each case's worst run."""
    folder = os.path.join(SCRATCH, "benchmark-any-controller")
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    files = {}
    for name, change in [("no feedforward", lambda d: d.pop("compensation", None)),
                         ("stiffer PI", lambda d: d["servo"].update(
                             {"controller": {"proportional_gain": 3, "integral_gain_per_s": 120}}))]:
        files[name] = []
        for case in (1, 2):
            with open(SCENARIO.format(case)) as f:
                doc = yaml.safe_load(f)
            doc["ground_motion"] = {"synthetic": {"seed": 7, "model": "kanai_tajimi", "duration_s": 4,
                                                  "target_pga_g": 0.1}}
            doc["monte_carlo"]["runs"] = 2
            change(doc)
            path = os.path.join(folder, f"{name.replace(' ', '-')}-case-{case}.yaml")
            with open(path, "w") as f:
                yaml.safe_dump(doc, f)
            files[name].append(path)
    out_dir = os.path.join(folder, "study")
    command = [sys.executable, os.path.join(SOURCE, "scripts/rths-benchmark-study.py"), "--rpsd", RPSD, "--out",
               out_dir, "--without-sample-controller"]
    for name, paths in files.items():
        command += ["--controller", name, *paths]
    out = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=900)
    if out.returncode != 0:
        sys.exit(f"FAIL: study exited {out.returncode}: {out.stdout[-2000:]}")
    with open(os.path.join(out_dir, "benchmark-table.csv")) as f:
        table = list(csv.DictReader(f))
    check([(r["controller"], r["case"]) for r in table] ==
          [("no feedforward", "1"), ("no feedforward", "2"), ("stiffer PI", "1"), ("stiffer PI", "2")],
          f"one row per controller and case: {[(r['controller'], r['case']) for r in table]}")
    names = [("J1", "J1_tracking_delay_ms"), ("J2", "J2_rms_tracking_error_percent"),
             ("J4", "J4_rms_error_floor_1_percent"), ("J7", "J7_peak_error_floor_1_percent"),
             ("J9", "J9_peak_error_floor_3_percent")]
    for row in table:
        case_dir = os.path.join(out_dir, row["controller"].replace(" ", "-").lower(), "case-" + row["case"])
        with open(os.path.join(case_dir, "runs.csv")) as f:
            runs = [r for r in csv.DictReader(f) if r["completed"] == "1"]
        check(len(runs) == 2 and row["runs_completed"] == "2", f"{case_dir}: 2 completed runs")
        for number_name, name in names:
            values = [float(r[name]) for r in runs]
            for suffix, expected in [("_mean", statistics.mean(values)), ("_std", statistics.stdev(values))]:
                got = float(row[number_name + suffix])
                check(math.isclose(got, expected, rel_tol=1e-12, abs_tol=1e-15),
                      f"{row['controller']} case {row['case']} {number_name}{suffix}: {got} != {expected}")
    # The two controllers' tables differ: the cases really ran their own scenarios.
    check(table[0]["J2_mean"] != table[2]["J2_mean"], "the two controllers gave the same J2")
    with open(os.path.join(out_dir, "constraints.csv")) as f:
        constraints = list(csv.DictReader(f))
    check(len(constraints) == 16, f"4 constraints per controller and case, got {len(constraints)}")
    for c in constraints:
        case_dir = os.path.join(out_dir, c["controller"].replace(" ", "-").lower(), "case-" + c["case"])
        with open(os.path.join(case_dir, "runs.csv")) as f:
            worst = max(float(r[c["quantity"]]) for r in csv.DictReader(f))
        check(math.isclose(float(c["worst"]), worst), f"{c['controller']} case {c['case']} {c['constraint']}")
        check((c["met"] == "True") == (worst <= float(c["bound"])), f"{c['constraint']}: met says otherwise")
    markdown = open(os.path.join(out_dir, "benchmark-table.md")).read()
    check("| no feedforward | 1 |" in markdown and "| stiffer PI | 2 |" in markdown, "the Markdown table's rows")
    check(os.path.getsize(os.path.join(out_dir, "benchmark-table.png")) > 1000, "the plot")
    # A controller named without scenarios is bad input.
    bad = subprocess.run([sys.executable, os.path.join(SOURCE, "scripts/rths-benchmark-study.py"), "--rpsd", RPSD,
                          "--out", os.path.join(folder, "bad"), "--controller", "lonely"],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=60)
    check(bad.returncode == 2 and "--controller lonely" in bad.stdout, f"bad input: {bad.returncode} {bad.stdout}")


{"monte_carlo_statistics": monte_carlo_statistics_are_those_of_its_runs,
 "benchmark_study": the_study_writes_the_benchmark_table_with_its_constraints,
 "any_controller": a_participants_controller_is_tabled_beside_another}[CASE]()
for p in problems:
    print("FAIL:", p)
sys.exit(1 if problems else 0)
