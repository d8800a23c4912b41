#!/usr/bin/env python3
"""`radc trace` against Radiance's `rtrace`: rays per second on one core and on all
cores, on the same rays with the same deterministic settings, and whether the results
agree.

Scenes are generated into a temporary folder with Radiance's own generators:

  room     genbox room (inward faces), 48 xform-arrayed desks (genbox), 20 polished
           metal spheres (roughness 0: rtrace samples rough highlights at random), 4 lamps
  spheres  20,000 random plastic spheres over a ground polygon, lit by a distant sun
  terrain  gensurf mat t 't*100' 's*100' 'sin(t*20)*cos(s*17)*3+5' 400 400
           (319,996 triangles), lit by a distant sun

Each scene is compiled by `oconv` for rtrace and by `radc build` for radc; those build
times are reported too. The rays (a fixed seed, the
same text file for both programs) are ASCII `ox oy oz dx dy dz` lines on stdin; both
print `-h -ov` in ASCII. Settings: `-ab 0 -dj 0 -dt 0 -dr 0 -u-` (deterministic: no
ambient bounces, jitter, probabilistic shadow tests or random orientation).

Rays per second = rays / (time with the rays - time with no rays): the start-up (loading
the octree or the compiled scene) is measured separately, by the same command on empty
input, and reported on its own. Times are the best of --runs runs: CPU time (user +
system, from wait4) for one thread, which load from other programs barely changes, and
wall time for all cores.
Single-threaded: `rtrace -n 1` and `radc trace -n 1`; all cores: `-n` with
os.cpu_count() for both (rtrace forks that many processes, radc runs that many threads).

Agreement: every number of every ray within 1e-3 relative (or 1e-6 absolute, for
values printed as zero by one side).

Usage (from the repository root):
  cargo build --release --bin radc
  python3 bench/trace_rays.py [--rays 100000] [--runs 3] [--radc target/release/radc]
                              [--only room,spheres,terrain] [--keep DIR]

Radiance is found on PATH, or else in the oracle venv (`bash tests/oracle/install.sh`).
Only the Python standard library is used.
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
SETTINGS = ["-ab", "0", "-dj", "0", "-dt", "0", "-dr", "0", "-u-"]


def run_text(cmd, env, cwd):
    return subprocess.run(cmd, env=env, cwd=cwd, check=True, capture_output=True, text=True).stdout


SUN = "void light sunlight 0 0 3 6e6 6e6 5.5e6\nsunlight source sun 0 0 4 0.4 0.3 0.85 0.5\n"


def scene_room(env, d, rng):
    text = (
        "void plastic wall 0 0 5 .6 .6 .55 0 0\n"
        "void plastic wood 0 0 5 .4 .25 .1 .02 .05\n"
        "void metal steel 0 0 5 .7 .7 .75 .9 0\n"
        "void light lamp 0 0 3 50 50 45\n"
    )
    text += run_text(["genbox", "wall", "room", "12", "16", "3", "-i"], env, d)
    desk = run_text(["genbox", "wood", "desk", "1.2", ".7", ".75"], env, d)
    (Path(d) / "desk.rad").write_text(desk)
    text += run_text(
        ["xform", "-t", "1", "1", "0", "-a", "6", "-t", "1.8", "0", "0", "-a", "8", "-t", "0",
         "1.8", "0", "desk.rad"], env, d)
    for i in range(20):
        x, y = rng.uniform(0.5, 11.5), rng.uniform(0.5, 15.5)
        text += f"steel sphere ball{i} 0 0 4 {x:.4f} {y:.4f} 1.0 0.15\n"
    for i, (x, y) in enumerate([(3, 4), (9, 4), (3, 12), (9, 12)]):
        text += f"lamp sphere bulb{i} 0 0 4 {x} {y} 2.7 0.1\n"

    def ray():
        org = (rng.uniform(1, 11), rng.uniform(1, 15), rng.uniform(0.9, 2.2))
        return org, unit(rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1))

    return text, ray


def scene_spheres(env, d, rng):
    text = SUN + "void plastic ground 0 0 5 .3 .35 .25 0 0\n"
    text += "ground polygon floor 0 0 12 -10 -10 0 110 -10 0 110 110 0 -10 110 0\n"
    for i in range(5):
        text += f"void plastic p{i} 0 0 5 {0.2 + 0.15 * i:.2f} .5 .6 .03 .1\n"
    for i in range(20000):
        x, y, z = rng.uniform(0, 100), rng.uniform(0, 100), rng.uniform(0.5, 20)
        text += f"p{i % 5} sphere s{i} 0 0 4 {x:.4f} {y:.4f} {z:.4f} {rng.uniform(0.1, 0.6):.4f}\n"

    def ray():
        org = (rng.uniform(0, 100), rng.uniform(0, 100), 30.0)
        return org, unit(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), -1)

    return text, ray


def scene_terrain(env, d, rng):
    text = SUN + "void plastic mat 0 0 5 .5 .5 .5 0 0\n"
    text += run_text(
        ["gensurf", "mat", "t", "t*100", "s*100", "sin(t*20)*cos(s*17)*3+5", "400", "400"], env, d)

    def ray():
        org = (rng.uniform(0, 100), rng.uniform(0, 100), 15.0)
        return org, unit(rng.uniform(-1, 1), rng.uniform(-1, 1), -1)

    return text, ray


SCENES = {"room": scene_room, "spheres": scene_spheres, "terrain": scene_terrain}


def unit(x, y, z):
    n = math.sqrt(x * x + y * y + z * z)
    return (x / n, y / n, z / n)


def best_time(cmd, stdin_path, env, cwd, runs, cpu=False):
    """Best wall time of `runs` runs, or with `cpu` the best CPU time (user + system of
    the program and the processes it waited for): on a shared machine the steadier
    figure for one thread."""
    best = math.inf
    for _ in range(runs):
        with open(stdin_path, "rb") as inp, tempfile.TemporaryFile() as out, \
                tempfile.TemporaryFile() as err:
            t0 = time.perf_counter()
            p = subprocess.Popen(cmd, stdin=inp, stdout=out, stderr=err, env=env, cwd=cwd)
            _, status, usage = os.wait4(p.pid, 0)
            t = time.perf_counter() - t0
            out.seek(0)
            stdout = out.read()
            if os.waitstatus_to_exitcode(status) != 0:
                err.seek(0)
                sys.exit(f"{' '.join(cmd)} failed:\n{err.read().decode(errors='replace')}")
        best = min(best, usage.ru_utime + usage.ru_stime if cpu else t)
    return best, stdout


def empty_input(d):
    p = Path(d) / "empty.rays"
    p.write_text("")
    return p


def numbers(out):
    return [float(w) for w in out.split()]


def agreement(a, b):
    a, b = numbers(a), numbers(b)
    if len(a) != len(b):
        return f"different counts: {len(a)} vs {len(b)} numbers"
    bad = sum(1 for x, y in zip(a, b)
              if abs(x - y) > max(1e-3 * max(abs(x), abs(y)), 1e-6))
    return f"{len(a) - bad}/{len(a)} numbers agree to 1e-3" + ("" if bad else " (all)")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rays", type=int, default=100_000)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--radc", default=str(ROOT / "target" / "release" / "radc"))
    ap.add_argument("--only", default=",".join(SCENES))
    ap.add_argument("--keep", help="write the scenes and rays here and keep them")
    args = ap.parse_args()
    env = radiance_env("rtrace", "gensurf")
    radc = str(Path(args.radc).resolve())
    cores = os.cpu_count() or 1
    d = args.keep or tempfile.mkdtemp(prefix="radc-trace-bench-")
    Path(d).mkdir(parents=True, exist_ok=True)
    print(f"rays per scene: {args.rays}, best of {args.runs}, cores: {cores}, "
          f"load average {os.getloadavg()[0]:.1f}")
    rows = []
    try:
        for name in args.only.split(","):
            rng = random.Random(1)
            text, ray = SCENES[name](env, d, rng)
            rad = Path(d) / f"{name}.rad"
            rad.write_text(text)
            rays = Path(d) / f"{name}.rays"
            with open(rays, "w") as f:
                for _ in range(args.rays):
                    (ox, oy, oz), (dx, dy, dz) = ray()
                    f.write(f"{ox:.6f} {oy:.6f} {oz:.6f} {dx:.8f} {dy:.8f} {dz:.8f}\n")
            empty = empty_input(d)
            oct_ = Path(d) / f"{name}.oct"
            rsc = Path(d) / f"{name}.rsc"
            builds = {}
            for prog, cmd in (("oconv", ["sh", "-c", f"oconv {rad.name} > {oct_.name}"]),
                              ("radc", [radc, "build", "-o", rsc.name, rad.name])):
                builds[prog], _ = best_time(cmd, empty_input(d), env, d, args.runs)
            programs = {
                "rtrace": lambda n: ["rtrace", "-h", "-ov", "-n", str(n)] + SETTINGS + [oct_.name],
                "radc": lambda n: [radc, "trace", "-h", "-ov", "-n", str(n)] + SETTINGS + [rsc.name],
            }
            result = {}
            for prog, cmd in programs.items():
                start, _ = best_time(cmd(1), empty, env, d, args.runs)
                start_cpu, _ = best_time(cmd(1), empty, env, d, args.runs, cpu=True)
                for n in (1, cores):
                    # One thread: CPU time; all cores: wall time.
                    t, out = best_time(cmd(n), rays, env, d, args.runs, cpu=n == 1)
                    t0 = start_cpu if n == 1 else start
                    result[(prog, n)] = (args.rays / max(t - t0, 1e-9), t, out)
                result[(prog, "start")] = start
            rad_start, _ = best_time(
                [radc, "trace", "-h", "-ov", "-n", "1"] + SETTINGS + [rad.name], empty, env, d,
                args.runs)
            agree = agreement(result[("rtrace", 1)][2], result[("radc", 1)][2])
            rows.append((name, result, rad_start, agree, builds))
            print(f"{name}: done ({agree})", flush=True)
    finally:
        if not args.keep:
            shutil.rmtree(d, ignore_errors=True)
    print()
    print("| scene | threads | rtrace rays/s | radc rays/s | radc / rtrace |")
    print("|---|---:|---:|---:|---:|")
    for name, r, _, _, _ in rows:
        for n in (1, cores):
            a, b = r[("rtrace", n)][0], r[("radc", n)][0]
            print(f"| {name} | {n} | {a:,.0f} | {b:,.0f} | {b / a:.2f}x |")
    print()
    print("| scene | oconv | radc build | start-up: rtrace (octree) | radc (.rsc) "
          "| radc (.rad) | results |")
    print("|---|---:|---:|---:|---:|---:|---|")
    for name, r, rad_start, agree, b in rows:
        print(f"| {name} | {b['oconv'] * 1e3:.0f} ms | {b['radc'] * 1e3:.0f} ms "
              f"| {r[('rtrace', 'start')] * 1e3:.0f} ms | "
              f"{r[('radc', 'start')] * 1e3:.0f} ms | {rad_start * 1e3:.0f} ms | {agree} |")


if __name__ == "__main__":
    main()
