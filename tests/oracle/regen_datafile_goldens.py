#!/usr/bin/env python3
"""Regenerate (or, with --check, verify) the data-file interpolation goldens.

Radiance interpolates data files inside the renderer only, so the oracle is rtrace: a huge
`glow` polygon at z = 0, modulated by a `brightdata` pattern that reads the data file, seen
by rays pointing straight down. Ray k starts at x = k, so it hits at Px = k, and the function
file maps Px to the k-th query point with `select(Px, ...)`; the query coordinates are
decimal literals that calcomp and Rust parse to the same doubles. With the glow colour 1 and
the identity as the pattern's function, the ray's value is the interpolated value rounded to
single precision, which rtrace prints as a double (`-fad`).

Inputs: every `*.dat` in ../shared/corpus/radiance/test/renders (read in place, never copied)
and the small files in tests/data/datafile. Outputs: tests/data/datafile/goldens/*.golden,
one per input, lines `x1 x2 ... = value`. jit/tests/datafile_oracle.rs replays them.

Also: each file in tests/data/datafile/malformed is loaded the same way with one ray at
coordinate 0.5 (every axis), and tests/data/datafile/malformed.golden records whether Radiance accepted it
(with the value) or the class of its fatal error ("bad format", "unexpected EOF", "bad
number of dimensions").

Usage:
    .oracle/bin/python tests/oracle/regen_datafile_goldens.py           # rewrite goldens
    .oracle/bin/python tests/oracle/regen_datafile_goldens.py --check   # exit 1 on drift

Query points are derived from each file's axes (nodes, cell interiors, points a little and
far outside the domain, points a hair from a node), a full grid up to 3 dimensions and a
seeded sample beyond, so the output is deterministic.
"""

import random
import struct
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
LOCAL = ROOT / "tests" / "data" / "datafile"
GOLDENS = LOCAL / "goldens"
CORPUS = ROOT.parent / "shared" / "corpus" / "radiance" / "test" / "renders"
BATCH = 200
SAMPLE_LIMIT = 400


def oracle_dir() -> Path:
    import pyradiance

    return Path(pyradiance.__file__).parent


def words(text: str):
    """Whitespace-separated words with '#' comments removed, as Radiance's fgetval reads."""
    for line in text.split("\n"):
        yield from line.split("#", 1)[0].split()


def read_axes(text: str):
    """Each axis as a sorted list of its node coordinates (enough to choose query points)."""
    it = words(text)
    ndim = int(next(it))
    axes = []
    for _ in range(ndim):
        begin, end, count = float(next(it)), float(next(it)), int(next(it))
        if begin == end:
            nodes = [float(next(it)) for _ in range(count)]
        else:
            nodes = [begin + (end - begin) * k / (count - 1) for k in range(count)]
        axes.append(sorted(set(nodes)))
    return axes


def fmt(x: float) -> str:
    return f"{x:.6g}"


