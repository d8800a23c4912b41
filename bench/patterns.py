#!/usr/bin/env python3
"""A pattern-heavy scene: `radc render` against `rpict -ps 1`, and the cost of the patterns
(issue 17's speed figures).

bench/data/patterned.rad: a room lit by a ceiling panel and a gensky sky through a glass
window, with noise-based colorfunc, texfunc and brightfunc patterns on the floor, walls,
ceiling and a ball. The same view is rendered by rpict (one ray per pixel, -ps 1 -pj 0)
and by radc (one thread), at -ab 0 and at -ab 1 -aa 0 (pure Monte Carlo in both), and by
radc again on the same scene with every pattern removed (the `void` modifier in their
place). Times are CPU seconds (user + system) of the whole command, best of --runs;
startup (reading, compiling the functions, building the BVH) is timed apart with a 1 x 1
picture and reported in its own column.

Usage (from the repository root; Radiance from PATH, or else the oracle venv):
  python3 bench/patterns.py [--radc target/release/radc] [--size 256] [--runs 3]
"""

import argparse
import os
import re
import resource
import subprocess
import sys
import tempfile

from radiance import radiance_env

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "bench", "data")
SCENE = "patterned.rad"
VIEW = ["-vtv", "-vp", "2", "4.6", "1.6", "-vd", "0", "-1", "-0.25", "-vu", "0", "0", "1",
        "-vh", "70", "-vv", "60"]


def cpu_of(cmd, env, cwd, stdout=subprocess.DEVNULL):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, env=env, cwd=cwd, stdout=stdout, stderr=subprocess.DEVNULL, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def best(runs, f):
    return min(f() for _ in range(runs))


def without_patterns(text):
    """The scene with every pattern's users modified by `void` instead."""
    names = re.findall(r"^void (?:colorfunc|texfunc|brightfunc) (\S+)", text, re.M)
    out = []
    for line in text.splitlines():
        words = line.split()
        if words and words[0] in names:
            line = "void" + line[len(words[0]):]
        if re.match(r"^void (?:colorfunc|texfunc|brightfunc) ", line):
            continue
        out.append(line)
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--radc", default=os.path.join(ROOT, "target", "release", "radc"))
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--runs", type=int, default=3)
    a = ap.parse_args()
    env = radiance_env("rpict", "oconv")
    env["RAYON_NUM_THREADS"] = "1"
    with tempfile.TemporaryDirectory() as tmp:
        for name in ("patterned.rad", "patterned.cal"):
            with open(os.path.join(DATA, name)) as f, open(os.path.join(tmp, name), "w") as g:
                g.write(f.read())
        with open(os.path.join(tmp, "plain.rad"), "w") as g:
            g.write(without_patterns(open(os.path.join(DATA, SCENE)).read()))
        oct_ = os.path.join(tmp, "patterned.oct")
        with open(oct_, "wb") as f:
            subprocess.run(["oconv", SCENE], env=env, cwd=tmp, stdout=f, check=True)
        size = ["-x", str(a.size), "-y", str(a.size)]
        print(f"{a.size}x{a.size} pixels, one thread, best of {a.runs} (CPU seconds)")
        print(f"{'settings':<14}{'rpict':>9}{'radc':>9}{'ratio':>8}{'radc plain':>12}"
              f"{'patterns cost':>15}{'radc startup':>14}")
        for label, opts in (("-ab 0", ["-ab", "0"]),
                            ("-ab 1 -ad 64", ["-ab", "1", "-ad", "64", "-as", "0", "-aa", "0"])):
            common = opts + ["-dj", "0", "-dt", "0"] + VIEW
            rp = best(a.runs, lambda: cpu_of(
                ["rpict", "-ps", "1", "-pj", "0"] + common + size + [oct_], env, tmp))
            rc = best(a.runs, lambda: cpu_of(
                [a.radc, "render"] + common + size + ["-o", "p.hdr", SCENE], env, tmp))
            plain = best(a.runs, lambda: cpu_of(
                [a.radc, "render"] + common + size + ["-o", "q.hdr", "plain.rad"], env, tmp))
            start = best(a.runs, lambda: cpu_of(
                [a.radc, "render"] + common + ["-x", "1", "-y", "1", "-o", "s.hdr", SCENE], env, tmp))
            print(f"{label:<14}{rp:>9.2f}{rc:>9.2f}{rp / rc:>7.1f}x{plain:>12.2f}"
                  f"{(rc - plain) / plain * 100:>14.0f}%{start:>14.3f}")


if __name__ == "__main__":
    sys.exit(main())
