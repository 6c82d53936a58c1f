#!/usr/bin/env python3
"""The RTHS benchmark's table (Silva et al. 2020) for any controller beside the sample one: runs
each controller's partitioning cases (one scenario per case, each a `monte_carlo:` batch of
perturbed plants, or a single run) through `rpsd run`, then writes the benchmark's table of
J1-J9 per controller and case, mean +/- sample standard deviation over the runs, and the
benchmark's constraints checked on every run, as CSV, Markdown and a plot (docs/benchmark.md).

    scripts/rths-benchmark-study.py --out results/benchmark \\
        [--controller "my controller" my-case-1.yaml my-case-2.yaml my-case-3.yaml my-case-4.yaml] \\
        [--without-sample-controller] [--cases 1,2,3,4] [--runs N] [--end-s S] [--set key=value ...]

The sample controller (examples/scenarios/rths-benchmark-sample-controller-case-N.yaml) is in
the table unless --without-sample-controller; each --controller gives a name and its scenarios
in the benchmark's case order (case 1 first). --cases picks cases by number for every
controller. --runs, --end-s (the record cut at S seconds, no trailing zeros) and --set (any
key, passed to every run) shorten the study for a quick look or a test; the table then says
so. Exit 0 when the table is written (constraints met or not: the table says which), 1 when a
case could not run at all, 2 on bad arguments.
"""
import argparse
import csv
import json
import math
import os
import re
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SAMPLE = "sample controller"
CASES = {  # case: floor mass kg, modal damping (the benchmark's partitioning cases)
    1: (1000, 0.05),
    2: (1100, 0.04),
    3: (1300, 0.03),
    4: (1000, 0.03),
}
# J1-J9 by the names rpsd gives them, in the paper's order (hybrid_test/src/benchmark_criteria.cpp).
CRITERIA = [
    ("J1", "J1_tracking_delay_ms"),
    ("J2", "J2_rms_tracking_error_percent"),
    ("J3", "J3_peak_tracking_error_percent"),
    ("J4", "J4_rms_error_floor_1_percent"),
    ("J5", "J5_rms_error_floor_2_percent"),
    ("J6", "J6_rms_error_floor_3_percent"),
    ("J7", "J7_peak_error_floor_1_percent"),
    ("J8", "J8_peak_error_floor_2_percent"),
    ("J9", "J9_peak_error_floor_3_percent"),
]
# The benchmark's constraints, on every run: (quantity in runs.csv, bound, unit, what).
CONSTRAINTS = [
    ("peak_measured_force_n", 8900.0, "N", "actuator force"),
    ("peak_measured_m", 0.007, "m", "stroke"),
    ("peak_command_velocity_m_per_s", 0.3, "m/s", "velocity"),
    ("J1_tracking_delay_ms", 10.0, "ms", "tracking delay J1"),
]


def sample_scenario(case):
    return os.path.join(ROOT, "examples", "scenarios", f"rths-benchmark-sample-controller-case-{case}.yaml")


def slug(name):
    return re.sub(r"[^A-Za-z0-9]+", "-", name).strip("-").lower() or "controller"


def number(text):
    return float(text) if text not in ("", None) else math.nan


def single_run_row(summary):
    """A scenario without monte_carlo: its one run, as a row of runs.csv would give it."""
    row = {name: summary["benchmark_criteria"].get(number_name) for number_name, name in CRITERIA}
    channel = summary["channels"][0] if summary.get("channels") else {}
    for quantity, _, _, _ in CONSTRAINTS:
        if quantity in channel:
            row[quantity] = channel[quantity]
    row["completed"] = summary.get("completed", False)
    return {k: ("" if v is None else str(v)) for k, v in row.items()}


def run_case(rpsd, scenario, out, args):
    """Runs one case's scenario; returns its runs (rows of runs.csv, or the single run)."""
    command = [rpsd, "run", scenario, "--out", out, "--replace"]
    if args.runs is not None:
        command += ["--set", f"monte_carlo.runs={args.runs}"]
    if args.end_s is not None:
        command += ["--set", f"ground_motion.trim.end_s={args.end_s}", "--set", "ground_motion.pad_after_s=0"]
    for s in args.set:
        command += ["--set", s]
    print("rths-benchmark-study: " + " ".join(command), flush=True)
    # Exit 3: a run stopped (a limit, a run-away); the batch goes on and the table counts it.
    code = subprocess.call(command)
    if code not in (0, 3):
        sys.exit(f"rths-benchmark-study: {scenario}: rpsd run exited {code}")
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    if summary.get("study") == "rpsd_test_monte_carlo":
        with open(os.path.join(out, "runs.csv")) as f:
            return list(csv.DictReader(f))
    return [single_run_row(summary)]


