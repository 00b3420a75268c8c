#!/usr/bin/env python3
"""Ctrl-C (SIGINT) and SIGTERM stop `gdr 2d` (or another meshing command) cleanly: it says
"gdr: interrupted", exits with 128 + the signal, soon, and leaves an existing output as it
was, with no other file (statistics, temporaries) written.

Usage: interrupt_test.py GDR INPUT WORKDIR [COMMAND OPTION...]
(default: 2d --max-area 1e-6 --backend cpu)

The signal goes out once the progress bar shows refinement iterations (stderr is a
pseudo-terminal, so the bar appears after 0.3 s), into a run that takes tens of seconds."""
import os
import pty
import shutil
import signal
import subprocess
import sys
import time

OLD = b"an output of an earlier run, which must survive\n"


def read_until(fd, token, timeout):
    seen = b""
    end = time.monotonic() + timeout
    while token not in seen and time.monotonic() < end:
        try:
            chunk = os.read(fd, 4096)
        except OSError:  # the child closed the terminal
            break
        if not chunk:
            break
        seen += chunk
    return seen


def check(gdr, poly, work, sig, command):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    with open(os.path.join(work, "out.vtu"), "wb") as f:
        f.write(OLD)
    master, slave = pty.openpty()
    cmd = [gdr, command[0], poly, "-o", "out.vtu", "--stats-json", "s.json"] + command[1:]
    proc = subprocess.Popen(cmd, cwd=work, stdin=subprocess.DEVNULL,
                            stdout=subprocess.DEVNULL, stderr=slave)
    os.close(slave)
    problems = []
    text = read_until(master, b"iteration", 120)
    if b"iteration" not in text:
        problems.append("no refinement iteration shown within 120 s")
    sent = time.monotonic()
    proc.send_signal(sig)
    try:
        rc = proc.wait(timeout=120)
    except subprocess.TimeoutExpired:
        proc.kill()
        rc = proc.wait()
        problems.append("still running 120 s after the signal")
    took = time.monotonic() - sent
    text += read_until(master, b"\0", 5)
    os.close(master)
    lines = text.decode(errors="replace").replace("\r", "\n")
    print(f"{signal.Signals(sig).name}: exit code {rc} after {took:.2f} s")
    print(lines[-400:])
    if rc != 128 + sig:
        problems.append(f"exit code {rc}, expected {128 + sig}")
    if "gdr: interrupted" not in lines:
        problems.append("no 'gdr: interrupted' message")
    if took > 30:
        problems.append(f"took {took:.1f} s to stop")
    with open(os.path.join(work, "out.vtu"), "rb") as f:
        if f.read() != OLD:
            problems.append("the existing out.vtu was replaced")
    left = sorted(set(os.listdir(work)) - {"out.vtu"})
    if left:
        problems.append(f"files written: {left}")
    return [f"{signal.Signals(sig).name}: {p}" for p in problems]


def main():
    gdr, poly, work = (os.path.abspath(a) for a in sys.argv[1:4])
    command = sys.argv[4:] or ["2d", "--max-area", "1e-6", "--backend", "cpu"]
    problems = check(gdr, poly, os.path.join(work, "int"), signal.SIGINT, command)
    problems += check(gdr, poly, os.path.join(work, "term"), signal.SIGTERM, command)
    for p in problems:
        print("FAILED:", p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
