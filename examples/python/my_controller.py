#!/usr/bin/env python3
"""A benchmark participant's controller written in Python, put through the RTHS benchmark study
(examples/scenarios/rths-benchmark-sample-controller-case-1.yaml) beside the sample controller:
the same Monte Carlo batch, criteria J1-J9 and statistics, once with the sample controller's
G_T given in YAML (`compensation: kind: lti_filter`) and once with this file's controller
(`compensation: {kind: external, name: participant}` and rpsd.run(..., callables=...)).

The controller here is a first-order lead-lag feedforward, (b1 s + b0) / (s + a0) discretised
by Tustin at the test's rate, with the command's input clamped as the sample controller's is.
Its defaults are the released G_T's coefficients with a lead 10 % stronger (--lead-scale 1.0
gives G_T itself): edit the class to try your own. It runs as fast as possible in this process
(a real-time clock is refused for Python parts; docs/python.md).

    python3 examples/python/my_controller.py --out results/my-controller            # 20 runs
    python3 examples/python/my_controller.py --out /tmp/mc --runs 2 --duration 5    # a short look

Needs the package rpsd (PYTHONPATH=build/python after a build, or installed). Writes
OUT/sample/ and OUT/participant/ (each as `rpsd run` writes a batch) and prints the two
criteria tables side by side.
"""
import argparse
from pathlib import Path

import rpsd

SCENARIO = Path(__file__).resolve().parent.parent / "scenarios/rths-benchmark-sample-controller-case-1.yaml"
CRITERIA = ["J1_tracking_delay_ms", "J2_rms_tracking_error_percent", "J3_peak_tracking_error_percent",
            "J4_rms_error_floor_1_percent", "J5_rms_error_floor_2_percent", "J6_rms_error_floor_3_percent",
            "J7_peak_error_floor_1_percent", "J8_peak_error_floor_2_percent", "J9_peak_error_floor_3_percent"]


class LeadLagController:
    """(b1 s + b0) / (s + a0) by Tustin, state kept between steps; input clamped to +/- clamp_m."""

    def __init__(self, b1=50.83163, b0=8570.3973, a0=8570.3973, clamp_m=3.8, lead_scale=1.1):
        # Scaling the s-term of the numerator strengthens the lead and keeps the unit DC gain.
        self.b1, self.b0, self.a0, self.clamp_m = 1.0 + (b1 - 1.0) * lead_scale, b0, a0, clamp_m

    def configure(self, dt_s):
        k = 2.0 / dt_s  # s = k (1 - z^-1) / (1 + z^-1)
        d0 = k + self.a0
        self.c0, self.c1 = (self.b1 * k + self.b0) / d0, (self.b0 - self.b1 * k) / d0
        self.d1 = (self.a0 - k) / d0

    def reset(self, x0_m):
        self.x, self.y = x0_m, x0_m  # at rest: a constant target gives the same command

    def command(self, target_m):
        x = min(max(target_m, -self.clamp_m), self.clamp_m)
        y = self.c0 * x + self.c1 * self.x - self.d1 * self.y
        self.x, self.y = x, y
        return y

    def observe(self, target_m, measured_m):
        pass  # an adaptive controller would learn here from the measured displacement


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", required=True, help="a new or empty folder")
    parser.add_argument("--runs", type=int, help="Monte Carlo runs (default: the study's 20)")
    parser.add_argument("--duration", type=float, help="seconds of the record kept (default: all of it)")
    parser.add_argument("--lead-scale", type=float, default=1.1, help="1.0: the sample controller's G_T itself")
    args = parser.parse_args()

    overrides = {}
    if args.runs:
        overrides["monte_carlo.runs"] = args.runs
    if args.duration:
        overrides["ground_motion.trim.end_s"] = args.duration
    out = Path(args.out)
    sample = rpsd.run(SCENARIO, out=out / "sample", overrides=overrides)
    participant = rpsd.run(SCENARIO, out=out / "participant",
                           overrides={**overrides, "compensation": {"kind": "external", "name": "participant"}},
                           callables={"participant": LeadLagController(lead_scale=args.lead_scale)})

    def means(batch):
        stats = batch.statistics
        return {q: m for q, m in zip(stats["quantity"], stats["mean"])}

    a, b = means(sample), means(participant)
    print("%d runs each; mean over the runs" % sample.table.rows)
    print("%-34s %14s %14s" % ("criterion", "sample", "participant"))
    for name in CRITERIA:
        print("%-34s %14.4f %14.4f" % (name, a[name], b[name]))


if __name__ == "__main__":
    main()
