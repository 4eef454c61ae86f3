#!/usr/bin/env python3
"""Crash -> first frame again: the kiosk under a stand-in for systemd's
Restart=always (this machine runs no systemd as PID 1).

Each round starts bodyview with NOTIFY_SOCKET pointing here, waits for READY=1
(sent after the first frame), lets it draw for a moment, kills it with SIGKILL,
waits RestartSec (the unit's 200 ms) and starts it again; the figure is the
time from the kill to the new process's READY=1, RestartSec included.

  bench/restart_first_frame.py BODYVIEW BUNDLE/ [ROUNDS] [-- extra bodyview options]
"""
import os
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import time

RESTART_SEC = 0.2  # packaging/systemd/bodyview.service


def wait_for(sock, prefix, proc, timeout=60.0):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        sock.settimeout(0.01)
        try:
            msg = sock.recv(4096).decode()
            if msg.startswith(prefix):
                return time.monotonic()
        except socket.timeout:
            if proc.poll() is not None:
                raise RuntimeError(f"bodyview exited with {proc.returncode} before {prefix}")
    raise RuntimeError(f"no {prefix} within {timeout} s")


def main():
    args = sys.argv[1:]
    extra = []
    if "--" in args:
        extra = args[args.index("--") + 1:]
        args = args[: args.index("--")]
    bodyview, bundle = args[0], args[1]
    rounds = int(args[2]) if len(args) > 2 else 10
    tmp = tempfile.mkdtemp()
    path = os.path.join(tmp, "notify")
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
    sock.bind(path)
    env = dict(os.environ, NOTIFY_SOCKET=path)
    cmd = [bodyview, "--headless", bundle] + extra

    def start():
        return subprocess.Popen(cmd, env=env, stderr=subprocess.DEVNULL)

    proc = start()
    t0 = time.monotonic()
    first = wait_for(sock, "READY=1", proc) - t0
    times = []
    for _ in range(rounds):
        time.sleep(0.5)  # drawing
        killed = time.monotonic()
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        time.sleep(RESTART_SEC)
        proc = start()
        times.append(wait_for(sock, "READY=1", proc) - killed)
    proc.send_signal(signal.SIGTERM)
    proc.wait()
    os.unlink(path)
    os.rmdir(tmp)
    print(f"cold start to first frame: {first * 1000:.0f} ms")
    print(f"kill -9 -> first frame again ({rounds} rounds, RestartSec {RESTART_SEC * 1000:.0f} ms included): "
          f"median {statistics.median(times) * 1000:.0f} ms, max {max(times) * 1000:.0f} ms, "
          f"min {min(times) * 1000:.0f} ms")


if __name__ == "__main__":
    main()
