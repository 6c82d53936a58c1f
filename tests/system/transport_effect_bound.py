#!/usr/bin/env python3
"""Checks a real-time distributed run against the single-process run of the same scenario.

usage: transport_effect_bound.py RESULTS_IN_ONE_PROCESS RESULTS_OVER_DDS PLANT_TIME_CONSTANT_S NODE_SUMMARY...

The two runs may differ only by what the transport did. Each step whose feedback was `a`
periods old replaced the specimen force k x(t) by k x(t - aT): a force error of at most
k a T v_peak for one period, an impulse of k a T^2 v_peak. Each tick a node made off the
command timeline (on its own deadline before a late command, or a command skipped because a
newer one superseded it) fed the plant one command for one period more or less: an input
error of at most the largest command change dc, which the plant (a lag of time constant
tau, its response delay) carries on as a decaying error, an impulse of at most k dc tau. For an undamped linear structure with mass-normalised
modes, an impulse I at any DOF moves any DOF by at most I / (m_min w_min) (sum over modes
of |phi_ik phi_ij| / w_i <= sqrt(Minv_kk Minv_jj) / w_min), and damping only lowers it. So
the largest displacement difference must stay below the sum of the impulses over
m_min w_min, with w_min the structure's lowest circular frequency including the specimens.
"""
import csv
import json
import math
import sys

import yaml


def lowest_circular_frequency(mass, stiffness):
    """w_min of K x = w^2 M x by inverse iteration on K^-1 M (small dense matrices)."""
    n = len(mass)

    def solve(a, b):
        a = [row[:] + [b[i]] for i, row in enumerate(a)]
        for c in range(n):
            p = max(range(c, n), key=lambda r: abs(a[r][c]))
            a[c], a[p] = a[p], a[c]
            for r in range(n):
                if r != c:
                    f = a[r][c] / a[c][c]
                    a[r] = [x - f * y for x, y in zip(a[r], a[c])]
        return [a[i][n] / a[i][i] for i in range(n)]

    x = [1.0] * n
    lam = 0.0
    for _ in range(500):
        y = solve(stiffness, [sum(mass[i][j] * x[j] for j in range(n)) for i in range(n)])
        norm = max(abs(v) for v in y)
        x = [v / norm for v in y]
        lam = 1.0 / norm
    return math.sqrt(lam)


def main():
    local, dds, tau, nodes = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4:]
    summary = json.load(open(f"{dds}/summary.json"))
    scenario = yaml.safe_load(open(f"{dds}/effective-scenario.yaml"))
    # YAML 1.1 reads 0.4e6 as text: convert every entry.
    mass = [[float(v) for v in row] for row in scenario["structure"]["mass_kg"]]
    stiffness = [[float(v) for v in row] for row in scenario["structure"]["stiffness_n_per_m"]]
    k_specimen = 0.0
    for e in scenario["experimental"]:
        k = float(e["specimen_stiffness_n_per_m"])
        stiffness[int(e["dof"])][int(e["dof"])] += k
        k_specimen = max(k_specimen, k)
    w_min = lowest_circular_frequency(mass, stiffness)
    m_min = min(mass[i][i] for i in range(len(mass)))  # a lumped (diagonal) mass matrix
    if any(mass[i][j] != 0.0 for i in range(len(mass)) for j in range(len(mass)) if i != j):
        sys.exit("FAIL: the bound assumes a diagonal mass matrix")
    period = 1.0 / summary["control_rate_hz"]

    a = list(csv.DictReader(open(f"{local}/time_history.csv")))
    b = list(csv.DictReader(open(f"{dds}/time_history.csv")))
    if len(a) != len(b):
        sys.exit(f"FAIL: {len(b)} steps over DDS, {len(a)} in one process")
    dofs = [c[len("displacement_m_dof"):] for c in a[0] if c.startswith("displacement_m_dof")]
    v_peak = max(abs(float(r[f"velocity_m_per_s_dof{d}"])) for r in a for d in dofs)
    ages = sum(int(r["feedback_age_periods"]) for r in b)
    node_events = 0
    for path in nodes:
        n = json.load(open(path))
        ticks_while_commanded = n["last_command_tick"] - n["first_command_tick"] + 1
        node_events += (ticks_while_commanded - n["commands_applied"]) + (n["commands_accepted"] - n["commands_applied"])
    channels = [c[len("command_m_ch"):] for c in a[0] if c.startswith("command_m_ch")]
    command_step = max(abs(float(r[f"command_m_ch{c}"]) - float(s[f"command_m_ch{c}"]))
                       for r, s in zip(a[1:], a[:-1]) for c in channels)
    impulse = k_specimen * (period * period * v_peak * ages + command_step * tau * node_events)
    bound = impulse / (m_min * w_min)
    worst = max(abs(float(r[f"displacement_m_dof{d}"]) - float(s[f"displacement_m_dof{d}"])) for r, s in zip(a, b) for d in dofs)
    peak = max(abs(float(r[f"displacement_m_dof{d}"])) for r in a for d in dofs)
    print(f"{len(b)} steps; late feedback: {sum(1 for r in b if r['feedback_age_periods'] != '0')} steps, "
          f"{ages} periods in all; node ticks off the command timeline: {node_events}; "
          f"largest difference {worst * 1e3:.4f} mm ({100 * worst / peak:.3f} % of the peak), bound {bound * 1e3:.4f} mm")
    if not worst <= bound:
        sys.exit("FAIL: the distributed run differs by more than the transport's measured delays explain")


if __name__ == "__main__":
    main()
