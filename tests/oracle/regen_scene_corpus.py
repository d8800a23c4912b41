#!/usr/bin/env python3
"""Regenerates the generator-made scene corpus and the binary side files of the valid scenes.

    source tests/oracle/env.sh
    .oracle/bin/python tests/oracle/regen_scene_corpus.py          # rewrite the files
    .oracle/bin/python tests/oracle/regen_scene_corpus.py --check  # verify them, exit 1 on drift

Writes:
- `tests/data/scenes/generated/*.rad`: the output of Radiance's generators (genbox, genprism,
  genrev, gensurf, genworm, gensky, xform) for a spread of arguments. A scene that only
  defines a sky (gensky) gets a fixed sky-dome suffix so it contains surfaces a ray can hit;
  geometry gets the materials it names (`white`, `black`) prepended so each file is a
  complete scene.
- binary side files that hand-written scenes in `tests/data/scenes/valid/` name: an octree
  for `instance` (oconv -f), a triangle mesh for `mesh` (obj2mesh), a constant tensor-tree
  BSDF for `BSDF`/`aBSDF` (bsdf2ttree), a 4x4 picture for the `*pict` primitives and a 2x2
  hyperspectral one for `specpict` (both written byte by byte here: pcomb would stamp the
  date into them).

Every output is deterministic; `--check` regenerates into memory and lists each file whose
bytes differ from the committed one. Needs the oracle (`tests/oracle/env.sh`) on PATH.
"""

from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCENES = ROOT / "tests" / "data" / "scenes"
GENERATED = SCENES / "generated"
VALID = SCENES / "valid"

# A fixed suffix turning a gensky sky function into visible geometry, as Radiance's manual
# recommends: a glowing sky dome and a ground hemisphere.
SKY_DOME = """
# --- appended by regen_scene_corpus.py: sky and ground domes ---
skyfunc glow sky_glow
0
0
4 .9 .9 1 0

sky_glow source sky
0
0
4 0 0 1 180

skyfunc glow ground_glow
0
0
4 1.4 .9 .6 0

ground_glow source ground
0
0
4 0 0 -1 180
"""

# name -> (argv, kind). kind "plain" keeps stdout; "sky" appends SKY_DOME.
GENERATORS: list[tuple[str, list[str], str]] = [
    ("genbox_plain", ["genbox", "white", "box", "1", "2", "3"], "plain"),
    ("genbox_inward", ["genbox", "white", "room", "4", "5", "2.5", "-i"], "plain"),
    ("genbox_round", ["genbox", "white", "rbox", "1", "1", "1", "-r", ".1", "-n", "3"], "plain"),
    (
        "genbox_round_smooth",
        ["genbox", "white", "sbox", "2", "1", ".5", "-r", ".2", "-n", "2", "-s"],
        "plain",
    ),
    ("genbox_bevel", ["genbox", "white", "bbox", "1", "1", "1", "-b", ".05"], "plain"),
    ("genbox_bevel_inward", ["genbox", "white", "bibox", "3", "2", "1", "-b", ".1", "-i"], "plain"),
    (
        "genprism_triangle",
        ["genprism", "white", "tri", "3", "0", "0", "1", "0", "0", "1", "-l", "0", "0", "2"],
        "plain",
    ),
    (
        "genprism_rounded",
        ["genprism", "white", "rp", "4", "0", "0", "2", "0", "2", "1", "0", "1", "-l", "0", "0", "1",
         "-r", ".2", "-c"],
        "plain",
    ),
    (
        "genprism_ends",
        ["genprism", "white", "ep", "5", "0", "0", "1", "0", "1.3", ".9", ".5", "1.5", "-.3", ".9",
         "-l", ".2", ".1", "1", "-e"],
        "plain",
    ),
    (
        "genrev_vase",
        ["genrev", "white", "vase", "t", ".2+.1*sin(2*PI*t)", "8"],
        "plain",
    ),
    (
        "genrev_smooth",
        ["genrev", "white", "bowl", "cos(PI/2*t)", "sin(PI/2*t)", "6", "-s"],
        "plain",
    ),
    (
        "genrev_expr",
        ["genrev", "white", "horn", "zf(t)", "rf(t)", "5", "-e", "zf(t)=3*t;rf(t)=.1+t*t"],
        "plain",
    ),
    (
        "gensurf_plane",
        ["gensurf", "white", "wave", "s", "t", ".1*sin(2*PI*s)*cos(2*PI*t)", "4", "4"],
        "plain",
    ),
    (
        "gensurf_smooth",
        ["gensurf", "white", "hill", "2*s-1", "2*t-1", "exp(-4*((2*s-1)^2+(2*t-1)^2))", "5", "3",
         "-s"],
        "plain",
    ),
    (
        "gensurf_sphere",
        ["gensurf", "white", "ball", "xs(s,t)", "ys(s,t)", "zs(s,t)", "6", "4", "-e",
         "xs(s,t)=sin(PI*t)*cos(2*PI*s);ys(s,t)=sin(PI*t)*sin(2*PI*s);zs(s,t)=cos(PI*t)"],
        "plain",
    ),
    (
        "genworm_helix",
        ["genworm", "white", "spring", "cos(4*PI*t)", "sin(4*PI*t)", "t", ".05", "10"],
        "plain",
    ),
    (
        "genworm_taper",
        ["genworm", "white", "tail", "2*t", "0", "t*t", "r(t)", "6", "-e", "r(t)=.2*(1-t)+.01"],
        "plain",
    ),
    ("gensky_clear_noon", ["gensky", "3", "21", "12", "-a", "40", "-o", "98", "-m", "105", "+s"],
     "sky"),
    ("gensky_clear_nosun", ["gensky", "6", "21", "9.5", "-a", "52", "-o", "0", "-m", "15", "-s"],
     "sky"),
    ("gensky_intermediate", ["gensky", "12", "21", "15", "-a", "-33.9", "-o", "-18.4", "-m", "-30",
                             "+i"], "sky"),
    ("gensky_intermediate_nosun", ["gensky", "9", "1", "10", "-a", "35", "-o", "-139", "-m", "-135",
                                   "-i"], "sky"),
    ("gensky_overcast", ["gensky", "1", "15", "14", "-a", "60", "-o", "-10", "-m", "-15", "-c"],
     "sky"),
    ("gensky_uniform", ["gensky", "7", "4", "11", "-u", "-a", "30", "-o", "-90", "-m", "-90"], "sky"),
    ("gensky_angles", ["gensky", "-ang", "45", "30", "+s"], "sky"),
    ("gensky_zenith_brightness", ["gensky", "4", "10", "16.25", "-c", "-b", "22.86", "-g", ".3"],
     "sky"),
]

