#!/usr/bin/env python3
"""`radc check` against Radiance's `oconv`, side by side: wall time and peak memory.

oconv is what people run today to find out whether a scene is readable; `radc check`
reads the same files and reports every problem at once. Both read the same scene; oconv
also builds its octree (written to /dev/null), radc also runs its semantic checks.

Scenes are generated into a temporary folder with Radiance's own generators, so the
benchmark needs no checked-in data:

  big      gensurf, 400x400 quads = 320,000 triangles (~63 MB), as in the issue
  room     genbox walls and 2,400 xform-arrayed boxes of furniture, 8 materials
  lathe    genrev vases and a genworm coil with 2,000 segments each, plus spheres
  smooth   gensurf -s 150x150: Phong-smoothed triangles with texfunc normals

Wall time is the best of N runs. CPU time (user + system, best of N) is printed too: on
a shared machine it is the steadier figure. Peak memory is the child's ru_maxrss as
GNU time (/usr/bin/time, Debian package `time`) reports it. Not os.wait4 from here:
Linux carries the high-water mark across exec, so a child forked from this Python
would report at least Python's own size (which holds the generated scenes).

Usage (from the repository root):
  python3 bench/check_vs_oconv.py [--runs 5] [--no-build] [--radc PATH] [--keep DIR]
                                  [--only NAME]

Radiance is found on PATH, or else in the oracle venv (`bash tests/oracle/install.sh`).
Only the Python standard library is used.
"""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from radiance import radiance_env

ROOT = Path(__file__).resolve().parent.parent
MATERIAL = "void plastic mat 0 0 5 .5 .5 .5 0 0\n"


def run_text(cmd, env, cwd):
    return subprocess.run(cmd, env=env, cwd=cwd, check=True, capture_output=True, text=True).stdout


def scene_big(env, d):
    surf = run_text(
        ["gensurf", "mat", "t", "t*100", "s*100", "sin(t*20)*cos(s*17)*3+5", "400", "400"], env, d
    )
    return MATERIAL + surf


def scene_room(env, d):
    mats = "".join(
        f"void plastic m{i} 0 0 5 {0.2 + 0.1 * i:.2f} .5 .5 0 0\n" for i in range(6)
    )
    mats += "void light lamp 0 0 3 100 100 100\nvoid glass pane 0 0 3 .9 .9 .9\n"
    parts = [mats, run_text(["genbox", "m0", "room", "20", "30", "4", "-i"], env, d)]
    box = run_text(["genbox", "m1", "desk", "1.5", ".8", ".05"], env, d)
    (Path(d) / "desk.rad").write_text(box)
    # 40 x 60 desks, each a 6-polygon box: xform -a repeats and renames them.
    parts.append(
        run_text(
            ["xform", "-t", ".2", ".2", ".75", "-a", "40", "-t", ".5", "0", "0",
             "-a", "60", "-t", "0", ".5", "0", "desk.rad"], env, d
        )
    )
    for i in range(100):
        parts.append(
            f"lamp sphere bulb{i} 0 0 4 {i % 10 * 2 + 1} {i // 10 * 3 + 1} 3.8 .05\n"
        )
    parts.append("pane polygon window 0 0 12 0 5 1 0 25 1 0 25 3 0 5 3\n")
    return "".join(parts)


def scene_lathe(env, d):
    parts = [MATERIAL, "void metal chrome 0 0 5 .8 .8 .8 .9 0\n"]
    for i in range(20):
        parts.append(
            run_text(["genrev", "mat", f"vase{i}", "t", "0.3+0.1*sin(t*6*PI)", "100", "-s"], env, d)
        )
    parts.append(
        run_text(["genworm", "chrome", "coil", "cos(t*40*PI)", "sin(t*40*PI)", "t*5",
                  ".05", "2000"], env, d)
    )
    for i in range(1000):
        parts.append(f"chrome sphere s{i} 0 0 4 {i % 50} {i // 50} 0 .2\n")
    return "".join(parts)


def scene_smooth(env, d):
    surf = run_text(
        ["gensurf", "mat", "sm", "t*10", "s*10", "sin(t*7)*cos(s*5)", "150", "150", "-s"], env, d
    )
    return MATERIAL + surf


SCENES = {"big": scene_big, "room": scene_room, "lathe": scene_lathe, "smooth": scene_smooth}


GNU_TIME = "/usr/bin/time"


