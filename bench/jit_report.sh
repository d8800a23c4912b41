#!/usr/bin/env bash
# calcomp JIT report: time 1,000,000 records of a two-argument function with trig,
# sqrt and exp through `radc calc --interp` (reference interpreter), `radc calc` (the
# Cranelift JIT) and Radiance's `rcalc`, from one run, and check the three outputs
# agree. Usage: bash bench/jit_report.sh [rows]   (needs the oracle for rcalc:
# bash tests/oracle/install.sh). Numbers go to BENCHMARKS.md, section "calcomp JIT".
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
rows="${1:-1000000}"
expr='f(x,y) = sqrt(x*x + y*y) * sin(x) * cos(y) + exp(-x*y/100); $1 = f($1, $2)'

cargo build --release --quiet --bin radc --manifest-path "$root/Cargo.toml"
radc="$root/target/release/radc"
rcalc=""
if [ -f "$root/.oracle/bin/python" ]; then
    # shellcheck disable=SC1091
    source "$root/tests/oracle/env.sh"
    rcalc="$(command -v rcalc || true)"
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
awk -v n="$rows" 'BEGIN { for (i = 0; i < n; i++) printf "%.6f\t%.6f\n", (i % 1000) / 100, (i % 997) / 97 - 5 }' > "$work/in.txt"

seconds() { # command... ; prints wall-clock seconds, output to $work/out.<label>
    local label="$1"; shift
    local start end
    start=$(date +%s.%N)
    "$@" < "$work/in.txt" > "$work/out.$label"
    end=$(date +%s.%N)
    awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }'
}

t_interp=$(seconds interp "$radc" calc --interp -e "$expr")
t_jit=$(seconds jit "$radc" calc -e "$expr")
printf 'rows: %s   expression: %s\n' "$rows" "$expr"
printf '%-28s %8s s\n' "radc calc --interp" "$t_interp"
printf '%-28s %8s s   (%.2fx the interpreter)\n' "radc calc (JIT)" "$t_jit" \
    "$(awk -v a="$t_interp" -v b="$t_jit" 'BEGIN { print a / b }')"
if [ -n "$rcalc" ]; then
    t_rcalc=$(seconds rcalc "$rcalc" -e "$expr")
    printf '%-28s %8s s   (JIT is %.2fx rcalc)\n' "rcalc (Radiance)" "$t_rcalc" \
        "$(awk -v a="$t_rcalc" -v b="$t_jit" 'BEGIN { print a / b }')"
    cmp -s "$work/out.jit" "$work/out.rcalc" && echo "outputs: JIT identical to rcalc" \
        || echo "outputs: JIT differs from rcalc"
else
    echo "rcalc: not installed (bash tests/oracle/install.sh)"
fi
cmp -s "$work/out.jit" "$work/out.interp" && echo "outputs: JIT identical to the interpreter" \
    || { echo "outputs: JIT differs from the interpreter"; exit 1; }