# Transforms applied by xform to some generator outputs: (name, source, xform options).
XFORMS: list[tuple[str, str, list[str]]] = [
    ("xform_box_rotated", "genbox_plain", ["-rz", "30", "-t", "1", "0", "0"]),
    ("xform_box_mirrored", "genbox_round", ["-mx", "-t", "2", "0", "0"]),
    ("xform_box_array", "genbox_bevel", ["-n", "arr", "-a", "3", "-t", "1.5", "0", "0"]),
    ("xform_box_nested_array", "genbox_plain",
     ["-a", "2", "-t", "2", "0", "0", "-i", "1", "-a", "2", "-t", "0", "3", "0"]),
    ("xform_surf_scaled", "gensurf_smooth", ["-s", "2.5", "-rx", "-90"]),
    ("xform_rev_remod", "genrev_smooth", ["-m", "black", "-ry", "45"]),
    ("xform_worm_mirrored_z", "genworm_helix", ["-mz", "-s", ".5"]),
]

# Prepended to generated geometry so each file is a complete scene: the generators name
# modifier `white` (and xform -m names `black`) but never define it.
MATERIALS = """# --- prepended by regen_scene_corpus.py: the materials the generator output names ---
void plastic white
0
0
5 .7 .7 .7 0 0

void plastic black
0
0
5 .05 .05 .05 0 0

"""

# Side files for hand-written scenes in valid/.
INSTANCE_SOURCE = "instance_part.rad"  # committed, hand-written; octree made from it
INSTANCE_OCTREE = "instance_part.oct"
MESH_OBJ = "mesh_tri.obj"  # committed, hand-written; mesh made from it
MESH_FILE = "mesh_tri.rtm"
PICTURE = "tiny.hdr"
SPECTRAL_PICTURE = "tiny.hsr"
BSDF_XML = "lambert.xml"  # a constant tensor-tree BSDF for BSDF/aBSDF (bsdf2ttree)
BSDF_FUNC = "lamb(ix,iy,iz,ox,oy,oz)=.1/PI"


