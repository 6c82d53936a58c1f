#!/usr/bin/env python3
"""rpsd validate on a Matrix Market model of the documented maximum, 100,000 DOFs, within a
bounded memory: a fixed-free chain of equal springs k and masses m, generated here (never
committed), whose lowest frequencies are known in closed form,
  w_j = 2 sqrt(k/m) sin((2j - 1) pi / (2 (2n + 1))).
A dense copy of one matrix alone would take 80 GB; validate must find the modes it prints,
and the Rayleigh damping through modes 1 and 2, without one (sparse eigen-solver) under
`ulimit -v`.

  large_model_test.py RPSD SCRATCH_DIR"""
import math
import os
import re
import resource
import subprocess
import sys

RPSD, SCRATCH = sys.argv[1:3]
N, K, M = 100_000, 1.6e11, 1.0  # f_1 = 1.000 Hz
MEMORY_LIMIT_BYTES = 2 * 1024**3  # against 80 GB for a dense 100,000 x 100,000 matrix

folder = os.path.join(SCRATCH, "large-model")
os.makedirs(folder, exist_ok=True)
with open(os.path.join(folder, "mass.mtx"), "w") as f:
    f.write(f"%%MatrixMarket matrix coordinate real symmetric\n{N} {N} {N}\n")
    f.writelines(f"{i} {i} {M:.17g}\n" for i in range(1, N + 1))
with open(os.path.join(folder, "stiffness.mtx"), "w") as f:
    # Spring i joins mass i - 1 (the ground for i = 1) to mass i; the last mass is free.
    f.write(f"%%MatrixMarket matrix coordinate real symmetric\n{N} {N} {2 * N - 1}\n")
    f.writelines(f"{i} {i} {(2 * K if i < N else K):.17g}\n" for i in range(1, N + 1))
    f.writelines(f"{i + 1} {i} {-K:.17g}\n" for i in range(1, N))
with open(os.path.join(folder, "record.txt"), "w") as f:
    f.write("0\n0.01\n0.02\n0.01\n0\n")
with open(os.path.join(folder, "chain.yaml"), "w") as f:
    f.write(f"""study: rpsd_test
structure:
  kind: matrix_market
  mass_file: mass.mtx
  stiffness_file: stiffness.mtx
  damping:
    rayleigh: {{mode_a: 1, mode_b: 2, damping_ratio_a: 0.02, damping_ratio_b: 0.02}}
experimental:
  - {{dof: {N - 1}, specimen_stiffness_n_per_m: 1.0e3, restoring_force: stiffness_times_displacement}}
servo:
  kind: ideal_delay
  delay_s: 0.01
  rig: {{stroke_m: 0.25, force_n: 1.0e6, velocity_m_per_s: 1.0}}
integrator: {{scheme: newmark}}
compensation: {{kind: none}}
clock: {{mode: as_fast_as_possible, control_rate_hz: 100}}
ground_motion: {{file: record.txt, format: plain_text, dt_s: 0.01, units: g}}
""")


def bounded():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT_BYTES, MEMORY_LIMIT_BYTES))


run = subprocess.run([RPSD, "validate", os.path.join(folder, "chain.yaml")], stdout=subprocess.PIPE,
                     stderr=subprocess.STDOUT, text=True, timeout=600, preexec_fn=bounded)
problems = []
if run.returncode != 0:
    problems.append(f"exit code {run.returncode}, expected 0")
line = re.search(r"modes of the numerical part alone[^:]*: (.*)", run.stdout)
if not line:
    problems.append("no modes of the numerical part printed")
else:
    printed = [float(f) for f in re.findall(r"([0-9.e+-]+) Hz", line.group(1))]
    # Rayleigh damping through modes 1 and 2 (found by the sparse solver too) gives 2 % there.
    ratios = re.findall(r"Hz \(([0-9.e+-]+) %\)", line.group(1))
    if ratios[:2] != ["2", "2"]:
        problems.append(f"damping of modes 1 and 2: {ratios[:2]} %, expected 2 % (Rayleigh through them)")
    if len(printed) < 5:
        problems.append(f"{len(printed)} modes printed, expected the lowest 5 at least")
    for j, f in enumerate(printed, start=1):
        expected = 2 * math.sqrt(K / M) * math.sin((2 * j - 1) * math.pi / (2 * (2 * N + 1))) / (2 * math.pi)
        if abs(f - expected) > 1e-3 * expected:  # printed to 4 significant digits
            problems.append(f"mode {j}: {f} Hz printed, {expected:.6g} Hz in closed form")
if problems:
    print(run.stdout[-4000:])
    for p in problems:
        print("FAILED: " + p)
    sys.exit(1)
print(line.group(0))
