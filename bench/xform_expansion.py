#!/usr/bin/env python3
"""Side-by-side: expanding a scene of many `!xform` lines.

Radiance's oconv runs each `!xform` line through the shell (a process per line);
radc expands the built-in generators in-process. This script makes a scene with N
`!xform` lines placing copies of a small object file, then times, in one run,
`oconv scene.rad > /dev/null` and `radc check scene.rad` (expansion plus every check),
best of several runs each, and prints the ratio.

Usage: bench/xform_expansion.py [N] [runs]      (default N=10000, runs=3)
Needs the oracle (`bash tests/oracle/install.sh`) and a release build of radc
(`cargo build --release`).
"""

import os
import subprocess
import sys
import tempfile
import time

from radiance import radiance_env

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def best_time(cmd, cwd, env, runs):
    best = float("inf")
    for _ in range(runs):
        start = time.perf_counter()
        result = subprocess.run(cmd, cwd=cwd, env=env, stdout=subprocess.DEVNULL,
                                stderr=subprocess.PIPE)
        elapsed = time.perf_counter() - start
        if result.returncode not in (0,):
            sys.exit(f"{' '.join(cmd)} failed: {result.stderr.decode()[:500]}")
        best = min(best, elapsed)
    return best


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 10000
    runs = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    radc = os.path.join(ROOT, "target/release/radc")
    if not os.path.exists(radc):
        sys.exit("build radc first: cargo build --release")
    env = radiance_env("xform")
    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, "chair.rad"), "w") as f:
            f.write(subprocess.run(["genbox", "wood", "seat", ".5", ".5", ".05"],
                                   capture_output=True, text=True, env=env,
                                   check=True).stdout)
        with open(os.path.join(tmp, "scene.rad"), "w") as f:
            f.write("void plastic wood 0 0 5 .4 .3 .2 0 0\n")
            for i in range(n):
                x, y = i % 100, i // 100
                f.write(f"!xform -n c{i} -rz {i % 360} -t {x} {y} 0 chair.rad\n")
        t_oconv = best_time(["oconv", "scene.rad"], tmp, env, runs)
        t_radc = best_time([radc, "check", "--quiet", "scene.rad"], tmp, env, runs)
    print(f"{n} !xform lines, best of {runs}")
    print(f"{'program':<28}{'seconds':>10}")
    print(f"{'oconv scene.rad':<28}{t_oconv:>10.3f}")
    print(f"{'radc check scene.rad':<28}{t_radc:>10.3f}")
    print(f"radc is {t_oconv / t_radc:.1f}x faster")


if __name__ == "__main__":
    main()
