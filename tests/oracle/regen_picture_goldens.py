"""Goldens for the picture commands (`radc getinfo pvalue pfilt pflip protate ra_ppm
ra_rgbe ra_xyze`) from the real programs, and the pictures they run on.

Pictures (tests/data/picture/inputs/): made by rpict at widths below and above the
run-length threshold (17), by `radc render`, turned and flipped by protate and pflip
(other orientations), converted to XYZE by ra_xyze, given EXPOSURE and COLORCORR lines
by `getinfo -a`, one without a FORMAT line, one with old-style run-length scanlines,
one truncated, one that is not a picture, and a stream of frames (`FRAME=`). pvalue's text and binary output of one
picture is kept as input for `pvalue -r`, and ra_ppm's pixmaps as input for `ra_ppm -r`.

Each case (tests/data/picture/cases.json) runs one program in the inputs directory (some
with an input picture or text on standard input); its
standard output is kept in tests/data/picture/expected/<n>.out with the exit status.
Where the program fails part way (a truncated picture) it has written part of its
output; radc writes nothing then (no partial output), which the test allows.
The header line the program adds names it as Radiance does (`pflip -h`): it is stored as
radc writes it (`radc pflip -h`), the only change. tests/picture_tools.rs runs radc on
the same cases and compares byte for byte.

colorpict.json: what rtrace sees of some of the pictures used as `colorpict` patterns
(on a glow, so the radiance is the pattern's value) over a grid of (u, v) inside and
outside each picture; picture/tests/colorpict.rs samples them with radc_picture.

    python tests/oracle/regen_picture_goldens.py           # rewrite inputs and goldens
    python tests/oracle/regen_picture_goldens.py --keep-inputs  # rewrite the goldens only
    python tests/oracle/regen_picture_goldens.py --check   # rerun the programs on the
                                                           # kept inputs; fail on change
"""

import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "tests", "data", "picture")
INPUTS = os.path.join(DATA, "inputs")
SCENES = os.path.join(ROOT, "tests", "data", "trace", "scenes")
DETERMINISTIC = ["-pj", "0", "-ps", "1", "-ab", "0", "-dj", "0", "-dt", "0", "-dr", "0", "-u-"]
VIEW = "-vp 3 -3 2.5 -vd -1 1 -.7 -vh 50 -vv 40 -pa 0"


def run(cmd, out_path=None, stdin=None):
    p = subprocess.run(cmd, capture_output=True, cwd=INPUTS, input=stdin)
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed: {p.stderr.decode()}")
    if out_path:
        with open(os.path.join(INPUTS, out_path), "wb") as f:
            f.write(p.stdout)
    return p.stdout


def radc_binary():
    subprocess.run(["cargo", "build", "-q", "--bin", "radc"], cwd=ROOT, check=True)
    return os.path.join(ROOT, "target", "debug", "radc")


def old_style(path_in, path_out):
    """Rewrites a flat picture's scanlines with old-style runs: (1,1,1,n) repeats."""
    data = open(os.path.join(INPUTS, path_in), "rb").read()
    head_end = data.index(b"\n\n") + 2
    res_end = data.index(b"\n", head_end) + 1
    res = data[head_end:res_end].split()
    width, height = int(res[3]), int(res[1])
    px = data[res_end:]
    assert len(px) == 4 * width * height, "expected a flat picture"
    out = bytearray(data[:res_end])
    for y in range(height):
        row = [px[4 * (y * width + x):4 * (y * width + x) + 4] for x in range(width)]
        x = 0
        while x < width:
            out += row[x]
            n = 1
            while x + n < width and row[x + n] == row[x] and n < 255:
                n += 1
            if n > 1:
                out += bytes([1, 1, 1, n - 1])
            x += n
    open(os.path.join(INPUTS, path_out), "wb").write(bytes(out))


