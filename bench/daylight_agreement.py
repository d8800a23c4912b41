#!/usr/bin/env python3
"""Desk illuminance under a gensky sunny sky through a window: radc against rtrace at
-ab 1 and -ab 2 -aa 0 (pure Monte Carlo in both), as means over desk points with the
standard error of the mean difference (each point's difference is independent noise).
Scene: tests/data/trace/scenes/daylight.rad.

Usage (from the repository root; Radiance from PATH, or else the oracle venv):
  python3 bench/daylight_agreement.py [--radc target/release/radc] [--points 40] [--ad 1024]
"""

import argparse
import os
import random
import statistics as st
import subprocess
import sys
import tempfile

from radiance import radiance_env

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = os.path.join(ROOT, "tests", "data", "trace", "scenes")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--radc", default=os.path.join(ROOT, "target", "release", "radc"))
    ap.add_argument("--points", type=int, default=40)
    ap.add_argument("--ad", default="1024")
    a = ap.parse_args()
    env = radiance_env("rtrace", "oconv")
    rng = random.Random(5)
    pts = [(rng.uniform(.3, 3.7), rng.uniform(.5, 4.7), .8) for _ in range(a.points)]
    rays = "".join(f"{x} {y} {z} 0 0 1\n" for x, y, z in pts)
    with tempfile.TemporaryDirectory() as tmp:
        octree = os.path.join(tmp, "daylight.oct")
        with open(octree, "wb") as f:
            subprocess.run(["oconv", "daylight.rad"], env=env, cwd=SCENES, stdout=f, check=True)

        def run(cmd):
            out = subprocess.run(cmd, input=rays, capture_output=True, text=True, env=env,
                                 cwd=SCENES, check=True).stdout
            return [sum(map(float, l.split()[:3])) / 3 for l in out.strip().splitlines()]

        for ab in ("1", "2"):
            opts = ["-h", "-I", "-ab", ab, "-ad", a.ad, "-as", "0"]
            r = run(["rtrace"] + opts + ["-aa", "0", octree])
            c = run([a.radc, "trace"] + opts + ["daylight.rad"])
            d = [x - y for x, y in zip(c, r)]
            m = st.mean(r)
            print(f"-ab {ab} -ad {a.ad}: rtrace mean {m:.3f}, radc mean {st.mean(c):.3f}, "
                  f"difference {st.mean(d) / m * 100:+.2f}% +- "
                  f"{st.stdev(d) / len(d) ** .5 / m * 100:.2f}% (1 SE, {len(d)} points)")


if __name__ == "__main__":
    sys.exit(main())