def run(argv: list[str], cwd: Path) -> bytes:
    """Runs a Radiance program and returns its stdout; any failure is fatal here."""
    proc = subprocess.run(argv, cwd=cwd, capture_output=True, check=False)
    if proc.returncode != 0:
        sys.exit(f"{' '.join(argv)} failed ({proc.returncode}): {proc.stderr.decode(errors='replace')}")
    return proc.stdout


def generated_files() -> dict[Path, bytes]:
    """Every generated scene, keyed by its path, before prepending materials."""
    raw: dict[str, bytes] = {}
    for name, argv, kind in GENERATORS:
        out = run(argv, GENERATED if GENERATED.exists() else ROOT)
        if kind == "sky":
            out += SKY_DOME.encode()
        raw[name] = out
    with tempfile.TemporaryDirectory() as tmp:
        for name, src, opts in XFORMS:
            source = Path(tmp) / f"{src}.rad"
            source.write_bytes(raw[src])
            # xform writes its command line as a comment: run it on a bare file name so the
            # output does not depend on the temporary directory.
            raw[name] = run(["xform", *opts, source.name], Path(tmp))
    files = {}
    for name, body in raw.items():
        prefix = b"" if name.startswith("gensky") else MATERIALS.encode()
        files[GENERATED / f"{name}.rad"] = prefix + body
    return files


def rgbe(r: float, g: float, b: float) -> bytes:
    """One flat RGBE pixel (Radiance's float2rgbe: mantissas scaled by the largest)."""
    v = max(r, g, b)
    if v < 1e-32:
        return bytes(4)
    m, e = math.frexp(v)
    scale = m * 256.0 / v
    return bytes([int(r * scale), int(g * scale), int(b * scale), e + 128])


def picture() -> bytes:
    """A 4x4 flat (uncompressed) Radiance picture with a colour ramp."""
    header = b"#?RADIANCE\nSOFTWARE= regen_scene_corpus.py\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 4\n"
    pixels = b"".join(rgbe((x + 1) / 4, (y + 1) / 4, 0.5) for y in range(4) for x in range(4))
    return header + pixels


def hyperspectral() -> bytes:
    """A 2x2 flat hyperspectral picture (4 bands, one common exponent per pixel), in the
    header layout rtrace -co+ writes."""
    header = (
        b"#?RADIANCE\nSOFTWARE= regen_scene_corpus.py\nNCOMP=4\n"
        b"WAVELENGTH_SPLITS= 780 588 480 380\nFORMAT=Radiance_spectra\n\n-Y 2 +X 2\n"
    )
    pixels = b""
    for k in range(4):
        bands = [0.2 + 0.15 * ((k + b) % 4) for b in range(4)]
        m, e = math.frexp(max(bands))
        pixels += bytes(int(v * m * 256.0 / max(bands)) for v in bands) + bytes([e + 128])
    return header + pixels


def side_files() -> dict[Path, bytes]:
    """Binary files that hand-written valid scenes name."""
    files = {VALID / PICTURE: picture(), VALID / SPECTRAL_PICTURE: hyperspectral()}
    files[VALID / INSTANCE_OCTREE] = run(["oconv", "-f", INSTANCE_SOURCE], VALID)
    with tempfile.TemporaryDirectory() as tmp:
        mesh = Path(tmp) / MESH_FILE
        run(["obj2mesh", MESH_OBJ, str(mesh)], VALID)
        files[VALID / MESH_FILE] = mesh.read_bytes()
    files[VALID / BSDF_XML] = run(["bsdf2ttree", "-g", "2", "-e", BSDF_FUNC, "lamb"], VALID)
    return files


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="verify instead of writing")
    args = parser.parse_args()
    if "RAYPATH" not in os.environ:
        sys.exit("source tests/oracle/env.sh first")
    GENERATED.mkdir(parents=True, exist_ok=True)
    files = {**generated_files(), **side_files()}
    if args.check:
        stale = [p for p, body in sorted(files.items()) if not p.exists() or p.read_bytes() != body]
        known = {p.name for p in files if p.parent == GENERATED}
        extra = sorted(p for p in GENERATED.iterdir() if p.name not in known)
        for p in stale:
            print(f"differs from what the generators print: {p.relative_to(ROOT)}")
        for p in extra:
            print(f"not produced by this script: {p.relative_to(ROOT)}")
        if stale or extra:
            return 1
        print(f"scene corpus ok: {len(files)} files")
        return 0
    for old in GENERATED.glob("*.rad"):
        if old not in files:
            old.unlink()
    for path, body in sorted(files.items()):
        path.write_bytes(body)
    print(f"wrote {len(files)} files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
