#!/usr/bin/env python3
"""Error against time for `radc render` and `rpict` with ambient bounces (issue #6).

One simple room (tests/data/accuracy/room-ab1.rad: a grey genbox room, a red wall, a
ceiling panel) seen from a corner at 64 x 48 pixels, one ray per pixel centre in both
(rpict -pj 0 -ps 1), one ambient bounce, pure Monte Carlo (rpict -aa 0: no irradiance
cache, which radc does not have), every shadow tested (-dt 0), no source jitter.

The reference is rpict with -ad 4096 (computed once, 4x the samples of the largest row;
its own noise, about 0.15% per pixel, adds in quadrature to the figures), with its
direct light at each pixel's own point replaced by the exact value: rpict -ab 0 is
subtracted and radc -dx+ -ab 0 added. In this room (matte walls, one rectangular lamp
that nothing shadows) the latter is Lambert's closed-form polygon formula at every
pixel (tests/trace_accuracy.rs checks it against the corner form factor), while
rpict's partition centres are off by about 0.9% RMS, more than the noise of the larger
-ad rows. (rpict -dj 1 is unbiased but 2% noisy per pixel.) The direct light at the
bounce points stays rpict's: its 0.3% bias, on the quarter of the light that is
indirect, leaves about 0.07% in the reference, below its noise. "bias" is the picture's mean brightness against the reference's
(systematic differences show there, noise averages out). For each -ad, rpict, radc
(Radiance's source samples) and radc -dx+ (exact solid angles per source partition)
render the same view; the table gives the CPU time (user + system) and the RMSE of
pixel brightness against the reference, relative to the reference's mean brightness.
radc runs on one thread (RAYON_NUM_THREADS=1, as rpict runs one process). Pictures
are read with Radiance's pvalue.

Usage (from the repository root; Radiance from PATH, or else the oracle venv):
  python3 bench/render_error_vs_time.py [--no-build] [--radc PATH] [--ads 16,64,256]
"""

import argparse
import math
import os
import struct
import subprocess
import sys
import tempfile

from radiance import radiance_env

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "tests", "data", "accuracy", "room-ab1.rad")
VIEW = ["-vtv", "-vp", "0.3", "0.3", "1.4", "-vd", "1", "0.7", "-0.15", "-vu", "0", "0", "1",
        "-vh", "75", "-vv", "60"]
SIZE = ["-x", "64", "-y", "48"]
COMMON = ["-ab", "1", "-aa", "0", "-as", "0", "-dt", "0", "-dj", "0", "-lr", "7", "-lw", "1e-4"]
REFERENCE_AD = 4096


def brightness(pic):
    """Pixel brightness values, via pvalue (binary doubles, no header or coordinates)."""
    out = subprocess.run(["pvalue", "-h", "-H", "-b", "-dd", pic], capture_output=True,
                         check=True).stdout
    return struct.unpack("<%dd" % (len(out) // 8), out)


def rmse(a, ref):
    mean = sum(ref) / len(ref)
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, ref)) / len(ref)) / mean


def bias(a, ref):
    return sum(a) / sum(ref) - 1.0


def timed(cmd, out, env=None):
    """CPU time (user + system) of the command, which load from other programs barely
    changes."""
    with open(out, "wb") as f:
        p = subprocess.Popen(cmd, stdout=f, env=env)
        _, status, usage = os.wait4(p.pid, 0)
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit("%s failed" % " ".join(cmd))
    return usage.ru_utime + usage.ru_stime


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--no-build", action="store_true")
    ap.add_argument("--radc", default=os.path.join(ROOT, "target", "release", "radc"))
    ap.add_argument("--ads", default="16,64,256,1024")
    args = ap.parse_args()
    if not args.no_build:
        subprocess.run(["cargo", "build", "--release", "--bin", "radc"], cwd=ROOT, check=True)
    env = radiance_env("rpict", "oconv")
    one = dict(env, RAYON_NUM_THREADS="1")
    with tempfile.TemporaryDirectory() as tmp:
        octree = os.path.join(tmp, "room.oct")
        with open(octree, "wb") as f:
            subprocess.run(["oconv", SCENE], stdout=f, check=True, env=env)
        rpict = ["rpict", "-pj", "0", "-ps", "1"] + VIEW + SIZE + COMMON
        radc = [args.radc, "render"] + VIEW + SIZE + COMMON
        ref_pic = os.path.join(tmp, "ref.hdr")
        tref = timed(rpict + ["-ad", str(REFERENCE_AD), octree], ref_pic, env=env)
        timed(rpict + ["-ab", "0", octree], os.path.join(tmp, "rpict_direct.hdr"), env=env)
        timed(radc + ["-ab", "0", "-dx+", SCENE], os.path.join(tmp, "exact_direct.hdr"))
        ref = [r - d + x for r, d, x in zip(
            brightness(ref_pic), brightness(os.path.join(tmp, "rpict_direct.hdr")),
            brightness(os.path.join(tmp, "exact_direct.hdr")))]
        print("reference: rpict -ad %d, %.1f s, with exact direct light; mean brightness %.4g; "
              "load average %.1f" % (REFERENCE_AD, tref, sum(ref) / len(ref), os.getloadavg()[0]))
        print("| -ad | rpict s | rpict RMSE | rpict bias | radc s | radc RMSE | radc bias "
              "| radc -dx+ s | radc -dx+ RMSE | radc -dx+ bias |")
        print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        for ad in [int(x) for x in args.ads.split(",")]:
            p1 = os.path.join(tmp, "rpict%d.hdr" % ad)
            p2 = os.path.join(tmp, "radc%d.hdr" % ad)
            p3 = os.path.join(tmp, "radcdx%d.hdr" % ad)
            t1 = timed(rpict + ["-ad", str(ad), octree], p1, env=env)
            t2 = timed(radc + ["-ad", str(ad), SCENE], p2, env=one)
            t3 = timed(radc + ["-ad", str(ad), "-dx+", SCENE], p3, env=one)
            b1, b2, b3 = brightness(p1), brightness(p2), brightness(p3)
            print("| %d | %.2f | %.4f | %+.4f | %.2f | %.4f | %+.4f | %.2f | %.4f | %+.4f |" % (
                ad, t1, rmse(b1, ref), bias(b1, ref), t2, rmse(b2, ref), bias(b2, ref),
                t3, rmse(b3, ref), bias(b3, ref)))
            sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
