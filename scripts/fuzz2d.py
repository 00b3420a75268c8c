#!/usr/bin/env python3
"""Seeded fuzzer for `gdr 2d` (issue 9): degenerate geometry and mutated input files.

Every run must end with exit 0 and a mesh that --check accepts, or exit 3 with a short
one-line message; never a signal, exit 1 or 5, a timeout, or a changed input file. A run
that breaks this is reported with its seed and input (kept in the work folder) and makes
the script exit 1.

  scripts/fuzz2d.py build/bin/gdr --seed 3 --runs 40 --max-angle 33   # the short run of CI
  scripts/fuzz2d.py build/bin/gdr --seconds 3600 --seed 7 --work /tmp/fuzz   # a long one
"""
import argparse
import math
import os
import random
import subprocess
import sys

from fuzzlib import add_arguments, digest, fuzz, judge, mutate

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.join(HERE, "..", "apps", "gdr", "examples", "gear.poly")


def poly_text(points, segments, holes=(), number_from=1):
    lines = [f"{len(points)} 2 0 0"]
    lines += [f"{i + number_from} {x!r} {y!r}" for i, (x, y) in enumerate(points)]
    lines.append(f"{len(segments)} 0")
    lines += [f"{i + number_from} {a + number_from} {b + number_from}"
              for i, (a, b) in enumerate(segments)]
    lines.append(str(len(holes)))
    lines += [f"{i + number_from} {x!r} {y!r}" for i, (x, y) in enumerate(holes)]
    return ("\n".join(lines) + "\n").encode()


def loop(n, start=0):
    return [(start + i, start + (i + 1) % n) for i in range(n)]


# ---- degenerate geometry ------------------------------------------------------------------

def star(r):  # segments through one point
    n = r.randint(2, 40)
    pts, segs = [], []
    for i in range(n):
        a = math.pi * i / n + r.uniform(-1e-9, 1e-9) * r.choice([0, 1])
        pts += [(math.cos(a), math.sin(a)), (-math.cos(a), -math.sin(a))]
        segs.append((2 * i, 2 * i + 1))
    return pts, segs, []


def cocircular(r):
    n = r.randint(3, 2000)
    pts = [(math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n)) for i in range(n)]
    return pts, (loop(n) if r.random() < 0.5 else []), []


def collinear(r):
    n = r.randint(3, 50)
    pts = [(float(i), 0.0) for i in range(n)] + [(n / 2.0, r.choice([1.0, 1e-8, 1e-15, 1e-30]))]
    segs = [(i, i + 1) for i in range(n - 1)] if r.random() < 0.5 else []
    return pts, segs, []


def fan(r):  # segments from one point at tiny angles
    pts = [(-1.0, -1.0), (3.0, -1.0), (3.0, 3.0), (-1.0, 3.0), (0.0, 0.0)]
    segs = loop(4)
    for _ in range(r.randint(2, 6)):
        a = 10.0 ** -r.uniform(3, 16)
        pts.append((2 * math.cos(a), 2 * math.sin(a)))
        segs.append((4, len(pts) - 1))
    return pts, segs, []


def soup(r):
    n = r.randint(2, 200)
    pts, segs = [], []
    for i in range(n):
        pts += [(r.random(), r.random()), (r.random(), r.random())]
        segs.append((2 * i, 2 * i + 1))
    return pts, segs, []


def thin(r):  # needle triangles and thin rectangles
    h = 10.0 ** -r.uniform(1, 12)
    pts = [(0.0, 0.0), (1.0, 0.0), (1.0, h), (0.0, h)] if r.random() < 0.5 else \
          [(0.0, 0.0), (1.0, 0.0), (0.5, h)]
    return pts, loop(len(pts)), []


def nested(r):  # square rings, hole seeds inside, on segments, on vertices, outside
    pts, segs, holes = [], [], []
    for k in range(r.randint(1, 4)):
        s = 4.0 - k
        base = len(pts)
        pts += [(-s, -s), (s, -s), (s, s), (-s, s)]
        segs += loop(4, base)
    for _ in range(r.randint(0, 3)):
        holes.append(r.choice([(0.0, 0.0), (3.5, 0.0), (4.0, 0.0), (4.0, 4.0), (10.0, 10.0),
                               (r.uniform(-4, 4), r.uniform(-4, 4))]))
    if r.random() < 0.3:
        segs.pop(r.randrange(len(segs)))  # an open chain
    return pts, segs, holes


GENERATORS = [star, cocircular, collinear, fan, soup, thin, nested]


def scaled(r, pts, holes):
    e = r.choice([0, 0, r.randint(-300, 300)])
    s = 10.0 ** e
    return [(x * s, y * s) for x, y in pts], [(x * s, y * s) for x, y in holes]


def options(r, max_angle):
    o = ["--min-angle", str(r.choice([a for a in (0, 10, 20, 25, 30, 33) if a <= max_angle]))]
    if r.random() < 0.3:
        o.append("--remove-exterior")
    if r.random() < 0.2:  # the defaults are Triangle's rules; sometimes the others
        o.append("--no-off-centers")
    if r.random() < 0.2:
        o += ["--mode", "ruppert"]
    if r.random() < 0.2:
        o.append("--strict")
    if r.random() < 0.2:
        o += ["--max-steiner", str(r.choice([0, 10, 1000]))]
    return o


def one_run(gdr, work, seed, timeout, max_angle=33, extra=()):
    r = random.Random(seed)
    if r.random() < 0.6:
        gen = r.choice(GENERATORS)
        pts, segs, holes = gen(r)
        pts, holes = scaled(r, pts, holes)
        data = poly_text(pts, segs, holes)
        what = gen.__name__
    else:
        with open(EXAMPLE, "rb") as f:
            data = mutate(r, f.read())
        what = "mutation"
    inp = os.path.join(work, f"case{seed}.poly")
    out = os.path.join(work, f"case{seed}.vtu")
    with open(inp, "wb") as f:
        f.write(data)
    before = digest(inp)
    cmd = [gdr, "2d", inp, "-o", out, "--check", "--backend", "cpu"] + options(r, max_angle) + list(extra)
    try:
        p = subprocess.run(cmd, capture_output=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return what, cmd, "timeout"
    problem = judge(p.returncode, p.stderr.decode(errors="replace"), out, inp, before)
    if problem is None:
        for f in (inp, out):
            if os.path.exists(f):
                os.remove(f)
    return what, cmd, problem


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_arguments(ap, "fuzz2d", timeout=60)
    ap.add_argument("--max-angle", type=float, default=33,
                    help="largest minimum angle tried (33: Triangle's practical limit)")
    ap.add_argument("--extra", default="", help="more gdr options for every run, e.g. '--cdt parallel'")
    a = ap.parse_args()
    return fuzz("fuzz2d", a, lambda seed: one_run(a.gdr, a.work, seed, a.timeout, a.max_angle, a.extra.split()))


if __name__ == "__main__":
    sys.exit(main())
