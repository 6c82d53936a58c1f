#!/usr/bin/env python3
"""Another process on the controller link's host (issue 25): sends the UDP controller emulator
a command with sequence 10^12 and x = 0.2 m over a 1 s period, then a query with sequence 0
(protocol version 1, as reported: before, these moved the emulated piston to 0.2 m), and the
same command as a version 2 datagram with a made-up session and tag; and sends the node
replies it did not ask for (version 1, and version 2 with a made-up tag). Prints one JSON line:
how many datagrams it sent to each and any reply it got, with the displacement the reply reported."""
import argparse
import json
import os
import socket
import struct

MAX_CHANNELS = 8


def command(version, sequence, x_m, period_s, query=False):
    flags = 1 if query else 0
    body = b"RPSC" + struct.pack("<HBBQd", version, 1, flags, sequence, period_s)
    body += struct.pack("<8d", x_m, *([0.0] * (MAX_CHANNELS - 1)))
    return body if version == 1 else body + os.urandom(32) + os.urandom(32)


def reply(version, sequence, x_m):
    body = b"RPSR" + struct.pack("<HBBQ", version, 1, 0, sequence)
    body += struct.pack("<8d", x_m, *([0.0] * 7)) + struct.pack("<8d", 1e5 * x_m, *([0.0] * 7))
    return body if version == 1 else body + os.urandom(32) + os.urandom(32)


def endpoint(text):
    host, port = text.rsplit(":", 1)
    return host, int(port)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--controller", type=endpoint, required=True, help="the emulator's HOST:PORT")
    p.add_argument("--node", type=endpoint, help="the node's HOST:PORT, to send it forged replies")
    p.add_argument("--tries", type=int, default=3)
    a = p.parse_args()
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.bind(("127.0.0.1", 0))
    s.settimeout(0.2)
    to_controller, to_node, replies = 0, 0, []
    for _ in range(a.tries):
        for datagram in (command(1, 10**12, 0.2, 1.0), command(1, 0, 0.0, 0.0, query=True),
                         command(2, 10**12, 0.2, 1.0)):
            s.sendto(datagram, a.controller)
            to_controller += 1
            try:
                data, _ = s.recvfrom(512)
                if len(data) >= 24 and data[:4] == b"RPSR":
                    replies.append({"bytes": len(data), "x_m": struct.unpack_from("<d", data, 16)[0]})
            except socket.timeout:
                pass
        if a.node:
            for datagram in (reply(1, 10**12, 0.2), reply(2, 10**12, 0.2)):
                s.sendto(datagram, a.node)
                to_node += 1
    print(json.dumps({"sent_to_controller": to_controller, "sent_to_node": to_node, "replies": replies}))


if __name__ == "__main__":
    main()
