"""Goldens for radc's generators: what real genbox, genprism and xform print.

Runs each case below with the oracle's programs (source tests/oracle/env.sh first, or
let check_all.sh do it) in tests/data/generators/inputs/, and writes
tests/data/generators/cases.json (the case list with exit statuses) and one
<id>.out file per successful case. tests/generators.rs runs `radc <program>` on the same
cases and compares.

    python tests/oracle/regen_generator_goldens.py           # rewrite the goldens
    python tests/oracle/regen_generator_goldens.py --check   # fail if any would change
"""

import json
import shlex
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "tests", "data", "generators")
INPUTS = os.path.join(DATA, "inputs")

# (id, program, arguments, file for standard input or None). Ids name the output file.
CASES = [
    # genbox: plain, inverted, bevelled, rounded (one segment), odd sizes, errors
    ("genbox-plain", "genbox", "m b 1 2 3", None),
    ("genbox-inverted", "genbox", "m b 1 2 3 -i", None),
    ("genbox-bevel", "genbox", "m b 1 2 3 -b 0.1", None),
    ("genbox-bevel-inverted", "genbox", "m b 1 2 3 -b .2 -i", None),
    ("genbox-round", "genbox", "m b 1 2 3 -r 0.1", None),
    ("genbox-round-n2", "genbox", "m b 2 2 2 -r .25 -n 2", None),
    ("genbox-round-smooth-flag", "genbox", "m b 2 2 2 -r .25 -s", None),
    ("genbox-round-mesh-inverted", "genbox", "m b 2 2 2 -r .25 -n 3 -i", None),
    ("genbox-round-mesh-smooth", "genbox", "m b 1 2 3 -r 0.1 -n 3 -s", None),
    ("genbox-obj", "genbox", "m b 1 2 3 -o", None),
    ("genbox-obj-bevel", "genbox", "m b 1 2 3 -b .1 -o", None),
    ("genbox-obj-round-smooth", "genbox", "m b 1 2 3 -r .1 -n 3 -o -s", None),
    ("genbox-tiny", "genbox", "glass pane 1e-3 123.456789 7.25", None),
    ("genbox-quoted-name", "genbox", "m 'my box' 1 1 1", None),
    ("genbox-sci", "genbox", "m b 1e5 2.5e-7 3", None),
    ("genbox-err-few", "genbox", "m b 1 2", None),
    ("genbox-err-zero", "genbox", "m b 0 1 1", None),
    ("genbox-err-option", "genbox", "m b 1 1 1 -q", None),
    ("genbox-err-bevel", "genbox", "m b 1 1 1 -b -1", None),
    # genprism: vertices on the command line, from a file, from stdin, -l -r -c -e
    ("genprism-triangle", "genprism", "m p 3 0 0 1 0 0 1", None),
    ("genprism-square-l", "genprism", "m p 4 0 0 1 0 1 1 0 1 -l 0 0 2", None),
    ("genprism-slanted", "genprism", "m p 4 0 0 1 0 1 1 0 1 -l .3 .2 -2", None),
    ("genprism-closed", "genprism", "m p 4 0 0 1 0 1 1 0 0 -c", None),
    ("genprism-no-ends", "genprism", "m p 3 0 0 1 0 0 1 -e", None),
    ("genprism-round", "genprism", "m p 4 0 0 1 0 1 1 0 1 -l 0 0 2 -r .1", None),
    ("genprism-round-down", "genprism", "m p 4 0 0 1 0 1 1 0 1 -l .3 .2 -2 -r .1", None),
    ("genprism-round-concave", "genprism", "m p 5 0 0 2 0 2 2 1 1 0 2 -r .2", None),
    ("genprism-round-cw", "genprism", "m p 3 0 0 0 1 1 0 -r .05 -l 0 0 .5", None),
    ("genprism-file", "genprism", "wood slab verts.txt -l 0 0 .1", None),
    ("genprism-stdin", "genprism", "m p - -l 1 1 1", "verts.txt"),
    ("genprism-err-two", "genprism", "m p 2 0 0 1 1", None),
    ("genprism-err-flat", "genprism", "m p 3 0 0 1 0 0 1 -l 1 1 0", None),
    ("genprism-err-tall-round", "genprism", "m p 3 0 0 1 0 0 1 -r 2", None),
    ("genprism-err-option", "genprism", "m p 3 0 0 1 0 0 1 -x", None),
    # xform: every transform option, names, modifiers, arrays, commands, mirroring
    ("xform-identity", "xform", "scene.rad", None),
    ("xform-rz", "xform", "-rz 30 scene.rad", None),
    ("xform-rx-ry-s", "xform", "-rx 45 -ry 60 -s 2 scene.rad", None),
    ("xform-translate", "xform", "-t 1 -2 3.5 scene.rad", None),
    ("xform-mx", "xform", "-mx scene.rad", None),
    ("xform-my-mz", "xform", "-my -mz scene.rad", None),
    ("xform-mirror-scale", "xform", "-mz -s 0.5 scene.rad", None),
    ("xform-negative-scale", "xform", "-s -2 scene.rad", None),
    ("xform-invert", "xform", "-I scene.rad", None),
    ("xform-invert-mirror", "xform", "-I -mx scene.rad", None),
    ("xform-name", "xform", "-n pre -rz 45 -s 2 scene.rad", None),
    ("xform-two-names", "xform", "-n a -n b -t 0 0 1 scene.rad", None),
    ("xform-modifier", "xform", "-m newmat -my -t 1 2 3 scene.rad", None),
    ("xform-iterate", "xform", "-i 3 -rz 10 -t 1 0 0 -i 2 -s 2 scene.rad", None),
    ("xform-iterate-zero", "xform", "-t 1 0 0 -i 0 -s 3 scene.rad", None),
    ("xform-array", "xform", "-a 3 -t 1 0 0 -rz 15 sub/small.rad", None),
    ("xform-array-named", "xform", "-n x -a 2 -rz 10 -a 2 -t 0 1 0 sub/small.rad", None),
    ("xform-odd-angles", "xform", "-ry 123.456 -s 1e-3 -rz -0.001 scene.rad", None),
    ("xform-stdin", "xform", "-rz 90 -t 5 5 5", "scene.rad"),
    ("xform-commands", "xform", "-n top -t 1 2 3 commands.rad", None),
    ("xform-commands-mirror", "xform", "-mx -t 0 0 1 commands.rad", None),
    ("xform-commands-kept", "xform", "-c -s 2 commands.rad", None),
    ("xform-commands-kept-named", "xform", "-c -n q -rx 90 commands.rad", None),
    ("xform-e", "xform", "-c -e -t 0 0 1 sub/small.rad", None),
    ("xform-two-files", "xform", "-rz 5 sub/small.rad scene.rad", None),
    ("xform-err-option", "xform", "-q scene.rad", None),
    ("xform-err-late-name", "xform", "-rz 10 -n pre scene.rad", None),
    ("xform-err-zero-scale", "xform", "-s 0 scene.rad", None),
    ("xform-err-missing-arg", "xform", "-t 1 2 scene.rad", None),
    ("xform-err-array", "xform", "-a 0 scene.rad", None),
    ("xform-err-bad-object", "xform", "-rz 10", "verts.txt"),
]


