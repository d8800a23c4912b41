#!/usr/bin/env python3
"""Regenerate (or, with --check, verify) the goldens of the renderer's pure functions.

`noise3 noise3x noise3y noise3z fnoise3 erf erfc` exist only inside the renderer, so the
oracle is rtrace: a huge `glow` at z = 0 modulated by a `colorfunc`, seen by rays pointing
straight down. Ray k starts at x = k, so it hits at Px = k, and the function file maps Px
to the k-th query point with `select(Px, ...)`; coordinates are decimal literals that
calcomp and Rust parse to the same doubles.

A pattern's value reaches rtrace's output through single-precision colour, so one channel
would give only 24 bits of the double. To get all 53, each value f is split into three
channels that are exact in single precision: with E about f's binary exponent
(floor(log2|f|), computed in the function file and read back by a first pass),
red = floor(f*2^(22-E)) (|red| < 2^24), green = floor(frac(f*2^(22-E))*2^24) and
blue = frac(frac(f*2^(22-E))*2^24)*2^24. Scaling by a power of two, floor and the
subtraction behind frac are exact in double precision, so
f = (red + (green + blue/2^24)/2^24)/2^(22-E), which this script reconstructs exactly and
checks is a double whose float is what rtrace gave for f alone (rtrace prints the channels
as doubles with `-fad`). An infinite or NaN f keeps the first pass's value.

Output: tests/data/renderer-math/<function>.golden, lines `x y z = value` (one argument
for erf and erfc), value as Python's repr of the double. lang/tests/renderer_math.rs
replays them against radc_lang::cal::renderer_math.

Usage:
    .oracle/bin/python tests/oracle/regen_renderer_math.py           # rewrite goldens
    .oracle/bin/python tests/oracle/regen_renderer_math.py --check   # exit 1 on drift

Query points come from a seeded generator, so the output is deterministic.
"""

import math
import random
import struct
import subprocess
import sys
import tempfile
from fractions import Fraction
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
GOLDENS = ROOT / "tests" / "data" / "renderer-math"
BATCH = 500
NOISE = ["noise3", "noise3x", "noise3y", "noise3z", "fnoise3"]
ERF = ["erf", "erfc"]

SCENE = """void colorfunc probe
4 red green blue probe.cal
0
0
probe glow lamp
0
0
4 1 1 1 0
lamp polygon floor
0
0
12 -1e7 -1e7 0  1e7 -1e7 0  1e7 1e7 0  -1e7 1e7 0
"""

# About the binary exponent of v (log rounds, so within one), 0 for v = 0 or NaN.
EXPONENT = "E = if(abs(v) - 1e-300, floor(log(abs(v))/log(2)), 0);\n"

# The channels of the exact split (see the module docstring).
SPLIT = """scale = 2^(22 - E);
hi = floor(v*scale);
r1 = v*scale - hi;
mid = floor(r1*16777216);
red = hi;
green = mid;
blue = (r1*16777216 - mid)*16777216;
"""


def oracle_dir() -> Path:
    import pyradiance

    return Path(pyradiance.__file__).parent


def lit(x: float) -> str:
    """An expression calcomp evaluates to exactly x: the shortest round-trip decimal, or
    for the values no literal spells, sqrt(-1) (NaN in the reference build) and exp(1000)."""
    if math.isnan(x):
        return "sqrt(-1)"
    if math.isinf(x):
        return "exp(1000)" if x > 0 else "-exp(1000)"
    return repr(float(x)).replace("e+", "e")


def text(x: float) -> str:
    """How a golden spells an argument: Python's repr, which Rust's f64 parser reads."""
    return repr(float(x))


