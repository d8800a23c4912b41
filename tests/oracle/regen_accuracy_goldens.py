"""Goldens for tests/trace_accuracy.rs: rtrace's answers on scenes with closed-form
illuminance, so that the test can require radc's error to be no larger than Radiance's.

Each case is one scene (written to tests/data/accuracy/<id>.rad), rtrace options and
`-I` rays; tests/data/accuracy/cases.json records them with what rtrace printed. For
stochastic cases (`repeat` > 1: the same ray traced many times with ambient bounces)
it records the mean and standard deviation of rtrace's values instead; --check then
accepts a fresh run whose mean is within 5 standard errors of the stored one (rtrace's
random numbers differ from run to run), deterministic cases must match to the printed
precision.

    python tests/oracle/regen_accuracy_goldens.py           # rewrite the goldens
    python tests/oracle/regen_accuracy_goldens.py --check   # fail if any would change
    python tests/oracle/regen_accuracy_goldens.py --only a,b  # rewrite only these cases
"""

import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "tests", "data", "accuracy")

# Pure Monte Carlo (no irradiance cache), every shadow tested, sources not jittered.
BASE = ["-aa", "0", "-dt", "0", "-dj", "0", "-dr", "0", "-as", "0"]

SPHERE = "void light lamp 0 0 3 100 100 100\nlamp sphere bulb 0 0 4 0 0 5 0.5\n"
DISK = "void light lamp 0 0 3 40 40 40\nlamp ring disk 0 0 8 0 0 2 0 0 -1 0 1\n"
RECT = (
    "void light panel 0 0 3 25 25 25\n"
    "panel polygon rect 0 0 12 0 0 1.5 0 2 1.5 3 2 1.5 3 0 1.5\n"
)
# The same sources half hidden by an opaque black plane between them and the point: at
# z = .75 beyond x = .65 for the rectangle (its shadow edge falls at x = 1.3 on the
# lamp, inside a partition), at z = 1 beyond x = .25 for the disk (a chord at x = .5).
BLACK = "void plastic black 0 0 5 0 0 0 0 0\n"
RECT_OCCLUDED = RECT + BLACK + "black polygon blind 0 0 12 .65 -3 .75 5 -3 .75 5 5 .75 .65 5 .75\n"
DISK_OCCLUDED = DISK + BLACK + "black polygon blind 0 0 12 .25 -3 1 5 -3 1 5 5 1 .25 5 1\n"
TRIANGLE = (
    "void light panel 0 0 3 25 25 25\n"
    "panel polygon tri 0 0 9 0 0 1.5 0 2 1.5 3 0 1.5\n"
)
GLOW_DOME = (
    "void glow sky 0 0 4 2 2 2 0\n"
    "sky bubble dome 0 0 4 0 0 0 10\n"
    "void plastic black 0 0 5 0 0 0 0 0\n"
    "black ring floor 0 0 8 0 0 0 0 0 1 0 11\n"
)
# An integrating sphere: a white (rho = .5) bubble of radius 1 around a small lamp
# (small so that ambient rays almost never meet it: the cases stay deterministic).
INTEGRATING = (
    "void light lamp 0 0 3 1e5 1e5 1e5\n"
    "lamp sphere bulb 0 0 4 0 0 0 0.001\n"
    "void plastic white 0 0 5 .5 .5 .5 0 0\n"
    "white bubble wall 0 0 4 0 0 0 1\n"
)
# A room 4 x 3 x 2.5 (genbox, expanded) with a ceiling panel and a red wall, for the
# statistical comparison.
def room():
    box = subprocess.run(["genbox", "grey", "room", "4", "3", "2.5", "-i"],
                         capture_output=True, text=True, check=True).stdout
    body = "".join(l + "\n" for l in box.splitlines() if l.strip() and not l.startswith("#"))
    return (
        "void plastic grey 0 0 5 .6 .6 .6 0 0\n"
        "void plastic red 0 0 5 .7 .2 .2 0 0\n"
        "void light panel 0 0 3 30 30 30\n"
        + body +
        "red polygon redwall 0 0 12 3.999 0 0 3.999 0 2.5 3.999 3 2.5 3.999 3 0\n"
        "panel polygon lamp 0 0 12 1.5 1 2.499 1.5 2 2.499 2.5 2 2.499 2.5 1 2.499\n"
    )