def axis_samples(nodes):
    """Coordinates that exercise one axis: in cells, on nodes, near and far outside."""
    lo, hi = nodes[0], nodes[-1]
    div = (hi - lo) / max(len(nodes) - 1, 1) or 1.0
    mid = nodes[len(nodes) // 2]
    picks = [
        lo - 7.5 * div,
        lo - 1.5 * div,
        lo - 0.5 * div,
        lo,
        lo + 1e-7 * div,
        lo + 0.37 * div,
        mid,
        lo + 0.61 * (hi - lo),
        hi - 0.25 * div,
        hi,
        hi + 0.5 * div,
        hi + 1.75 * div,
        hi + 40 * div,
        # 2^31 divisions and more: C's (int) conversion gives INT_MIN on x86-64.
        lo + 3e9 * div,
    ]
    # Cell midpoints of unevenly spaced axes, where the spacing matters.
    picks += [(a + b) / 2 for a, b in zip(nodes, nodes[1:])][:4]
    return sorted({fmt(p) for p in picks}, key=float)


def query_points(axes, seed: int):
    samples = [axis_samples(a) for a in axes]
    if len(axes) <= 2:
        grid = [[]]
        for s in samples:
            grid = [g + [v] for g in grid for v in s]
        return grid
    rng = random.Random(seed)
    if len(axes) == 3:
        picked = [rng.sample(s, min(len(s), 7)) for s in samples]
        grid = [[]]
        for s in picked:
            grid = [g + [v] for g in grid for v in sorted(s, key=float)]
        return grid
    points = [[rng.choice(s) for s in samples] for _ in range(SAMPLE_LIMIT // 2)]
    for _ in range(SAMPLE_LIMIT // 2):
        points.append(
            [fmt(rng.uniform(a[0] - 0.3 * (a[-1] - a[0]), a[-1] + 0.3 * (a[-1] - a[0]))) for a in axes]
        )
    return points


SCENE = """void brightdata dpat
{nstr} id {data} query.cal {coords}
0
0
dpat glow dglow
0
0
4 1 1 1 0
dglow polygon floor
0
0
12 -1e7 -1e7 0  1e7 -1e7 0  1e7 1e7 0  -1e7 1e7 0
"""


def run_batch(bin_dir: Path, lib: Path, work: Path, data: Path, points):
    ndim = len(points[0])
    cal = ["id(v) = v;"]
    for d in range(ndim):
        cal.append(f"c{d + 1} = select(Px, {', '.join(p[d] for p in points)});")
    (work / "query.cal").write_text("\n".join(cal) + "\n")
    coords = " ".join(f"c{d + 1}" for d in range(ndim))
    (work / "scene.rad").write_text(SCENE.format(nstr=3 + ndim, data=data.name, coords=coords))
    env = {"PATH": f"{bin_dir}:/usr/bin:/bin", "RAYPATH": f".:{data.parent}:{lib}", "LC_ALL": "C"}
    octree = subprocess.run(
        ["oconv", "scene.rad"], cwd=work, env=env, capture_output=True, check=True
    ).stdout
    (work / "scene.oct").write_bytes(octree)
    rays = "".join(f"{k} 0.5 10 0 0 -1\n" for k in range(1, len(points) + 1))
    proc = subprocess.run(
        ["rtrace", "-h", "-w", "-ov", "-ab", "0", "-fad", "scene.oct"],
        cwd=work,
        env=env,
        input=rays.encode(),
        capture_output=True,
        check=True,
    )
    values = struct.unpack(f"<{len(proc.stdout) // 8}d", proc.stdout)
    if len(values) != 3 * len(points):
        raise SystemExit(f"rtrace returned {len(values)} numbers for {len(points)} rays on {data}")
    return [values[3 * k] for k in range(len(points))]


def sources():
    """(golden name, path, how the golden names it) for every input data file."""
    found = [(f"corpus-{p.stem}", p, f"corpus {p.name}") for p in sorted(CORPUS.glob("*.dat"))]
    found += [(f"local-{p.stem}", p, f"local {p.name}") for p in sorted(LOCAL.glob("*.dat"))]
    return found


def render(bin_dir: Path, lib: Path, name: str, path: Path, label: str) -> str:
    axes = read_axes(path.read_text())
    points = query_points(axes, seed=sum(map(ord, name)))
    lines = [
        "# Generated by tests/oracle/regen_datafile_goldens.py: do not edit.",
        f"# source: {label}",
        f"# {len(axes)} dimensions; each line: coordinates = rtrace's brightdata value (a float)",
    ]
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for start in range(0, len(points), BATCH):
            chunk = points[start : start + BATCH]
            for p, v in zip(chunk, run_batch(bin_dir, lib, work, path, chunk)):
                lines.append(f"{' '.join(p)} = {v!r}")
    return "\n".join(lines) + "\n"


MALFORMED = LOCAL / "malformed"


def malformed_outcome(bin_dir: Path, lib: Path, path: Path) -> str:
    """'accepted <value>' or 'rejected <Radiance's message, without the file name>'."""
    try:
        ndim = int(next(words(path.read_text(errors="replace"))))
    except (StopIteration, ValueError):
        ndim = 1
    ndim = min(max(ndim, 1), 6)
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        (work / "query.cal").write_text("id(v) = v;\n")
        coords = " ".join(["0.5"] * ndim)
        (work / "scene.rad").write_text(SCENE.format(nstr=3 + ndim, data=path.name, coords=coords))
        env = {"PATH": f"{bin_dir}:/usr/bin:/bin", "RAYPATH": f".:{path.parent}:{lib}", "LC_ALL": "C"}
        octree = subprocess.run(
            ["oconv", "scene.rad"], cwd=work, env=env, capture_output=True, check=True
        ).stdout
        (work / "scene.oct").write_bytes(octree)
        proc = subprocess.run(
            ["rtrace", "-h", "-w", "-ov", "-ab", "0", "-fad", "scene.oct"],
            cwd=work,
            env=env,
            input=b"0 0.5 10 0 0 -1\n",
            capture_output=True,
        )
    if proc.returncode == 0 and len(proc.stdout) == 24:
        return f"accepted {struct.unpack('<3d', proc.stdout)[0]!r}"
    message = proc.stderr.decode(errors="replace").strip().split("fatal - ", 1)[-1]
    return f"rejected {message.split(' in data file')[0].split(' for ')[0]}"


def render_malformed(bin_dir: Path, lib: Path) -> str:
    lines = [
        "# Generated by tests/oracle/regen_datafile_goldens.py: do not edit.",
        "# Each line: file: what rtrace did when a brightdata pattern loaded it (coords 0.5).",
    ]
    for path in sorted(MALFORMED.glob("*.dat")):
        lines.append(f"{path.name}: {malformed_outcome(bin_dir, lib, path)}")
    return "\n".join(lines) + "\n"


def main() -> int:
    args = sys.argv[1:]
    if args not in ([], ["--check"]):
        print(__doc__)
        return 2
    check = args == ["--check"]
    radiance = oracle_dir()
    bin_dir, lib = radiance / "bin", radiance / "lib"
    if not CORPUS.is_dir():
        print(f"warning: corpus directory {CORPUS} not found; only local files are checked")
    GOLDENS.mkdir(parents=True, exist_ok=True)
    status = 0
    jobs = [(name, path, label) for name, path, label in sources()]
    jobs.append(("malformed", None, None))
    for name, path, label in jobs:
        golden = LOCAL / "malformed.golden" if path is None else GOLDENS / f"{name}.golden"
        if path is None:
            fresh = render_malformed(bin_dir, lib)
        else:
            fresh = render(bin_dir, lib, name, path, label)
        if not check:
            golden.write_text(fresh)
            points = sum(1 for line in fresh.split("\n") if line and not line.startswith("#"))
            print(f"wrote {golden.relative_to(ROOT)} ({points} entries)")
        elif not golden.exists() or golden.read_text() != fresh:
            old = golden.read_text().split("\n") if golden.exists() else []
            new = fresh.split("\n")
            differing = [n for n in new if n not in old][:5]
            print(f"{golden.relative_to(ROOT)}: differs from rtrace, e.g.:")
            for line in differing:
                print(f"  {line}")
            status = 1
        else:
            print(f"{golden.relative_to(ROOT)}: up to date")
    return status


if __name__ == "__main__":
    sys.exit(main())
