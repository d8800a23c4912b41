"""Goldens for `radc trace`: what real rtrace prints for the same rays and options.

Scenes live in tests/data/trace/scenes/. For each case below this script writes the
rays it sends (tests/data/trace/<id>.rays, generated from a fixed seed) and rtrace's
answers (tests/data/trace/<id>.out), plus tests/data/trace/cases.json listing every
case. tests/trace_differential.rs runs `radc trace` on the same rays and compares.

Options: every case runs rtrace deterministically: no ambient bounces (-ab 0), no
source jitter (-dj 0), every shadow tested (-dt 0), no virtual sources (-dr 0), and no
randomized source orientation (-u-).

    python tests/oracle/regen_trace_goldens.py           # rewrite the goldens
    python tests/oracle/regen_trace_goldens.py --check   # fail if any would change
"""

import json
import math
import os
import random
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "tests", "data", "trace")
SCENES = os.path.join(DATA, "scenes")

DETERMINISTIC = ["-ab", "0", "-dj", "0", "-dt", "0", "-dr", "0", "-u-"]


def unit(rng):
    while True:
        v = [rng.uniform(-1, 1) for _ in range(3)]
        n = math.sqrt(sum(x * x for x in v))
        if 1e-3 < n <= 1:
            return [x / n for x in v]


def box_rays(rng, n, lo, hi, toward=None, spread=1.0):
    """Rays from random points in a box; aimed near `toward` when given, else anywhere."""
    rays = []
    for _ in range(n):
        o = [rng.uniform(a, b) for a, b in zip(lo, hi)]
        if toward is None:
            d = unit(rng)
        else:
            t = [c + spread * rng.uniform(-1, 1) for c in toward]
            d = [a - b for a, b in zip(t, o)]
        rays.append(o + d)
    return rays


def grazing_rays(rng, n, z, lo, hi, tilt):
    """Nearly horizontal rays just above a plane at height z (tilt: max slope)."""
    rays = []
    for _ in range(n):
        o = [rng.uniform(lo[0], hi[0]), rng.uniform(lo[1], hi[1]), z + rng.uniform(1e-4, 1e-2)]
        a = rng.uniform(0, 2 * math.pi)
        rays.append(o + [math.cos(a), math.sin(a), -rng.uniform(0, tilt)])
    return rays


def irradiance_points(rng, n, lo, hi, normals):
    rays = []
    for i in range(n):
        o = [rng.uniform(a, b) for a, b in zip(lo, hi)]
        rays.append(o + list(normals[i % len(normals)]))
    return rays


def hard_rays(rng):
    """Rays at the scene's edges, vertices, seams, tangents and coincident surfaces."""
    rays = []
    down, up = [0, 0, -1], [0, 0, 1]
    # coincident patches, their edges and corners, from above and below
    for x, y in [(.5, .5), (1.5, 1.5), (2.5, 2.5), (-.5, -.5), (0, 0), (2, 0), (1, 1), (3, 3), (2, 2), (1, 2.5),
                 (-1.5, -1.5), (-1, -1), (0, 1), (2, 1.5)]:
        rays.append([x, y, 1] + down)
        rays.append([x, y, -1] + up)
    # frame with a hole: inside the hole, on the seam, on the hole's edge, on the frame
    for x, y in [(-3, -3), (-3.75, -3.75), (-3.5, -3.5), (-3.9, -3), (-2.25, -3), (-3.5, -3), (-2.5, -2.5)]:
        rays.append([x, y, 2] + down)
    # in the floor's plane, and starting on it
    rays += [[-6, .3, 0, 1, 0, 0], [0, 0, 0] + up, [.5, .5, 0] + down, [1.5, 1.5, .001] + up, [4, 4, 0, .3, .2, .9]]
    # tangent to the ball (centre -2 2 1, radius 1), and just inside or outside it
    for dz in [0, 1e-7, -1e-7, 1e-3, -1e-3]:
        rays.append([-6, 2, 2 + dz, 1, 0, 0])
        rays.append([-2 + 1 + dz, -3, 1, 0, 1, 0])
    # the nested shell and bubble, from outside and from inside
    rays += [[2, -2, 3] + down, [2, -2, 1, 1, 0, 0], [2, -2, 1.6, 0, 0, -1], [4, -4, 1, -1, 1, 0]]
    # the lamp from behind and the lantern from inside
    rays += [[0, 0, 6] + down, [.5, .5, 5] + down, [3, 3, 1, 1, 0, 0], [3, 3, 1] + down, [3, 3, 3] + down]
    for _ in range(20):
        o = [rng.uniform(-4.5, 4.5), rng.uniform(-4.5, 4.5), rng.uniform(.01, 3.5)]
        rays.append(o + unit(rng))
    return rays


