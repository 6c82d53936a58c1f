#!/usr/bin/env python3
"""Draws each experimental-setup kind (docs/experimental-setups.md) as an SVG in docs/figures/:
fixed ends on the reaction frame, attachment points on the specimen, the rigid links between
them and the control point, in the lab's frame (x right, y up, rotation counterclockwise).

The points are placed as each kind's planar() places them (setups/src/*_setup.cpp), with the
dimensions of tests/setups/setup_examples.h; run it again after changing either:
    python3 scripts/setup-figures.py docs/figures
"""
import math
import os
import sys

SCALE = 170.0  # pixels per metre
MARGIN = 60.0


def one_actuator():
    la = 1.25
    return {
        "title": "one_actuator (ESOneActuator), dof: translation_x",
        "actuators": [("actuator", (-la, 0.0), (0.0, 0.0), "La")],
        "links": [],
        "labels": [],
    }


def two_actuators():
    la1, la2, l = 1.2, 1.5, 0.8
    return {
        "title": "two_actuators (ESTwoActuators2d), actuators_side: left",
        "actuators": [("actuator_1", (-la1, 0.0), (0.0, 0.0), "La1"), ("actuator_2", (-la2, l), (0.0, l), "La2")],
        "links": [((0.0, 0.0), (0.0, l))],
        "labels": [((0.08, l / 2), "L")],
    }


def three_actuators():
    la1, la2, la3 = 1.1, 1.3, 1.4
    l1, l2, l3, l5, l6 = 0.2, 0.6, 0.9, 0.15, 0.25
    h = -(l1 + l2)
    return {
        "title": "three_actuators (ESThreeActuatorsJntOff2d), horizontal_actuator_side: left",
        "actuators": [
            ("horizontal", (h - la1, 0.0), (h, 0.0), "La1"),
            ("left", (-l2, -l5 - la2), (-l2, -l5), "La2"),
            ("right", (l3, -l6 - la3), (l3, -l6), "La3"),
        ],
        "links": [((h, 0.0), (l3, 0.0)), ((-l2, 0.0), (-l2, -l5)), ((l3, 0.0), (l3, -l6))],
        "labels": [((h / 2 - 0.3, 0.07), "L1"), ((-l2 / 2 - 0.05, 0.07), "L2"), ((l3 / 2 - 0.05, 0.07), "L3"),
                   ((-l2 + 0.05, -l5 / 2 - 0.02), "L5"), ((l3 + 0.05, -l6 / 2 - 0.02), "L6")],
    }


def planar():
    acts = [("west", (-1.3, 0.1), (-0.2, 0.0), ""), ("south_east", (1.0, -1.2), (0.4, -0.1), ""),
            ("south_west", (-0.9, -1.1), (-0.5, -0.2), "")]
    return {
        "title": "planar: fixed_end_m and attachment_m of each actuator",
        "actuators": acts,
        "links": [((0.0, 0.0), a[2]) for a in acts],
        "labels": [],
    }


