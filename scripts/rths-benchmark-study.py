#!/usr/bin/env python3
"""The RTHS benchmark's table (Silva et al. 2020): runs the four partitioning cases with the
sample controller (examples/scenarios/rths-benchmark-sample-controller-case-N.yaml, each a
`monte_carlo:` batch of perturbed plants) through `rpsd run`, then writes the benchmark's table
of J1-J9 per case, mean +/- standard deviation over the runs, as CSV, Markdown and a plot, with
the benchmark's constraints checked on every run (docs/benchmark.md).

    scripts/rths-benchmark-study.py --rpsd build/rpsd --out results/benchmark [--runs N] [--end-s S]

--runs and --end-s shorten the study (fewer runs; the record cut at S seconds and no trailing
zeros), for a quick look or a test; the table then says so. Exit 0 when the table is written
(constraints met or not: the table says which), 1 when a case could not run at all.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
CASES = [  # case, floor mass kg, modal damping (the benchmark's partitioning cases)
    (1, 1000, 0.05),
    (2, 1100, 0.04),
    (3, 1300, 0.03),
    (4, 1000, 0.03),
]
# The benchmark's constraints, on every run: (quantity in runs.csv, bound, unit, what).
CONSTRAINTS = [
    ("peak_measured_force_n", 8900.0, "N", "actuator force"),
    ("peak_measured_m", 0.007, "m", "stroke"),
    ("peak_command_velocity_m_per_s", 0.3, "m/s", "velocity"),
    ("J1_tracking_delay_ms", 10.0, "ms", "tracking delay J1"),
]


def scenario(case):
    return os.path.join(ROOT, "examples", "scenarios", f"rths-benchmark-sample-controller-case-{case}.yaml")


def run_case(rpsd, case, out, runs, end_s):
    command = [rpsd, "run", scenario(case), "--out", out, "--replace"]
    if runs is not None:
        command += ["--set", f"monte_carlo.runs={runs}"]
    if end_s is not None:
        command += ["--set", f"ground_motion.trim.end_s={end_s}", "--set", "ground_motion.pad_after_s=0"]
    print("rths-benchmark-study: " + " ".join(command), flush=True)
    # Exit 3: a run stopped (a limit, a run-away); the batch goes on and the table counts it.
    code = subprocess.call(command)
    if code not in (0, 3):
        sys.exit(f"rths-benchmark-study: case {case}: rpsd run exited {code}")
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    with open(os.path.join(out, "runs.csv")) as f:
        rows = list(csv.DictReader(f))
    return summary, rows


def number(text):
    return float(text) if text not in ("", None) else math.nan


def cell(mean, std, digits=3):
    if mean is None or (isinstance(mean, float) and math.isnan(mean)):
        return "n/a"
    return f"{mean:.{digits}g} ± {std:.2g}" if std is not None else f"{mean:.{digits}g}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rpsd", default=os.path.join(ROOT, "build", "rpsd"))
    parser.add_argument("--out", required=True)
    parser.add_argument("--runs", type=int, help="runs per case (default: the scenarios', 20)")
    parser.add_argument("--end-s", type=float, help="cut the record here, without trailing zeros")
    parser.add_argument("--cases", default="1,2,3,4", help="which cases, e.g. 1,4")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    chosen = [c for c in CASES if str(c[0]) in args.cases.split(",")]

    table, checks, criteria = [], [], []
    for case, mass, zeta in chosen:
        summary, rows = run_case(args.rpsd, case, os.path.join(args.out, f"case-{case}"), args.runs, args.end_s)
        stats = summary["statistics"]
        # J1-J9 by the names rpsd gives them ("J4_rms_error_floor_1_percent"), in order.
        criteria = sorted(((name.split("_")[0], name) for name in stats if name.startswith("J")),
                          key=lambda c: int(c[0][1:]))
        entry = {"case": case, "floor_mass_kg": mass, "modal_damping": zeta, "runs": summary["runs_planned"],
                 "runs_completed": summary["runs_completed"]}
        for number_name, name in criteria:
            entry[number_name + "_mean"] = stats[name]["mean"]
            entry[number_name + "_std"] = stats[name]["standard_deviation"]
        table.append(entry)
        for quantity, bound, unit, what in CONSTRAINTS:
            values = [number(r[quantity]) for r in rows]
            finite = [v for v in values if not math.isnan(v)]
            worst = max(finite) if finite else math.nan
            over = sum(1 for v in finite if v > bound) + (len(values) - len(finite))
            checks.append({"case": case, "constraint": what, "quantity": quantity, "bound": bound, "unit": unit,
                           "worst": worst, "runs_beyond": over, "runs": len(values), "met": over == 0})

    columns = ["case", "floor_mass_kg", "modal_damping", "runs", "runs_completed"]
    for n, _ in criteria:
        columns += [n + "_mean", n + "_std"]
    with open(os.path.join(args.out, "benchmark-table.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns)
        w.writeheader()
        for entry in table:
            w.writerow({k: ("" if isinstance(v, float) and math.isnan(v) else v) for k, v in entry.items()})
    with open(os.path.join(args.out, "constraints.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(checks[0].keys()))
        w.writeheader()
        w.writerows(checks)

    shortened = args.runs is not None or args.end_s is not None
    lines = ["# RTHS benchmark, sample controller (PI 2 + 95/s, phase lead G_T), El Centro x 0.4", ""]
    if shortened:
        lines += [f"**Shortened study** (runs {args.runs or 'as in the scenarios'}, record end "
                  f"{args.end_s if args.end_s is not None else 'full'}): not the benchmark's table.", ""]
    lines += ["Mean ± standard deviation over the perturbed runs; J1 in ms, J2-J9 in % (the paper's order: J4-J6 "
              "RMS and J7-J9 peak errors of floors 1-3, floor 1 measured).", "",
              "| case | floor mass | damping | runs | " + " | ".join(n for n, _ in criteria) + " |",
              "|---|---|---|---|" + "---|" * len(criteria)]
    for e in table:
        lines.append(f"| {e['case']} | {e['floor_mass_kg']} kg | {e['modal_damping'] * 100:g} % | "
                     f"{e['runs_completed']}/{e['runs']} | " +
                     " | ".join(cell(e[n + '_mean'], e[n + '_std']) for n, _ in criteria) + " |")
    lines += ["", "## Constraints, every run", "", "| case | constraint | bound | worst | runs beyond | met |",
              "|---|---|---|---|---|---|"]
    for c in checks:
        lines.append(f"| {c['case']} | {c['constraint']} | {c['bound']:g} {c['unit']} | {c['worst']:.4g} {c['unit']} | "
                     f"{c['runs_beyond']}/{c['runs']} | {'yes' if c['met'] else 'NO'} |")
    with open(os.path.join(args.out, "benchmark-table.md"), "w") as f:
        f.write("\n".join(lines) + "\n")

    # The plot: each criterion's mean with its standard deviation, one group per case.
    data = os.path.join(args.out, "benchmark-table.dat")
    with open(data, "w") as f:
        for i, (n, _) in enumerate(criteria):
            f.write(f"{i} {n} " + " ".join(f"{e[n + '_mean']} {e[n + '_std']}" for e in table) + "\n")
    plot = ["set terminal pngcairo size 1200,600", f"set output '{os.path.join(args.out, 'benchmark-table.png')}'",
            "set title 'RTHS benchmark, sample controller: J1 (ms) and J2-J9 (%), mean and standard deviation'",
            "set xrange [-0.5:8.5]", "set grid ytics", "set key top left", "set bars 2",
            "set xtics (" + ", ".join(f"'{n}' {i}" for i, (n, _) in enumerate(criteria)) + ")"]
    series = []
    for k, e in enumerate(table):
        offset = (k - (len(table) - 1) / 2) * 0.15
        series.append(f"'{data}' using ($1+{offset}):{3 + 2 * k}:{4 + 2 * k} with yerrorbars pt 7 lw 2 "
                      f"title 'case {e['case']} ({e['floor_mass_kg']} kg, {e['modal_damping'] * 100:g} %)'")
    plot.append("plot " + ", ".join(series))
    try:
        subprocess.run(["gnuplot"], input="\n".join(plot) + "\n", text=True, check=True)
    except (OSError, subprocess.CalledProcessError) as e:
        print(f"rths-benchmark-study: warning: no plot ({e})", file=sys.stderr)
    print(f"rths-benchmark-study: {os.path.join(args.out, 'benchmark-table.md')}")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
