#!/usr/bin/env python3
"""Regenerate (or, with --check, verify) the goldens of radc's built-in function files.

radc carries its own rayinit.cal, skybright.cal, perezlum.cal, surf.cal, rev.cal and
tmesh.cal (lang/src/library/). Each name each file defines is evaluated here by the real
rcalc with *Radiance's* file of that name (from pyradiance's lib/), at many points, and
the values are written, bit for bit, to tests/data/library/cases.json.
`tests/library_differential.rs` replays every case through `radc calc` with the same
arguments and no RAYPATH, so radc answers with its built-in text.

The renderer's own names (the ray Dx.., the shading values NxP.., arg(n), noise3 and its
gradient) do not exist in rcalc: each case binds them with -e definitions to input
columns and to smooth stand-in functions, the same on both sides.

Usage (the oracle must be installed, see tests/oracle/install.sh):
    .oracle/bin/python tests/oracle/regen_library_goldens.py           # rewrite goldens
    .oracle/bin/python tests/oracle/regen_library_goldens.py --check   # exit 1 on drift
"""

import json
import math
import os
import random
import struct
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = ROOT / "tests" / "data" / "library" / "cases.json"
POINTS = 200

# Stand-ins for the renderer's noise: smooth, deterministic, different per component.
NOISE = (
    "noise3(x,y,z)=sin(1.3*x+.7*y)*cos(1.1*z-y);"
    "noise3x(x,y,z)=cos(x-2*z)*.8;"
    "noise3y(x,y,z)=sin(y*z+x)*.6;"
    "noise3z(x,y,z)=cos(x*y-z)*.9;"
)


def ray_bindings(first_arg_column: int, nargs: int) -> str:
    """Columns 1-13: D, N, P, NP, RdotP; arg(n) from the columns that follow."""
    names = ["Dx", "Dy", "Dz", "Nx", "Ny", "Nz", "Px", "Py", "Pz", "NxP", "NyP", "NzP", "RdotP"]
    text = "".join(f"{n}=${i + 1};" for i, n in enumerate(names))
    cols = ",".join(f"${first_arg_column + i}" for i in range(nargs))
    text += f"arg(n)=select(n+1,{nargs},{cols});"
    return text + NOISE


def unit(rng, upper=False):
    while True:
        v = [rng.uniform(-1, 1) for _ in range(3)]
        n = math.sqrt(sum(c * c for c in v))
        if 0.1 < n <= 1:
            v = [c / n for c in v]
            if upper:
                v[2] = abs(v[2])
            return v


def ray_row(rng, args):
    """One input record: a ray, a normal, a point, a perturbed normal, RdotP, args."""
    d, n, npert = unit(rng), unit(rng), unit(rng)
    if rng.random() < 0.1:
        n = [0.0, 0.0, rng.choice([-1.0, 1.0])]
    p = [rng.uniform(-5, 5) for _ in range(3)]
    return d + n + p + npert + [rng.uniform(-1, 1)] + args


def fmt(row):
    return " ".join("%.7g" % v for v in row)


# ---------------------------------------------------------------- the cases
# A group is one file with one set of input records; each of its cases is one name
# the file defines, evaluated at every record.


class Columns:
    """Named blocks of input columns after the ray and the arguments, each drawn
    from the range that exercises the functions reading it."""

    def __init__(self, first, rng):
        self.next = first
        self.rng = rng
        self.draws = []

    def block(self, count, draw):
        cols = [f"${self.next + i}" for i in range(count)]
        self.next += count
        self.draws.append((count, draw))
        return cols

    def values(self):
        out = []
        for count, draw in self.draws:
            out += [draw() for _ in range(count)]
        return out