def svg(kind):
    points = [(0.0, 0.0)]
    for _, f, a, _ in kind["actuators"]:
        points += [f, a]
    xs = [p[0] for p in points]
    ys = [p[1] for p in points]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    width = (x1 - x0) * SCALE + 2 * MARGIN + 120
    height = (y1 - y0) * SCALE + 2 * MARGIN + 30

    def at(p):
        return MARGIN + (p[0] - x0) * SCALE, MARGIN + 30 + (y1 - p[1]) * SCALE

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" height="{height:.0f}" '
           f'font-family="sans-serif" font-size="13">',
           '<rect width="100%" height="100%" fill="white"/>',
           f'<text x="10" y="20" font-size="14">{kind["title"]}</text>']
    for a, b in kind["links"]:
        (ax, ay), (bx, by) = at(a), at(b)
        out.append(f'<line x1="{ax:.1f}" y1="{ay:.1f}" x2="{bx:.1f}" y2="{by:.1f}" stroke="#555" stroke-width="6"/>')
    for name, f, a, label in kind["actuators"]:
        (fx, fy), (ax, ay) = at(f), at(a)
        out.append(f'<line x1="{fx:.1f}" y1="{fy:.1f}" x2="{ax:.1f}" y2="{ay:.1f}" stroke="#1f5fa8" stroke-width="4"/>')
        # The reaction frame behind the fixed end: a short hatched bar across the actuator.
        dx, dy = ax - fx, ay - fy
        n = math.hypot(dx, dy)
        ux, uy = dx / n, dy / n
        px, py = -uy, ux
        out.append(f'<line x1="{fx + 14 * px:.1f}" y1="{fy + 14 * py:.1f}" x2="{fx - 14 * px:.1f}" '
                   f'y2="{fy - 14 * py:.1f}" stroke="black" stroke-width="3"/>')
        for k in range(-2, 3):
            sx, sy = fx + 7 * k * px, fy + 7 * k * py
            out.append(f'<line x1="{sx:.1f}" y1="{sy:.1f}" x2="{sx - 8 * ux + 5 * px:.1f}" '
                       f'y2="{sy - 8 * uy + 5 * py:.1f}" stroke="black" stroke-width="1"/>')
        out.append(f'<circle cx="{fx:.1f}" cy="{fy:.1f}" r="5" fill="white" stroke="black" stroke-width="2"/>')
        out.append(f'<circle cx="{ax:.1f}" cy="{ay:.1f}" r="5" fill="#c0392b" stroke="black" stroke-width="1"/>')
        mx, my = (fx + ax) / 2 + 12 * px, (fy + ay) / 2 + 12 * py
        text = name + (f" ({label})" if label else "")
        out.append(f'<text x="{mx:.1f}" y="{my:.1f}" fill="#1f5fa8">{text}</text>')
        out.append(f'<text x="{ax + 8:.1f}" y="{ay + 16:.1f}" font-size="11">({a[0]:g}, {a[1]:g})</text>')
        out.append(f'<text x="{fx - 30:.1f}" y="{fy + 22:.1f}" font-size="11">({f[0]:g}, {f[1]:g})</text>')
    for p, text in kind["labels"]:
        x, y = at(p)
        out.append(f'<text x="{x:.1f}" y="{y:.1f}" font-style="italic">{text}</text>')
    cx, cy = at((0.0, 0.0))
    # The control point with its DOFs: x, y and the counterclockwise rotation.
    out.append(f'<line x1="{cx:.1f}" y1="{cy:.1f}" x2="{cx + 45:.1f}" y2="{cy:.1f}" stroke="green" stroke-width="2"/>')
    out.append(f'<line x1="{cx:.1f}" y1="{cy:.1f}" x2="{cx:.1f}" y2="{cy - 45:.1f}" stroke="green" stroke-width="2"/>')
    out.append(f'<text x="{cx + 48:.1f}" y="{cy + 4:.1f}" fill="green">x</text>')
    out.append(f'<text x="{cx - 4:.1f}" y="{cy - 49:.1f}" fill="green">y</text>')
    out.append(f'<path d="M {cx + 22:.1f} {cy:.1f} A 22 22 0 0 0 {cx:.1f} {cy - 22:.1f}" fill="none" stroke="green"/>')
    out.append(f'<text x="{cx + 18:.1f}" y="{cy - 18:.1f}" fill="green">θ</text>')
    out.append(f'<rect x="{cx - 5:.1f}" y="{cy - 5:.1f}" width="10" height="10" fill="green"/>')
    out.append('<text x="10" y="%.0f" font-size="11">red: attachment points (specimen); open: fixed ends '
               '(reaction frame); green: the control point, metres</text>' % (height - 8))
    out.append('</svg>')
    return "\n".join(out) + "\n"


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else "docs/figures"
    os.makedirs(folder, exist_ok=True)
    for name, kind in [("one_actuator", one_actuator()), ("two_actuators", two_actuators()),
                       ("three_actuators", three_actuators()), ("planar", planar())]:
        with open(os.path.join(folder, f"setup-{name}.svg"), "w", encoding="utf-8") as f:
            f.write(svg(kind))


if __name__ == "__main__":
    main()
