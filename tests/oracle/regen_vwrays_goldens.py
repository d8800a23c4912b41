#!/usr/bin/env python3
"""Regenerate (or, with --check, verify) the goldens of `radc vwrays`: Radiance's vwrays
run on every case of CASES (views of each type, clipping planes, shift and lift, `-d`,
`-fa -ff -fd`, `-c`, a picture's view, `-i` pixel positions). tests/vwrays.rs runs radc
on the same cases and compares byte for byte (jitter is random in both and left out).

Output: tests/data/vwrays/cases.json (id, arguments, stdin) and <id>.out (vwrays'
standard output), plus view.hdr, the picture the picture cases read.

Usage:
    .oracle/bin/python tests/oracle/regen_vwrays_goldens.py           # rewrite goldens
    .oracle/bin/python tests/oracle/regen_vwrays_goldens.py --check   # exit 1 on drift
"""

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data" / "vwrays"

PERSPECTIVE = "-vp 1 2 3 -vd 0 1 0 -vu 0 0 1 -vh 60 -vv 40"
CASES = [
    ("perspective", f"{PERSPECTIVE} -x 8 -y 6", ""),
    ("perspective-dims", f"-d {PERSPECTIVE} -x 800 -y 600", ""),
    ("perspective-aspect", f"-d {PERSPECTIVE} -x 800 -y 600 -pa 2", ""),
    ("shift-lift", f"{PERSPECTIVE} -vs .3 -vl -.2 -x 5 -y 4", ""),
    ("parallel-clipped", "-vtl -vp 0 0 0 -vd 1 0 0 -vh 4 -vv 3 -va 10 -vo 1 -x 4 -y 3", ""),
    ("parallel-clipped-dims", "-d -vtl -vp 0 0 0 -vd 1 0 0 -vh 4 -vv 3 -va 10 -vo 1 -x 4 -y 3", ""),
    ("hemispherical", "-vth -vp 0 0 1 -vd 0 0 1 -vu 0 1 0 -vh 180 -vv 180 -x 5 -y 5", ""),
    ("angular", "-vta -vh 180 -vv 180 -x 4 -y 4", ""),
    ("planispheric", "-vts -vh 180 -vv 180 -x 4 -y 4", ""),
    ("cylindrical", "-vtc -vh 360 -vv 90 -x 6 -y 3", ""),
    ("float", f"-ff {PERSPECTIVE} -x 3 -y 2", ""),
    ("double", f"-fd {PERSPECTIVE} -x 3 -y 2", ""),
    ("repeat", f"-c 2 {PERSPECTIVE} -x 2 -y 2", ""),
    ("picture", "view.hdr", ""),
    ("picture-dims", "-d view.hdr", ""),
    ("stdin-pixels", f"-i {PERSPECTIVE} -x 10 -y 10", "0 0\n9 9\n4.5 2.25\n-1 12\n"),
]


def picture():
    """A 6 by 4 rpict picture of an empty scene: its header holds the view."""
    scene = DATA / "empty.rad"
    scene.write_text("void plastic m 0 0 5 .5 .5 .5 0 0\nm sphere s 0 0 4 0 5 0 1\n")
    octree = subprocess.run(["oconv", str(scene)], check=True, capture_output=True).stdout
    oct_path = DATA / "empty.oct"
    oct_path.write_bytes(octree)
    pic = subprocess.run(
        ["rpict", "-vp", "0", "0", "0", "-vd", "0", "1", "0", "-vh", "50", "-vv", "30",
         "-x", "6", "-y", "4", "-pj", "0", str(oct_path)],
        check=True, capture_output=True).stdout
    scene.unlink()
    oct_path.unlink()
    return pic


def run(args, stdin):
    out = subprocess.run(["vwrays"] + args.split(), input=stdin.encode(), cwd=DATA,
                         capture_output=True)
    return out.stdout


def main():
    check = "--check" in sys.argv
    DATA.mkdir(parents=True, exist_ok=True)
    if not check:
        (DATA / "view.hdr").write_bytes(picture())
    manifest = [{"id": i, "args": a.split(), "stdin": s} for i, a, s in CASES]
    drift = False
    for case_id, args, stdin in CASES:
        out = run(args, stdin)
        golden = DATA / f"{case_id}.out"
        if check:
            if not golden.exists() or golden.read_bytes() != out:
                print(f"drift: {case_id}")
                drift = True
        else:
            golden.write_bytes(out)
    manifest_text = json.dumps(manifest, indent=1) + "\n"
    if check:
        if (DATA / "cases.json").read_text() != manifest_text:
            print("drift: cases.json")
            drift = True
    else:
        (DATA / "cases.json").write_text(manifest_text)
    sys.exit(1 if drift else 0)


if __name__ == "__main__":
    main()