def make_inputs():
    if os.path.isdir(INPUTS):
        shutil.rmtree(INPUTS)
    os.makedirs(INPUTS)
    radc = radc_binary()
    with tempfile.TemporaryDirectory() as tmp:
        octree = os.path.join(tmp, "scene.oct")
        # Relative names, so the headers the goldens keep name no local folder; a frozen
        # octree (-f), so rpict needs no scene file beside it.
        with open(octree, "wb") as f:
            subprocess.run(["oconv", "-f", "sphere_lamp.rad"], stdout=f, check=True, cwd=SCENES)
        for name, size in [("small", "-x 12 -y 9"), ("wide", "-x 24 -y 16"), ("tall", "-x 18 -y 22")]:
            run(["rpict"] + DETERMINISTIC + VIEW.split() + size.split() + [octree], f"{name}.hdr")
    run([radc, "render"] + VIEW.split() + ["-x", "20", "-y", "18", "-o", "radc.hdr",
         os.path.relpath(os.path.join(SCENES, "sphere_lamp.rad"), INPUTS)])
    run(["protate", "wide.hdr"], "turned.hdr")
    run(["protate", "-r", "tall.hdr"], "turned-ccw.hdr")
    run(["pflip", "-h", "wide.hdr"], "flipped.hdr")
    run(["pflip", "-v", "-c", "small.hdr"], "corrected.hdr")
    run(["ra_xyze", "wide.hdr", "xyz.hdr"])
    run(["getinfo", "-a", "EXPOSURE=0.25", "COLORCORR= 1.2 1 0.8", "PIXASPECT=0.5"],
        "exposed.hdr", stdin=open(os.path.join(INPUTS, "radc.hdr"), "rb").read())
    data = open(os.path.join(INPUTS, "small.hdr"), "rb").read()
    open(os.path.join(INPUTS, "no-format.hdr"), "wb").write(
        data.replace(b"FORMAT=32-bit_rle_rgbe\n", b""))
    old_style("small.hdr", "old-rle.hdr")
    wide = open(os.path.join(INPUTS, "wide.hdr"), "rb").read()
    open(os.path.join(INPUTS, "truncated.hdr"), "wb").write(wide[: len(wide) - 100])
    open(os.path.join(INPUTS, "not-a-picture.hdr"), "wb").write(b"\x00\x01\x02 plainly not a picture\n")
    small = open(os.path.join(INPUTS, "small.hdr"), "rb").read()
    framed = [wide.replace(b"\n\n", b"\nFRAME=%d\n\n" % n, 1) for n in (1, 2, 3)]
    open(os.path.join(INPUTS, "frames.hdr"), "wb").write(wide + small + b"".join(framed))
    run(["pvalue", "wide.hdr"], "wide.txt")
    run(["pvalue", "-h", "-H", "-d", "tall.hdr"], "tall-data.txt")
    run(["pvalue", "-df", "wide.hdr"], "wide.float")
    run(["pvalue", "-h", "-H", "-dd", "-b", "small.hdr"], "small-bright.double")
    run(["pvalue", "-db", "radc.hdr"], "radc.byte")
    run(["ra_ppm", "wide.hdr"], "wide.ppm")
    run(["ra_ppm", "-a", "-b", "small.hdr"], "small.pgm")
    run(["ra_ppm", "-a", "-s", "100", "radc.hdr"], "radc-100.ppm")
    run(["ra_ppm", "-b", "turned.hdr"], "turned.pgm")


PICTURES = ["small.hdr", "wide.hdr", "tall.hdr", "radc.hdr", "turned.hdr", "turned-ccw.hdr",
            "flipped.hdr", "corrected.hdr", "xyz.hdr", "exposed.hdr", "no-format.hdr", "old-rle.hdr"]
DAMAGED = ["truncated.hdr", "not-a-picture.hdr", "missing.hdr"]


