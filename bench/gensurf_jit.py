#!/usr/bin/env python3
"""Side-by-side: a large gensurf, whose cost is evaluating its calcomp curves.

Runs, in one go, Radiance's `gensurf` and `radc gensurf` (and, with --before PATH, an
older radc binary, e.g. one built before the curves were compiled by the JIT) on the
same surface, best of several runs each, checks that every output is byte-identical to
Radiance's, and prints the times and ratios.

Two surfaces, each an N by N grid (default 400, so 401 x 401 points), from one function
file: `sheet`, a bumpy sheet through nested user functions, the spline functions and
library calls, with `valid(s,t)` cutting a hole and `-s` smoothing (printing dominates
its cost); and `terrain`, a 16-term recursive Fourier sum per coordinate (evaluation
dominates). Times are CPU seconds (user + system) of the child, best of R runs, with
wall time beside: the machine is shared, and CPU time is what load disturbs least.

Usage: bench/gensurf_jit.py [--n N] [--runs R] [--radc PATH] [--before PATH]
Needs the oracle (`bash tests/oracle/install.sh`) and a release build of radc
(`cargo build --release --bin radc`).
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time

from radiance import radiance_env

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

SHEET_CAL = """\
{ A bumpy sheet: nested user functions, splines and library calls per point. }
bump(x, y) = .1 * sin(4*PI*x) * cos(3*PI*y) + .05 * exp(-((x-.5)^2 + (y-.5)^2) * 8);
edge(x) = bezier(0, .3, .7, 1, x);
height(s, t) = bump(edge(s), edge(t)) + hermite(0, .2, 1, -1, s*t);
valid(s, t) = (s - .4)^2 + (t - .6)^2 - .01;
wave(x, k) = if(k - .5, sin(k*x + k*k)/(k*k) + wave(x, k - 1), 0);
ridge(s, t) = wave(7*s + 3*t, 16) * wave(5*t - 2*s, 16);
"""

SURFACES = {
    "sheet": ["m", "sheet", "s", "t", "height(s,t)", "-f", "sheet.cal", "-s"],
    "terrain": ["m", "terrain", "s+.1*wave(9*t,16)", "t+.1*wave(8*s,16)", "ridge(s,t)",
                "-f", "sheet.cal"],
}


def best_run(cmd, cwd, env, runs):
    """(best CPU seconds, best wall seconds, stdout of the last run)."""
    best_cpu, best_wall, out = float("inf"), float("inf"), b""
    for _ in range(runs):
        with tempfile.TemporaryFile() as sink, tempfile.TemporaryFile() as err:
            start = time.perf_counter()
            child = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=sink, stderr=err)
            _, status, usage = os.wait4(child.pid, 0)
            wall = time.perf_counter() - start
            child.returncode = os.waitstatus_to_exitcode(status)
            if child.returncode != 0:
                err.seek(0)
                sys.exit(f"{' '.join(cmd)} failed: {err.read().decode()[:500]}")
            sink.seek(0)
            out = sink.read()
        best_cpu = min(best_cpu, usage.ru_utime + usage.ru_stime)
        best_wall = min(best_wall, wall)
    return best_cpu, best_wall, out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=400)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--radc", default=os.path.join(ROOT, "target/release/radc"))
    ap.add_argument("--before", help="an older radc binary to time as well")
    a = ap.parse_args()
    a.radc = os.path.abspath(a.radc)
    a.before = a.before and os.path.abspath(a.before)
    if not os.path.exists(a.radc):
        sys.exit("build radc first: cargo build --release --bin radc")
    env = radiance_env("gensurf")
    failed = False
    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, "sheet.cal"), "w") as f:
            f.write(SHEET_CAL)
        for surface, words in SURFACES.items():
            args = words[:5] + [str(a.n), str(a.n)] + words[5:]
            failed |= compare(surface, args, a, tmp, env)
    return 1 if failed else 0


def compare(surface, args, a, tmp, env):
    """Times one surface with each program; True if an output differs."""
    programs = [("gensurf (Radiance)", ["gensurf"]), ("radc gensurf", [a.radc, "gensurf"])]
    if a.before:
        programs.append(("radc gensurf (before)", [a.before, "gensurf"]))
    results = [(label, *best_run(cmd + args, tmp, env, a.runs)) for label, cmd in programs]
    want = results[0][3]
    print(f"{surface}: gensurf {' '.join(args)}")
    print(f"  best of {a.runs}, load average {os.getloadavg()[0]:.1f}")
    for label, cpu, wall, out in results:
        same = "identical" if out == want else "DIFFERS from Radiance"
        print(f"  {label:24} {cpu:7.3f} s CPU {wall:7.3f} s wall  {len(out)} bytes, {same}")
    base = results[0][1]
    for label, cpu, _, _ in results[1:]:
        print(f"  {label}: {base / cpu:.2f}x Radiance's speed (CPU)")
    if a.before:
        print(f"  JIT against the interpreter: {results[2][1] / results[1][1]:.2f}x (CPU)")
    return any(out != want for _, _, _, out in results)


if __name__ == "__main__":
    sys.exit(main())
