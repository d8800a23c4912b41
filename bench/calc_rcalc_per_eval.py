#!/usr/bin/env python3
"""rcalc's evaluation time per record, for the programs of jit/benches/calc.rs.

rcalc has no way to time evaluation alone, so this runs it on N records of the
bench's input rows twice: with the program, and with a program that only copies the
same number of input columns to the same number of output columns (`$1=$1;...`). The
difference per record is the evaluation (reading and printing cancel out). CPU time
(user + system of the child), best of RUNS, both runs interleaved.

Usage: python3 bench/calc_rcalc_per_eval.py [--rows N] [--runs K]
(needs the oracle: bash tests/oracle/install.sh). Figures: BENCHMARKS.md, "calcomp JIT".
"""
import argparse, math, os, subprocess, sys, tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def oracle():
    py = os.path.join(ROOT, ".oracle", "bin", "python")
    lib = subprocess.check_output(
        [py, "-c", "import pyradiance, os; print(os.path.dirname(pyradiance.__file__))"],
        text=True).strip()
    env = dict(os.environ)
    env["PATH"] = os.path.join(lib, "bin") + os.pathsep + env["PATH"]
    env["RAYPATH"] = "." + os.pathsep + os.path.join(lib, "lib")
    return env, os.path.join(lib, "lib")


def sky(n, z0, dz):
    rows = []
    for i in range(n):
        t = i / n
        a, z = t * 2 * math.pi, z0 + dz * t
        s = math.sqrt(1 - z * z)
        rows.append((math.cos(a) * s, math.sin(a) * s, z))
    return rows


def grid(n, f):
    return [f(i / n) for i in range(n)]


PATTERN = ("Px=$1;Py=$2;Pz=$3;"
           "frac(x) : x - floor(x); and(a,b) : if(a, b, a);"
           "mortar : 0.02; bw : 0.2; bh : 0.1;"
           "row = floor(Pz/bh); shift = if(frac(row/2) - 0.25, 0.5, 0);"
           "bx = frac(Px/bw + shift); bz = frac(Pz/bh);"
           "inbrick = and(bx - mortar/bw, bz - mortar/bh);"
           "grain = 0.9 + 0.1*sin(Px*40 + 3*cos(Pz*25)) * cos(Py*17);"
           "$1 = if(inbrick, grain * (0.7 + 0.3*rand(row*37 + floor(Px/bw + shift))), 0.35)")

# name, rcalc arguments before -e, expression, input rows (64, as the bench), outputs
PROGRAMS = [
    ("skybright.cal", ["-f", "rayinit.cal", "-f", "skybright.cal"],
     "Dx=$1;Dy=$2;Dz=$3;A1=1;A2=3.2;A3=0.2;A4=0.9;A5=0.3;A6=0.4;A7=0.866;$1=skybr",
     sky(64, 0.05, 0.9), 1),
    ("perezlum.cal", ["-f", "rayinit.cal", "-f", "perezlum.cal"],
     "Dx=$1;Dy=$2;Dz=$3;A1=1.2;A2=0.2;A3=-1;A4=-0.32;A5=10;A6=-3;A7=0.45;"
     "A8=0.5;A9=0.1;A10=0.86;$1=skybright",
     sky(64, 0.05, 0.9), 1),
    ("sun.cal", ["-f", "sun.cal"], "MONTH=$1;DAY=$2;TIME=$3;$1=SALT;$2=SAZI;$3=HALFDAY",
     grid(64, lambda t: (1 + math.floor(t * 12), 1 + t * 27, 6 + 12 * t)), 3),
    ("cielab.cal", ["-f", "cielab.cal"],
     "$1=Ls($2);$2=as($1,$2,$3);$3=bs($1,$2,$3);$4=Cs($1,$2,$3);$5=bfunc($1)",
     grid(64, lambda t: (0.1 + t, 0.005 + 0.9 * t, 1.2 - t)), 5),
    ("reinhart.cal", ["-e", "MF:4", "-f", "reinhart.cal"], "Dx=$1;Dy=$2;Dz=$3;$1=rbin;$2=r_row",
     sky(64, 0.02, 0.95), 2),
    ("pattern (bricks)", [], PATTERN,
     grid(64, lambda t: (t * 3.1, 1 - t, t * 1.7)), 1),
    ("two-argument function", [],
     "f(x,y) = sqrt(x*x + y*y) * sin(x) * cos(y) + exp(-x*y/100); $1 = f($1, $2)",
     grid(64, lambda t: (t * 10, 5 - t * 3)), 1),
]


def cpu(cmd, rows_path, env):
    with open(rows_path, "rb") as fin:
        p = subprocess.Popen(cmd, stdin=fin, stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL, env=env)
        _, status, usage = os.wait4(p.pid, 0)
    if status != 0:
        sys.exit(f"failed: {cmd}")
    return usage.ru_utime + usage.ru_stime


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rows", type=int, default=200_000)
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    env, _ = oracle()
    work = tempfile.mkdtemp()
    print(f"{'program':28} {'rcalc us/rec':>12} {'copy us/rec':>12} {'eval ns/rec':>12}")
    for name, pre, expr, rows, nout in PROGRAMS:
        path = os.path.join(work, "rows.txt")
        with open(path, "w") as f:
            for i in range(args.rows):
                f.write(" ".join(f"{v:.17g}" for v in rows[i % len(rows)]) + "\n")
        ncols = len(rows[0])
        copy = ";".join(f"${k}=${(k - 1) % ncols + 1}" for k in range(1, nout + 1))
        full = ["rcalc"] + pre + ["-e", expr]
        base = ["rcalc", "-e", copy]
        best_full = best_base = float("inf")
        for _ in range(args.runs):
            best_full = min(best_full, cpu(full, path, env))
            best_base = min(best_base, cpu(base, path, env))
        per = (best_full - best_base) / args.rows * 1e9
        print(f"{name:28} {best_full / args.rows * 1e6:12.3f} "
              f"{best_base / args.rows * 1e6:12.3f} {per:12.0f}")


if __name__ == "__main__":
    main()
