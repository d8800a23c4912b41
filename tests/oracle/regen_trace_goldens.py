"""Goldens for `radc trace`: what real rtrace prints for the same rays and options.

Scenes live in tests/data/trace/scenes/. For each case below this script writes the
rays it sends (tests/data/trace/<id>.rays, generated from a fixed seed) and rtrace's
answers (tests/data/trace/<id>.out), plus tests/data/trace/cases.json listing every
case. tests/trace_differential.rs runs `radc trace` on the same rays and compares.

Options: every case runs rtrace deterministically: no ambient bounces (-ab 0), no
source jitter (-dj 0), every shadow tested (-dt 0), no randomized source orientation
(-u-), and no virtual sources (-dr 0) unless a case asks for relays through mirrors.

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


def limited(rays, rng):
    """The same rays with directions scaled to random lengths (for -ld)."""
    out = []
    for r in rays:
        n = math.sqrt(sum(x * x for x in r[3:]))
        k = rng.choice([.5, 1, 2, 4, 8, 50]) / n
        out.append(r[:3] + [x * k for x in r[3:]])
    return out


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
    spot_view = box_rays(rng, 50, [-3, -3, 1], [3, 3, 3.5], toward=[0, 0, 0], spread=3)
    case("spots-view", "spots.rad", [], spot_view, "-ovL")
    case(
        "spots-irradiance",
        "spots.rad",
        ["-I"],
        irradiance_points(rng, 40, [-3, -3, 0], [3, 3, 0], [(0, 0, 1)]),
    )
    trans_view = box_rays(rng, 50, [-3, -3, .5], [3, 3, 3.5], toward=[0, 0, 1], spread=2.5)
    case("trans-view", "trans.rad", ["-av", ".1", ".1", ".1"], trans_view, "-ovlL")
    case(
        "trans-irradiance",
        "trans.rad",
        ["-I"],
        irradiance_points(rng, 40, [-3, -3, 0], [3, 3, 0], [(0, 0, 1)]) + [[-2.5, 2.5, .35, 0, 0, 1]],
    )
    case("trans-hit-irradiance", "trans.rad", ["-i"], trans_view[:25], "-ov")
    refl = [[x + .5, .5, 1, 0, dy, dz] for x in (0, 2, 4, 6) for dy, dz in ((0, -1), (.5, -1), (3, -.5), (-1, -1))]
    refl += box_rays(rng, 30, [-1, -1, .5], [8, 2, 2], toward=[3.5, .5, 0], spread=3.5)
    case("reflections-parts", "reflections.rad", ["-av", ".1", ".1", ".1"], refl, "-ovrRxXlLwc")
    glass_view = box_rays(rng, 50, [-3, -3, .5], [3, 3, 3.5], toward=[0, 0, 1], spread=2.5)
    case("glass-view", "glass.rad", ["-av", ".1", ".1", ".1"], glass_view, "-ovrRxXlL")
    case(
        "glass-irradiance",
        "glass.rad",
        ["-I"],
        irradiance_points(rng, 40, [-3, -3, 0], [3, 3, 0], [(0, 0, 1)]),
    )
    case("glass-hit-irradiance", "glass.rad", ["-i"], glass_view[:25], "-ov")
    die_view = box_rays(rng, 60, [-3, -3, .5], [3, 3, 3.5], toward=[0, -.5, .6], spread=2)
    # A positive -lr: rays inside the ball fall below -lw, where rtrace would otherwise
    # play (random) Russian roulette.
    case("dielectric-view", "dielectric.rad", ["-lr", "12", "-av", ".1", ".1", ".1"], die_view, "-ovrRxXlL")
    case(
        "dielectric-irradiance",
        "dielectric.rad",
        ["-I"],
        irradiance_points(rng, 30, [-3, -3, 0], [3, 3, 0], [(0, 0, 1)]),
    )
    tube_pts = irradiance_points(rng, 30, [-1.4, -.9, .8], [1.4, .9, .8], [(0, 0, 1), (.3, 0, .95)])
    tube_pts += irradiance_points(rng, 20, [-4, -4, 0], [4, 4, 0], [(0, 0, 1)])
    tube_pts += [[0, 0, 1.9, 0, 0, 1], [0, .05, 2, 0, 1, 0], [1.5, 0, 2, -1, 0, 0], [0, 0, 1.2, 0, 0, 1]]
    case("tube_lamp-irradiance", "tube_lamp.rad", ["-I"], tube_pts)
    case("tube_lamp-irradiance-ds05", "tube_lamp.rad", ["-I", "-ds", ".05"], tube_pts)
    case("tube_lamp-view", "tube_lamp.rad", [], box_rays(rng, 30, [-2, -2, 1], [2, 2, 3], toward=[0, 0, .8], spread=1.5), "-ovL")
    # light relayed by mirrors (virtual sources): one mirror, and two facing mirrors
    case("emitters-relay", "emitters.rad", ["-I", "-dr", "2"],
         irradiance_points(rng, 40, [-3.8, -3, 0], [0, 3, 1.5], [(0, 0, 1), (-1, 0, 0), (-.6, .3, .7)]))
    case("emitters-relay-view", "emitters.rad", ["-dr", "1"], em_view, "-ovL")
    relay_pts = irradiance_points(rng, 40, [3.5, -1.5, 0], [4.45, 1.5, 2.5], [(1, 0, 0), (.5, 0, .8), (0, 0, 1)])
    case("hard-relay", "hard.rad", ["-I", "-dr", "2"], relay_pts)
    case("hard-relay-dr3", "hard.rad", ["-I", "-dr", "3"], relay_pts)
    mirror_pts = irradiance_points(rng, 50, [-3.5, -3.5, 0], [3.5, 3.5, 0], [(0, 0, 1)])
    mirror_pts += irradiance_points(rng, 20, [-1, .9, .2], [1, .9, 1.4], [(0, -1, 0)])
    for dr in ("0", "1", "2", "3"):
        case("mirrors-relay-dr" + dr, "mirrors.rad", ["-I", "-dr", dr], mirror_pts)
    case("mirrors-view", "mirrors.rad", ["-dr", "2"], box_rays(rng, 40, [-2, -2, .5], [2, 2, 2]), "-ovL")
    anti_view = box_rays(rng, 40, [-1, -1, 3], [2, 2, 4], toward=[.5, .3, 1.2], spread=.9)
    anti_view += box_rays(rng, 30, [-4.5, -4.5, 1], [-1.5, -1.5, 3], toward=[-3, -3, -.5], spread=.8)
    anti_view += box_rays(rng, 20, [-3, -3, .5], [3, 3, 1.2], toward=[.5, .3, 1.75], spread=.3)
    case("antimatter-view", "antimatter.rad", ["-av", ".05", ".05", ".05"], anti_view, "-ovLN")
    anti_pts = irradiance_points(rng, 30, [-.5, -.7, 0], [1.5, 1.3, 0], [(0, 0, 1)])
    anti_pts += irradiance_points(rng, 20, [-4, -4, -2], [-2, -2, -2], [(0, 0, 1)])
    case("antimatter-irradiance", "antimatter.rad", ["-I"], anti_pts)
    aniso_view = box_rays(rng, 50, [-3, -3, 1], [3, 3, 3], toward=[0, 0, 0], spread=2)
    aniso_view += box_rays(rng, 20, [-1, -2, .5], [1, 0, 1.5], toward=[0, 1, 1], spread=.8)
    case("aniso-view", "aniso.rad", ["-av", ".05", ".05", ".05"], aniso_view, "-ovL")
    case("aniso-hit-irradiance", "aniso.rad", ["-i"], aniso_view[:30], "-ov")
    mist_view = box_rays(rng, 40, [-3, -3, .5], [3, 3, 3.5], toward=[0, 0, 1.5], spread=2.5)
    mist_view += box_rays(rng, 15, [2.2, 2.2, .3], [3.8, 3.8, 1.7])  # inside the fog
    case("mist-view", "mist.rad", ["-av", ".05", ".05", ".05"], mist_view, "-ovlL")
    case("mist-irradiance", "mist.rad", ["-I"], irradiance_points(rng, 30, [-3, -3, 0], [3, 3, 0], [(0, 0, 1)]))
    case("medium-view", "dielectric.rad", ["-me", ".05", ".1", ".2", "-lr", "12"], die_view[:30], "-ovL")
    case("emitters-invisible-sources", "emitters.rad", ["-dv-", "-dr", "1"], em_view, "-ov")
    case("glass-limited", "glass.rad", ["-ld"], limited(glass_view, rng), "-ovL")
    case("distant-limited", "distant.rad", ["-ld"], limited(box_rays(rng, 40, [-5, -5, .5], [5, 5, 4]), rng), "-ovL")
    case("polygon_lamp-lengths", "polygon_lamp.rad", [], room[:40], "-olLo")
    alias_view = box_rays(rng, 50, [-3, -2, .5], [3, 2, 3], toward=[0, 0, .5], spread=2)
    alias_view += box_rays(rng, 20, [-2, 0, 1], [2, 2, 2], toward=[0, 3, 2], spread=1)
    case("aliases-view", "aliases.rad", ["-av", ".05", ".05", ".05"], alias_view, "-ovL")
    case("aliases-irradiance", "aliases.rad", ["-I"],
         irradiance_points(rng, 30, [-4, -4, 0], [4, 2.5, 0], [(0, 0, 1)]))
    pat_view = box_rays(rng, 60, [-3, -4, .5], [3, -2, 3], toward=[0, 0, .8], spread=2.5)
    pat_view += box_rays(rng, 20, [-1, -1, 1.5], [1, 1, 2.5], toward=[0, 0, 8], spread=3)
    pat_view += box_rays(rng, 30, [0, -2, 1], [2, 0, 2], toward=[1.5, 1.5, .8], spread=.6)
    case("patterns-view", "patterns.rad", ["-av", ".05", ".05", ".05"], pat_view, "-ovL")
    case("patterns-irradiance", "patterns.rad", ["-I"],
         irradiance_points(rng, 40, [-4.5, -4.5, 0], [4.5, 2.5, 0], [(0, 0, 1)]))
    tex_view = box_rays(rng, 60, [-3, -4, .5], [3, -2, 3], toward=[0, 0, .5], spread=2.5)
    tex_view += box_rays(rng, 30, [-2.5, -2, .5], [-.5, -1, 1.5], toward=[-1.5, 0, 1], spread=.6)
    tex_view += box_rays(rng, 20, [-2, 0, 1], [2, 2, 2], toward=[0, 3, 2], spread=1)
    tex_view += box_rays(rng, 40, [1, -4, 1], [3, -3, 2], toward=[2, -1.2, .3], spread=.5)
    tex_view += box_rays(rng, 30, [0, -3, .8], [2, -2.5, 1.6], toward=[1.2, -1, 1.15], spread=.3)
    case("textures-view", "textures.rad", ["-av", ".05", ".05", ".05"], tex_view, "-ovL")
    case("textures-irradiance", "textures.rad", ["-I"],
         irradiance_points(rng, 30, [-4.5, -4.5, 0], [4.5, 2.5, 0], [(0, 0, 1)]))
    day_view = box_rays(rng, 40, [1, 1, 1], [3, 4, 2], toward=[2, 0, 1.75], spread=.8)
    day_view += [[x, 3.0, z, dx, -1.0, 0.0]
                 for x, z, dx in ((1.5, 1.2, 0), (2, 1.5, .1), (2.5, 2, -.2), (2, 2.4, .05))]
    case("daylight-view", "daylight.rad", ["-av", ".05", ".05", ".05"], day_view, "-ovL")
    case("daylight-irradiance", "daylight.rad", ["-I"],
         irradiance_points(rng, 30, [.2, .2, .8], [3.8, 4.8, .8], [(0, 0, 1)]))
    data_view = box_rays(rng, 60, [-3, -4, .5], [3, -2, 3], toward=[0, 0, .8], spread=2.5)
    data_view += box_rays(rng, 30, [-1, -2, 1], [2, 0, 2], toward=[.5, 2.9, 1.5], spread=1.2)
    data_view += box_rays(rng, 30, [-1, -2, 1], [2, 0, 2], toward=[-1.5, 0, 1], spread=.8)
    data_view += box_rays(rng, 20, [-1, -1, 1.5], [1, 1, 2.5], toward=[0, 0, 8], spread=3)
    data_view += box_rays(rng, 20, [-1, -3, .5], [2, -2.5, 1.5], toward=[.5, -1, .4], spread=.3)
    case("data_patterns-view", "data_patterns.rad", ["-av", ".05", ".05", ".05"], data_view, "-ovL")
    case("data_patterns-irradiance", "data_patterns.rad", ["-I"],
         irradiance_points(rng, 40, [-4.5, -4.5, 0], [4.5, 2.5, 0], [(0, 0, 1)]))
    texd_view = box_rays(rng, 60, [-3, -4, .5], [3, -2, 3], toward=[0, 0, .3], spread=2.5)
    texd_view += box_rays(rng, 30, [-1, -2, 1], [2, 0, 2], toward=[0, 3, 2], spread=1.5)
    texd_view += box_rays(rng, 30, [-2.5, -2, .5], [-.5, -1, 1.5], toward=[-1.5, 0, 1], spread=.6)
    case("texture_data-view", "texture_data.rad", ["-av", ".05", ".05", ".05"], texd_view, "-ovL")
    case("texture_data-irradiance", "texture_data.rad", ["-I"],
         irradiance_points(rng, 30, [-4.5, -4.5, 0], [4.5, 2.5, 0], [(0, 0, 1)]))
    mix_view = box_rays(rng, 60, [-3, -4, .5], [3, -2, 3], toward=[0, 0, .3], spread=2.5)
    mix_view += box_rays(rng, 30, [-1, -2, 1], [2, 0, 2], toward=[0, 3, 2], spread=1.5)
    mix_view += box_rays(rng, 30, [-2.5, -2, .5], [-.5, -1, 1.5], toward=[-1.5, 0, 1], spread=.6)
    mix_view += box_rays(rng, 30, [0, -4, .5], [1, -3, 1.5], toward=[0, -1.5, 1], spread=.8)
    mix_view += box_rays(rng, 30, [0, -1, .5], [2.5, 0, 1.5], toward=[1.5, .5, .8], spread=.5)
    mix_view += box_rays(rng, 30, [0, -2, 1], [2, 0, 2], toward=[-4, 0, 1.5], spread=2)
    mix_view += box_rays(rng, 30, [0, -1, 1], [1, 1, 2], toward=[.5, 2.9, 1.5], spread=1)
    case("mixtures-view", "mixtures.rad", ["-av", ".05", ".05", ".05"], mix_view, "-ovL")
    case("mixtures-irradiance", "mixtures.rad", ["-I"],
         irradiance_points(rng, 40, [-4.5, -4.5, 0], [4.5, 2.5, 0], [(0, 0, 1)]))
    fn_view = box_rays(rng, 60, [-3, -4, .5], [3, -2, 3], toward=[0, 0, .3], spread=2.5)
    fn_view += box_rays(rng, 30, [-1, -2, 1], [2, 0, 2], toward=[0, 3, 2], spread=1.5)
    fn_view += box_rays(rng, 30, [-2.5, -2, .5], [-.5, -1, 1.5], toward=[-1.5, 0, 1], spread=.6)
    fn_view += box_rays(rng, 30, [-.5, -3, .5], [.5, -2.5, 1.5], toward=[0, -2.75, 3], spread=.6)
    fn_view += box_rays(rng, 30, [0, -1, .5], [2.5, 0, 1.5], toward=[1.5, .5, .8], spread=.5)
    fn_view += box_rays(rng, 30, [0, -2, 1], [2, 0, 2], toward=[-4, 0, 1.5], spread=2)
    fn_view += box_rays(rng, 30, [2, -2, .5], [3.5, -.5, 1.5], toward=[2.75, -1.25, 2.5], spread=.6)
    case("functions-view", "functions.rad", ["-av", ".05", ".05", ".05"], fn_view, "-ovL")
    case("functions-irradiance", "functions.rad", ["-I"],
         irradiance_points(rng, 40, [-4.5, -4.5, 0], [4.5, 2.5, 0], [(0, 0, 1)]))
    br_view = box_rays(rng, 60, [-3, -4, .5], [3, -2, 3], toward=[0, 0, .3], spread=2.5)
    br_view += box_rays(rng, 40, [-1, -2, 1], [1, 0, 2], toward=[0, 2, 1.5], spread=1.2)
    br_view += box_rays(rng, 40, [-2.5, -3, .5], [-.5, -2, 1.5], toward=[-1.5, -1, 1], spread=.6)
    br_view += box_rays(rng, 30, [-.5, -3, .5], [.5, -2.5, 1.5], toward=[0, -2.75, 3], spread=.6)
    br_view += box_rays(rng, 20, [-.5, -3, 4], [.5, -2.5, 4.5], toward=[0, -2.75, 3], spread=.6)
    br_view += box_rays(rng, 30, [-1, 2, 1], [1, 2.8, 2], toward=[0, 0, 1.5], spread=1.2)
    case("brtd-view", "brtd.rad", ["-av", ".05", ".05", ".05"], br_view, "-ovL")
    case("brtd-irradiance", "brtd.rad", ["-I"],
         irradiance_points(rng, 40, [-4.5, -4.5, 0], [4.5, 2.5, 0], [(0, 0, 1)]))
    an_view = box_rays(rng, 60, [-3, -3, 1], [3, 3, 3], toward=[0, 0, 0], spread=2)
    an_view += box_rays(rng, 20, [-1, -2, .5], [1, 0, 1.5], toward=[0, 1, 1], spread=.8)
    an_view += box_rays(rng, 20, [-1, -3, .3], [0, -2.5, 1], toward=[-1.5, -1.5, .5], spread=.4)
    case("aniso_functions-view", "aniso_functions.rad", ["-av", ".05", ".05", ".05"], an_view, "-ovL")
    case("aniso_patterns-view", "aniso_patterns.rad", ["-av", ".05", ".05", ".05"], an_view, "-ovL")
    case("aniso_patterns-irradiance", "aniso_patterns.rad", ["-I"],
         irradiance_points(rng, 30, [-2.9, -2.9, 0], [2.9, 2.9, 0], [(0, 0, 1)]))
    mp_view = box_rays(rng, 40, [-2, -2, .5], [2, 0, 2.5], toward=[0, 3, 1.5], spread=2)
    mp_view += box_rays(rng, 40, [-2, -2, .5], [2, 2, 2.5], toward=[3, 0, 1.5], spread=2)
    mp_view += box_rays(rng, 30, [-2, -2, .5], [2, 2, 2.5], toward=[-3, 0, 1.5], spread=2)
    mp_view += box_rays(rng, 20, [-2, -2, 1], [2, 2, 2], toward=[0, 0, 0], spread=3)
    case("mirror_patterns-view", "mirror_patterns.rad", ["-av", ".05", ".05", ".05"], mp_view, "-ovL")
    case("mirror_patterns-relayed", "mirror_patterns.rad", ["-av", ".05", ".05", ".05", "-dr", "1"], mp_view, "-ovL")
    gp_view = box_rays(rng, 50, [-3, -3, .5], [3, -1, 2.2], toward=[0, 1, 1.2], spread=2.5)
    gp_view += box_rays(rng, 30, [-3, 2, .5], [3, 3.5, 2.2], toward=[0, 1, 1.2], spread=2.5)
    gp_view += box_rays(rng, 30, [-1, -1, 1], [1, 1, 2], toward=[0, 0, 4], spread=2)
    case("glass_patterns-view", "glass_patterns.rad", ["-av", ".05", ".05", ".05"], gp_view, "-ovL")
    case("glass_patterns-irradiance", "glass_patterns.rad", ["-I"],
         irradiance_points(rng, 40, [-3.9, -3.9, 0], [3.9, 3.9, 0], [(0, 0, 1)]))
    case("trans_textures-view", "trans_textures.rad", ["-av", ".05", ".05", ".05"], gp_view, "-ovL")
    case("trans_textures-irradiance", "trans_textures.rad", ["-I"],
         irradiance_points(rng, 40, [-3.9, -3.9, 0], [3.9, 3.9, 0], [(0, 0, 1)]))
    dp_view = box_rays(rng, 40, [-3, -3, .5], [0, -1, 2.2], toward=[-1.5, 0, 1], spread=.8)
    dp_view += box_rays(rng, 40, [0, -3, 1], [3, -1, 2.5], toward=[1.5, 0, .5], spread=1.5)
    dp_view += box_rays(rng, 30, [0, -1, 1], [3, 1, 2.5], toward=[1.5, 1.5, 1.5], spread=.6)
    # A positive -lr: rays below -lw are dropped, not played at Russian roulette (random
    # in Radiance), which absorbing patterned media reach after a few internal bounces.
    case("dielectric_patterns-view", "dielectric_patterns.rad", ["-av", ".05", ".05", ".05", "-lr", "12"],
         dp_view, "-ovL")
    case("dielectric_patterns-irradiance", "dielectric_patterns.rad", ["-I", "-lr", "12"],
         irradiance_points(rng, 40, [-3.9, -3.9, 0], [3.9, 3.9, 0], [(0, 0, 1)]))
    # ashik2 looks where the anisotropic scenes look.
    as_view = box_rays(rng, 60, [-3, -3, 1], [3, 3, 3], toward=[0, 0, 0], spread=2)
    as_view += box_rays(rng, 20, [-1, -2, .5], [1, 0, 1.5], toward=[0, 1, 1], spread=.8)
    as_view += box_rays(rng, 20, [-1, -3, .3], [0, -2.5, 1], toward=[-1.5, -1.5, .5], spread=.4)
    case("ashik-view", "ashik.rad", ["-av", ".05", ".05", ".05"], as_view, "-ovL")
    case("ashik-irradiance", "ashik.rad", ["-I"],
         irradiance_points(rng, 30, [-2.9, -2.9, 0], [2.9, 2.9, 0], [(0, 0, 1)]))
    # Meshes: Radiance's obj2mesh files (make_meshes), smoothed and uv-mapped, with
    # their own materials and the scene's, patterns on (u,v), textures on smoothed
    # normals, transforms; rays also aimed at the closed box's edges and corners.
    me_view = box_rays(rng, 120, [-4.5, -4, 3], [3.5, 2.5, 4.5], toward=[-.5, -.5, -.5], spread=3)
    me_view += box_rays(rng, 40, [-4, -4, 1], [-2, -1, 2], toward=[-3, -2, -.4], spread=.8)
    me_view += box_edge_rays(rng, 40)
    case("meshes-view", "meshes.rad", ["-av", ".05", ".05", ".05"], me_view, "-ovnNpcL")
    case("meshes-irradiance", "meshes.rad", ["-I"],
         irradiance_points(rng, 40, [-4.5, -4.5, -1], [3.5, 3.5, -1], [(0, 0, 1)]))
    return out


def box_edge_rays(rng, n):
    """Rays from above aimed at points on the edges and at the corners of meshes.rad's
    box (box.rtm placed with -rz 35 -s 1.2 -t -3 -2.5 -1)."""
    c, s = math.cos(math.radians(35)), math.sin(math.radians(35))

    def place(p):
        x, y, z = p
        return [1.2 * (c * x - s * y) - 3, 1.2 * (s * x + c * y) - 2.5, 1.2 * z - 1]

    edges = [((0, 0, 1), (1, 0, 1)), ((1, 0, 1), (1, 1, 1)), ((1, 1, 1), (0, 1, 1)),
             ((0, 1, 1), (0, 0, 1)), ((0, 0, 1), (1, 1, 1)), ((1, 0, 0), (1, 0, 1))]
    rays = []
    for i in range(n):
        a, b = edges[i % len(edges)]
        f = 0.0 if i % 5 == 0 else rng.uniform(0, 1)
        target = place([u + f * (v - u) for u, v in zip(a, b)])
        o = [rng.uniform(-4, -2), rng.uniform(-3.5, -1.5), rng.uniform(1.5, 3)]
        rays.append(o + [t - q for t, q in zip(target, o)])
    return rays


def make_meshes():
    """The mesh files meshes.rad places, made by the oracle's obj2mesh."""
    for obj, mats in (("ball", "ball_materials.rad"), ("box", "box_materials.rad")):
        subprocess.run(["obj2mesh", "-a", mats, obj + ".obj", obj + ".rtm"], cwd=SCENES, check=True)