def cases():
    ROOM = room()
    s30 = math.sin(math.radians(50)), math.cos(math.radians(50))
    return [
        dict(id="sphere-below", scene=SPHERE, options=["-ab", "0"], rays=[[0, 0, 0, 0, 0, 1]]),
        dict(id="sphere-off-axis", scene=SPHERE, options=["-ab", "0"],
             rays=[[0, 0, 0, s30[0], 0, s30[1]]]),
        # Tilted 87 degrees: the horizon cuts the lamp's cone (half-angle 5.7 degrees).
        dict(id="sphere-horizon", scene=SPHERE, options=["-ab", "0", "-ds", ".05"],
             rays=[[0, 0, 0, math.sin(math.radians(87)), 0, math.cos(math.radians(87))]]),
        dict(id="sphere-horizon-jitter", scene=SPHERE,
             options=["-ab", "0", "-ds", ".05", "-dj", "1", "-u-"],
             rays=[[0, 0, 0, math.sin(math.radians(87)), 0, math.cos(math.radians(87))]],
             repeat=400),
        dict(id="disk-jitter", scene=DISK, options=["-ab", "0", "-ds", ".05", "-dj", "1", "-u-"],
             rays=[[0, 0, 0, 0, 0, 1]], repeat=400),
        dict(id="disk-axis", scene=DISK, options=["-ab", "0", "-ds", ".05"], rays=[[0, 0, 0, 0, 0, 1]]),
        dict(id="rect-corner", scene=RECT, options=["-ab", "0", "-ds", ".05"], rays=[[0, 0, 0, 0, 0, 1]]),
        dict(id="triangle", scene=TRIANGLE, options=["-ab", "0", "-ds", ".05"],
             rays=[[0, 0, 0, 0, 0, 1], [1, 0.5, 0, 0, 0, 1], [-1, -1, 0, 0.6, 0, 0.8]]),
        # Jittered source samples (-dj 1): random points over each partition.
        dict(id="rect-jitter", scene=RECT, options=["-ab", "0", "-ds", ".05", "-dj", "1"],
             rays=[[0, 0, 0, 0, 0, 1]], repeat=400),
        # -u-: rtrace's default -u+ turns each source's partitions at random, which
        # moves the partitions a shadow's edge crosses (radc orients them as -u-).
        dict(id="rect-occluded", scene=RECT_OCCLUDED, options=["-ab", "0", "-ds", ".05", "-u-"],
             rays=[[0, 0, 0, 0, 0, 1]]),
        dict(id="rect-occluded-jitter", scene=RECT_OCCLUDED,
             options=["-ab", "0", "-ds", ".05", "-dj", "1", "-u-"], rays=[[0, 0, 0, 0, 0, 1]],
             repeat=400),
        dict(id="disk-occluded", scene=DISK_OCCLUDED, options=["-ab", "0", "-ds", ".05", "-u-"],
             rays=[[0, 0, 0, 0, 0, 1]]),
        dict(id="glow-dome", scene=GLOW_DOME, options=["-ab", "1", "-ad", "64"],
             rays=[[0, 0, 0, 0, 0, 1], [3, -2, 0, 0, 0, 1]]),
        dict(id="integrating-ab3", scene=INTEGRATING, options=["-ab", "3", "-ad", "64"],
             rays=[[1, 0, 0, -1, 0, 0], [0, -0.6, 0.8, 0, 0.6, -0.8]]),
        # -av set to the converged wall radiance (see the test): one bounce is exact.
        dict(id="integrating-converged", scene=INTEGRATING,
             options=["-ab", "1", "-ad", "64", "-av"] + ["%.9g" % integrating_av()] * 3,
             rays=[[1, 0, 0, -1, 0, 0]]),
        dict(id="room-ab1", scene=ROOM, options=["-ab", "1", "-ad", "16"],
             rays=[[1, 1, 0, 0, 0, 1], [3.5, 2.5, 1.2, -1, 0, 0], [2, 1.5, 2.5, 0, 0, -1]], repeat=400),
        dict(id="room-ab2", scene=ROOM, options=["-ab", "2", "-ad", "16"],
             rays=[[1, 1, 0, 0, 0, 1]], repeat=400),
    ]