def cases():
    c = []
    for p in PICTURES:
        c += [["getinfo", p], ["getinfo", "-d", p], ["getinfo", "+d", p]]
        c += [["pvalue", p], ["pvalue", "-h", "-H", "-d", p], ["pvalue", "-H", "-d", p], ["pvalue", "-b", p], ["pvalue", "-o", p],
              ["pvalue", "-h", "-df", p], ["pvalue", "-dd", "-H", p], ["pvalue", "-b", "-db", p],
              ["pvalue", "-o", "-b", "-d", p], ["pvalue", "-u", "-h", p], ["pvalue", "-pg", "-d", p]]
        c += [["pflip", "-h", p], ["pflip", "-v", p], ["pflip", "-h", "-v", p], ["pflip", "-h", "-c", p]]
        c += [["protate", p], ["protate", "-r", p], ["protate", "-c", p]]
        c += [["ra_rgbe", p], ["ra_rgbe", "-r", p], ["ra_rgbe", "-e", "-2", p]]
        c += [["ra_xyze", p], ["ra_xyze", "-r", p], ["ra_xyze", "-c", "-o", p], ["ra_xyze", "-r", "-u", "-e", "+1", p]]
        c += [["ra_ppm", p], ["ra_ppm", "-a", p], ["ra_ppm", "-b", "-e", "-2", p], ["ra_ppm", "-a", "-b", "-g", "1.6", p]]
    c += [["getinfo"] + PICTURES, ["getinfo", "-d"] + PICTURES]
    c += [["ra_xyze", "-r", "-p", ".7", ".3", ".2", ".7", ".1", ".05", ".3333", ".3333", "wide.hdr"],
          ["ra_xyze", "-r", "-o", "-p", ".64", ".33", ".3", ".6", ".15", ".06", ".3333", ".3333", "xyz.hdr"],
          ["ra_xyze", "-e", "0.3", "radc.hdr"]]
    for pixmap in ["wide.ppm", "small.pgm", "radc-100.ppm", "turned.pgm"]:
        c += [["ra_ppm", "-r", pixmap], ["ra_ppm", "-r", "-g", "2.6", "-e", "+1", pixmap]]
    c += [["ra_ppm", "-s", "100", "wide.hdr"], ["ra_ppm", "-r", "wide.hdr"]]
    c += [["pvalue", "-e", "+2", "wide.hdr"], ["pvalue", "-e", "0.5", "-R", "-d", "wide.hdr"],
          ["pvalue", "-di", "small.hdr"]]
    for d in DAMAGED:
        c += [["getinfo", d], ["getinfo", "-d", d], ["pvalue", d], ["pflip", "-h", d], ["protate", d],
              ["ra_rgbe", d], ["ra_xyze", d], ["ra_ppm", d]]
    c += [["getinfo", "small.hdr", "missing.hdr", "not-a-picture.hdr"],
          ["getinfo", "-d", "small.hdr", "missing.hdr", "not-a-picture.hdr"]]
    c += [["pvalue", "-r", "wide.txt"], ["pvalue", "-r", "-h", "-H", "-d", "-y", "22", "+x", "18", "tall-data.txt"],
          ["pvalue", "-r", "-df", "wide.float"], ["pvalue", "-r", "wide.float"],
          ["pvalue", "-r", "-db", "radc.byte"], ["pvalue", "-r", "-h", "-H", "-dd", "-b", "-y", "9", "+x", "12",
                                                 "small-bright.double"],
          ["pvalue", "-r", "-u", "wide.txt"], ["pvalue", "-r", "-e", "-1", "wide.txt"]]
    return [(x, None) for x in c] + STDIN_CASES + pfilt_cases() + getinfo_r_cases()


