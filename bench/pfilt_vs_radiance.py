#!/usr/bin/env python3
"""radc pfilt against Radiance's pfilt on the same picture, side by side in one run.

Writes a W x H picture (flat RGBE scanlines: a gradient with a deterministic ripple and
a few hot pixels), then runs each configuration RUNS times, reports the best wall time,
and checks that radc's output equals pfilt's byte for byte (the command line in the
header aside, which names the program).

Usage: python3 bench/pfilt_vs_radiance.py [--width 3000] [--height 2000] [--runs 3]
[--radc target/release/radc] (needs the oracle: bash tests/oracle/install.sh).
"""
import argparse, math, os, shutil, subprocess, sys, tempfile, time

from radiance import radiance_env

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CONFIGS = [
    ["-x", "/3", "-y", "/3"],
    ["-1", "-x", "/2", "-y", "/2", "-r", ".6"],
    ["-1", "-r", "1", "-x", "128", "-y", "128", "-pa", "1"],
]


def rgbe(r, g, b):
    d = max(r, g, b)
    if d <= 1e-32:
        return b"\0\0\0\0"
    m, e = math.frexp(d)
    s = m * 256.0 / d
    return bytes([int(r * s), int(g * s), int(b * s), e + 128])


def picture(path, w, h):
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n")
        f.write(f"-Y {h} +X {w}\n".encode())
        for y in range(h):
            row = bytearray()
            for x in range(w):
                v = (x + y) / (w + h) + 0.2 * math.sin(x * 0.05) * math.cos(y * 0.07) + 0.3
                hot = 500.0 if (x * 7 + y * 13) % 9973 == 0 else 1.0
                row += rgbe(v * hot, 0.8 * v * hot, 0.6 * v * hot)
            f.write(row)


def best(cmd, path, runs, env):
    t = None
    out = b""
    for _ in range(runs):
        start = time.perf_counter()
        p = subprocess.run(cmd + [path], capture_output=True, env=env)
        wall = time.perf_counter() - start
        if p.returncode != 0:
            sys.exit(f"{cmd[0]} failed: {p.stderr.decode()}")
        t = wall if t is None else min(t, wall)
        out = p.stdout
    return t, out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--width", type=int, default=3000)
    ap.add_argument("--height", type=int, default=2000)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--radc", default=os.path.join(ROOT, "target", "release", "radc"))
    a = ap.parse_args()
    env = radiance_env("pfilt")
    pfilt = shutil.which("pfilt", path=env["PATH"])
    if not pfilt:
        sys.exit("pfilt not found: bash tests/oracle/install.sh")
    work = tempfile.mkdtemp()
    try:
        path = os.path.join(work, "in.hdr")
        picture(path, a.width, a.height)
        print(f"picture: {a.width} x {a.height}   runs: {a.runs} (best of)   load average: {os.getloadavg()[0]:.1f}")
        one = ["taskset", "-c", "0"] if shutil.which("taskset") else []
        print(f"{'options':40} {'pfilt s':>8} {'radc 1 core':>12} {'radc all':>9} {'ratios':>14}  output")
        for opts in CONFIGS:
            tp, op = best([pfilt] + opts, path, a.runs, env)
            t1, o1 = best(one + [a.radc, "pfilt"] + opts, path, a.runs, env)
            tr, orc = best([a.radc, "pfilt"] + opts, path, a.runs, env)
            same = all(o.replace(b"\nradc pfilt", b"\npfilt", 1) == op for o in (o1, orc))
            print(f"{' '.join(opts):40} {tp:8.3f} {t1:12.3f} {tr:9.3f} {tp / t1:6.2f}x {tp / tr:6.2f}x  "
                  f"{'identical' if same else 'DIFFERS'}")
    finally:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