def cpu_ms(seconds):
    # The kernel accounts CPU time in 10 ms ticks as GNU time reports it.
    return "<10ms" if seconds < 0.01 else f"{seconds * 1e3:.0f}ms"


def cpu_ratio(radc, oconv):
    return "-" if radc < 0.01 else f"{oconv / radc:.1f}x"


def measure(cmd, env, cwd, runs):
    """Best wall time, best CPU time (s), largest peak RSS (KiB) and the exit codes."""
    times, cpu, rss, codes = [], [], [], set()
    with tempfile.NamedTemporaryFile("r", suffix=".time") as report:
        for _ in range(runs):
            t0 = time.perf_counter()
            p = subprocess.run([GNU_TIME, "-o", report.name, "-f", "%U %S %M %x", *cmd],
                               env=env, cwd=cwd, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
            times.append(time.perf_counter() - t0)
            report.seek(0)
            # GNU time writes "Command exited with non-zero status N" first when N != 0.
            user, system, maxrss, code = report.read().split()[-4:]
            cpu.append(float(user) + float(system))
            rss.append(int(maxrss))
            codes.add(int(code))
            del p
    return min(times), min(cpu), max(rss), codes


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--no-build", action="store_true", help="use target/release/radc as it is")
    ap.add_argument("--radc", metavar="PATH", help="the radc binary to measure (implies --no-build)")
    ap.add_argument("--keep", metavar="DIR", help="write the scenes to DIR and keep them")
    ap.add_argument("--only", action="append", choices=list(SCENES), help="run only these scenes")
    args = ap.parse_args()

    if not os.access(GNU_TIME, os.X_OK):
        sys.exit("GNU time is needed for peak memory: apt-get install time")
    env = radiance_env("oconv", "gensurf")
    if not (args.no_build or args.radc):
        subprocess.run(["cargo", "build", "--release", "-q", "-p", "radc"], cwd=ROOT, check=True)
    radc = Path(args.radc).resolve() if args.radc else ROOT / "target" / "release" / "radc"
    oconv = shutil.which("oconv", path=env["PATH"])

    tmp = None
    if args.keep:
        d = Path(args.keep)
        d.mkdir(parents=True, exist_ok=True)
    else:
        tmp = tempfile.TemporaryDirectory(prefix="radc-bench-")
        d = Path(tmp.name)

    rows = []
    for name in args.only or list(SCENES):
        path = d / f"{name}.rad"
        path.write_text(SCENES[name](env, str(d)))
        size = path.stat().st_size
        prims = sum(1 for line in path.open() if " " in line and line.split()[1:2] and
                    line.split()[1] in ("polygon", "sphere", "cone", "cylinder", "ring", "tube", "cup"))
        check = subprocess.run([str(radc), "check", path.name], cwd=d, env=env,
                               capture_output=True, text=True)
        summary = (check.stdout.strip().splitlines() or ["?"])[-1]
        r = measure([str(radc), "check", "--quiet", path.name], env, d, args.runs)
        o = measure([oconv, path.name], env, d, args.runs)
        rows.append((name, size, prims, summary, r, o))

    print(f"\nbest of {args.runs} runs; peak RSS is the largest over the runs\n")
    head = (f"{'scene':<7} {'size':>7} {'surfaces':>8} | {'wall radc':>9} {'oconv':>7} {'ratio':>6}"
            f" | {'CPU radc':>8} {'oconv':>7} {'ratio':>6} | {'RSS radc':>8} {'oconv':>8} {'ratio':>5}")
    print(head)
    print("-" * len(head))
    for name, size, prims, _, r, o in rows:
        print(f"{name:<7} {size / 1e6:>5.1f}MB {prims:>8} |"
              f" {r[0] * 1e3:>7.0f}ms {o[0] * 1e3:>5.0f}ms {o[0] / r[0]:>5.1f}x |"
              f" {cpu_ms(r[1]):>8} {cpu_ms(o[1]):>7} {cpu_ratio(r[1], o[1]):>6} |"
              f" {r[2] / 1024:>6.1f}MB {o[2] / 1024:>6.1f}MB {o[2] / r[2]:>4.1f}x")
    print()
    for name, _, _, summary, r, o in rows:
        print(f"{name}: radc check says '{summary}' (exit {sorted(r[3])}), oconv exit {sorted(o[3])}")
    if tmp:
        tmp.cleanup()


if __name__ == "__main__":
    main()
