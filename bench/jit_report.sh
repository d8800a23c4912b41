#!/usr/bin/env bash
# Kept for old instructions: the calc report is bench/calc_vs_rcalc.py.
exec python3 "$(dirname "${BASH_SOURCE[0]}")/calc_vs_rcalc.py" --rows "${1:-1000000}"
