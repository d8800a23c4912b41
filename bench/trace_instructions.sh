#!/usr/bin/env bash
# Instructions per ray of `radc trace` on bench/trace_rays.py's scenes, by callgrind
# (exact whatever the load, unlike timings): the first 20,000 rays, one thread,
# `-h -ov -ab 0 -dj 0 -dt 0 -dr 0 -u-`, start-up (the same command on empty input)
# subtracted. Each scene's .rsc is rebuilt with the radc measured.
#
# Usage (from the repository root):
#   python3 bench/trace_rays.py --rays 100000 --keep DIR   # once: scenes and rays
#   bash bench/trace_instructions.sh target/release/radc DIR [room spheres terrain]
set -euo pipefail
radc=$(readlink -f "$1")
dir=$(readlink -f "$2")
shift 2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
opts=(trace -h -ov -n 1 -ab 0 -dj 0 -dt 0 -dr 0 -u-)
count() { valgrind --tool=callgrind --callgrind-out-file="$2" "$radc" "${opts[@]}" "$1" \
  < "$3" 2>&1 >/dev/null | awk '/Collected/ {print $4}'; }
: > "$work/empty.rays"
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(room spheres terrain)
for s in "${scenes[@]}"; do
  (cd "$dir" && "$radc" build -o "$work/$s.rsc" "$s.rad")
  head -20000 "$dir/$s.rays" > "$work/$s.20k"
  with=$(count "$work/$s.rsc" "$work/cg.$s" "$work/$s.20k")
  without=$(count "$work/$s.rsc" /dev/null "$work/empty.rays")
  echo "$s $(( (with - without) / 20000 )) instructions per ray"
done
