"""Goldens for radc's record tools (`total`, `rlam`, `rsplit`): what Radiance's programs print
(and their exit status) for each case, on the inputs in tests/data/record_tools/, some
with standard input. tests/record_tools.rs runs radc on the same cases.

    python tests/oracle/regen_record_tools_goldens.py           # rewrite the goldens
    python tests/oracle/regen_record_tools_goldens.py --check   # fail if any would change
"""
import json, os, subprocess, sys, tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "tests", "data", "record_tools")

TOTAL = [[*opts, "columns.txt"] for opts in (
    [], ["-m"], ["-p"], ["-u"], ["-l"], ["-s2"], ["-m", "-s2"], ["-s1"], ["-s-1"], ["-3"], ["-3", "-r"],
    ["-7", "-m", "-r"], ["-in", "10"], ["-on", "2", "-5"], ["-m", "-p"], ["-u", "-10"], ["-t,"], ["-od"],
    ["-of", "-m"], ["-m", "-u"], ["-s2", "-p"], ["-x"])] + [
    ["-t\t", "tabs.txt"], ["-m", "tabs.txt"], ["-p", "tabs.txt"], ["-id3", "doubles.bin"],
    ["-id2", "-m", "doubles.bin"], ["-if3", "floats.bin"], ["-if", "floats.bin"],
    ["columns.txt", "missing.txt", "tabs.txt"], ["-on", "3", "-10", "columns.txt", "columns.txt"],
]
RLAM = [
    ["letters.txt", "digits.txt"], ["digits.txt", "letters.txt"], ["-t,", "letters.txt", "-t:", "pairs.txt"],
    ["-t", "letters.txt", "digits.txt"], ["-in", "2", "letters.txt", "pairs.txt"],
    ["-in", "9", "letters.txt", "pairs.txt"], ["-ia2", "pairs.txt", "letters.txt"], ["doubles.bin"],
    ["-id", "doubles.bin", "-ia", "letters.txt"], ["-if3", "floats.bin", "-id", "doubles.bin"],
    ["-ib4", "letters.txt", "-ia", "digits.txt"], ["no-newline.txt", "letters.txt"], ["-x", "letters.txt"],
    [], ["missing.txt"], ["-", "letters.txt"], ["-iq", "letters.txt"],
]
# rsplit: (standard input, arguments); it writes files, kept as expected/<n>.<name>.
RSPLIT = [
    ("fields.txt", ["-t ", "a", "-oa2", "b"]), ("fields.txt", ["-t ", "a", ".", "c"]),
    ("fields.txt", ["-t ", "-oh", "a", "-oa2", "b"]),
    ("with-header.txt", ["-ih", "-iH", "-t ", "-oh", "-oH", "a", "-oa2", "b"]),
    ("fields.txt", ["-t ", "-"]), ("fields.txt", ["-t ", "-", "-oa2", "-"]),
    ("fields.txt", ["-on", "2", "-t ", "a", "b", "c"]), ("fields.txt", ["-on", "5", "-t ", "a", "b", "c"]),
    ("twelve.bin", ["-of", "a", "-of2", "b"]), ("twelve.bin", ["-oh", "-of2", "a", "-od", "b"]),
    ("twelve.bin", ["-x", "2", "-y", "1", "-oH", "-of3", "a", "-of3", "b"]), ("fields.txt", ["-oH", "a"]),
    ("fields.txt", ["a", "a"]), ("fields.txt", ["-q", "a"]), ("fields.txt", []),
    ("fields.txt", ["-t,", "a"]), ("fields.txt", ["-a", "-oh", "a"]), ("with-header.txt", ["-ih", "-oh", "-"]),
]
CASES = [("total", a) for a in TOTAL] + [("rlam", a) for a in RLAM]
STDIN = b"q1\nq2\n"


def main():
    check = "--check" in sys.argv
    cases = []
    changed = 0
    os.makedirs(os.path.join(DATA, "expected"), exist_ok=True)
    for n, (program, args) in enumerate(CASES):
        p = subprocess.run([program] + args, capture_output=True, cwd=DATA, input=STDIN)
        out = f"expected/{n:02}.out"
        cases.append({"program": program, "args": args, "status": p.returncode, "stdout": out})
        path = os.path.join(DATA, out)
        if check:
            changed += not os.path.exists(path) or open(path, "rb").read() != p.stdout
        else:
            open(path, "wb").write(p.stdout)
    for k, (stdin, args) in enumerate(RSPLIT):
        n = len(CASES) + k
        with tempfile.TemporaryDirectory() as tmp:
            data = open(os.path.join(DATA, stdin), "rb").read()
            p = subprocess.run(["rsplit"] + args, capture_output=True, cwd=tmp, input=data)
            files = {"stdout": p.stdout}
            for name in sorted(os.listdir(tmp)):
                files[name] = open(os.path.join(tmp, name), "rb").read()
        outs = {}
        for name, content in files.items():
            out = f"expected/{n:02}.{name}"
            outs[name] = out
            path = os.path.join(DATA, out)
            if check:
                changed += not os.path.exists(path) or open(path, "rb").read() != content
            else:
                open(path, "wb").write(content)
        cases.append({"program": "rsplit", "stdin": stdin, "args": args, "status": p.returncode,
                      "outputs": outs})
    text = json.dumps(cases, indent=1) + "\n"
    path = os.path.join(DATA, "cases.json")
    if check:
        if changed or open(path).read() != text:
            sys.exit("record tool goldens differ from the oracle")
        print(f"{len(cases)} record tool cases agree with the oracle")
    else:
        open(path, "w").write(text)
        print(f"wrote {len(cases)} cases")


if __name__ == "__main__":
    main()
