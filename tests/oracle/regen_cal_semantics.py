#!/usr/bin/env python3
"""Goldens for calcomp's tricky semantics, produced by real rcalc.

Each case is an rcalc command line plus its standard input. This script runs rcalc
(from the oracle: `source tests/oracle/env.sh`) and writes
tests/data/cal-semantics/golden.json with rcalc's stdout and exit status;
tests/calc.rs runs `radc calc` on the same cases and compares. With --check it
re-runs rcalc and fails if any golden no longer matches.

RAYPATH is set to tests/data/cal-semantics so `-f defs.cal` finds the fixture.
"""
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "tests", "data", "cal-semantics")
GOLDEN = os.path.join(DATA, "golden.json")

N = ["-n"]


def e(*exprs):
    out = []
    for x in exprs:
        out += ["-e", x]
    return out


# (name, arguments, stdin)
CASES = [
    # --- precedence and signs (calexpr.c getE1..getE5) ---
    ("neg-base-of-power", N + e("$1=-2^2;$2=2^-2;$3=2^3^2;$4=-(2^2)"), ""),
    ("neg-var-power", e("x=$1;$1=-x^2;$2=-x*x;$3=2*-x"), "3\n"),
    ("left-assoc", N + e("$1=8/2/2;$2=2-3-4;$3=1+2*3;$4=(1+2)*3;$5=+2"), ""),
    ("literals", N + e("$1=.5;$2=5.;$3=1e3;$4=1E-3;$5=2.5e+2;$6=007"), ""),
    ("nested-comments", N + e("$1=1{a{b}c}+{x}2;{ $2=9 }$3=3"), ""),
    ("names", N + e("a.b_c=2;A1=3;$1=a.b_c*A1"), ""),
    ("context-marks", N + e("x`=2;`y=3;$1=x*y;$2=x`*`y"), ""),
    ("whitespace-everywhere", N + e("  $ 1 =\t1 +\n2 ; $2 = ( 3 ) "), ""),
    # --- if / select / min / max ---
    ("if", N + e("$1=if(1,2,3);$2=if(0,2,3);$3=if(-1,2,3);$4=if(1e-300,2,3)"), ""),
    ("if-is-lazy", e("z=$1;$1=if(1,5,1/z);$2=if(-1,undefinedname,6)"), "0\n"),
    ("select", N + e("$1=select(0,7,8,9);$2=select(2,7,8,9);$3=select(2.4,7,8,9);$4=select(2.6,7,8,9);$5=select(1.5,7,8,9)"), ""),
    ("select-out-of-range", N + e("$1=select(5,7,8);$2=select(-1,7,8);$3=1"), ""),
    ("select-huge-index", N + e("$1=1;$2=select(1e20,5,6)"), ""),
    ("in-huge-index", e("$1=1;$2=in(1e20)"), "1\n"),
    ("min-max-many", N + e("$1=max(1,5,3);$2=min(4,2,8,-1);$3=max(7);$4=min(-0,0);$5=max(0,-0)"), ""),
    ("min-max-nan", N + e("n=sqrt(-1);$1=max(n,5);$2=max(5,n);$3=min(n,5);$4=max(1,n,3);$5=max(1,2,n)"), ""),
    ("select-nan", N + e("$1=select(sqrt(-1),7,8);$2=1"), ""),
    # --- library functions ---
    ("library", N + e("$1=sin(1);$2=cos(1);$3=tan(1);$4=asin(.5);$5=acos(.5);$6=atan(1);$7=atan2(1,-1);$8=exp(1);$9=log(10);$10=log10(2);$11=sqrt(2);$12=floor(-1.5);$13=ceil(-1.5)"), ""),
    ("rand", N + e("$1=rand(1);$2=rand(0);$3=rand(-3.25);$4=rand(1e6);$5=rand(0.5)"), ""),
    ("pi", N + e("$1=PI;$2=2*PI;$3=PI/4"), ""),
    # --- errors yield 0 and propagate through library calls (calfunc.c libfunc) ---
    ("division-by-zero", e("z=$1;$1=1/z;$2=1+1/z;$3=max(1/z,5);$4=sqrt(1/z+4);$5=2^(1/z)"), "0\n"),
    ("error-propagates-through-calls", e("z=$1;f(x)=x/z;$1=sqrt(f($1)+4);$2=sqrt(4)"), "0\n"),
    ("cached-error-does-not-repeat", e("z=$1;a=1/z;$1=a;$2=sqrt(a+4)"), "0\n"),
    ("domain-errors-pass-through", N + e("$1=sqrt(-1);$2=log(0);$3=exp(1000);$4=acos(2);$5=(-8)^(1/3);$6=0^-1;$7=1+sqrt(-1)"), ""),
    ("argument-order-right-to-left", e("z=$1;$1=sin(z+1)^(1/z);$2=(1/z)^sin(z+1);$3=atan2(1/z,sin(z+1));$4=atan2(sin(z+1),1/z)"), "0\n"),
    ("nan-operands", e("$1=$1+$2;$2=$2+$1;$3=$1*$2;$4=$2*$1;$5=$1-$2;$6=$2-$1;$7=$1/$2;$8=$2/$1;$9=$1^$2;$10=$2^$1;$11=1+$2;$12=$2*2"), "nan -nan\n-nan nan\n"),
    ("nan-denominator", e("$1=1/$1;$2=sqrt(4+1/$1);$3=2^(1/$1);$4=$2/$1"), "nan 2\n"),
    ("fold-nan-constants", e("$1=sqrt(-1)*$1;$2=$1*sqrt(-1);$3=$1^sqrt(-1);$4=sqrt(-1)^$1;$5=sqrt(-1)/$1;$6=$1+sqrt(-1);$7=$1-sqrt(-1)"), "2\n"),
    ("fold-divide-by-nan-constant", e("$1=$1/sqrt(-1)"), "2\n"),
    ("division-by-negative-zero", e("z=-$1;$1=1/z;$2=-1/z;$3=1/$1;c:3.25/-$1*k;k=2^$1;$4=c"), "0\n"),
    ("zero-signs", e("z=$1;$1=ceil(-0.5);$2=ceil(z);$3=floor(-z);$4=sin(-z);$5=tan(-z);$6=atan(-z);$7=asin(-z);$8=sqrt(-z);$9=-z;$10=ceil(-0.5+z);$11=atan2(-z,1);$12=log10(1+z)*-1;$13=y*ceil(y*.001-1);y=-2/3+z"), "0\n"),
    ("nan-signs", N + e("i=1e300*1e300;$1=acos(2);$2=asin(-2);$3=log(-1);$4=log10(-1);$5=sqrt(-1);$6=(-1)^.5;$7=sin(i);$8=i-i;$9=exp(-i);$10=atan2(i,i);$11=-acos(2)"), ""),
    ("nan-input", e("n=$1;$1=n;$2=-n;$3=acos(n);$4=n^2;$5=max(n,1);$6=n+1;$7=floor(n)"), "nan\n-nan\n"),
    ("select-error-propagates", e("$1=max(select(9,$1),3);$2=1+select(9,$1)"), "1\n"),
    # --- constant folding (calexpr.c rconst, epflatten) ---
    ("fold-divide-by-constant", e("$1=$1/3;$2=$1/10;$3=$1/7*7"), "1\n2\n0.1\n"),
    ("no-fold-with-n", N + e("x=1;$1=x/3;$2=x/10;$3=x/7*7"), ""),
    ("fold-flatten-sums", e("$1=$1+1e20-1e20;$2=1e20+$1-1e20;$3=($1+1)+(2+$1)"), "1\n"),
    ("fold-flatten-products", e("$1=$1*.1*3;$2=.1*$1*3;$3=$1*(.1*3)"), "7\n"),
    ("fold-negative-zero", e("$1=-$1+-$1;$2=-$1;$3=-$1*2;$4=0*-1"), "0\n"),
    ("fold-times-zero-skips-evaluation", e("z=$1;$1=0*(1/z);$2=(1/z)*0;$3=(1/z)^0;$4=1^(1/z)"), "0\n"),
    ("n-evaluates-times-zero", N + e("z=0;$1=0*(1/z);$2=(1/z)^0"), ""),
    ("fold-bad-constant", e("$1=1/0"), ""),
    ("fold-divide-by-zero-constant", e("$1=$1/0"), "1\n"),
    ("fold-bad-constant-select", e("$1=select(3,1,2)"), ""),
    ("n-runtime-division", N + e("$1=1/0;$2=2"), ""),
    ("constant-function-folds", e("f(x):x*2;g(x)=x*2;$1=f(3)+g($1)"), "1\n"),
    ("constant-variable", e("c:2;$1=c*$1"), "3\n4\n"),
    ("nonconstant-constant-first-record-only", e("x:2*$1;$1=x"), "1\n2\n3\n"),
    ("forward-constant", e("$1=c*$1;c:3"), "2\n"),
    # --- definitions, laziness, caching ---
    ("self-reference-counts", e("a=a+$1;$1=a;b=c+1;c=b*2;$2=b;$3=c"), "1\n1\n1\n"),
    ("self-reference-n", N + e("a=a+1;$1=a;c:c+1;$2=c"), ""),
    ("forward-reference", e("$1=a;a=$1*2"), "4\n5\n"),
    ("redefinition", N + e("a=1;a=2;$1=a;b:1;b=2;$2=b;c=1;c:3;$3=c"), ""),
    ("output-redefined", N + e("$1=1;$1=2;$2=3"), ""),
    ("undefined-unused-is-fine", N + e("a=nosuch;$1=1"), ""),
    ("undefined-used-fails", N + e("$1=1;$2=nosuch"), ""),
    ("recursion", N + e("fact(n)=if(n,n*fact(n-1),1);$1=fact(10);fib(n)=if(n-1.5,fib(n-1)+fib(n-2),1);$2=fib(15)"), ""),
    ("deep-recursion", N + e("f(n)=if(n,1+f(n-1),0);$1=f(3000)"), ""),
    ("function-arguments", N + e("g(h,x)=h(x);$1=g(sin,1);$2=g(sqrt,16);k(h,x)=g(h,x);$3=k(exp,1)"), ""),
    ("function-argument-not-function", N + e("g(h,x)=h(x);$1=g(2,1)"), ""),
    ("extra-arguments-ignored", N + e("f(x)=x*2;$1=f(3,4,5)"), ""),
    ("missing-unused-argument", N + e("f(x,y)=x;$1=f(3)"), ""),
    ("missing-used-argument", N + e("f(x,y)=y;$1=f(3)"), ""),
    ("variable-shadows-library", N + e("sin=2;$1=sin(0)+sin"), ""),
    ("function-hides-library", N + e("sin(x)=x*10;$1=sin(2)"), ""),
    ("function-as-variable-fails", N + e("f(x)=x;$1=f"), ""),
    ("undefined-function", N + e("$1=nosuch(1)"), ""),
    ("args-evaluated-once", e("f(x)=x+x+x;$1=f($1*2)"), "1.5\n"),
    # --- syntax errors ---
    ("syntax-double-sign", e("$1=--2"), ""),
    ("syntax-empty-call", e("$1=f()"), ""),
    ("syntax-missing-semicolon", e("a=1 b=2"), ""),
    ("syntax-bad-number", e("$1=1e"), ""),
    ("syntax-unclosed-comment", e("$1=1 {"), ""),
    ("syntax-empty-statements", N + e(";;$1=1;;"), ""),
    # --- records and columns (rcalc.c chanvalue, l_in, chanset) ---
    ("columns", e("$1=$3;$2=$1;$3=in(0);$4=in(2);$5=$9"), "1 2 3\n  4\t\t5   6  7\n\n"),
    ("columns-junk", e("$1=$1;$2=$2;$3=$3;$4=$4"), "12abc x -.5e1q 1e\n0x10 inf -nan 1e999\n"),
    ("separator", ["-t,"] + e("$1=$2;$3=$1;$4=in(0)"), "1,2,3\n4,,6\n"),
    ("gap-columns", e("$2=$1;$5=$1*2"), "1\n"),
    ("output-format", N + e("$1=1e9;$2=123456789;$3=1234567890;$4=1e-5;$5=0.0001;$6=1/3;$7=2/3;$8=-2.5e-300;$9=999999999.5;$10=1e100;$11=-0"), ""),
    ("cond", e("cond=$1-2;$1=$1;$2=recno;$3=outno"), "1\n2\n3\n4\n"),
    ("cond-nan-rejects", e("cond=sqrt($1);$1=$1"), "4\n-1\nnan\n"),
    ("cond-constant-fails", e("cond:1;$1=$1"), "1\n"),
    ("in-zero", e("$1=in(0)"), "a b c\n\n1\n"),
    ("record-limit", ["-in", "2"] + e("$1=$1"), "1\n2\n3\n"),
    ("output-limit", ["-on", "1"] + e("cond=$1-1;$1=$1"), "1\n2\n3\n"),
    ("no-input-no-output", e("$1=1"), ""),
    ("n-with-input-names-fails", N + e("$1=$1"), ""),
    ("file-arguments", e("$1=$1*2"), None),
    ("files-restart-recno", e("$1=$1;$2=recno;$3=outno") + ["data.txt", "data2.txt"], ""),
    ("files-limit-each", ["-in", "1"] + e("$1=$1") + ["data.txt", "data2.txt"], ""),
    # --- output formats (rcalc.c putrec) ---
    ("format-inline", ["-s", "s=hello", "-o", "$(s) x=${ a*1000.5 } [${b}] $$ ${a/3}"] + e("a=$1;b=$2"), "1.5 2\n-3 1e6\n"),
    ("format-adjacent", ["-o", "${a}${b};${a+b}"] + e("a=$1;b=$2"), "1.5 2\n0.1 -7\n"),
    ("format-wide-fields", ["-o", "v ${  a/3          } w ${b/7 }\n"] + e("a=$1;b=$2"), "1 2\n1e10 3\n"),
    ("format-with-n", N + ["-o", "pi=${PI} e=${exp(1)}"], ""),
    ("format-undefined-string", ["-o", "$(nope) ${1}"], "1\n"),
    ("format-cond", ["-o", "${$1}"] + e("cond=$1-1"), "1\n2\n3\n"),
    # --- input formats (rcalc.c getrec, getfield) ---
    ("iformat-numbers-strings", ["-i", "x=${a} y=${b} name=$(n)"] + e("$1=a;$2=b*2"), "junk line\nx=1.5 y=2 name=foo\n  x=3 y=-4e1 name=bar\nx=oops y=1 name=z\nx=5 y=6 name=q extra\n"),
    ("iformat-to-oformat", ["-i", "x=${a} y=${b} name=$(n)", "-o", "${a+b}: $(n)"], "junk line\nx=1.5 y=2 name=foo\n  x=3 y=-4e1 name=bar\nx=oops y=1 name=z\nx=5 y=6 name=q extra\n"),
    ("iformat-no-final-newline-match", ["-i", "x=${a} y=${b}", "-o", "${a+b}"], "junk line\nx=1.5 y=2 name=foo\n  x=3 y=-4e1 name=bar\nx=oops y=1 name=z\nx=5 y=6 name=q extra\n"),
    ("iformat-repeated-variable", ["-i", "${a} ${a}"] + e("$1=a"), "1 1\n2 3\n4 4.003\n5 5.0001\n"),
    ("iformat-cond-recno", ["-i", "x=${a} y=${b} name=$(n)"] + e("$1=a;$2=recno;$3=outno;cond=a-2"), "junk line\nx=1.5 y=2 name=foo\n  x=3 y=-4e1 name=bar\nx=oops y=1 name=z\nx=5 y=6 name=q extra\n"),
    ("iformat-preset-string", ["-s", "n=bar", "-i", "x=${a} y=${b} name=$(n)"] + e("$1=a"), "junk line\nx=1.5 y=2 name=foo\n  x=3 y=-4e1 name=bar\nx=oops y=1 name=z\nx=5 y=6 name=q extra\n"),
    ("iformat-columns-fail", ["-i", "x=${a} y=${b} name=$(n)"] + e("$1=$1"), "junk line\nx=1.5 y=2 name=foo\n  x=3 y=-4e1 name=bar\nx=oops y=1 name=z\nx=5 y=6 name=q extra\n"),
    ("passive-unmatched", ["-p", "-i", "x=${a} y=${b} name=$(n)", "-o", "A=${a}"], "junk line\nx=1.5 y=2 name=foo\n  x=3 y=-4e1 name=bar\nx=oops y=1 name=z\nx=5 y=6 name=q extra\n"),
    ("passive-rejected", ["-P", "-i", "x=${a} y=${b} name=$(n)", "-o", "A=${a}"] + e("cond=a-2"), "junk line\nx=1.5 y=2 name=foo\n  x=3 y=-4e1 name=bar\nx=oops y=1 name=z\nx=5 y=6 name=q extra\n"),
    ("ignore-eol", ["-l", "-i", "${x} ${y}"] + e("$1=x;$2=y"), "a 1\n2 b 3\n4\n5 junk\n"),
    ("ignore-eol-after-iformat", ["-i", "${x} ${y}", "-l", "-o", "[${x+y}]"], "a 1\n2 b 3\n4\n5 junk\n"),
    # --- files and RAYPATH ---
    ("function-file", ["-f", "defs.cal"] + N + e("$1=hyp(3,4);$2=twice(sq,3);$3=scale;$4=local"), ""),
    ("table-functions", ["-f", "tables.cal"] + e("$1=ta($1);$2=tb($1);$3=ta`q7(2)"), "0\n1.5\n2\n4.75\n9\n20\n-3\n"),
    ("function-file-dot", ["-f", "."] + N + e("$1=1"), ""),
    ("function-file-missing", ["-f", "nosuch.cal"] + N + e("$1=1"), ""),
    ("order-of-e-and-f", ["-e", "scale=1", "-f", "defs.cal"] + N + e("$1=scale"), ""),
]


