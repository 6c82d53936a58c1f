#!/usr/bin/env python3
"""Runs one rpsd command as a user would and checks what the user gets: the exit code, what
was printed (stdout and stderr together), the files written and values in JSON files.

  run_cli.py --exit N [--prints REGEX]... [--file PATH]... [--json PATH:KEY=VALUE]...
             [--json-near PATH:KEY=VALUE~TOLERANCE]... [--json-matches PATH:KEY=REGEX]... [--rows PATH=N]... [--header PATH=REGEX]... [--absent PATH]... [--fresh DIR] -- COMMAND...

KEY is a dotted path into the JSON document (list items by index). Every check that fails is
reported; the exit code is 1 if any did."""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys


def lookup(document, key):
    value = document
    for part in key.split("."):
        value = value[int(part)] if isinstance(value, list) else value[part]
    return value


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--exit", type=int, required=True)
    parser.add_argument("--prints", action="append", default=[])
    parser.add_argument("--file", action="append", default=[])
    parser.add_argument("--header", action="append", default=[])
    parser.add_argument("--json", action="append", default=[])
    parser.add_argument("--json-near", action="append", default=[])
    parser.add_argument("--json-matches", action="append", default=[])
    parser.add_argument("--rows", action="append", default=[])
    parser.add_argument("--fresh", action="append", default=[])
    parser.add_argument("--absent", action="append", default=[])
    parser.add_argument("command", nargs=argparse.REMAINDER)
    args = parser.parse_args()
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    for directory in args.fresh:
        shutil.rmtree(directory, ignore_errors=True)
    run = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=600)
    output = run.stdout
    problems = []
    if run.returncode != args.exit:
        problems.append(f"exit code {run.returncode}, expected {args.exit}")
    for pattern in args.prints:
        if not re.search(pattern, output, re.DOTALL):
            problems.append(f"the output does not match {pattern!r}")
    for path in args.file:
        try:
            with open(path, "rb") as f:
                if not f.read(1):
                    problems.append(f"{path} is empty")
        except OSError as e:
            problems.append(f"{path}: {e.strerror}")
    for check in args.json:
        path, rest = check.split(":", 1)
        key, expected = rest.split("=", 1)
        try:
            value = lookup(json.load(open(path)), key)
            if json.dumps(value) != expected and str(value) != expected:
                problems.append(f"{path}: {key} is {json.dumps(value)}, expected {expected}")
        except (OSError, KeyError, IndexError, ValueError) as e:
            problems.append(f"{path}: {key}: {e!r}")
    for check in args.json_near:
        path, rest = check.split(":", 1)
        key, rest = rest.split("=", 1)
        expected, tolerance = rest.split("~", 1)
        try:
            value = float(lookup(json.load(open(path)), key))
            if abs(value - float(expected)) > float(tolerance):
                problems.append(f"{path}: {key} is {value}, expected {expected} +- {tolerance}")
        except (OSError, KeyError, IndexError, ValueError, TypeError) as e:
            problems.append(f"{path}: {key}: {e!r}")
    for check in args.json_matches:
        path, rest = check.split(":", 1)
        key, pattern = rest.split("=", 1)
        try:
            value = str(lookup(json.load(open(path)), key))
            if not re.search(pattern, value):
                problems.append(f"{path}: {key} is {value!r}, which does not match {pattern!r}")
        except (OSError, KeyError, IndexError, ValueError) as e:
            problems.append(f"{path}: {key}: {e!r}")
    for check in args.rows:
        path, expected = check.rsplit("=", 1)
        try:
            with open(path) as f:
                rows = sum(1 for _ in f) - 1  # the header
            if rows != int(expected):
                problems.append(f"{path} has {rows} rows, expected {expected}")
        except OSError as e:
            problems.append(f"{path}: {e.strerror}")
    for check in args.header:
        path, pattern = check.split("=", 1)
        try:
            with open(path) as f:
                header = f.readline()
            if not re.search(pattern, header):
                problems.append(f"{path}: its header does not match {pattern!r}")
        except OSError as e:
            problems.append(f"{path}: {e.strerror}")
    for path in args.absent:
        if os.path.exists(path):
            problems.append(f"{path} exists, expected none")
    if problems:
        print("command: " + " ".join(command))
        print("output:\n" + output[-4000:])
        for p in problems:
            print("FAILED: " + p)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