def mirror_rays(rng):
    """Rays bouncing between the two facing mirrors at x = 4.5 and 4.9."""
    rays = []
    for _ in range(30):
        o = [rng.uniform(4.55, 4.85), rng.uniform(-.8, .8), rng.uniform(.3, 1.9)]
        a = rng.uniform(-.3, .3)
        d = [rng.choice([-1, 1]), a, rng.uniform(-.2, .2)]
        rays.append(o + d)
    return rays


def shift(rays, by):
    return [[r[0] + by[0], r[1] + by[1], r[2] + by[2]] + r[3:] for r in rays]


def cases():
    rng = random.Random(20261125)
    out = []

    def case(cid, scene, opts, rays, outputs="-ov"):
        out.append({"id": cid, "scenes": [scene], "options": DETERMINISTIC + opts + [outputs], "rays": rays})

    lamp_view = box_rays(rng, 60, [-3, -3, .2], [3, 3, 2.5], toward=[0, 0, .5], spread=2)
    case("sphere_lamp-view", "sphere_lamp.rad", ["-av", ".05", ".05", ".05"], lamp_view, "-ovnNpL")
    case("sphere_lamp-any", "sphere_lamp.rad", [], box_rays(rng, 40, [-4, -4, -1], [4, 4, 4]), "-ovL")
    case("sphere_lamp-grazing", "sphere_lamp.rad", [], grazing_rays(rng, 30, 0, [-3, -3], [3, 3], 0.01), "-ovL")
    case(
        "sphere_lamp-irradiance",
        "sphere_lamp.rad",
        ["-I"],
        irradiance_points(rng, 30, [-3, -3, 0], [3, 3, 1], [(0, 0, 1), (1, 0, 0), (0, .6, .8), (0, 0, -1)]),
    )
    room = box_rays(rng, 60, [-2.5, -2.5, .2], [2.5, 2.5, 2.8], toward=[0, 0, 1], spread=3)
    case("polygon_lamp-view", "polygon_lamp.rad", ["-av", ".1", ".1", ".1"], room, "-ovnL")
    case("polygon_lamp-ds0", "polygon_lamp.rad", ["-ds", "0"], room[:30], "-ov")
    case("polygon_lamp-ds05", "polygon_lamp.rad", ["-ds", ".05"], room[30:], "-ov")
    case(
        "polygon_lamp-irradiance",
        "polygon_lamp.rad",
        ["-I"],
        irradiance_points(rng, 30, [-2.5, -2.5, 0], [2.5, 2.5, 2.5], [(0, 0, 1), (0, 0, -1), (1, 0, 0), (-.6, 0, .8)]),
    )
    case("distant-view", "distant.rad", [], box_rays(rng, 50, [-5, -5, .5], [5, 5, 4]), "-ovL")
    case(
        "distant-irradiance",
        "distant.rad",
        ["-I"],
        irradiance_points(rng, 20, [-4, -4, 0], [4, 4, 0], [(0, 0, 1), (0, .8, .6)]),
    )
    huge_view = shift(box_rays(rng, 40, [-3, -3, .2], [3, 3, 2.5], toward=[.5, 0, .4], spread=2), [250000, -120000, 80000])
    case("huge-view", "huge.rad", [], huge_view, "-ovL")
    case("round-view", "round.rad", ["-av", ".02", ".02", ".02"], box_rays(rng, 60, [-3, -3, .1], [3, 3, 3], toward=[0, 0, .7], spread=2), "-ovnL")
    case(
        "round-irradiance",
        "round.rad",
        ["-I"],
        irradiance_points(rng, 20, [-3, -3, 0], [3, 3, 0], [(0, 0, 1)]),
    )
    em_view = box_rays(rng, 60, [-3, -3, .2], [3, 3, 2.5], toward=[0, 0, .8], spread=3)
    case("emitters-view", "emitters.rad", ["-av", ".05", ".05", ".05"], em_view, "-ovlLN")
    case("emitters-up", "emitters.rad", [], box_rays(rng, 30, [1.5, -1, 1], [3.5, 1, 2.5], toward=[2.5, 0, 3.5], spread=1), "-ovL")
    case(
        "emitters-irradiance",
        "emitters.rad",
        ["-I"],
        irradiance_points(rng, 30, [-3, -3, 0], [3, 3, 1], [(0, 0, 1), (-.5, .5, .707), (1, 0, 0)]),
    )
    case("emitters-hit-irradiance", "emitters.rad", ["-i", "-av", ".1", ".1", ".1"], em_view[:40], "-ov")
    hard = hard_rays(rng)
    case("hard-view", "hard.rad", ["-av", ".05", ".05", ".05"], hard, "-ovnNL")
    case("hard-no-backfaces", "hard.rad", ["-bv-"], hard, "-ovL")
    mirrors = mirror_rays(rng)
    case("hard-mirrors", "hard.rad", [], mirrors, "-ovlL")
    case("hard-mirrors-lr3", "hard.rad", ["-lr", "3"], mirrors, "-ov")
    # A positive -lr: below -lw rtrace would otherwise play (random) Russian roulette.
    case("hard-mirrors-lw", "hard.rad", ["-lr", "10", "-lw", ".3"], mirrors, "-ov")
    case("polygon_lamp-lengths", "polygon_lamp.rad", [], room[:40], "-olLo")
    return out