def rayinit_group(rng):
    nargs = 10
    k = Columns(14 + nargs, rng)
    wide = k.block(5, lambda: rng.uniform(-3, 3))
    sign = k.block(2, lambda: rng.choice([-1.0, 0.0, 1.0, rng.uniform(-2, 2)]))
    index = k.block(1, lambda: rng.choice([1, 2, 3, 1.4, 2.6]))
    unitish = k.block(1, lambda: rng.uniform(-1.5, 1.5))
    exparg = k.block(1, lambda: rng.uniform(-130, 5))
    sqarg = k.block(1, lambda: rng.uniform(-2, 3))
    modn = k.block(1, lambda: rng.uniform(-9, 9))
    modd = k.block(1, lambda: rng.choice([-1, 1]) * rng.uniform(0.1, 4))
    dist = k.block(1, lambda: rng.uniform(0, 20))
    t = k.block(1, lambda: rng.uniform(-0.5, 1.5))
    scale = k.block(1, lambda: rng.choice([0.01, 0.1, 0.3, 0.7, 1.0, 1.5, rng.uniform(0.003, 1.2)]))
    prob = k.block(1, lambda: rng.choice([rng.uniform(1e-6, 1 - 1e-6), rng.uniform(0.45, 0.55), 0.5]))
    w = wide
    cases = [(v, v) for v in ["AC"] + [f"A{i}" for i in range(1, 11)]]
    cases += [(f, f"{f}({w[0]},{w[1]},{w[2]})") for f in ["noise3a", "noise3b", "noise3c"]]
    cases.append(("noise3d", f"noise3d({index[0]},{w[0]},{w[1]},{w[2]})"))
    cases += [(f, f"{f}({index[0]})") for f in ["D", "N", "P"]]
    cases.append(("bound", f"bound({unitish[0]},{w[0]},{w[1]})"))
    cases += [(f, f"{f}({unitish[0]})") for f in ["Acos", "Asin"]]
    cases.append(("Atan2", f"Atan2({sign[0]},{sign[1]})"))
    cases.append(("Exp", f"Exp({exparg[0]})"))
    cases.append(("Sqrt", f"Sqrt({sqarg[0]})"))
    cases += [(v, v) for v in ["PI", "DEGREE", "FTINY"]]
    cases += [(f, f"{f}({sign[0]},{sign[1]})") for f in ["and", "or", "xor"]]
    cases += [(f, f"{f}({sign[0]})") for f in ["not", "sgn"]]
    cases += [(f, f"{f}({w[0]})") for f in ["abs", "sq", "frac", "noop", "clip", "noneg"]]
    cases.append(("inside", f"inside({w[0]},{w[1]},{w[2]})"))
    cases += [(f, f"{f}({modn[0]},{modd[0]})") for f in ["mod", "tri"]]
    cases.append(("linterp", f"linterp({t[0]},{w[0]},{w[1]})"))
    rgb = f"({w[0]},{w[1]},{w[2]})"
    cases += [(f, f + rgb) for f in ["red", "green", "blue", "grey", "clip_r", "clip_g", "clip_b", "clipgrey"]]
    cases.append(("dot", "dot(D,N)"))
    cases.append(("cross", f"cross({index[0]},D,P)"))
    cases.append(("fade", f"fade({w[0]},{w[1]},{dist[0]})"))
    cases += [(f, f"{f}({w[0]},{w[1]},{w[2]},{w[3]},{t[0]})") for f in ["hermite", "bezier", "bspline"]]
    turb = f"({w[0]},{w[1]},{w[2]},{scale[0]})"
    cases += [(f, f + turb) for f in ["turbulence", "turbulencex", "turbulencey", "turbulencez"]]
    cases.append(("unif2norm", f"unif2norm({prob[0]})"))
    cases.append(("nrand", f"nrand({modn[0]})"))
    cases += [(v, v) for v in ["U", "V", "Idx", "Idy", "Idz"]]
    cases += [(f, f"{f}({w[0]},{w[1]},{w[2]})") for f in ["Ldx", "Ldy", "Ldz"]]
    rows = [ray_row(rng, [rng.uniform(-3, 3) for _ in range(nargs)]) + k.values() for _ in range(POINTS)]
    return ("rayinit.cal", [], ray_bindings(14, nargs), cases, rows)


def sky_group(rng, file, nargs, names, arg_row):
    rows = []
    for _ in range(POINTS):
        row = ray_row(rng, arg_row())
        if rng.random() < 0.2:  # near and below the horizon
            row[2] = rng.uniform(-0.05, 0.05)
            s = math.sqrt(max(1e-12, 1 - row[2] ** 2) / (row[0] ** 2 + row[1] ** 2 + 1e-300))
            row[0] *= s
            row[1] *= s
        rows.append(row + [rng.uniform(-2, 2) for _ in range(4)])
    x = 14 + nargs
    wmean = f"wmean(${x},${x + 1},${x + 2},${x + 3})"
    cases = [(n, wmean if n == "wmean" else n) for n in names]
    return (file, ["rayinit.cal"], ray_bindings(14, nargs), cases, rows)


