#!/usr/bin/env python3
"""radc calc against rcalc on the same rows, side by side in one run.

Writes ROWS rows of two columns, then runs each configuration RUNS times on them and
reports the best wall time and the best CPU time (user + system of the child), and
checks that every output is byte-identical to rcalc's:

    radc calc --interp --threads 1   the reference interpreter, one thread
    radc calc --threads 1            the Cranelift JIT, one thread
    radc calc                        the JIT on every core (records in chunks)
    rcalc                            Radiance (pyradiance), one thread by design

Usage: python3 bench/calc_vs_rcalc.py [--rows N] [--runs K] [--no-build] [--radc BIN]
[--before OLD_BIN] (--before runs an older build's three configurations in the same
rounds, for before/after figures)
(needs the oracle for rcalc: bash tests/oracle/install.sh). Figures go to
BENCHMARKS.md, section "radc calc vs rcalc".
"""
import argparse, os, resource, shutil, subprocess, sys, tempfile, time

from radiance import radiance_env

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXPR = "f(x,y) = if(x-y, sqrt(x*x + y*y) * sin(x) * cos(y), exp(-x*y/100)); $1 = f($1, $2)"


def timed(cmd, stdin_path, out_path, env):
    """Wall seconds and CPU seconds (user + system) of one run."""
    with open(stdin_path, "rb") as fin, open(out_path, "wb") as fout:
        start = time.perf_counter()
        p = subprocess.Popen(cmd, stdin=fin, stdout=fout, stderr=subprocess.DEVNULL, env=env)
        _, status, usage = os.wait4(p.pid, 0)
        wall = time.perf_counter() - start
    if status != 0:
        sys.exit(f"{cmd[0]} failed (status {status})")
    return wall, usage.ru_utime + usage.ru_stime


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rows", type=int, default=1_000_000)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--no-build", action="store_true")
    ap.add_argument("--radc", default=os.path.join(ROOT, "target", "release", "radc"))
    ap.add_argument("--before", help="another radc binary (an older build) to run alongside")
    args = ap.parse_args()
    if not args.no_build:
        subprocess.check_call(["cargo", "build", "--release", "--quiet", "--bin", "radc"], cwd=ROOT)
    radc = args.radc
    env = radiance_env("rcalc")
    rcalc = shutil.which("rcalc", path=env["PATH"])
    work = tempfile.mkdtemp()
    try:
        rows = os.path.join(work, "in.txt")
        with open(rows, "w") as f:
            for i in range(args.rows):
                f.write(f"{(i % 1000) / 100:.6f}\t{(i % 997) / 97 - 5:.6f}\n")
        configs = [
            ("radc calc --interp --threads 1", [radc, "calc", "--interp", "--threads", "1", "-e", EXPR]),
            ("radc calc --threads 1 (JIT)", [radc, "calc", "--threads", "1", "-e", EXPR]),
            (f"radc calc (JIT, {os.cpu_count()} cores)", [radc, "calc", "-e", EXPR]),
        ]
        if args.before:
            b = args.before
            configs += [
                ("before: radc calc --interp --threads 1", [b, "calc", "--interp", "--threads", "1", "-e", EXPR]),
                ("before: radc calc --threads 1 (JIT)", [b, "calc", "--threads", "1", "-e", EXPR]),
                (f"before: radc calc (JIT, {os.cpu_count()} cores)", [b, "calc", "-e", EXPR]),
            ]
        if rcalc:
            configs.append(("rcalc (Radiance)", [rcalc, "-e", EXPR]))
        best = {}
        for run in range(args.runs):
            for label, cmd in configs:
                wall, cpu = timed(cmd, rows, os.path.join(work, label[:4] + str(len(best))), env)
                b = best.setdefault(label, [wall, cpu])
                b[0], b[1] = min(b[0], wall), min(b[1], cpu)
        # Outputs, from one more run each, compared byte for byte.
        outs = {}
        for label, cmd in configs:
            path = os.path.join(work, f"out{len(outs)}")
            timed(cmd, rows, path, env)
            outs[label] = open(path, "rb").read()
        load = os.getloadavg()[0]
        print(f"rows: {args.rows}   runs: {args.runs} (best of)   load average: {load:.1f}")
        print(f"expression: {EXPR}")
        ref = best.get("rcalc (Radiance)")
        print(f"{'program':44} {'wall s':>8} {'cpu s':>8}  {'vs rcalc (wall, cpu)':>22}")
        for label, _ in configs:
            wall, cpu = best[label]
            ratio = f"{ref[0] / wall:8.2f}x {ref[1] / cpu:8.2f}x" if ref else ""
            print(f"{label:44} {wall:8.3f} {cpu:8.3f}  {ratio:>22}")
        want = outs.get("rcalc (Radiance)", next(iter(outs.values())))
        for label, data in outs.items():
            print(f"output of {label}: {'identical to rcalc' if data == want else 'DIFFERS'}")
        if any(d != want for d in outs.values()):
            sys.exit(1)
    finally:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
