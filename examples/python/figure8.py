#!/usr/bin/env python3
"""The seed paper's Figure 8 from Python: the delay-compensation study
(examples/scenarios/paper-fig8-delay-compensation.yaml) run in this process with rpsd.run, read
back through rpsd.load, and its panel (c) drawn with matplotlib: the effective damping ratio of
the RPsD free vibration against the residual delay, identified from each case's response beside
the exact root of m s^2 + c s + k e^{-s tau} = 0, its approximation zeta - omega_n tau / 2, and the
root with the compensator and the servo's linear model (docs/paper-reproduction.md, Figure 8).

    python3 examples/python/figure8.py --out results/fig8-python            # the whole study
    python3 examples/python/figure8.py --out /tmp/f8 --delays 60,90 --duration 2   # a short one

Needs the package rpsd (PYTHONPATH=build/python after a build, or installed) and
python3-matplotlib. Writes OUT/ (the study's folder, as `rpsd run` writes it) and the figure
(--png, by default OUT/figure8c.png).
"""
import argparse
from pathlib import Path

import matplotlib.pyplot as plt  # any backend: the figure is only saved (headless: Agg)

import rpsd

SCENARIO = Path(__file__).resolve().parent.parent / "scenarios/paper-fig8-delay-compensation.yaml"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", required=True, help="the study's output folder (must be new or empty)")
    parser.add_argument("--png", help="the figure (default OUT/figure8c.png)")
    parser.add_argument("--delays", help="compensated delays in ms, comma-separated (default: the study's ten)")
    parser.add_argument("--duration", type=float, help="each case's length in s (default: the study's 8 s)")
    args = parser.parse_args()

    overrides = {}
    if args.delays:
        overrides["compensation.compensated_delays_ms"] = [float(d) for d in args.delays.split(",")]
    if args.duration:
        overrides["duration_s"] = args.duration
    rpsd.run(SCENARIO, out=args.out, overrides=overrides)

    study = rpsd.load(args.out)  # the folder as any rpsd run left it
    damping = study.tables["damping"]
    residual_ms = damping["residual_delay_ms"]
    order = residual_ms.argsort()

    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(residual_ms[order], damping["identified_damping_ratio"][order], "o", ms=7,
            label="identified from RPsD response")
    ax.plot(residual_ms[order], damping["predicted_damping_ratio"][order], "o-", mfc="none", lw=2,
            label=r"exact root, $m s^2 + c s + k e^{-s\tau}$")
    ax.plot(residual_ms[order], damping["approximate_damping_ratio"][order], "--", lw=1,
            label=r"$\zeta - \omega_n \tau / 2$")
    ax.plot(residual_ms[order], damping["predicted_damping_ratio_loop"][order], "s-", mfc="none", lw=1,
            label=r"root with $G_c(s)\,G_a(s)$")
    ax.axhline(study.summary["structure"]["damping_ratio"], color="grey", lw=0.8, ls=":",
               label="true damping ratio")
    ax.set_xlabel("residual delay (ms)")
    ax.set_ylabel("damping ratio")
    ax.set_title("(c) effective damping ratio against residual delay (%s)" % study.summary["plant"])
    ax.grid(True)
    ax.legend(fontsize=8)
    fig.tight_layout()
    png = Path(args.png) if args.png else Path(args.out) / "figure8c.png"
    fig.savefig(png, dpi=120)
    print("figure8: %d cases, panel (c) in %s" % (len(residual_ms), png))


if __name__ == "__main__":
    main()