def skybright_args(rng):
    sun = unit(rng, upper=True)
    return [rng.choice([1, 2, 3, 4]), rng.uniform(0.5, 5e3), rng.uniform(0.1, 50), rng.uniform(0.5, 5)] + sun


def perez_args(rng):
    sun = unit(rng, upper=True)
    coeffs = [rng.uniform(-1.5, 0), rng.uniform(-1, -0.1), rng.uniform(0, 20), rng.uniform(-4, 0), rng.uniform(-1, 1)]
    return [rng.uniform(0.5, 3e3), rng.uniform(0.1, 50)] + coeffs + sun


def generator_groups(rng):
    out = []
    axis = lambda: float(rng.choice([0, 1, 2]))
    surf = lambda: [axis()] + [rng.uniform(-1, 1) for _ in range(12)]
    rev = lambda: [rng.uniform(-1, 1) for _ in range(4)]
    tmesh = lambda: [axis()] + [rng.uniform(-1, 1) for _ in range(9)]
    for file, nargs, names, gen in [
        ("surf.cal", 13, ["surf_u", "surf_v", "surf_dx", "surf_dy", "surf_dz"], surf),
        ("rev.cal", 4, ["rev_rad", "rev_dr", "rev_dx", "rev_dy", "rev_dz"], rev),
        ("tmesh.cal", 10, ["bu", "bv", "v1", "v2", "v3", "nf", "dx", "dy", "dz", "u", "v"], tmesh),
    ]:
        rows = [ray_row(rng, gen()) for _ in range(POINTS)]
        out.append((file, ["rayinit.cal"], ray_bindings(14, nargs), [(n, n) for n in names], rows))
    return out


def all_groups():
    rng = random.Random(17)
    groups = [rayinit_group(rng)]
    sky = ["cosgamma", "gamma", "zt", "eta", "wmean"]
    groups.append(sky_group(rng, "skybright.cal", 7, sky + ["sunnysky", "cloudysky", "unifsky", "intersky", "skybr"], lambda: skybright_args(rng)))
    groups.append(sky_group(rng, "perezlum.cal", 10, sky + ["intersky", "skybright"], lambda: perez_args(rng)))
    return groups + generator_groups(rng)


# ---------------------------------------------------------------- running rcalc


def rcalc_args(file, before, bindings, expr):
    args = []
    for f in before + [file]:
        args += ["-f", f]
    return args + ["-e", bindings, "-e", f"$1={expr}", "-od"]


def run(oracle: Path, args, rows):
    env = dict(os.environ, LC_ALL="C", RAYPATH=str(oracle / "lib"))
    proc = subprocess.run(
        [str(oracle / "bin" / "rcalc")] + args,
        input="".join(fmt(r) + "\n" for r in rows).encode(),
        capture_output=True,
        env=env,
        timeout=60,
    )
    if proc.returncode != 0:
        raise SystemExit(f"rcalc failed on {args}: {proc.stderr.decode()}")
    n = len(proc.stdout) // 8
    values = struct.unpack(f"<{n}d", proc.stdout)
    if n != len(rows):
        raise SystemExit(f"rcalc gave {n} values for {len(rows)} records: {args}")
    return [struct.pack("<d", v).hex() for v in values], proc.stderr.decode()


def build(oracle: Path):
    groups = []
    for file, before, bindings, cases, rows in all_groups():
        out = []
        for name, expr in cases:
            args = rcalc_args(file, before, bindings, expr)
            values, stderr = run(oracle, args, rows)
            out.append({"name": name, "expr": expr, "expected": values, "warns": bool(stderr)})
        groups.append(
            {
                "file": file,
                "before": before,
                "bindings": bindings,
                "input": "".join(fmt(r) + "\n" for r in rows),
                "cases": out,
            }
        )
    note = "rcalc's values (little-endian f64, hex) with Radiance's own files; see tests/oracle/regen_library_goldens.py"
    return {"note": note, "groups": groups}


def main():
    import pyradiance

    oracle = Path(pyradiance.__file__).parent
    text = json.dumps(build(oracle), indent=0) + "\n"
    if "--check" in sys.argv[1:]:
        if not GOLDEN.exists() or GOLDEN.read_text() != text:
            print(f"{GOLDEN.relative_to(ROOT)} differs from the oracle: rerun without --check")
            sys.exit(1)
        print("library goldens match the oracle")
        return
    GOLDEN.write_text(text)
    print(f"wrote {GOLDEN.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