def make_poster():
    """The colorpict picture: drawn by the oracle's pcomb (RLE scanlines), with its
    capture-time lines dropped so the file is the same each run, and a pixel aspect
    ratio added (colorpict sizes the picture by it)."""
    p = subprocess.run(
        ["pcomb", "-x", "12", "-y", "8", "-e", "ro=x/12;go=y/8;bo=if(x-6,1,.2)"],
        capture_output=True,
        check=True,
    )
    head, sep, rest = p.stdout.partition(b"\n\n")
    lines = [l for l in head.split(b"\n") if not l.startswith((b"CAPDATE=", b"GMT="))]
    lines.append(b"PIXASPECT=1.5")
    with open(os.path.join(SCENES, "poster.hdr"), "wb") as f:
        f.write(b"\n".join(lines) + sep + rest)


def fmt(rays):
    return "".join(" ".join("%.9g" % x for x in r) + "\n" for r in rays)


def run_case(c, workdir):
    octree = os.path.join(workdir, c["id"] + ".oct")
    with open(octree, "wb") as f:
        # From the scenes' folder: mesh files are found there, as radc finds them.
        subprocess.run(["oconv"] + c["scenes"], stdout=f, check=True, cwd=SCENES)
    p = subprocess.run(
        ["rtrace", "-h"] + c["options"] + [octree],
        input=fmt(c["rays"]),
        capture_output=True,
        text=True,
        check=True,
        cwd=SCENES,  # function files (patterns.cal) are found beside the scenes
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
    if not check:
        make_poster()
        make_meshes()
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