def pfilt_cases():
    """pfilt's cases, after the others so adding them kept the earlier numbering."""
    c = []
    for p in PICTURES:
        c += [["pfilt", "-x", "/2", "-y", "/2", p], ["pfilt", "-1", p], ["pfilt", "-x", "10", "-y", "8", "-r", ".6", p],
              ["pfilt", "-1", "-e", "+1", "-x", "/3", "-y", "/3", p], ["pfilt", "-e", "2", "-er", "1.5", "-h", "1", "-a", p],
              ["pfilt", "-c", "-p", "1", "-x", "20", "-y", "30", p],
              ["pfilt", "-1", "-r", "1", "-x", "128", "-y", "128", "-pa", "1", p],
              ["pfilt", "-1", "-x", "64", "-y", "64", "-r", "1", p]]
    for d in DAMAGED:
        c += [["pfilt", d], ["pfilt", "-1", d]]
    stdin = [(["pfilt", "-x", "/2", "-y", "/2"], "wide.hdr"), (["pfilt", "-1", "-r", ".6"], "small.hdr")]
    return [(x, None) for x in c] + stdin


# Cases reading standard input: (arguments, the input file given on standard input).
STDIN_CASES = [
    (["getinfo"], "wide.hdr"), (["getinfo", "-d"], "turned.hdr"), (["getinfo", "+d"], "small.hdr"),
    (["getinfo", "-"], "wide.hdr"), (["getinfo", "-d", "-"], "wide.hdr"), (["getinfo", "+d", "-"], "xyz.hdr"),
    (["getinfo", "-a", "EXPOSURE=2", "VIEW= -vtv -vh 30\n", ""], "wide.hdr"),
    (["getinfo", "-a", "SOFTWARE= x"], "no-format.hdr"),
    (["getinfo", "-c", "cat"], "wide.hdr"), (["getinfo", "-d", "-c", "wc", "-c"], "wide.hdr"),
    (["getinfo", "+d", "-c", "cat"], "turned.hdr"), (["getinfo", "-c", "cat"], "not-a-picture.hdr"),
    (["getinfo", "-"], "not-a-picture.hdr"), (["getinfo"], "truncated.hdr"),
    (["pflip", "-h"], "wide.hdr"), (["pflip", "-h", "-"], "flipped.hdr"), (["pflip", "-v"], "wide.hdr"),
    (["pvalue"], "small.hdr"), (["pvalue", "-r"], "wide.txt"), (["pvalue", "-r", "-df"], "wide.float"),
    (["ra_rgbe", "-r"], "frames.hdr"), (["ra_rgbe", "-e", "+1", "-n", "2"], "frames.hdr"),
    (["ra_rgbe", "-n", "3", "-"], "frames.hdr"), (["ra_xyze", "-r"], "xyz.hdr"), (["ra_ppm"], "wide.hdr"), (["ra_ppm", "-r", "-a"], "wide.ppm"), (["ra_rgbe"], "not-a-picture.hdr"), (["ra_rgbe", "-r"], "old-rle.hdr"),
]


def radc_header(prog, out):
    """The line the program adds to the header, as radc writes it."""
    end = out.find(b"\n\n")
    if end < 0:
        return out
    head = out[: end + 1]
    lines = head.split(b"\n")
    for i in range(len(lines) - 1, -1, -1):
        if re.match(rb"^" + prog.encode() + rb"( |$)", lines[i]):
            lines[i] = b"radc " + lines[i]
            break
    return b"\n".join(lines) + out[end + 1:]


def golden(case, stdin):
    data = open(os.path.join(INPUTS, stdin), "rb").read() if stdin else b""
    p = subprocess.run(case, capture_output=True, cwd=INPUTS, input=data)
    out = p.stdout
    if case[0] == "ra_rgbe":
        # Every frame's header names the program.
        out = re.sub(rb"(^|\n)ra_rgbe( |\n)", rb"\1radc ra_rgbe\2", out)
    elif case[0] != "getinfo":
        out = radc_header(case[0], out)
    return out, p.returncode


