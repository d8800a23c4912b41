#!/usr/bin/env python3
"""Records what Radiance says about every scene in the corpus: tests/data/scenes/oracle.json.

    source tests/oracle/env.sh
    .oracle/bin/python tests/oracle/regen_scene_goldens.py           # rewrite oracle.json
    .oracle/bin/python tests/oracle/regen_scene_goldens.py --check   # fail on any change
    .oracle/bin/python tests/oracle/regen_scene_goldens.py SCENE...  # print verdicts only

Scenes: every `.rad`/`.mat` file in tests/data/scenes/{generated,valid,invalid}/ and in
../shared/corpus/radiance/ (Radiance's own test scenes, read in place; skipped when absent).
Keys are paths relative to the workspace root.

For each scene, run from the scene's own folder (so relative `.cal`, `.dat`, octree and
picture names resolve the way they do for a Radiance user), with RAYPATH = `.` + the oracle's
library:

1. `oconv SCENE`: `oconv_ok` is its exit status. oconv checks syntax, counts of geometry and
   modifier references, but not the arguments of materials, patterns or lights.
2. When oconv accepts, a probe render with `rtrace -h -ab 0` (deterministic, no ambient
   cache). Radiance checks a material's arguments (and loads its `.cal`/`.dat`/picture/font
   files) only when a ray first hits a surface wearing it, and checks lights when it sets up
   sources, so the probe has to hit every surface. The probe rays are:
   - for every surface primitive in the expanded scene (`xform SCENE`, which also runs `!`
     commands), rays aimed at it from just off its surface on both sides: polygons at their
     centroid and first fan triangle along the normal; spheres/bubbles along the six axes;
     cones, cups, cylinders and tubes at the middle of the axis from outside and inside;
     rings at their mean radius along the normal; `source`s from the scene's centre along
     their direction;
   - a 7x7 grid of rays inward from each of the six faces of the scene's bounding box
     (`getbbox`), which reaches instances and meshes whose contents the probe cannot see.
   A surface hidden behind a coincident one can still escape; the corpus scenes avoid that.
   `--probe-coverage` proves the probe's reach: it breaks each modifier of each accepted
   scene in turn (all arguments removed) and lists those whose breakage rtrace never notices.
   `render_ok` is rtrace's exit status (false when oconv failed: nothing to render).
3. `radiance_says`, for a rejected scene only: the first `fatal`/`system`/`internal`/
   `consistency` line (oconv's, else rtrace's); when a failing
   run printed none (calcomp errors), its first three lines joined by " / "; otherwise "".
   `warnings`: the distinct warning lines, in order, at most 8. Absolute paths of the scene
   folder and the oracle library are replaced by `.` and `$RAYPATH_LIB`.
4. `library_files`: the files of the oracle's library (`$RAYPATH_LIB`) the scene names, sorted:
   every word of the scene or of its `xform` expansion that is no file in the scene's folder
   but is one in the library. On a machine without the oracle radc cannot find them (and
   rightly reports them missing), so the Rust test compares those scenes only where the
   oracle is installed, and every other scene everywhere.
5. Shared-corpus scenes also get `needs_commands`: true when the file runs `!` commands or
   Radiance could not find a file it names (meshes, octrees, BSDF XML not copied there), so
   the Rust test can skip them until radc expands commands.

Each Radiance run is limited to 2 GB of address space and a timeout; a run that hits either
counts as a rejection, with the limit as its message. Output is sorted and deterministic.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCENES = ROOT / "tests" / "data" / "scenes"
OWN_FOLDERS = ("generated", "valid", "invalid")
SHARED = ROOT.parent / "shared" / "corpus" / "radiance"
SHARED_KEY = "../shared/corpus/radiance"
GOLDEN = SCENES / "oracle.json"
SCENE_SUFFIXES = (".rad", ".mat")
OCONV_TIMEOUT = 60
RTRACE_TIMEOUT = 300
MEMORY_LIMIT = 2 << 30
MAX_WARNINGS = 8
GRID = 7
# Messages meaning Radiance could not find a file the scene names.
MISSING_FILE = re.compile(r"cannot (open|find|load)|load error|no such file", re.IGNORECASE)
# Radiance's error levels other than warnings (src/common/error.c), and our timeout.
ERROR_LINE = re.compile(r": (fatal|system|internal|consistency) - |timed out after")


# ---------------------------------------------------------------- running Radiance


def limit_memory() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))


def run(argv: list[str], cwd: Path, stdin: bytes, timeout: int) -> tuple[int, str, bytes]:
    """Runs a Radiance program; returns (status, stderr text, stdout)."""
    try:
        proc = subprocess.run(
            argv,
            cwd=cwd,
            input=stdin,
            capture_output=True,
            timeout=timeout,
            preexec_fn=limit_memory,
            check=False,
        )
    except subprocess.TimeoutExpired:
        return 124, f"{argv[0]}: timed out after {timeout}s (radc-oracle)", b""
    return proc.returncode, proc.stderr.decode("utf-8", errors="replace"), proc.stdout


# ---------------------------------------------------------------- reading scenes


def words(text: str) -> list[str | None]:
    """Splits a scene into words, roughly as Radiance's fgetword does:
    whitespace separates, a double quote opens a segment in which whitespace is kept,
    a word starting with `#` or `!` runs to the end of the line (`None` marks a command).
    Only used on scenes oconv accepted, where such words start statements, so no error
    handling beyond not crashing."""
    tokens: list[str | None] = []  # None marks a `!` line
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c.isspace():
            i += 1
            continue
        if c in "#!":
            end = text.find("\n", i)
            end = n if end < 0 else end
            if c == "!":
                tokens.append(None)
            i = end
            continue
        word = []
        while i < n and not text[i].isspace():
            if text[i] == '"':
                close = text.find('"', i + 1)
                close = n if close < 0 else close
                word.append(text[i + 1 : close])
                i = close + 1
            else:
                word.append(text[i])
                i += 1
        tokens.append("".join(word))
    return tokens


def statements(text: str) -> list[list[str]]:
    """The word lists of each primitive of an expanded scene (alias included)."""
    toks = [t for t in words(text) if t is not None]
    out = []
    i = 0
    while i + 2 < len(toks):
        start = i
        i += 3
        if toks[start + 1] == "alias":
            i += 1
        else:
            try:
                for _ in range(3):
                    i += 1 + int(toks[i])
            except (ValueError, IndexError):
                break
        out.append(toks[start:i])
    return out


def primitives(text: str) -> list[tuple[str, str, list[str], list[float]]]:
    """(modifier, type, strings, reals) of each non-alias primitive in an expanded scene."""
    out = []
    for words_ in statements(text):
        if words_[1] == "alias":
            continue
        try:
            ns = int(words_[3])
            nr_at = 3 + 1 + ns + 1 + int(words_[4 + ns])
            reals = [float(x) for x in words_[nr_at + 1 :]]
        except (ValueError, IndexError):
            continue
        out.append((words_[0], words_[1], words_[4 : 4 + ns], reals))
    return out


# ---------------------------------------------------------------- probe rays

Vec = tuple[float, float, float]


def sub(a: Vec, b: Vec) -> Vec:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def add(a: Vec, b: Vec) -> Vec:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def scale(a: Vec, s: float) -> Vec:
    return (a[0] * s, a[1] * s, a[2] * s)


def cross(a: Vec, b: Vec) -> Vec:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a: Vec) -> Vec | None:
    length = math.sqrt(a[0] ** 2 + a[1] ** 2 + a[2] ** 2)
    return None if length < 1e-12 or not math.isfinite(length) else scale(a, 1 / length)


def perpendicular(n: Vec) -> Vec:
    other = (1.0, 0.0, 0.0) if abs(n[0]) < 0.9 else (0.0, 1.0, 0.0)
    return norm(cross(n, other)) or (1.0, 0.0, 0.0)


def both_sides(p: Vec, n: Vec, eps: float) -> list[tuple[Vec, Vec]]:
    """Two rays hitting point p of a surface with normal n, one from each side."""
    return [(add(p, scale(n, eps)), scale(n, -1)), (sub(p, scale(n, eps)), n)]


def surface_rays(typ: str, r: list[float], centre: Vec, eps: float) -> list[tuple[Vec, Vec]]:
    """Rays aimed at one surface primitive (see the module docstring)."""
    if typ == "polygon" and len(r) >= 9 and len(r) % 3 == 0:
        vs = [tuple(r[k : k + 3]) for k in range(0, len(r), 3)]
        newell = (0.0, 0.0, 0.0)
        for a, b in zip(vs, vs[1:] + vs[:1]):
            newell = add(newell, cross(a, b))  # type: ignore[arg-type]
        n = norm(newell)
        if n is None:
            return []
        mean = scale(tuple(map(sum, zip(*vs))), 1 / len(vs))  # type: ignore[arg-type]
        fan = scale(add(add(vs[0], vs[1]), vs[2]), 1 / 3)  # type: ignore[arg-type]
        return both_sides(mean, n, eps) + both_sides(fan, n, eps)
    if typ in ("sphere", "bubble") and len(r) == 4:
        c, rad = (r[0], r[1], r[2]), abs(r[3])
        rays = []
        for d in ((1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)):
            d = (float(d[0]), float(d[1]), float(d[2]))
            rays.append((add(c, scale(d, rad + eps)), scale(d, -1)))
        rays.append((c, (0.0, 0.0, 1.0)))
        return rays
    if typ in ("cone", "cup", "cylinder", "tube") and len(r) in (7, 8):
        p0, p1 = (r[0], r[1], r[2]), (r[3], r[4], r[5])
        rad = abs(r[6]) if len(r) == 7 else (abs(r[6]) + abs(r[7])) / 2
        axis = norm(sub(p1, p0))
        if axis is None:
            return []
        mid = scale(add(p0, p1), 0.5)
        rays = []
        for u in (perpendicular(axis), scale(perpendicular(axis), -1)):
            rays.append((add(mid, scale(u, rad + eps)), scale(u, -1)))
            rays.append((mid, u))
        return rays
    if typ == "ring" and len(r) == 8:
        c, n = (r[0], r[1], r[2]), norm((r[3], r[4], r[5]))
        if n is None:
            return []
        p = add(c, scale(perpendicular(n), (abs(r[6]) + abs(r[7])) / 2))
        return both_sides(p, n, eps)
    if typ == "source" and len(r) == 4:
        d = norm((r[0], r[1], r[2]))
        return [] if d is None else [(centre, d)]
    return []


def bbox_grid(box: list[float]) -> list[tuple[Vec, Vec]]:
    """Rays inward from a GRID x GRID lattice on each face of the bounding box."""
    lo, hi = (box[0], box[2], box[4]), (box[1], box[3], box[5])
    size = max(hi[k] - lo[k] for k in range(3))
    pad = 0.01 * size + 1e-3
    rays = []
    for axis in range(3):
        a, b = [k for k in range(3) if k != axis]
        for side, sign in ((lo[axis] - pad, 1.0), (hi[axis] + pad, -1.0)):
            for i in range(GRID):
                for j in range(GRID):
                    o = [0.0, 0.0, 0.0]
                    o[axis] = side
                    o[a] = lo[a] + (hi[a] - lo[a]) * (i + 0.5) / GRID
                    o[b] = lo[b] + (hi[b] - lo[b]) * (j + 0.5) / GRID
                    d = [0.0, 0.0, 0.0]
                    d[axis] = sign
                    rays.append((tuple(o), tuple(d)))
    return rays  # type: ignore[return-value]


def probe_rays(scene: Path) -> bytes:
    """The rtrace input aimed at every surface of a scene oconv accepted."""
    cwd, name = scene.parent, scene.name
    status, _, out = run(["xform", name], cwd, b"", OCONV_TIMEOUT)
    text = out.decode("utf-8", errors="replace") if status == 0 else ""
    if not text:
        text = scene.read_bytes().decode("utf-8", errors="replace")
    status, _, out = run(["getbbox", "-h", name], cwd, b"", OCONV_TIMEOUT)
    try:
        box = [float(x) for x in out.split()]
    except ValueError:
        box = []
    if status != 0 or len(box) != 6 or not all(map(math.isfinite, box)):
        box = [-1.0, 1.0, -1.0, 1.0, -1.0, 1.0]
    centre = ((box[0] + box[1]) / 2, (box[2] + box[3]) / 2, (box[4] + box[5]) / 2)
    size = max(box[1] - box[0], box[3] - box[2], box[5] - box[4], 1e-3)
    eps = max(1e-4 * size, 1e-4)
    rays = []
    for _, typ, _, reals in primitives(text):
        rays += surface_rays(typ, reals, centre, eps)
    rays += bbox_grid(box)
    lines = [" ".join(f"{x:.9g}" for x in (*o, *d)) for o, d in rays]
    return ("\n".join(lines) + "\n").encode()


# ---------------------------------------------------------------- verdicts


def tidy(line: str, scene: Path) -> str:
    lib = os.environ.get("ORACLE_DIR", "")
    line = line.replace(str(scene.parent) + "/", "./")
    if lib:
        line = line.replace(f"{lib}/lib", "$RAYPATH_LIB")
    return line.strip()


def runs_commands(scene: Path) -> bool:
    return any(
        line.lstrip().startswith("!")
        for line in scene.read_bytes().decode("utf-8", errors="replace").splitlines()
    )


def library_files(scene: Path) -> list[str]:
    """The library files a scene names (item 4 of the module docstring)."""
    lib = Path(os.environ.get("ORACLE_DIR", "")) / "lib"
    if not os.environ.get("ORACLE_DIR") or not lib.is_dir():
        sys.exit("ORACLE_DIR is unset: source tests/oracle/env.sh first")
    cwd = scene.parent
    status, _, out = run(["xform", scene.name], cwd, b"", OCONV_TIMEOUT)
    text = scene.read_bytes().decode("utf-8", errors="replace")
    named = set(words(text))
    if status == 0:
        named |= set(words(out.decode("utf-8", errors="replace")))
    found = set()
    for word in named:
        if not word or word.startswith("/") or "\0" in word:
            continue
        try:
            if (lib / word).is_file() and not (cwd / word).exists():
                found.add(word)
        except (OSError, ValueError):
            continue
    return sorted(found)


def verdict(scene: Path, shared: bool) -> dict:
    """What oconv and a probe rtrace say about one scene."""
    cwd, name = scene.parent, scene.name
    messages: list[str] = []
    with tempfile.TemporaryDirectory() as tmp:
        octree = Path(tmp) / "scene.oct"
        status, err, out = run(["oconv", name], cwd, b"", OCONV_TIMEOUT)
        messages += err.splitlines()
        oconv_ok = status == 0
        render_ok = False  # nothing to render when oconv fails
        if oconv_ok:
            octree.write_bytes(out)
            rays = probe_rays(scene)
            status, err, _ = run(
                ["rtrace", "-h", "-ab", "0", "-ov", str(octree)], cwd, rays, RTRACE_TIMEOUT
            )
            messages += err.splitlines()
            render_ok = status == 0
    messages = [tidy(m, scene) for m in messages if m.strip()]
    errors = [m for m in messages if ERROR_LINE.search(m)]
    if oconv_ok and render_ok:
        errors = []
    elif not errors:
        # calcomp reports a syntax error on three lines: where, the text, a caret.
        errors = [" / ".join(messages[:3])] if messages else ["(no message; nonzero exit)"]
    warnings: list[str] = []
    for m in messages:
        if "warning" in m and m not in warnings and len(warnings) < MAX_WARNINGS:
            warnings.append(m)
    entry = {
        "oconv_ok": oconv_ok,
        "render_ok": render_ok,
        "radiance_says": errors[0] if errors else "",
        "warnings": warnings,
        "library_files": library_files(scene),
    }
    if shared:
        missing = any(MISSING_FILE.search(m) for m in errors)
        entry["needs_commands"] = runs_commands(scene) or missing
    return entry


# Types whose argument checks the probe must trigger: everything but geometry, alias and the
# two types for which `0 0 0` (no arguments at all) is legal.
UNPROBED_TYPES = {"polygon", "cone", "sphere", "ring", "cylinder", "cup", "bubble", "tube",
                  "source", "instance", "mesh", "alias", "mist", "antimatter"}


def quoted(word: str) -> str:
    return f'"{word}"' if any(c.isspace() for c in word) else word


def probe_coverage(scene: Path) -> list[str]:
    """Proves the probe reaches every modifier of an accepted scene: strips each modifier in
    turn of all its arguments (`0 0 0`, illegal for every probed type) and expects the probe
    render to fail. Returns the modifiers whose breakage went unnoticed."""
    status, _, out = run(["xform", scene.name], scene.parent, b"", OCONV_TIMEOUT)
    if status != 0:
        return [f"(xform failed on {scene.name})"]
    prims = statements(out.decode("utf-8", errors="replace"))
    unreached = []
    with tempfile.TemporaryDirectory() as tmp:
        for k, prim in enumerate(prims):
            if prim[1] in UNPROBED_TYPES:
                continue
            mutated = [p if j != k else p[:3] + ["0", "0", "0"] for j, p in enumerate(prims)]
            copy = Path(tmp) / scene.name
            copy.write_text("\n".join(" ".join(map(quoted, p)) for p in mutated) + "\n")
            octree = Path(tmp) / "probe.oct"
            status, _, oct_bytes = run(["oconv", str(copy)], scene.parent, b"", OCONV_TIMEOUT)
            if status != 0:
                continue  # oconv itself noticed
            octree.write_bytes(oct_bytes)
            rays = probe_rays(scene)
            status, _, _ = run(
                ["rtrace", "-h", "-ab", "0", "-ov", str(octree)], scene.parent, rays, RTRACE_TIMEOUT
            )
            if status == 0:
                unreached.append(f"{prim[1]} {prim[2]}")
    return unreached


def scene_files() -> list[tuple[str, Path, bool]]:
    """(key, path, from the shared corpus) for every scene, sorted by key."""
    found = []
    for folder in OWN_FOLDERS:
        for p in sorted((SCENES / folder).glob("*")):
            if p.suffix in SCENE_SUFFIXES:
                found.append((p.relative_to(ROOT).as_posix(), p, False))
    if SHARED.is_dir():
        for p in sorted(SHARED.rglob("*")):
            if p.suffix in SCENE_SUFFIXES and p.is_file():
                found.append((f"{SHARED_KEY}/{p.relative_to(SHARED).as_posix()}", p, True))
    else:
        print(f"note: {SHARED} absent; shared-corpus scenes not examined", file=sys.stderr)
    return sorted(found)


def render_json(golden: dict) -> str:
    return json.dumps(golden, indent=1, sort_keys=True, ensure_ascii=True) + "\n"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="fail if any verdict changed")
    parser.add_argument(
        "--probe-coverage",
        action="store_true",
        help="for accepted own-corpus scenes (or SCENEs), list modifiers the probe never reaches",
    )
    parser.add_argument("scenes", nargs="*", type=Path, help="print verdicts of these only")
    args = parser.parse_args()
    if "RAYPATH" not in os.environ:
        sys.exit("source tests/oracle/env.sh first")
    if args.probe_coverage:
        targets = [p.resolve() for p in args.scenes] or [
            path
            for key, path, shared in scene_files()
            if not shared and "/invalid/" not in key
        ]
        total = 0
        for p in targets:
            missed = probe_coverage(p)
            total += len(missed)
            for m in missed:
                print(f"{p.relative_to(ROOT) if ROOT in p.parents else p}: probe never reaches {m}")
        print(f"probe coverage: {total} modifier(s) unreached in {len(targets)} scene(s)")
        return 1 if total else 0
    if args.scenes:
        for p in args.scenes:
            p = p.resolve()
            print(p, json.dumps(verdict(p, SHARED in p.parents), sort_keys=True))
        return 0
    files = scene_files()
    golden = {}
    for key, path, shared in files:
        golden[key] = verdict(path, shared)
    if not args.check:
        GOLDEN.write_text(render_json(golden))
        accepted = sum(v["oconv_ok"] and v["render_ok"] for v in golden.values())
        print(f"wrote {GOLDEN.relative_to(ROOT)}: {len(golden)} scenes, {accepted} accepted")
        return 0
    old = json.loads(GOLDEN.read_text())
    if not SHARED.is_dir():
        old = {k: v for k, v in old.items() if not k.startswith(SHARED_KEY)}
    problems = []
    for key in sorted(set(old) | set(golden)):
        before, now = old.get(key), golden.get(key)
        if before is None:
            problems.append(f"{key}: new scene, not in oracle.json")
        elif now is None:
            problems.append(f"{key}: in oracle.json but no longer present")
        elif (before["oconv_ok"], before["render_ok"]) != (now["oconv_ok"], now["render_ok"]):
            problems.append(
                f"{key}: verdict changed: oconv_ok {before['oconv_ok']} -> {now['oconv_ok']}, "
                f"render_ok {before['render_ok']} -> {now['render_ok']} ({now['radiance_says']})"
            )
        elif before != now:
            problems.append(f"{key}: same verdict, different messages: {json.dumps(now)}")
    for p in problems:
        print(p)
    if problems:
        print(f"{len(problems)} scene(s) differ; rerun without --check to accept")
        return 1
    print(f"scene oracle ok: {len(golden)} scenes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