def noise_points():
    """Coordinates for the noise functions: lattice points, steps of EPSILON across cell
    walls, the unit cube, negatives, large (1e4..1e6) and huge (beyond 2^31) values."""
    rng = random.Random(17)
    pts = []
    lattice = [-257.0, -3.0, -1.0, 0.0, 1.0, 2.0, 255.0, 256.0]
    for _ in range(120):
        pts.append(tuple(rng.choice(lattice) for _ in range(3)))
    for _ in range(150):
        base = [float(rng.randint(-20, 20)) for _ in range(3)]
        off = [rng.choice([0.0, 1e-9, -1e-9, 0.0005, -0.0005, 0.00025, 0.5]) for _ in range(3)]
        pts.append(tuple(b + o for b, o in zip(base, off)))
    for _ in range(700):
        pts.append(tuple(rng.uniform(-10, 10) for _ in range(3)))
    for _ in range(200):
        pts.append(tuple(rng.uniform(-1000, 1000) for _ in range(3)))
    for _ in range(450):
        pts.append(tuple(rng.choice([-1, 1]) * 10 ** rng.uniform(4, 6) for _ in range(3)))
    edges = [2147483647.5, 2147483648.0, -2147483648.0, -2147483648.5, -2147483649.0]
    for _ in range(60):
        pts.append(tuple(rng.choice(edges) if rng.random() < 0.5 else rng.uniform(-5, 5) for _ in range(3)))
    for _ in range(120):
        pts.append(tuple(rng.choice([-1, 1]) * 10 ** rng.uniform(9.4, 12) for _ in range(3)))
    # fnoise3 scales by 2000 into C longs: around 2^63/2000 the conversion saturates.
    for _ in range(40):
        pts.append(tuple(rng.choice([-1, 1]) * 10 ** rng.uniform(15, 17) for _ in range(3)))
    pts = list(dict.fromkeys(tuple(float(c) for c in p) for p in pts))
    return [list(p) for p in pts]


# Non-finite coordinates, for the functions that keep no state between calls.
NON_FINITE = [
    (math.nan, 0.5, 0.5),
    (0.5, math.nan, 0.5),
    (math.nan, math.nan, math.nan),
    (math.inf, 0.5, 0.5),
    (0.5, -math.inf, 0.5),
    (0.5, 0.5, math.inf),
]


def cache_sequence():
    """Points in an order that shows noise3.c's one-point cache: the reference build
    compares coordinates without NaN checks, so a NaN coordinate reuses the previous
    point's values, and a cached NaN point matches whatever follows."""
    return [
        [math.nan, 1.25, 2.5],  # a cold cache computes the NaN point
        [0.5, 1.25, 2.5],  # matches the cached NaN: the NaN point's value again
        [0.5, 1.25, 2.5],
        [3.75, -1.5, 0.25],  # differs from a NaN-free cache: computed
        [math.nan, -1.5, 0.25],  # the previous point's value
        [math.nan, math.nan, math.nan],
        [-7.125, 4.0625, 9.5],
        [-7.125, math.nan, 9.5],
        [-7.125, 4.0625, math.nan],
        [1.0, 2.0, 3.5],
        [1.0, 2.0, 3.5],
        [math.inf, 2.0, 3.5],
        [math.inf, 2.0, 3.5],
    ]


def erf_points():
    rng = random.Random(29)
    xs = [0.0, 0.5, -0.5, 10.0, -10.0, 1e-300, -1e-300, 1e-8, 0.49999999999999994, 9.999999999999998]
    xs += [k / 8 for k in range(-100, 101)]
    xs += [rng.uniform(-12, 12) for _ in range(300)]
    xs += [rng.uniform(-0.6, 0.6) for _ in range(150)]
    xs += [rng.choice([-1, 1]) * 10 ** rng.uniform(-12, 3) for _ in range(100)]
    xs = list(dict.fromkeys(float(x) for x in xs))
    return [[x] for x in xs + [math.nan, math.inf, -math.inf]]


def run(bin_dir: Path, lib: Path, work: Path, cal: str, count: int):
    """rtrace's three channels for rays 1..count against a scene whose colorfunc is cal."""
    (work / "probe.cal").write_text(cal)
    (work / "scene.rad").write_text(SCENE)
    env = {"PATH": f"{bin_dir}:/usr/bin:/bin", "RAYPATH": f".:{lib}", "LC_ALL": "C"}
    octree = subprocess.run(["oconv", "scene.rad"], cwd=work, env=env, capture_output=True, check=True).stdout
    (work / "scene.oct").write_bytes(octree)
    rays = "".join(f"{k} 0.5 10 0 0 -1\n" for k in range(1, count + 1))
    proc = subprocess.run(
        ["rtrace", "-h", "-w", "-ov", "-ab", "0", "-dj", "0", "-fad", "scene.oct"],
        cwd=work,
        env=env,
        input=rays.encode(),
        capture_output=True,
        check=True,
    )
    values = struct.unpack(f"<{len(proc.stdout) // 8}d", proc.stdout)
    if len(values) != 3 * count:
        raise SystemExit(f"rtrace returned {len(values)} numbers for {count} rays")
    return [values[3 * k : 3 * k + 3] for k in range(count)]


