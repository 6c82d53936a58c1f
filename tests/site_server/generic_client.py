#!/usr/bin/env python3
"""A scripted OpenSees genericClient for the site server's command-line and system tests: the
bytes a genericClient of one basic DOF sends (docs/opensees.md, "The wire protocol"), and the
ways a client misbehaves (floods, stalls, never reads, steps backwards).

As a module: GenericClient and start_server. As a command (for a client in a network namespace):

  generic_client.py steps HOST PORT N [--source ADDR] [--displacement-m D]
      N steps of NewmarkExplicit's shape ([3, d, v, a, t] then [10]), d = D sin(2 pi n / 400),
      then 99; prints
      "steps S answered A nan Z closed C" (C: 1 if the server closed the connection)."""
import argparse
import math
import os
import select
import socket
import struct
import subprocess
import sys
import time

DATA_SIZE = 256
DT = 1.0 / 1024.0
SET_TRIAL, COMMIT, GET_FORCE, DIE = 3.0, 5.0, 10.0, 99.0


def setup_bytes(dofs=1):
    # [ctrlDisp, ctrlVel, ctrlAccel, ctrlForce, ctrlTime, daqDisp, daqVel, daqAccel, daqForce, daqTime, dataSize]
    return struct.pack("<11i", dofs, dofs, dofs, 0, 1, 0, 0, 0, dofs, 0, DATA_SIZE)


def request_bytes(*values):
    return struct.pack(f"<{DATA_SIZE}d", *values, *([0.0] * (DATA_SIZE - len(values))))


class GenericClient:
    """One connection to the server, speaking as a 1-DOF genericClient."""

    def __init__(self, host, port, source=None, timeout_s=30.0):
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        if source:
            self.sock.bind((source, 0))
        self.sock.settimeout(timeout_s)
        self.sock.connect((host, port))
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)

    def send(self, data):
        """False if the server has closed the connection."""
        try:
            self.sock.sendall(data)
            return True
        except OSError:
            return False

    def read_reply(self):
        """The reply's doubles, or None if the connection ended first."""
        want = DATA_SIZE * 8
        data = b""
        try:
            while len(data) < want:
                chunk = self.sock.recv(want - len(data))
                if not chunk:
                    return None
                data += chunk
        except OSError:
            return None
        return struct.unpack(f"<{DATA_SIZE}d", data)

    def step(self, displacement_m, time_s):
        """One explicit step: the trial, then its force. The force, NaN, or None if closed."""
        if not self.send(request_bytes(SET_TRIAL, displacement_m, 0.0, 0.0, time_s) + request_bytes(GET_FORCE)):
            return None
        reply = self.read_reply()
        return None if reply is None else reply[0]

    def closed_by_server(self, timeout_s=30.0):
        """True once the server has closed the connection (EOF or reset) within timeout_s."""
        self.sock.settimeout(timeout_s)
        try:
            while True:
                if not self.sock.recv(65536):
                    return True
        except socket.timeout:
            return False
        except OSError:
            return True

    def fill_without_reading(self, quiet_s=1.0, limit_s=60.0):
        """Sends steps and never reads a reply, until the server takes nothing more for quiet_s
        (it is blocked writing replies nobody reads). Returns the steps sent."""
        self.sock.setblocking(False)
        pending = b""
        sent_steps = 0
        end = time.monotonic() + limit_s
        while time.monotonic() < end:
            if not pending:
                sent_steps += 1
                pending = request_bytes(SET_TRIAL, 1e-4 * (sent_steps % 10), 0.0, 0.0, sent_steps * DT) + \
                    request_bytes(GET_FORCE)
            _, writable, _ = select.select([], [self.sock], [], quiet_s)
            if not writable:
                break
            try:
                pending = pending[self.sock.send(pending):]
            except BlockingIOError:
                continue
            except OSError:
                break
        self.sock.setblocking(True)
        return sent_steps

    def close(self):
        self.sock.close()


def start_server(rpsd, site, out, sets=(), prefix=(), log_path=None, timeout_s=30.0):
    """Starts `rpsd site-server` (behind `prefix`, e.g. `ip netns exec NS`) and returns
    (process, port, start line) once it prints that it listens; its output goes to log_path."""
    log_path = log_path or os.path.join(os.path.dirname(out), os.path.basename(out) + ".log")
    log = open(log_path, "w")
    process = subprocess.Popen([*prefix, rpsd, "site-server", site, "--out", out,
                                *[a for s in sets for a in ("--set", s)]],
                               stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        with open(log_path, errors="replace") as f:
            text = f.read()
        for line in text.splitlines():
            if "listening on" in line and " for " in line:
                port = int(line.split("listening on", 1)[1].split()[0].rsplit(":", 1)[1])
                return process, port, line
        if process.poll() is not None:
            break
        time.sleep(0.05)
    process.kill()
    process.wait()
    with open(log_path, errors="replace") as f:
        raise RuntimeError("rpsd site-server did not start listening: " + f.read()[-2000:])


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("what", choices=["steps"])
    parser.add_argument("host")
    parser.add_argument("port", type=int)
    parser.add_argument("steps", type=int)
    parser.add_argument("--source")
    parser.add_argument("--displacement-m", type=float, default=0.001)
    args = parser.parse_args()
    try:
        client = GenericClient(args.host, args.port, args.source)
    except OSError as e:
        print(f"steps 0 answered 0 nan 0 closed 1 (connect: {e})")
        return 0
    closed = 0
    answered = nan = 0
    if not client.send(setup_bytes()):
        closed = 1
    for n in range(1, args.steps + 1):
        if closed:
            break
        # A sine of 400 steps: each step moves (a command each), by at most 0.8 mm for 50 mm,
        # within the rig's increment limit (velocity x period).
        force = client.step(args.displacement_m * math.sin(2 * math.pi * n / 400), n * DT)
        if force is None:
            closed = 1
            break
        answered += 1
        nan += math.isnan(force)
    if not closed:
        client.send(request_bytes(DIE))
    client.close()
    print(f"steps {args.steps} answered {answered} nan {nan} closed {closed}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