def completed(row):
    return str(row.get("completed", "true")).lower() in ("true", "1", "yes")


def mean_and_std(values):
    """Mean and sample standard deviation of the finite values (n - 1; none for one value)."""
    finite = [v for v in values if not math.isnan(v)]
    if not finite:
        return math.nan, math.nan
    return statistics.mean(finite), (statistics.stdev(finite) if len(finite) > 1 else math.nan)


def case_entry(controller, case, scenario, rows):
    mass, zeta = CASES.get(case, ("", ""))
    done = [r for r in rows if completed(r)]
    entry = {"controller": controller, "case": case, "scenario": os.path.basename(scenario), "floor_mass_kg": mass,
             "modal_damping": zeta, "runs": len(rows), "runs_completed": len(done)}
    # Over the completed runs, as rpsd's own statistics.csv (a run that stopped is counted apart).
    for number_name, name in CRITERIA:
        entry[number_name + "_mean"], entry[number_name + "_std"] = mean_and_std([number(r.get(name)) for r in done])
    return entry


def constraint_checks(controller, case, rows):
    checks = []
    for quantity, bound, unit, what in CONSTRAINTS:
        values = [number(r.get(quantity)) for r in rows]
        finite = [v for v in values if not math.isnan(v)]
        worst = max(finite) if finite else math.nan
        over = sum(1 for v in finite if v > bound) + (len(values) - len(finite))
        checks.append({"controller": controller, "case": case, "constraint": what, "quantity": quantity,
                       "bound": bound, "unit": unit, "worst": worst, "runs_beyond": over, "runs": len(values),
                       "met": over == 0})
    return checks


def cell(mean, std, digits=3):
    if isinstance(mean, float) and math.isnan(mean):
        return "n/a"
    return f"{mean:.{digits}g} ± {std:.2g}" if not math.isnan(std) else f"{mean:.{digits}g}"


def write_csv(path, rows, columns):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns)
        w.writeheader()
        for row in rows:
            w.writerow({k: ("" if isinstance(v, float) and math.isnan(v) else v) for k, v in row.items()})


def write_markdown(path, table, checks, args):
    shortened = args.runs is not None or args.end_s is not None or args.set
    lines = ["# RTHS benchmark: " + ", ".join(dict.fromkeys(e["controller"] for e in table)), ""]
    if shortened:
        lines += [f"**Shortened study** (runs {args.runs or 'as in the scenarios'}, record end "
                  f"{args.end_s if args.end_s is not None else 'full'}, overrides {args.set or 'none'}): "
                  "not the benchmark's table.", ""]
    lines += ["Mean ± sample standard deviation over each case's completed runs; J1 in ms (the benchmark's: "
              "whole-sample lags 0-49), J2-J9 in % (the paper's order: J4-J6 RMS and J7-J9 peak errors of "
              "floors 1-3, floor 1 measured).", "",
              "| controller | case | floor mass | damping | runs | " + " | ".join(n for n, _ in CRITERIA) + " |",
              "|---|---|---|---|---|" + "---|" * len(CRITERIA)]
    for e in table:
        mass = f"{e['floor_mass_kg']} kg" if e["floor_mass_kg"] != "" else ""
        damping = f"{e['modal_damping'] * 100:g} %" if e["modal_damping"] != "" else ""
        lines.append(f"| {e['controller']} | {e['case']} | {mass} | {damping} | {e['runs_completed']}/{e['runs']} | " +
                     " | ".join(cell(e[n + '_mean'], e[n + '_std']) for n, _ in CRITERIA) + " |")
    lines += ["", "## Constraints, every run", "",
              "| controller | case | constraint | bound | worst | runs beyond | met |", "|---|---|---|---|---|---|---|"]
    for c in checks:
        lines.append(f"| {c['controller']} | {c['case']} | {c['constraint']} | {c['bound']:g} {c['unit']} | "
                     f"{c['worst']:.4g} {c['unit']} | {c['runs_beyond']}/{c['runs']} | {'yes' if c['met'] else 'NO'} |")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return lines