def fmt(rays):
    return "".join(" ".join("%.9g" % x for x in r) + "\n" for r in rays)


def run_case(c, workdir):
    octree = os.path.join(workdir, c["id"] + ".oct")
    with open(octree, "wb") as f:
        subprocess.run(["oconv"] + [os.path.join(SCENES, s) for s in c["scenes"]], stdout=f, check=True)
    p = subprocess.run(
        ["rtrace", "-h"] + c["options"] + [octree],
        input=fmt(c["rays"]),
        capture_output=True,
        text=True,
        check=True,
    )
    return p.stdout


def close(a, b):
    """Numerically equal to the precision rtrace prints (%e: 7 significant digits)."""
    wa, wb = a.split(), b.split()
    if len(wa) != len(wb):
        return False
    for x, y in zip(wa, wb):
        try:
            fx, fy = float(x), float(y)
        except ValueError:
            if x != y:
                return False
            continue
        if abs(fx - fy) > 2e-6 * max(abs(fx), abs(fy), 1e-30):
            return False
    return True


def main():
    check = "--check" in sys.argv[1:]
    all_cases = cases()
    failed = []
    manifest = []
    with tempfile.TemporaryDirectory() as tmp:
        for c in all_cases:
            out = run_case(c, tmp)
            rays_path = os.path.join(DATA, c["id"] + ".rays")
            out_path = os.path.join(DATA, c["id"] + ".out")
            manifest.append({"id": c["id"], "scenes": c["scenes"], "options": c["options"]})
            if check:
                try:
                    same = open(rays_path).read() == fmt(c["rays"]) and close(open(out_path).read(), out)
                except OSError:
                    same = False
                if not same:
                    failed.append(c["id"])
            else:
                with open(rays_path, "w") as f:
                    f.write(fmt(c["rays"]))
                with open(out_path, "w") as f:
                    f.write(out)
    text = json.dumps(manifest, indent=1) + "\n"
    manifest_path = os.path.join(DATA, "cases.json")
    if check:
        try:
            if open(manifest_path).read() != text:
                failed.append("cases.json")
        except OSError:
            failed.append("cases.json")
        if failed:
            print("trace goldens out of date:", ", ".join(failed))
            sys.exit(1)
        print(f"{len(all_cases)} trace cases match rtrace")
    else:
        with open(manifest_path, "w") as f:
            f.write(text)
        print(f"wrote {len(all_cases)} cases, {sum(len(c['rays']) for c in all_cases)} rays")


if __name__ == "__main__":
    main()
