"""Goldens for `radc render`: pictures from real rpict, one ray per pixel centre.

For each case below this script renders tests/data/trace/scenes/<scene> with rpict
(deterministic: -pj 0 -ps 1 -ab 0 -dj 0 -dt 0 -dr 0 -u-) into
tests/data/render/<id>.hdr and lists the cases in tests/data/render/cases.json.
tests/render_differential.rs renders the same views with `radc render` and compares
pixels.

    python tests/oracle/regen_render_goldens.py           # rewrite the goldens
    python tests/oracle/regen_render_goldens.py --check   # fail if any would change
"""

import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "tests", "data", "render")
SCENES = os.path.join(ROOT, "tests", "data", "trace", "scenes")

DETERMINISTIC = ["-pj", "0", "-ps", "1", "-ab", "0", "-dj", "0", "-dt", "0", "-dr", "0", "-u-"]

# (id, scene, view and picture options, lighting options)
CASES = [
    ("room", "polygon_lamp.rad", "-vp 2.5 -2.5 1.5 -vd -1 1 -.3 -vu 0 0 1 -vh 60 -vv 45 -x 48 -y 48", "-av .1 .1 .1"),
    ("lamp", "sphere_lamp.rad", "-vp 3 -3 2.5 -vd -1 1 -.7 -vh 50 -vv 50 -x 40 -y 30", ""),
    ("round-parallel", "round.rad", "-vtl -vp 0 0 6 -vd 0 0 -1 -vu 0 1 0 -vh 8 -vv 8 -x 32 -y 32", "-av .02 .02 .02"),
    ("emitters", "emitters.rad", "-vp -3 3 1.8 -vd 1 -1 -.3 -vh 70 -vv 50 -x 40 -y 40", ""),
    # light sources smaller than a pixel, which rpict draws by their coverage
    ("small-glows", "emitters.rad", "-vp 3 3 1.8 -vd -1 -1 -.2 -vh 70 -vv 50 -x 40 -y 40", ""),
    ("small-sun", "distant.rad", "-vp 0 -8 .3 -vd .3 .4 .866 -vu 0 0 1 -vh 20 -vv 20 -x 32 -y 32", ""),
    ("small-lamp", "sphere_lamp.rad", "-vp 60 -60 20 -vd -1 1 -.25 -vh 8 -vv 8 -x 16 -y 16", ""),
    # the other projections, shift and lift, clipping planes, view files
    ("room-fisheye", "polygon_lamp.rad", "-vth -vp 0 0 1.5 -vd 0 0 1 -vu 0 1 0 -vh 180 -vv 180 -x 32 -y 32", "-av .1 .1 .1"),
    ("room-angular", "polygon_lamp.rad", "-vta -vp 0 0 1.5 -vd 1 0 0 -vh 180 -vv 180 -x 32 -y 32", "-av .1 .1 .1"),
    ("room-panorama", "polygon_lamp.rad", "-vtc -vp 0 0 1.5 -vd 1 0 0 -vh 360 -vv 90 -x 64 -y 32", "-av .1 .1 .1"),
    ("room-planisphere", "polygon_lamp.rad", "-vts -vp 0 0 1.5 -vd 0 1 0 -vh 200 -vv 200 -x 32 -y 32", "-av .1 .1 .1"),
    ("room-shifted-clipped", "polygon_lamp.rad", "-vp 2.5 -2.5 1.5 -vd -1 1 -.3 -vh 60 -vv 45 -vs .2 -vl -.1 -vo 1 -va 4 -x 32 -y 32", "-av .1 .1 .1"),
    ("room-view-file", "polygon_lamp.rad", "-vf tests/data/render/corner.vf -x 32 -y 32", "-av .1 .1 .1"),
    ("small-mirrored", "mirrors.rad", "-vp 0 -40 1.5 -vd 0 1 0 -vh 12 -vv 8 -x 24 -y 16", "-dr 2"),
    ("emitters-relay", "emitters.rad", "-vp 2 0 1.2 -vd -1 0 -.4 -vh 40 -vv 40 -x 40 -y 40", "-dr 1"),
    # the scene's functions: patterns, noise, textures, a level view of a daylit window
    ("patterns", "patterns.rad", "-vp 0 -4.5 2 -vd 0 1 -.35 -vh 70 -vv 55 -x 48 -y 40", "-av .05 .05 .05"),
    ("textures", "textures.rad", "-vp 0 -4.5 2 -vd 0 1 -.35 -vh 70 -vv 55 -x 48 -y 40", "-av .05 .05 .05"),
    ("daylight", "daylight.rad", "-vp 2 4 1.75 -vd 0 -1 0 -vu 0 0 1 -vh 60 -vv 45 -x 40 -y 30", "-av .05 .05 .05"),
]


def render(case, out_path):
    cid, scene, view, light = case
    view = view.replace("tests/data/render/", DATA + "/")
    with tempfile.TemporaryDirectory() as tmp:
        octree = os.path.join(tmp, "scene.oct")
        with open(octree, "wb") as f:
            subprocess.run(["oconv", os.path.join(SCENES, scene)], stdout=f, check=True)
        with open(out_path, "wb") as f:
            # function files (patterns.cal, ...) are found beside the scenes
            subprocess.run(["rpict"] + DETERMINISTIC + view.split() + light.split() + [octree],
                           stdout=f, check=True, cwd=SCENES)


def pixels(path):
    p = subprocess.run(["pvalue", "-h", "-H", "-d", path], capture_output=True, text=True, check=True)
    return p.stdout


def main():
    check = "--check" in sys.argv[1:]
    manifest = [{"id": c[0], "scene": c[1], "options": DETERMINISTIC + c[2].split() + c[3].split()} for c in CASES]
    failed = []
    with tempfile.TemporaryDirectory() as tmp:
        for case in CASES:
            path = os.path.join(DATA, case[0] + ".hdr")
            if check:
                fresh = os.path.join(tmp, case[0] + ".hdr")
                render(case, fresh)
                if not os.path.exists(path) or pixels(path) != pixels(fresh):
                    failed.append(case[0])
            else:
                # Keep an unchanged picture as it is (its header has the capture date).
                fresh = os.path.join(tmp, case[0] + ".hdr")
                render(case, fresh)
                if not os.path.exists(path) or pixels(path) != pixels(fresh):
                    with open(fresh, "rb") as src, open(path, "wb") as dst:
                        dst.write(src.read())
    text = json.dumps(manifest, indent=1) + "\n"
    manifest_path = os.path.join(DATA, "cases.json")
    if check:
        if not os.path.exists(manifest_path) or open(manifest_path).read() != text:
            failed.append("cases.json")
        if failed:
            print("render goldens out of date:", ", ".join(failed))
            sys.exit(1)
        print(f"{len(CASES)} render cases match rpict")
    else:
        with open(manifest_path, "w") as f:
            f.write(text)
        print(f"wrote {len(CASES)} pictures")


if __name__ == "__main__":
    main()
