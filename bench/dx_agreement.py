#!/usr/bin/env python3
"""How far `radc trace` with extra options (by default `-dx+`, exact source solid
angles) moves from rtrace on the differential rays of tests/data/trace: for each case of
cases.json, the rays of `<id>.rays` through its scenes with its options plus the extra
ones, compared number by number with rtrace's `<id>.out` as tests/trace_differential.rs
compares them (relative to the larger magnitude, at least 1e-6). Prints per case the
rays beyond 1e-3 and the worst difference, then the totals.

Usage (from the repository root):
  python3 bench/dx_agreement.py [--radc target/release/radc] [-- extra options...]
"""

import argparse
import json
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "tests" / "data" / "trace"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--radc", default=str(ROOT / "target" / "release" / "radc"))
    ap.add_argument("extra", nargs="*", default=["-dx+"])
    args = ap.parse_args()
    total = over = 0
    worst = (0.0, "")
    for c in json.loads((DATA / "cases.json").read_text()):
        rays = (DATA / f"{c['id']}.rays").read_text()
        expect = (DATA / f"{c['id']}.out").read_text().splitlines()
        cmd = [args.radc, "trace", "-h"] + c["options"] + args.extra
        cmd += [str(DATA / "scenes" / s) for s in c["scenes"]]
        got = subprocess.run(cmd, input=rays, capture_output=True, text=True,
                             check=True).stdout.splitlines()
        n_over, case_worst = 0, 0.0
        for i, (e, g) in enumerate(zip(expect, got)):
            pairs = zip(map(float, e.split()), map(float, g.split()))
            err = max((abs(a - b) / max(abs(a), abs(b), 1e-6) for a, b in pairs), default=0.0)
            total += 1
            n_over += err > 1e-3
            case_worst = max(case_worst, err)
            if err > worst[0]:
                worst = (err, f"{c['id']} ray {i}")
        over += n_over
        print(f"{c['id']}: {len(expect)} rays, {n_over} beyond 1e-3, worst {case_worst:.2e}")
    print(f"total {total} rays, {over} beyond 1e-3; worst {worst[0]:.3g} ({worst[1]})")


if __name__ == "__main__":
    main()
