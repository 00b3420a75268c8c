"""What the fuzzers and scripts/turned.py share: random rotations, file mutations, and the
judgement of one gdr run (exit 0 with its output, or exit 3 with one short error line;
never a signal, another exit code, or a changed input file)."""
import hashlib
import math
import os
import time

EXTREMES = [b"0", b"-0", b"1e308", b"-1e308", b"1e-308", b"5e-324", b"nan", b"inf", b"-1",
            b"2147483648", b"1e-300", b"1e300", b"0.1", b"3", b"999999999"]


def rotation(rng):
    """A uniformly random rotation matrix, from a random unit quaternion."""
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    w, x, y, z = (a * math.sin(2 * math.pi * u2), a * math.cos(2 * math.pi * u2),
                  b * math.sin(2 * math.pi * u3), b * math.cos(2 * math.pi * u3))
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def mutate(r, data):
    """1-4 random edits of a file's bytes: extreme numbers, dropped or repeated tokens, a
    random byte, a UTF-8 BOM, CR-only lines, a NUL, truncation."""
    tokens = data.split(b" ")
    for _ in range(r.randint(1, 4)):
        kind = r.randrange(8)
        if kind == 0 and tokens:
            tokens[r.randrange(len(tokens))] = r.choice(EXTREMES)
        elif kind == 1 and len(tokens) > 1:
            del tokens[r.randrange(len(tokens))]
        elif kind == 2 and tokens:
            i = r.randrange(len(tokens))
            tokens.insert(i, tokens[i])
        elif kind == 3:
            data = b" ".join(tokens)
            cut = r.randrange(len(data) + 1)
            tokens = (data[:cut] + bytes([r.randrange(256)]) + data[cut:]).split(b" ")
        elif kind == 4:
            tokens = (b"\xef\xbb\xbf" + b" ".join(tokens)).split(b" ")  # UTF-8 BOM
        elif kind == 5:
            tokens = b" ".join(tokens).replace(b"\n", b"\r").split(b" ")  # CR-only lines
        elif kind == 6:
            data = b" ".join(tokens)
            cut = r.randrange(len(data) + 1)
            tokens = (data[:cut] + b"\0" + data[cut:]).split(b" ")
        else:
            data = b" ".join(tokens)
            tokens = data[:r.randrange(len(data) + 1)].split(b" ")  # truncated
    return b" ".join(tokens)


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def judge(returncode, err, out, inp, before):
    """The problem with a finished run, or None: `err` its standard error (text), `out` the
    output it was asked for, `inp` its input and `before` the input's digest."""
    problem = None
    if returncode < 0:
        problem = f"signal {-returncode}"
    elif returncode not in (0, 3):
        problem = f"exit {returncode}: {err.strip()[-400:]}"
    elif returncode == 3:
        lines = [l for l in err.splitlines() if l.startswith("gdr: error:")]
        if len(lines) != 1 or len(lines[0]) > 1500:
            problem = f"exit 3 without one short error line: {err[:300]!r}"
        elif any(ord(c) < 32 and c not in "\t" for c in lines[0]):
            problem = f"raw control bytes in the message: {lines[0][:200]!r}"
    elif not os.path.exists(out):
        problem = "exit 0 without the output"
    if digest(inp) != before:
        problem = "the input file changed"
    return problem


def add_arguments(ap, name, timeout):
    """The command line every fuzzer shares."""
    ap.add_argument("gdr")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--seconds", type=float, default=60)
    ap.add_argument("--runs", type=int, default=0, help="stop after this many runs (0: by time)")
    ap.add_argument("--timeout", type=float, default=timeout, help="seconds per run")
    ap.add_argument("--work", default=f"{name}-work")
    ap.add_argument("--verbose", action="store_true", help="print every run")
    ap.add_argument("--case", type=int, help="run the one case of this seed (as a FAIL line names it)")


def fuzz(name, a, one_run):
    """Runs one_run(seed) -> (what, cmd, problem) from seed a.seed * 1000003 on, for a.runs
    runs or a.seconds; problems starting with "known" are counted apart. Exit status: 1
    when a run failed."""
    os.makedirs(a.work, exist_ok=True)
    start = time.time()
    runs = failures = known = 0
    seed = a.seed * 1000003
    if a.case is not None:
        seed, a.runs, a.verbose = a.case, 1, True
    while (a.runs and runs < a.runs) or (not a.runs and time.time() - start < a.seconds):
        t = time.time()
        what, cmd, problem = one_run(seed)
        runs += 1
        shown = " ".join(cmd[1:2] + cmd[7:])  # the mesher, the backend and the options
        if problem and problem.startswith("known"):
            known += 1
            if a.verbose:
                print(f"{problem} - seed {seed} ({what}): {shown}", flush=True)
        elif problem:
            failures += 1
            print(f"FAIL seed {seed} ({what}): {problem}\n  {' '.join(cmd)}", flush=True)
        elif a.verbose:
            print(f"ok seed {seed} ({what}) {time.time() - t:.1f} s: {shown}", flush=True)
        seed += 1
    print(f"{name}: {runs} runs, {failures} failures, {known} known limitations, {time.time() - start:.0f} s")
    return 1 if failures else 0