def to_float32(f: float) -> float:
    """f rounded to single precision, as C's double-to-float conversion rounds it."""
    try:
        return struct.unpack("<f", struct.pack("<f", f))[0]
    except OverflowError:
        return math.copysign(math.inf, f)


def selects(points):
    names = ["px", "py", "pz"][: len(points[0])]
    return "".join(
        f"{n} = select(Px, {', '.join(lit(p[d]) for p in points)});\n" for d, n in enumerate(names)
    ), ", ".join(names)


def evaluate(bin_dir: Path, lib: Path, work: Path, func: str, points):
    """rtrace's double value of func at each point, exactly (see the module docstring)."""
    coords, args = selects(points)
    value = f"v = {func}({args});\n" + EXPONENT
    rough = run(bin_dir, lib, work, coords + value + "red = E;\ngreen = v;\nblue = 0;\n", len(points))
    split = run(bin_dir, lib, work, coords + value + SPLIT, len(points))
    out = []
    for (e, r, _), (hi, mid, lo) in zip(rough, split):
        if not all(map(math.isfinite, (hi, mid, lo))):
            # v is infinite or NaN: the float is the whole answer.
            out.append(r)
            continue
        exact = (Fraction(hi) + (Fraction(mid) + Fraction(lo) / 2**24) / 2**24) / Fraction(2) ** int(22 - e)
        f = float(exact)
        if Fraction(f) != exact or r != to_float32(f):
            raise SystemExit(f"{func}: the channel split of {r!r} did not reconstruct a double")
        out.append(f)
    return out


def render(bin_dir: Path, lib: Path, func: str, points, what: str) -> str:
    lines = [
        "# Generated by tests/oracle/regen_renderer_math.py: do not edit.",
        f"# {func}: {what}",
        "# each line: arguments = rtrace's value in double precision (exact split)",
    ]
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for start in range(0, len(points), BATCH):
            chunk = points[start : start + BATCH]
            for p, v in zip(chunk, evaluate(bin_dir, lib, work, func, chunk)):
                lines.append(f"{' '.join(map(text, p))} = {v!r}")
    return "\n".join(lines) + "\n"


def main() -> int:
    args = sys.argv[1:]
    if args not in ([], ["--check"]):
        print(__doc__)
        return 2
    check = args == ["--check"]
    radiance = oracle_dir()
    bin_dir, lib = radiance / "bin", radiance / "lib"
    GOLDENS.mkdir(parents=True, exist_ok=True)
    status = 0
    points = noise_points()
    jobs = [(f, f, points, "finite points") for f in NOISE[:4]]
    jobs += [("fnoise3", "fnoise3", points + [list(p) for p in NON_FINITE], "finite and non-finite points")]
    jobs += [(f, f, erf_points(), "finite and non-finite arguments") for f in ERF]
    what = "one rtrace process, rays in this order, so noise3.c's cache carries over"
    jobs += [(f"{f}-cache", f, cache_sequence(), what) for f in NOISE[:4]]
    for name, func, points, what in jobs:
        golden = GOLDENS / f"{name}.golden"
        fresh = render(bin_dir, lib, func, points, what)
        if not check:
            golden.write_text(fresh)
            print(f"wrote {golden.relative_to(ROOT)} ({len(points)} points)")
        elif not golden.exists() or golden.read_text() != fresh:
            old = golden.read_text().split("\n") if golden.exists() else []
            differing = [n for n in fresh.split("\n") if n not in old][:5]
            print(f"{golden.relative_to(ROOT)}: differs from rtrace, e.g.:")
            for line in differing:
                print(f"  {line}")
            status = 1
        else:
            print(f"{golden.relative_to(ROOT)}: up to date")
    return status


if __name__ == "__main__":
    sys.exit(main())