COLORPICT = """void colorpict pic
7 red green blue {picture} . Px Py
0
0
pic glow g 0 0 4 1 1 1 0
g polygon sq 0 0 12 -9 -9 0  9 -9 0  9 9 0  -9 9 0
"""
COLORPICT_PICTURES = ["wide.hdr", "tall.hdr", "exposed.hdr", "turned.hdr", "small.hdr"]
COORDS = [-0.4, -0.05, 0.0, 0.013, 0.25, 0.5, 0.61, 0.999, 1.0, 1.2, 1.4, 1.5, 1.75, 2.2, 2.6, 4.0]


def colorpict_values():
    """What rtrace sees of each picture as a colorpict pattern on a glow (radiance
    = pattern value), at (u, v) = (Px, Py) on a square at z = 0."""
    out = []
    with tempfile.TemporaryDirectory() as tmp:
        for pic in COLORPICT_PICTURES:
            rad = os.path.join(tmp, "scene.rad")
            open(rad, "w").write(COLORPICT.format(picture=pic))
            octree = os.path.join(tmp, "scene.oct")
            with open(octree, "wb") as f:
                subprocess.run(["oconv", rad], stdout=f, check=True, cwd=INPUTS)
            points = [(u, v) for u in COORDS for v in COORDS]
            rays = "".join(f"{u} {v} 1 0 0 -1\n" for u, v in points)
            p = subprocess.run(["rtrace", "-h", "-ov", "-w", octree], input=rays.encode(),
                               capture_output=True, check=True, cwd=INPUTS)
            values = p.stdout.decode().split()
            for i, (u, v) in enumerate(points):
                out.append({"picture": pic, "u": u, "v": v, "rgb": values[3 * i:3 * i + 3]})
    return "[\n" + ",\n".join(json.dumps(e) for e in out) + "\n]\n"


def main():
    check = "--check" in sys.argv
    # --keep-inputs: new cases on the kept pictures (remaking them changes their
    # capture dates, so every golden would churn).
    if not check and "--keep-inputs" not in sys.argv:
        make_inputs()
    expected = os.path.join(DATA, "expected")
    listed = []
    failures = 0
    if not check:
        if os.path.isdir(expected):
            shutil.rmtree(expected)
        os.makedirs(expected)
    for n, (case, stdin) in enumerate(cases()):
        out, status = golden(case, stdin)
        path = os.path.join(expected, f"{n:03}.out")
        entry = {"args": case, "status": status, "stdout": f"expected/{n:03}.out"}
        if stdin:
            entry["stdin"] = stdin
        listed.append(entry)
        if check:
            if not os.path.exists(path) or open(path, "rb").read() != out:
                print(f"changed: {' '.join(case)}")
                failures += 1
        else:
            open(path, "wb").write(out)
    text = json.dumps(listed, indent=1) + "\n"
    cases_path = os.path.join(DATA, "cases.json")
    colorpict = colorpict_values()
    colorpict_path = os.path.join(DATA, "colorpict.json")
    if check:
        if open(colorpict_path).read() != colorpict:
            print("changed: colorpict.json")
            failures += 1
        if open(cases_path).read() != text:
            print("changed: cases.json")
            failures += 1
        if failures:
            sys.exit(f"{failures} picture goldens differ from the oracle")
        print(f"{len(listed)} picture cases agree with the oracle")
    else:
        open(cases_path, "w").write(text)
        open(colorpict_path, "w").write(colorpict)
        print(f"wrote {len(listed)} picture cases")


def getinfo_r_cases():
    """getinfo -r, after the others so adding them kept the earlier numbering."""
    args = [["VIEW"], ["VIEW", "SOFTWARE=x"], ["EXPOSURE=2"], ["COLORCORR= 1 1 1"], [" PIXASPECT"],
            ["VIEW= -vh 20"], ["FORMAT"], ["VIE"], ["NOPE= 1"]]
    return [(["getinfo", "-r"] + a, p) for a in args for p in ("exposed.hdr", "wide.hdr")] + \
        [(["getinfo", "-r", "VIEW"], "not-a-picture.hdr")]


if __name__ == "__main__":
    main()
