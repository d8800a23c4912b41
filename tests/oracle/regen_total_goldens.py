"""Goldens for `radc total`: what Radiance's total prints (and its exit status) for each
case, on the inputs in tests/data/total/. tests/total.rs runs radc on the same cases.

    python tests/oracle/regen_total_goldens.py           # rewrite tests/data/total/cases.json
    python tests/oracle/regen_total_goldens.py --check   # fail if any would change
"""
import json, os, subprocess, sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "tests", "data", "total")

CASES = [[*opts, "columns.txt"] for opts in (
    [], ["-m"], ["-p"], ["-u"], ["-l"], ["-s2"], ["-m", "-s2"], ["-s1"], ["-s-1"], ["-3"], ["-3", "-r"],
    ["-7", "-m", "-r"], ["-in", "10"], ["-on", "2", "-5"], ["-m", "-p"], ["-u", "-10"], ["-t,"], ["-od"],
    ["-of", "-m"], ["-m", "-u"], ["-s2", "-p"], ["-x"])] + [
    ["-t\t", "tabs.txt"], ["-m", "tabs.txt"], ["-p", "tabs.txt"], ["-id3", "doubles.bin"],
    ["-id2", "-m", "doubles.bin"], ["-if3", "floats.bin"], ["-if", "floats.bin"],
    ["columns.txt", "missing.txt", "tabs.txt"], ["-on", "3", "-10", "columns.txt", "columns.txt"],
]


def main():
    check = "--check" in sys.argv
    cases = []
    changed = 0
    os.makedirs(os.path.join(DATA, "expected"), exist_ok=True)
    for n, args in enumerate(CASES):
        p = subprocess.run(["total"] + args, capture_output=True, cwd=DATA)
        out = f"expected/{n:02}.out"
        cases.append({"args": args, "status": p.returncode, "stdout": out})
        path = os.path.join(DATA, out)
        if check:
            changed += not os.path.exists(path) or open(path, "rb").read() != p.stdout
        else:
            open(path, "wb").write(p.stdout)
    text = json.dumps(cases, indent=1) + "\n"
    path = os.path.join(DATA, "cases.json")
    if check:
        if changed or open(path).read() != text:
            sys.exit("total goldens differ from the oracle")
        print(f"{len(cases)} total cases agree with the oracle")
    else:
        open(path, "w").write(text)
        print(f"wrote {len(cases)} cases")


if __name__ == "__main__":
    main()
