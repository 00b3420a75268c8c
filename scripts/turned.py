#!/usr/bin/env python3
"""Meshes turned, scaled and moved copies of inputs: closed surfaces (.off) with `gdr tet` and
`gdr rdt`, planar straight-line graphs (.poly) with `gdr 2d`.

Real parts and maps come at any orientation and size: a copy turned by a random rotation is
straight or planar only up to rounding where the original was exactly so. Each copy is
meshed with --check on the CPU backend; a run that crashes, times out or fails --check makes
the script exit 1 (a clear refusal, exit 3, counts as a failure too). The bad volume or area
each run leaves is printed beside it (the README's "CAD parts turned to an angle" was
measured with this script).

  scripts/turned.py build/bin/gdr --seed 5 --trials 3 ../shared/data/surfaces/fandisk.off
  scripts/turned.py build/bin/gdr --seed 3 --trials 2 ../shared/data/pslg/*.poly
"""
import argparse
import math
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time

from fuzzlib import rotation


def read_off(path):
    tokens = " ".join(line.split("#")[0] for line in open(path)).split()
    if tokens[0] != "OFF":
        raise SystemExit(f"{path}: not an OFF file")
    nv, nf = int(tokens[1]), int(tokens[2])
    i = 4
    points = [tuple(map(float, tokens[i + 3 * k:i + 3 * k + 3])) for k in range(nv)]
    i += 3 * nv
    faces = []
    for _ in range(nf):
        n = int(tokens[i])
        faces.append(tokens[i + 1:i + 1 + n])
        i += 1 + n
    return points, faces


def read_poly(path):
    """The .poly's lines without comments, and where its coordinates are: (line, column)."""
    lines = [l.split("#")[0].split() for l in open(path)]
    lines = [l for l in lines if l]
    coords = []
    nv = int(lines[0][0])
    coords += [(1 + i, 1) for i in range(nv)]
    at = 1 + nv
    ns = int(lines[at][0])
    at += 1 + ns
    if at < len(lines):
        nh = int(lines[at][0])
        coords += [(at + 1 + i, 1) for i in range(nh)]
        at += 1 + nh
    if at < len(lines):
        nr = int(lines[at][0])
        coords += [(at + 1 + i, 1) for i in range(nr)]
    return lines, coords


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("gdr")
    ap.add_argument("surfaces", nargs="+", help=".off or .poly files")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--trials", type=int, default=3, help="copies per surface")
    ap.add_argument("--timeout", type=float, default=600, help="seconds per run")
    ap.add_argument("--keep", help="folder to copy the inputs of failed runs into")
    args = ap.parse_args()
    rng = random.Random(args.seed)
    runs3d = (["tet", "--radius-edge", "1.4"], ["tet", "--radius-edge", "2"],
              ["tet", "--radius-edge", "1.4", "--sliver-angle", "20"], ["rdt"])
    runs2d = (["2d", "-pcq20"], ["2d", "-pcq30"], ["2d", "-pq25"])
    failures = 0
    with tempfile.TemporaryDirectory() as work:
        for path in args.surfaces:
            name, ext = os.path.splitext(os.path.basename(path))
            planar = ext == ".poly"
            if planar:
                lines, coords = read_poly(path)
            else:
                points, faces = read_off(path)
            for trial in range(args.trials):
                R = rotation(rng)
                scale = 10 ** rng.uniform(-6, 6)
                move = [rng.uniform(-1, 1) * 10 ** rng.uniform(0, 5) * scale for _ in range(3)]
                copy = os.path.join(work, f"{name}_{trial}{ext}")
                with open(copy, "w") as out:
                    if planar:
                        turned = [list(l) for l in lines]
                        a = math.atan2(R[1][0], R[0][0])  # a turn in the plane
                        for row, col in coords:
                            x, y = float(lines[row][col]), float(lines[row][col + 1])
                            turned[row][col] = repr(scale * (math.cos(a) * x - math.sin(a) * y) + move[0])
                            turned[row][col + 1] = repr(scale * (math.sin(a) * x + math.cos(a) * y) + move[1])
                        out.write("\n".join(" ".join(l) for l in turned) + "\n")
                    else:
                        out.write(f"OFF\n{len(points)} {len(faces)} 0\n")
                        for p in points:
                            q = [scale * sum(R[i][k] * p[k] for k in range(3)) + move[i] for i in range(3)]
                            out.write("%r %r %r\n" % tuple(q))
                        for f in faces:
                            out.write(f"{len(f)} {' '.join(f)}\n")
                for run in runs2d if planar else runs3d:
                    cmd = [args.gdr, run[0], copy, "--check", "--backend", "cpu"] + run[1:]
                    start = time.time()
                    try:
                        r = subprocess.run(cmd, capture_output=True, text=True, timeout=args.timeout)
                        rc, text = r.returncode, r.stdout + r.stderr
                    except subprocess.TimeoutExpired:
                        rc, text = "timeout", ""
                    bad = re.findall(r"(\d[\d,]*) bad \(([\d.]+)% of the (?:volume|area)\)", text)
                    verdict = "ok" if rc == 0 else "FAILED"
                    failures += rc != 0
                    print(f"{name} copy {trial} (scale {scale:.2g}) {' '.join(run)}: {verdict} rc={rc}, "
                          f"{time.time() - start:.1f} s, bad " + (f"{bad[-1][0]} ({bad[-1][1]}%)" if bad else "-"),
                          flush=True)
                    if rc != 0:
                        print("\n".join(text.splitlines()[-5:]))
                        if args.keep:
                            os.makedirs(args.keep, exist_ok=True)
                            shutil.copy(copy, args.keep)
    print(f"turned: {failures} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
