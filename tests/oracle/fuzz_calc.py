#!/usr/bin/env python3
"""Random differential testing of `radc calc` against rcalc (a development tool, not a
golden generator): random calcomp programs over a few records, compared on stdout and
success. Usage, after `cargo build` and `source tests/oracle/env.sh`:

    python3 tests/oracle/fuzz_calc.py SEED COUNT

Programs that recurse forever crash rcalc (stack overflow) and are expected to differ.
Shrink a reported program by hand and add it to regen_cal_semantics.py.
"""
import os
import random
import subprocess
import sys

R = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                 "target", "debug", "radc")
random.seed(int(sys.argv[1]) if len(sys.argv) > 1 else 1)
FUNCS1 = ["sin","cos","tan","sqrt","exp","log","log10","floor","ceil","rand","asin","acos","atan"]
def num():
    return random.choice(["0","1","2","3",".5","0.1","1e3","2.5","7","1e-3","1e20","10","-1","3.25",
                          "1e308","1e-310","0.0"])
def atom(d):
    r = random.random()
    if r < 0.25: return num()
    if r < 0.45: return random.choice(["$1","$2","x","y","c","k"])
    if r < 0.55 and d>0: return "(" + expr(d-1) + ")"
    if r < 0.7 and d>0: return random.choice(FUNCS1) + "(" + expr(d-1) + ")"
    if r < 0.8 and d>0: return random.choice(["max","min"]) + "(" + ",".join(expr(d-1) for _ in range(random.randint(1,4))) + ")"
    if r < 0.85 and d>0: return "if(" + expr(d-1) + "," + expr(d-1) + "," + expr(d-1) + ")"
    if r < 0.9 and d>0: return "select(" + random.choice(["0","1","2","1.5",expr(d-1)]) + "," + expr(d-1) + "," + expr(d-1) + ")"
    if r < 0.95 and d>0: return "f(" + expr(d-1) + "," + expr(d-1) + ")"
    return num()
def unary(d):
    return random.choice(["","","","-","+"]) + atom(d)
def expr(d):
    e = unary(d)
    for _ in range(random.randint(0,3)):
        e += random.choice(["+","-","*","/","^","*","+"]) + unary(d)
    return e
def program():
    """A random program; some definitions constant, some functions passed by name."""
    kind = random.choice([":", "="])
    defs = [
        "x=$1*2-1", "y=$2/3",
        "c%s%s" % (kind, expr(1)),
        "k=%s" % expr(1),
        "f(a,b)%s a*b-%s" % (random.choice([":", "="]), expr(1).replace("$1", "a").replace("$2", "b")),
        "g(h,v)=h(v)+{comment {nested}}%s" % random.choice(["1", "v", "h(v*2)"]),
        "r(n)=if(n-.5,n+r(n-1),0)",
    ]
    random.shuffle(defs)
    outs = []
    for j in range(3):
        e = expr(2)
        r = random.random()
        if r < 0.15:
            e = "g(%s,%s)" % (random.choice(FUNCS1 + ["f", "g"] if False else FUNCS1), e)
        elif r < 0.25:
            e = "r(%s)" % random.choice(["3", "floor(abs1)", "5.2"]).replace("abs1", "$1*$1")
        elif r < 0.3:
            e = "in(%s)+%s" % (random.choice(["0", "1", "2", "3"]), e)
        outs.append("$%d=%s" % (j + 1, e))
    return ";".join(defs + outs)


fails = 0
for i in range(int(sys.argv[2]) if len(sys.argv) > 2 else 200):
    prog = program()
    nflag = random.random() < 0.3
    args = (["-n"] if nflag else []) + ["-e", prog.replace("$1","1.5").replace("$2","-2") if nflag else prog]
    vals = ["1.5", "-2", "0", "-0", "3", "0.25", "-7", "1e10", "nan", "-nan", "inf", "1e308",
            "-1e-320", "2.5e-5", "x"]
    inp = "".join("%s %s\n" % (random.choice(vals), random.choice(vals)) for _ in range(4))
    a = subprocess.run(["rcalc"] + args, input=inp.encode(), capture_output=True, timeout=20)
    b = subprocess.run([R, "calc"] + args, input=inp.encode(), capture_output=True, timeout=20)
    if a.stdout != b.stdout or (a.returncode == 0) != (b.returncode == 0):
        fails += 1
        if fails <= 6:
            print("ARGS", args)
            print(" rcalc", a.returncode, a.stdout[:300], a.stderr[:200])
            print(" radc ", b.returncode, b.stdout[:300], b.stderr[:300])
print("fails", fails)