def integrating_av():
    """(1 - s) L_inf, with s = (r/R)^2 and L_inf = rho E0 / pi / (1 - rho (1 - s))."""
    L, r, R, rho = 1e5, 0.001, 1.0, 0.5
    s = (r / R) ** 2
    e0 = math.pi * L * s
    return (1 - s) * rho * e0 / math.pi / (1 - rho * (1 - s))


def run(c, workdir):
    rad = os.path.join(DATA, c["id"] + ".rad")
    octree = os.path.join(workdir, c["id"] + ".oct")
    with open(octree, "wb") as f:
        subprocess.run(["oconv", rad], stdout=f, check=True, cwd=DATA)
    rays = [r for r in c["rays"] for _ in range(c.get("repeat", 1))]
    text = "".join(" ".join("%.9g" % x for x in r) + "\n" for r in rays)
    p = subprocess.run(["rtrace", "-h", "-I", "-ov"] + BASE + c["options"] + [octree],
                       input=text, capture_output=True, text=True, check=True)
    values = [[float(w) for w in l.split()] for l in p.stdout.splitlines() if l.strip()]
    n = c.get("repeat", 1)
    if n == 1:
        return {"values": values}
    stats = []
    for k in range(len(c["rays"])):
        block = values[k * n:(k + 1) * n]
        per = []
        for ch in range(3):
            xs = [v[ch] for v in block]
            m = sum(xs) / n
            sd = math.sqrt(sum((x - m) ** 2 for x in xs) / (n - 1))
            per.append([m, sd])
        stats.append(per)
    return {"stats": stats}


def agrees(old, new, c):
    if "values" in new:
        a, b = old.get("values"), new["values"]
        if a is None or len(a) != len(b):
            return False
        return all(abs(x - y) <= 2e-6 * max(abs(x), abs(y), 1e-30)
                   for ra, rb in zip(a, b) for x, y in zip(ra, rb))
    a, b = old.get("stats"), new["stats"]
    if a is None or len(a) != len(b):
        return False
    n = c["repeat"]
    for pa, pb in zip(a, b):
        for (ma, sa), (mb, sb) in zip(pa, pb):
            if abs(ma - mb) > 5 * math.sqrt((sa * sa + sb * sb) / n) + 1e-9:
                return False
    return True


def main():
    check = "--check" in sys.argv[1:]
    only = None
    if "--only" in sys.argv[1:]:
        at = sys.argv.index("--only")
        only = set(sys.argv[at + 1].split(",")) if at + 1 < len(sys.argv) else set()
    os.makedirs(DATA, exist_ok=True)
    path = os.path.join(DATA, "cases.json")
    old = {}
    if only is not None:
        old = {c["id"]: c for c in json.load(open(path))}
    if check:
        try:
            old = {c["id"]: c for c in json.load(open(path))}
        except (OSError, ValueError):
            print("missing or unreadable", path)
            return 1
    out, failed = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for c in cases():
            if only is not None and c["id"] not in only:
                if c["id"] in old:
                    out.append(old[c["id"]])
                continue
            rad = os.path.join(DATA, c["id"] + ".rad")
            if check:
                if open(rad).read() != c["scene"]:
                    failed.append(c["id"] + ".rad")
                    continue
            else:
                with open(rad, "w") as f:
                    f.write(c["scene"])
            res = run(c, tmp)
            entry = {"id": c["id"], "options": BASE + c["options"], "rays": c["rays"],
                     "repeat": c.get("repeat", 1)}
            entry.update(res)
            out.append(entry)
            if check:
                o = old.get(c["id"])
                if o is None or o["options"] != entry["options"] or o["rays"] != entry["rays"] \
                        or not agrees(o, res, c):
                    failed.append(c["id"])
    if check:
        if failed:
            print("accuracy goldens out of date:", ", ".join(failed))
            return 1
        print("accuracy goldens up to date (%d cases)" % len(out))
        return 0
    with open(path, "w") as f:
        f.write("[\n" + ",\n".join(json.dumps(c) for c in out) + "\n]\n")
    print("wrote %d cases to %s" % (len(out), path))
    return 0


if __name__ == "__main__":
    sys.exit(main())
