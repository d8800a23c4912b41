#!/usr/bin/env python3
"""`radc trace` against Radiance's `rtrace` on a large mesh: start-up (reading the
mesh, building its tree), rays per second on one core with the start-up measured apart,
and peak memory, for one `mesh` and for ten `mesh` primitives placing the same file.

The mesh is a smoothed terrain with (u,v): an N x N grid (default 1000: 2,000,000
triangles, 1,002,001 vertices) written as a Wavefront file and compiled by Radiance's
own obj2mesh (its time is reported too). rtrace gets the scene as an octree made by
oconv; radc reads the scene text. Rays: a fixed seed, from above the terrain, the same
text file for both; `-h -ov -ab 0 -dj 0 -n 1`.

Times are CPU time (user + system, from wait4), best of --runs; memory is the peak
resident set (wait4's ru_maxrss). Rays per second = rays / (time with the rays - time
with no rays).

Usage (from the repository root):
  cargo build --release --bin radc
  python3 bench/mesh_vs_radiance.py [--grid 1000] [--rays 200000] [--runs 3] [--keep DIR]
"""

import argparse
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from radiance import radiance_env

ROOT = Path(__file__).resolve().parent.parent
SETTINGS = ["-h", "-ov", "-ab", "0", "-dj", "0", "-n", "1"]


def write_terrain(path, n):
    """A height field 100 x 100 with analytic normals and (u,v) in [0,1]."""
    with open(path, "w") as f:
        for j in range(n + 1):
            for i in range(n + 1):
                s, t = i / n, j / n
                z = math.sin(s * 20) * math.cos(t * 17) * 3 + 5
                f.write(f"v {s * 100:.6f} {t * 100:.6f} {z:.6f}\n")
        for j in range(n + 1):
            for i in range(n + 1):
                f.write(f"vt {i / n:.6f} {j / n:.6f}\n")
        for j in range(n + 1):
            for i in range(n + 1):
                s, t = i / n, j / n
                dx = math.cos(s * 20) * 20 * math.cos(t * 17) * 3 / 100
                dy = -math.sin(s * 20) * math.sin(t * 17) * 17 * 3 / 100
                ln = math.sqrt(dx * dx + dy * dy + 1)
                f.write(f"vn {-dx / ln:.6f} {-dy / ln:.6f} {1 / ln:.6f}\n")
        for j in range(n):
            for i in range(n):
                a = j * (n + 1) + i + 1
                b, c, d = a + 1, a + n + 2, a + n + 1
                f.write(f"f {a}/{a}/{a} {b}/{b}/{b} {c}/{c}/{c}\n")
                f.write(f"f {a}/{a}/{a} {c}/{c}/{c} {d}/{d}/{d}\n")


SUN = "void light sunlight 0 0 3 6e6 6e6 5.5e6\nsunlight source sun 0 0 4 0.4 0.3 0.85 0.5\n"


def scenes():
    one = SUN + "void plastic mat 0 0 5 .5 .5 .5 0 0\nmat mesh terrain 1 terrain.rtm 0 0\n"
    ten = SUN + "void plastic mat 0 0 5 .5 .5 .5 0 0\n"
    for k in range(10):
        ten += (f"mat mesh terrain{k} 7 terrain.rtm -s .3 -t {(k % 5) * 32:.0f} "
                f"{(k // 5) * 32:.0f} 0 0 0\n")
    return {"one mesh": one, "ten meshes": ten}


def measure(cmd, stdin_path, env, cwd, runs):
    """Best CPU time of `runs` runs and the peak resident set (MB) of the best."""
    best = (math.inf, 0.0)
    for _ in range(runs):
        with open(stdin_path, "rb") as inp, tempfile.TemporaryFile() as out, \
                tempfile.TemporaryFile() as err:
            p = subprocess.Popen(cmd, stdin=inp, stdout=out, stderr=err, env=env, cwd=cwd)
            _, status, usage = os.wait4(p.pid, 0)
            if os.waitstatus_to_exitcode(status) != 0:
                err.seek(0)
                sys.exit(f"{' '.join(cmd)} failed:\n{err.read().decode(errors='replace')}")
            out.seek(0)
            stdout = out.read()
        t = usage.ru_utime + usage.ru_stime
        if t < best[0]:
            best = (t, usage.ru_maxrss / 1024, stdout)
    return best