def run(program, args, stdin_name):
    stdin = open(os.path.join(INPUTS, stdin_name), "rb") if stdin_name else subprocess.DEVNULL
    try:
        p = subprocess.run(
            [program] + shlex.split(args),
            cwd=INPUTS,
            stdin=stdin,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
        )
    finally:
        if stdin_name:
            stdin.close()
    return p.returncode, p.stdout.decode()


def main():
    check = "--check" in sys.argv[1:]
    manifest = []
    outputs = {}
    for case_id, program, args, stdin_name in CASES:
        status, out = run(program, args, stdin_name)
        manifest.append(
            {"id": case_id, "program": program, "args": shlex.split(args), "stdin": stdin_name,
             "status": status}
        )
        if status == 0:
            outputs[case_id + ".out"] = out
    manifest_text = "[\n" + ",\n".join(json.dumps(m) for m in manifest) + "\n]\n"
    stale = []
    if check:
        path = os.path.join(DATA, "cases.json")
        if not os.path.exists(path) or open(path).read() != manifest_text:
            stale.append("cases.json")
        for name, text in outputs.items():
            path = os.path.join(DATA, name)
            if not os.path.exists(path) or open(path).read() != text:
                stale.append(name)
        if stale:
            print("generator goldens out of date:", " ".join(stale))
            return 1
        print(f"generator goldens: {len(CASES)} cases up to date")
        return 0
    for name in os.listdir(DATA):
        if name.endswith(".out"):
            os.remove(os.path.join(DATA, name))
    with open(os.path.join(DATA, "cases.json"), "w") as f:
        f.write(manifest_text)
    for name, text in outputs.items():
        with open(os.path.join(DATA, name), "w") as f:
            f.write(text)
    failures = sum(1 for m in manifest if m["status"] != 0)
    print(f"wrote {len(CASES)} cases ({failures} expected failures) to {DATA}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