def rcalc_path():
    """rcalc from PATH (tests/oracle/env.sh), else from the pyradiance running this."""
    import shutil
    found = shutil.which("rcalc")
    if found:
        return found
    try:
        import pyradiance
        return os.path.join(os.path.dirname(pyradiance.__file__), "bin", "rcalc")
    except ImportError:
        sys.exit("rcalc not found: source tests/oracle/env.sh or run with .oracle/bin/python")


RCALC = rcalc_path()


def run(args, stdin):
    env = dict(os.environ)
    env["RAYPATH"] = DATA
    if stdin is None:
        # The record comes from a file argument instead of stdin.
        args = args + ["data.txt"]
        stdin = ""
    p = subprocess.run([RCALC, "-w"] + args, input=stdin.encode(), capture_output=True,
                       cwd=DATA, env=env, timeout=60)
    return {"stdout": p.stdout.decode("utf-8", "replace"), "status": p.returncode}


def main():
    check = "--check" in sys.argv[1:]
    with open(os.path.join(DATA, "data.txt"), "w") as f:
        f.write("1\n2.5\n-3\n")
    with open(os.path.join(DATA, "data2.txt"), "w") as f:
        f.write("10\n20\n")
    cases = []
    for name, args, stdin in CASES:
        r = run(args, stdin)
        cases.append({"name": name, "args": ["-w"] + args + (["data.txt"] if stdin is None else []),
                      "stdin": stdin or "", **r})
    if check:
        with open(GOLDEN) as f:
            old = json.load(f)
        if old != cases:
            old_by = {c["name"]: c for c in old}
            for c in cases:
                if old_by.get(c["name"]) != c:
                    print("mismatch:", c["name"], file=sys.stderr)
            return 1
        print(f"{len(cases)} calcomp semantics goldens match rcalc")
        return 0
    with open(GOLDEN, "w") as f:
        json.dump(cases, f, indent=1)
        f.write("\n")
    print(f"wrote {len(cases)} cases to {GOLDEN}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
