#!/usr/bin/env python3
"""radc's record tools (total, rlam, rsplit, cnt) against Radiance's on the same input,
side by side in one run: best wall time of RUNS runs each, and every output compared
byte for byte (as the goldens are).

Usage: python3 bench/record_tools_vs_radiance.py [--rows 1000000] [--runs 3]
[--radc target/release/radc] (needs the oracle: bash tests/oracle/install.sh).
"""
import argparse, os, shutil, subprocess, sys, tempfile, time

from radiance import radiance_env

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def best(cmd, stdin_path, runs, env, cwd):
    t, out = None, b""
    for _ in range(runs):
        with open(stdin_path, "rb") as fin:
            start = time.perf_counter()
            p = subprocess.run(cmd, stdin=fin, capture_output=True, env=env, cwd=cwd)
            wall = time.perf_counter() - start
        if p.returncode != 0:
            sys.exit(f"{' '.join(cmd)} failed: {p.stderr.decode()[:200]}")
        t = wall if t is None else min(t, wall)
        out = p.stdout
    return t, out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rows", type=int, default=1_000_000)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--radc", default=os.path.join(ROOT, "target", "release", "radc"))
    a = ap.parse_args()
    env = radiance_env("total")
    work = tempfile.mkdtemp()
    try:
        rows = os.path.join(work, "rows.txt")
        with open(rows, "w") as f:
            for i in range(a.rows):
                f.write(f"{(i % 1000) / 7:.6g}\t{(i % 997) / 97 - 5:.6g}\t{i % 13}\n")
        cases = [
            ("total", ["total"]),
            ("total -m -s2", ["total", "-m", "-s2"]),
            ("total -100 -u", ["total", "-100", "-u"]),
            ("rlam rows rows", ["rlam", rows, rows]),
            ("rsplit -t<tab> - . -", ["rsplit", "-t\t", "-", ".", "-"]),
            ("cnt 1000 1000", ["cnt", "1000", "1000"]),
        ]
        print(f"rows: {a.rows}   runs: {a.runs} (best of)   load average: {os.getloadavg()[0]:.1f}")
        print(f"{'program':26} {'Radiance s':>11} {'radc s':>8} {'ratio':>7}  output")
        for label, cmd in cases:
            prog = shutil.which(cmd[0], path=env["PATH"])
            tr, orad = best([prog] + cmd[1:], rows, a.runs, env, work)
            tc, orc = best([a.radc] + cmd, rows, a.runs, env, work)
            print(f"{label:26} {tr:11.3f} {tc:8.3f} {tr / tc:6.2f}x  {'identical' if orad == orc else 'DIFFERS'}")
    finally:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
