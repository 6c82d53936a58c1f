#!/usr/bin/env python3
"""Digest of everything the examples write, to show that a change leaves rpsd's outputs alone.

    scripts/output-digest.py RPSD OUT_DIR > digest.txt

runs every example scenario and study (examples/scenarios/*.yaml) with RPSD into OUT_DIR, each
Monte Carlo batch cut to its first 3 runs, and, when the environment names the OpenSees
interpreter (OPENSEES), every site-server file of examples/opensees/ under its genericClient
model. It prints one line per file written (CSV, JSON, YAML, Markdown, gnuplot scripts): its
path and the SHA-256 of its content, with the keys that change from run to run left out of
every JSON file (timing, provenance, run_id, the server's port and its client's address) and the
checkout's own path written as <repo> (summaries and effective scenarios name their input files
by absolute path). Two digests
taken before and after a change are compared with diff: no line may differ.
"""
import hashlib
import json
import os
import pathlib
import socket
import subprocess
import sys
import time

VOLATILE_KEYS = {"timing", "provenance", "run_id", "port", "peer", "elapsed_s", "wall_clock_s"}
DIGESTED = {".csv", ".json", ".yaml", ".md", ".gp", ".txt"}
MONTE_CARLO_RUNS = 3


def stripped(value):
    if isinstance(value, dict):
        return {k: stripped(v) for k, v in value.items() if k not in VOLATILE_KEYS}
    if isinstance(value, list):
        return [stripped(v) for v in value]
    return value


def digest_file(path, repo):
    data = path.read_bytes().replace(str(repo).encode(), b"<repo>")
    if path.suffix == ".json":
        data = json.dumps(stripped(json.loads(data)), sort_keys=True).encode()
    return hashlib.sha256(data).hexdigest()


def run_scenarios(rpsd, repo, out):
    codes = {}
    for scenario in sorted((repo / "examples" / "scenarios").glob("*.yaml")):
        folder = out / scenario.stem
        command = [rpsd, "run", str(scenario), "--out", str(folder)]
        if any(line.startswith("monte_carlo:") for line in scenario.read_text().splitlines()):
            command += ["--set", f"monte_carlo.runs={MONTE_CARLO_RUNS}"]
        codes[scenario.stem] = subprocess.run(command, capture_output=True).returncode
    return codes


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


# Site-server files and the genericClient model each serves (examples/opensees/README.md).
SITES = {
    "sdof-site-paper-rig.yaml": "sdof-generic-client.tcl",
    "sdof-site-perfect.yaml": "sdof-generic-client.tcl",
    "three-storey-site-perfect.yaml": "three-storey-generic-client.tcl",
}


def run_sites(rpsd, repo, out, opensees):
    codes = {}
    record = repo / "data" / "ground-motions" / "I-ELC180.AT2"
    for site, model in SITES.items():
        folder = out / pathlib.Path(site).stem
        port = free_port()
        server = subprocess.Popen(
            [rpsd, "site-server", str(repo / "examples" / "opensees" / site), "--out", str(folder),
             "--set", f"listen.port={port}"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(1.0)
        client = subprocess.run(
            [opensees, str(repo / "examples" / "opensees" / model), str(out / (folder.name + "-opensees")),
             str(record), "0.1", "10", str(port), "127.0.0.1"], capture_output=True, timeout=600)
        try:
            codes[folder.name] = server.wait(timeout=60)
        except subprocess.TimeoutExpired:
            server.kill()
            codes[folder.name] = "hung"
        codes[folder.name + "-opensees"] = client.returncode
    return codes


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    rpsd = os.path.abspath(sys.argv[1])
    out = pathlib.Path(sys.argv[2]).resolve()
    if out.exists() and any(out.iterdir()):
        sys.exit(f"output-digest: {out} is not empty")
    out.mkdir(parents=True, exist_ok=True)
    repo = pathlib.Path(__file__).resolve().parent.parent
    codes = run_scenarios(rpsd, repo, out)
    if os.environ.get("OPENSEES"):
        codes.update(run_sites(rpsd, repo, out, os.environ["OPENSEES"]))
    for name, code in sorted(codes.items()):
        print(f"exit {name} {code}")
    for path in sorted(p for p in out.rglob("*") if p.is_file() and p.suffix in DIGESTED):
        print(f"{digest_file(path, repo)}  {path.relative_to(out)}")


if __name__ == "__main__":
    main()