def agreement(a, b):
    a, b = [float(w) for w in a.split()], [float(w) for w in b.split()]
    if len(a) != len(b):
        return f"different counts: {len(a)} vs {len(b)}"
    bad = sum(1 for x, y in zip(a, b) if abs(x - y) > max(1e-3 * max(abs(x), abs(y)), 1e-6))
    return f"{len(a) - bad}/{len(a)} numbers agree to 1e-3"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--grid", type=int, default=1000)
    ap.add_argument("--rays", type=int, default=200_000)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--radc", default=str(ROOT / "target" / "release" / "radc"))
    ap.add_argument("--keep", help="write the files here and keep them")
    args = ap.parse_args()
    env = radiance_env("rtrace", "obj2mesh", "oconv")
    radc = str(Path(args.radc).resolve())
    d = Path(args.keep or tempfile.mkdtemp(prefix="radc-mesh-bench-"))
    d.mkdir(parents=True, exist_ok=True)
    try:
        write_terrain(d / "terrain.obj", args.grid)
        t0 = time.perf_counter()
        subprocess.run(["obj2mesh", "terrain.obj", "terrain.rtm"], cwd=d, env=env, check=True)
        obj2mesh_s = time.perf_counter() - t0
        rng = random.Random(3)
        with open(d / "rays.txt", "w") as f:
            for _ in range(args.rays):
                f.write(f"{rng.uniform(0, 100):.5f} {rng.uniform(0, 100):.5f} 15 "
                        f"{rng.uniform(-1, 1):.6f} {rng.uniform(-1, 1):.6f} -1\n")
        (d / "empty.txt").write_text("")
        print(f"{args.grid * args.grid * 2:,} triangles; obj2mesh {obj2mesh_s:.1f} s; "
              f"{args.rays:,} rays, best of {args.runs}; load {os.getloadavg()[0]:.1f}")
        print()
        print("| scene | program | start-up | rays/s (one core) | peak memory | radc / rtrace |")
        print("|---|---|---:|---:|---:|---|")
        for name, text in scenes().items():
            stem = name.replace(" ", "_")
            (d / f"{stem}.rad").write_text(text)
            with open(d / f"{stem}.oct", "wb") as f:
                subprocess.run(["oconv", f"{stem}.rad"], cwd=d, env=env, stdout=f, check=True)
            rows = {}
            for prog, cmd in (("rtrace", ["rtrace"] + SETTINGS + [f"{stem}.oct"]),
                              ("radc", [radc, "trace"] + SETTINGS + [f"{stem}.rad"])):
                start, start_mb, _ = measure(cmd, d / "empty.txt", env, d, args.runs)
                t, mb, out = measure(cmd, d / "rays.txt", env, d, args.runs)
                rows[prog] = (start, args.rays / max(t - start, 1e-9), max(mb, start_mb), out)
            agree = agreement(rows["rtrace"][3], rows["radc"][3])
            for prog in ("rtrace", "radc"):
                start, rps, mb, _ = rows[prog]
                ratio = "" if prog == "rtrace" else (
                    f"{rps / rows['rtrace'][1]:.2f}x rays/s, {mb / rows['rtrace'][2]:.2f}x "
                    f"memory; {agree}")
                print(f"| {name} | {prog} | {start:.2f} s | {rps:,.0f} | {mb:,.0f} MB | {ratio} |")
    finally:
        if not args.keep:
            shutil.rmtree(d, ignore_errors=True)


if __name__ == "__main__":
    main()