def draw(out, table):
    """One panel per case: each controller's criteria, mean with its standard deviation (gnuplot)."""
    data = os.path.join(out, "benchmark-table.dat")
    controllers = list(dict.fromkeys(e["controller"] for e in table))
    cases = list(dict.fromkeys(e["case"] for e in table))
    with open(data, "w") as f:
        for case in cases:
            for i, (n, _) in enumerate(CRITERIA):
                cells = []
                for controller in controllers:
                    e = next((e for e in table if e["controller"] == controller and e["case"] == case), None)
                    mean = e[n + "_mean"] if e else math.nan
                    std = e[n + "_std"] if e else math.nan
                    cells += ["NaN" if math.isnan(mean) else repr(mean), "0" if math.isnan(std) else repr(std)]
                f.write(f"{i} {n} " + " ".join(cells) + "\n")
            f.write("\n\n")  # one gnuplot index per case
    plot = [f"set terminal pngcairo size {max(600, 500 * len(cases))},600",
            f"set output '{os.path.join(out, 'benchmark-table.png')}'",
            f"set multiplot layout 1,{len(cases)} title 'RTHS benchmark: J1 (ms) and J2-J9 (%), mean and standard "
            "deviation'", "set xrange [-0.5:8.5]", "set grid ytics", "set key top left", "set bars 2",
            "set datafile missing 'NaN'",
            "set xtics (" + ", ".join(f"'{n}' {i}" for i, (n, _) in enumerate(CRITERIA)) + ")"]
    for k, case in enumerate(cases):
        plot.append(f"set title 'case {case}'")
        series = []
        for c, controller in enumerate(controllers):
            offset = (c - (len(controllers) - 1) / 2) * 0.2
            series.append(f"'{data}' index {k} using ($1+{offset}):{3 + 2 * c}:{4 + 2 * c} with yerrorbars pt 7 "
                          f"lw 2 title '{controller.replace(chr(39), '')}'")
        plot.append("plot " + ", ".join(series))
    plot.append("unset multiplot")
    try:
        subprocess.run(["gnuplot"], input="\n".join(plot) + "\n", text=True, check=True)
    except (OSError, subprocess.CalledProcessError) as e:
        print(f"rths-benchmark-study: warning: no plot ({e})", file=sys.stderr)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rpsd", default=os.path.join(ROOT, "build", "rpsd"))
    parser.add_argument("--out", required=True)
    parser.add_argument("--controller", nargs="+", action="append", default=[], metavar=("NAME", "SCENARIO"),
                        help="a controller's name and its case scenarios, case 1 first (repeatable)")
    parser.add_argument("--without-sample-controller", action="store_true",
                        help="leave the sample controller out of the table")
    parser.add_argument("--runs", type=int, help="runs per case (default: the scenarios')")
    parser.add_argument("--end-s", type=float, help="cut the record here, without trailing zeros")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="a scenario override for every run (repeatable)")
    parser.add_argument("--cases", default="1,2,3,4", help="which cases by number, e.g. 1,4")
    args = parser.parse_args()

    controllers = [] if args.without_sample_controller else [(SAMPLE, [sample_scenario(c) for c in sorted(CASES)])]
    for given in args.controller:
        if len(given) < 2:
            parser.error(f"--controller {given[0]}: give its name, then its case scenarios")
        missing = [f for f in given[1:] if not os.path.isfile(f)]
        if missing:
            parser.error(f"--controller {given[0]}: no such scenario: {', '.join(missing)}")
        controllers.append((given[0], [os.path.abspath(f) for f in given[1:]]))
    if not controllers:
        parser.error("no controller: give --controller, or leave out --without-sample-controller")
    if len({slug(name) for name, _ in controllers}) != len(controllers):
        parser.error("two controllers with the same name")
    try:
        wanted = [int(c) for c in args.cases.split(",")]
    except ValueError:
        parser.error(f"--cases {args.cases}: expected case numbers, e.g. 1,4")
    os.makedirs(args.out, exist_ok=True)

    table, checks = [], []
    for name, scenarios in controllers:
        for case, scenario in enumerate(scenarios, start=1):
            if case not in wanted:
                continue
            rows = run_case(args.rpsd, scenario, os.path.join(args.out, slug(name), f"case-{case}"), args)
            table.append(case_entry(name, case, scenario, rows))
            checks += constraint_checks(name, case, rows)
    if not table:
        parser.error(f"--cases {args.cases}: no controller has such a case")

    columns = ["controller", "case", "scenario", "floor_mass_kg", "modal_damping", "runs", "runs_completed"]
    for n, _ in CRITERIA:
        columns += [n + "_mean", n + "_std"]
    write_csv(os.path.join(args.out, "benchmark-table.csv"), table, columns)
    write_csv(os.path.join(args.out, "constraints.csv"), checks, list(checks[0].keys()))
    lines = write_markdown(os.path.join(args.out, "benchmark-table.md"), table, checks, args)
    draw(args.out, table)
    print(f"rths-benchmark-study: {os.path.join(args.out, 'benchmark-table.md')}")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
