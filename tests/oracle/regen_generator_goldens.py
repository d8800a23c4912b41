"""Goldens for radc's generators: what real genbox, gendaylit, genprism, genrev, gensky,
genworm and xform print.

Runs each case below with the oracle's programs (source tests/oracle/env.sh first, or
let check_all.sh do it) in tests/data/generators/inputs/, and writes
tests/data/generators/cases.json (the case list with exit statuses and what the program
printed on standard error) and one <id>.out file per case with what it printed on
standard output (for a failing case, what it wrote before failing: Radiance keeps it).
tests/generators.rs runs `radc <program>` on the same cases and compares all three.

    python tests/oracle/regen_generator_goldens.py           # rewrite the goldens
    python tests/oracle/regen_generator_goldens.py --check   # fail if any would change
    python tests/oracle/regen_generator_goldens.py --fuzz 500 target/debug/radc
        # compare radc with the oracle on 500 random invocations (nothing written)
"""

import json
import math
import random
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
    ("genbox-round-mesh-inverted-obj", "genbox", "m b 2 2 2 -r .25 -n 3 -i -o", None),
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
    # gensky: each sky type, date/time forms, time zones, the almanac (-y), units
    ("gensky-clear", "gensky", "3 21 12", None),
    ("gensky-defaults", "gensky", "-defaults", None),
    ("gensky-overcast-zone", "gensky", "6 21 10:30PST -a 37 -o 122 -c", None),
    ("gensky-intermediate-year", "gensky", "3 21 +12 -y 2020 +i", None),
    ("gensky-uniform", "gensky", "12 21 9 -u", None),
    ("gensky-no-sun", "gensky", "7 4 14.5 -s", None),
    ("gensky-edt", "gensky", "7 4 14.5EDT -a 40.7 -o 74", None),
    ("gensky-angles", "gensky", "-ang 45 30", None),
    ("gensky-zenith-clamp", "gensky", "-ang 89 0 +s", None),
    ("gensky-turbid-intermediate", "gensky", "-ang 30 -120 -i -t 4", None),
    ("gensky-given-radiances", "gensky", "1 15 8 -r 5e6 -b 10", None),
    ("gensky-given-irradiances", "gensky", "2 28 16 -R 500 -B 100 -g .3", None),
    ("gensky-cest-year", "gensky", "9 30 17:45CEST -a 48 -o -11 -y 2024", None),
    ("gensky-meridian", "gensky", "5 5 5 -m 90 -o 88", None),
    ("gensky-zone-beats-m", "gensky", "11 11 11GMT -a 51.5 -o 0.1 -m 30", None),
    ("gensky-night", "gensky", "1 1 2", None),
    ("gensky-err-month", "gensky", "13 1 12", None),
    # calcomp errors partway along a curve: what was written up to there is kept
    ("gensurf-err-late-undefined", "gensurf", "m s s t if(s-.6,x,0) 4 2", None),
    ("genworm-err-late-undefined", "genworm", "m w t t*2 if(t-.5,x,0) .1 4", None),
    ("genrev-err-late-undefined", "genrev", "m r t if(t-.5,x,1) 4", None),
    ("gensky-err-zone", "gensky", "3 21 12XYZ", None),
    ("gensky-err-solar-zone", "gensky", "3 21 +12PST", None),
    ("gensky-err-count", "gensky", "3 21", None),
    ("gensky-err-option", "gensky", "3 21 12 -q", None),
    # genworm: calcomp curves, cylinders for equal radii, cones otherwise, -e and -f
    ("genworm-circle", "genworm", "m w cos(2*PI*t) sin(2*PI*t) t .1+.05*t 4", None),
    ("genworm-line", "genworm", "m w t 0 0 .1 3", None),
    ("genworm-parabola", "genworm", "m w t t*t 0 .2-.1*t 10", None),
    ("genworm-splines", "genworm", "m w bezier(0,1,2,3,t) hermite(0,1,1,0,t) bspline(0,1,0,1,t) .05 7", None),
    ("genworm-defs", "genworm", "m w a*t 0 0 r 2 -e a=3 -e r:.2", None),
    ("genworm-rounded-nseg", "genworm", "m w t 0 0 .1 2.4", None),
    ("genworm-file", "genworm", "m h hx(t) hy(t) t rad(t) 12 -f helix.cal", None),
    ("genworm-err-nseg", "genworm", "m w t 0 0 .1 0", None),
    ("genworm-err-undefined", "genworm", "m w t 0 0 .1 x", None),
    ("genworm-err-option", "genworm", "m w t 0 0 .1 3 -q", None),
    # genrev: cylinders, tubes, cones, cups, rings; -s Phong smoothing; -e and -f
    ("genrev-cylinder", "genrev", "m v t .5 4", None),
    ("genrev-cone", "genrev", "m v t 1-t 5", None),
    ("genrev-tube", "genrev", "m v 1-t .3 3", None),
    ("genrev-rings", "genrev", "m v 0 t 4", None),
    ("genrev-rings-in", "genrev", "m v 0 1-t 4", None),
    ("genrev-sphere", "genrev", "m v sin(PI*t) cos(PI*t) 8", None),
    ("genrev-sphere-smooth", "genrev", "m v sin(PI*t) cos(PI*t) 8 -s", None),
    ("genrev-vase-smooth", "genrev", "m v t .5+.2*sin(2*PI*t) 10 -s", None),
    ("genrev-bezier-smooth", "genrev", "m v t bezier(.2,1,.5,.1,t) 6 -s", None),
    ("genrev-defs", "genrev", "m v a*t r 3 -e a=2 -e r:.4", None),
    ("genrev-file", "genrev", "m v hx(t) rad(t)+1 5 -f helix.cal", None),
    ("genrev-degenerate", "genrev", "m v 1 1 3 -s", None),
    ("genrev-err-nseg", "genrev", "m v t t*t 0", None),
    ("genrev-err-option", "genrev", "m v t t 3 -q", None),
    # gensurf: function surfaces (flat cells as quads), valid(), -i, -o, -s, data files
    ("gensurf-plane", "gensurf", "m s s t 0 2 3", None),
    ("gensurf-saddle", "gensurf", "m s s t s*t 3 2", None),
    ("gensurf-cylinder", "gensurf", "m s cos(PI*s) sin(PI*s) t 4 3", None),
    ("gensurf-bowl-inverted", "gensurf", "m s s t s*s+t*t 3 3 -i", None),
    ("gensurf-bowl-obj", "gensurf", "m s s t s*s+t*t 3 3 -o", None),
    ("gensurf-valid", "gensurf", "m s s t s*t 2 2 -e valid(s,t)=.8-s*t", None),
    ("gensurf-valid-obj", "gensurf", "m s s t s*t 2 2 -o -e valid(s,t)=.8-s*t", None),
    ("gensurf-sphere", "gensurf",
     "m s sin(PI*s)*cos(2*PI*t) sin(PI*s)*sin(2*PI*t) cos(PI*s) 4 6", None),
    ("gensurf-heights", "gensurf", "m h s t heights.dat 2 2", None),
    ("gensurf-heights-cells", "gensurf", "m h 3*s 2*t heights-cells.dat 2 2", None),
    ("gensurf-heights-noborder", "gensurf", "m h s t heights.dat 3 3", None),
    ("gensurf-points", "gensurf", "m p points.dat points.dat points.dat 2 2", None),
    ("gensurf-heights-stdin", "gensurf", "m h s t - 2 2", "heights.dat"),
    ("gensurf-saddle-smooth", "gensurf", "m s s t s*t 3 2 -s", None),
    ("gensurf-bowl-smooth-inverted", "gensurf", "m s s t s*s+t*t 3 3 -i -s", None),
    ("gensurf-bowl-smooth-obj", "gensurf", "m s s t s*s+t*t 3 3 -o -s", None),
    ("gensurf-valid-smooth", "gensurf", "m s s t s*t 2 2 -s -e valid(s,t)=.8-s*t", None),
    ("gensurf-valid-smooth-obj", "gensurf", "m s s t s*t 3 3 -o -s -e valid(s,t)=.8-s*t", None),
    ("gensurf-valid-smooth-stale-normals", "gensurf",
     "m s s t s*t 4 2 -s -e valid(s,t)=.832-s*t", None),
    ("gensurf-heights-smooth", "gensurf", "m h s t heights.dat 2 2 -s", None),
    ("gensurf-err-count", "gensurf", "m s s t 0 0 3", None),
    ("gensurf-err-data", "gensurf", "m h s t heights.dat 4 6", None),
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
    ("xform-pipeline", "xform", "-s 2 pipes.rad", None),
    ("xform-e", "xform", "-c -e -t 0 0 1 sub/small.rad", None),
    ("xform-two-files", "xform", "-rz 5 sub/small.rad scene.rad", None),
    ("xform-argfile", "xform", "-f placements.txt sub/small.rad", None),
    ("xform-argfile-modifier", "xform", "-m paint -f placements.txt scene.rad", None),
    ("xform-argfile-named", "xform", "-n top -f placements.txt -rz 5 sub/small.rad", None),
    ("xform-argfile-stdin", "xform", "-f - sub/small.rad", "placements.txt"),
    ("xform-err-argfile-quotes", "xform", "-f quoted-args.txt sub/small.rad", None),
    ("xform-err-option", "xform", "-q scene.rad", None),
    ("xform-err-late-name", "xform", "-rz 10 -n pre scene.rad", None),
    ("xform-err-zero-scale", "xform", "-s 0 scene.rad", None),
    ("xform-err-missing-arg", "xform", "-t 1 2 scene.rad", None),
    ("xform-err-array", "xform", "-a 0 scene.rad", None),
    ("xform-err-bad-object", "xform", "-rz 10", "verts.txt"),
    # xform failing partway: what was written is kept, messages as Radiance words them
    ("xform-err-missing-file", "xform", "missing.rad", None),
    ("xform-err-missing-second-file", "xform", "-rz 5 scene.rad missing.rad", None),
    ("xform-err-bad-type", "xform", "-rz 10 bad-type.rad", None),
    ("xform-err-bad-args", "xform", "-n x bad-args.rad", None),
    ("xform-err-argfile-bad-line", "xform", "-f bad-placements.txt sub/small.rad", None),
    ("xform-err-array-late-option", "xform", "-t 1 2 3 -a 2 -q scene.rad", None),
    ("xform-err-array-bad-angle", "xform", "-t 1 2 3 -a 2 -rz x scene.rad", None),
    ("xform-err-missing-f", "xform", "-f", None),
    ("xform-err-nested-bad-args", "xform", "-n top nested-bad-args.rad", None),
    # failing commands inside a scene only warn ("bad status"); empty files warn too
    ("xform-nested-missing", "xform", "nested-missing.rad", None),
    ("xform-nested-missing-array", "xform", "-a 2 -t 1 0 0 nested-missing.rad", None),
    ("xform-nested-failures", "xform", "-mx bad-commands.rad", None),
    ("xform-nested-empty", "xform", "nested-empty.rad", None),
    ("xform-empty", "xform", "empty.rad", None),
    ("xform-only-comment", "xform", "only-comment.rad", None),
    # gendaylit: each input type (-P -W -L -G -E), outputs -O 0/1/2, date and -ang forms,
    # site options, the sun (-s +s) and its clamp, -i near sunrise and sunset, error
    # skies (sun down, impossible values) and failures, colour (-C -CIE -l), -d, -w
    ("gendaylit-perez-clear", "gendaylit", "-ang 60 0 -P 6.3 0.12", None),
    ("gendaylit-perez-turbid", "gendaylit", "-ang 60 0 -P 3.2 0.24", None),
    ("gendaylit-perez-overcast", "gendaylit", "-ang 60 0 -P 1 0.08", None),
    ("gendaylit-perez-bright-overcast", "gendaylit", "3 2 15.25 -a 42 -o 108 -m 110 -P 1 0.35", None),
    ("gendaylit-perez-first-bin", "gendaylit", "-ang 35 20 -P 1.05 0.3", None),
    ("gendaylit-perez-delta-floor", "gendaylit", "-ang 35 20 -P 2 0.1", None),
    ("gendaylit-perez-held", "gendaylit", "-ang 40 -30 -P 20 0.9", None),
    ("gendaylit-perez-held-low", "gendaylit", "-ang 40 -30 -P 0.5 0.001", None),
    ("gendaylit-perez-top", "gendaylit", "-ang 50 0 -P 12.01 0.2", None),
    ("gendaylit-perez-top-solar", "gendaylit", "-ang 50 0 -P 12.01 0.2 -O 1", None),
    ("gendaylit-positive-b", "gendaylit", "-ang 87 0 -P 5 0.6", None),
    ("gendaylit-w-angles", "gendaylit", "-ang 60 0 -W 840 135", None),
    ("gendaylit-w-date", "gendaylit", "6 21 12 -W 800 100", None),
    ("gendaylit-w-solar-time", "gendaylit", "6 21 +14.5 -a 47 -o -8 -m -15 -W 600 150", None),
    ("gendaylit-w-year", "gendaylit", "9 30 10 -y 2024 -a 48 -o -11 -m -15 -W 650 120", None),
    ("gendaylit-w-year-solar", "gendaylit", "2 29 +9.25 -y 2020 -W 300 200", None),
    ("gendaylit-w-south", "gendaylit", "12 21 11 -a -33.9 -o -18.4 -m -30 -W 900 90 -g 0.35", None),
    ("gendaylit-w-negative", "gendaylit", "-ang 50 0 -W -10 100", None),
    ("gendaylit-w-zero", "gendaylit", "-ang 50 0 -W 0 0", None),
    ("gendaylit-w-above-solar-constant", "gendaylit", "-ang 50 0 -W 1400 100", None),
    ("gendaylit-l", "gendaylit", "6 21 12 -L 80000 20000", None),
    ("gendaylit-l-luminance", "gendaylit", "3 21 9 -L 50000 15000 -O 2", None),
    ("gendaylit-l-solar", "gendaylit", "3 21 9 -L 50000 15000 -O 1", None),
    ("gendaylit-l-overcast", "gendaylit", "11 5 13 -L 0 18000", None),
    ("gendaylit-l-above-solar-constant", "gendaylit", "-ang 50 0 -L 130000 10000", None),
    ("gendaylit-g", "gendaylit", "4 15 11 -G 500 120", None),
    ("gendaylit-g-solar", "gendaylit", "4 15 11 -G 500 120 -O 1", None),
    ("gendaylit-g-low-sun", "gendaylit", "-ang 3 100 -G 20 40", None),
    ("gendaylit-g-sun-down", "gendaylit", "-ang -4 48 -G 935 314", None),
    ("gendaylit-e-dull", "gendaylit", "12 21 12 -E 60", None),
    ("gendaylit-e-mid", "gendaylit", "6 21 13 -E 600", None),
    ("gendaylit-e-clear", "gendaylit", "6 21 12 -E 980", None),
    ("gendaylit-e-above-s0", "gendaylit", "6 21 12 -E 1500", None),
    ("gendaylit-e-sun-down", "gendaylit", "-ang -4 48 -E 300 -s", None),
    ("gendaylit-no-sun", "gendaylit", "-ang 45 10 -W 600 100 -s", None),
    ("gendaylit-plus-s", "gendaylit", "-ang 45 10 -W 600 100 -s +s", None),
    ("gendaylit-cloudy-flag", "gendaylit", "-ang 89 0 -P 6 0.1 -c", None),
    ("gendaylit-zenith-clamp", "gendaylit", "-ang 89 0 -P 6 0.1", None),
    ("gendaylit-zenith-clamp-quiet", "gendaylit", "-ang 89 0 -P 6 0.1 -w", None),
    ("gendaylit-sun-below", "gendaylit", "-ang -5 0 -P 3 0.2", None),
    ("gendaylit-night", "gendaylit", "1 1 2 -W 100 100", None),
    ("gendaylit-night-quiet", "gendaylit", "1 1 2 -W 100 100 -w", None),
    ("gendaylit-interval-sunrise", "gendaylit", "6 21 4.9 -i 60 -W 20 30", None),
    ("gendaylit-interval-sunset", "gendaylit", "6 21 19.4 -i 60 -W 20 30", None),
    ("gendaylit-interval-midday", "gendaylit", "6 21 12 -i 30 -W 700 100", None),
    ("gendaylit-interval-night", "gendaylit", "1 1 2 -i 60 -W 100 100", None),
    ("gendaylit-meridian-warning", "gendaylit", "6 21 12 -o 10 -m 120 -W 600 100", None),
    ("gendaylit-ground", "gendaylit", "5 5 15 -W 500 200 -g 0.5", None),
    ("gendaylit-dew-point", "gendaylit", "7 7 10 -W 500 200 -d 20", None),
    ("gendaylit-dew-point-out-of-range", "gendaylit", "7 7 10 -W 500 200 -d 50", None),
    ("gendaylit-output-truncated", "gendaylit", "7 7 10 -W 500 200 -O 1.9", None),
    ("gendaylit-color-clear", "gendaylit", "-ang 60 0 -P 6.3 0.12 -C", None),
    ("gendaylit-color-cie", "gendaylit", "-ang 60 0 -P 6.3 0.12 -CIE -C", None),
    ("gendaylit-color-locus", "gendaylit", "-ang 60 0 -P 1 0.2 -l 1 2 3 4 5 6 7 -C", None),
    ("gendaylit-color-intermediate", "gendaylit", "-ang 60 0 -P 3 0.2 -C", None),
    ("gendaylit-solar-radiance-option", "gendaylit", "-ang 60 0 -P 3 0.2 -R 100 -t 3 -b 5", None),
    ("gendaylit-defaults", "gendaylit", "-defaults", None),
    ("gendaylit-err-output", "gendaylit", "-ang 45 0 -P 3 0.2 -O 3", None),
    ("gendaylit-err-interval", "gendaylit", "6 21 12 -i -5 -W 600 100", None),
    ("gendaylit-err-month", "gendaylit", "13 1 12 -W 1 1", None),
    ("gendaylit-err-day", "gendaylit", "1 32 12 -W 1 1", None),
    ("gendaylit-err-hour", "gendaylit", "1 1 24 -W 1 1", None),
    ("gendaylit-err-count", "gendaylit", "1 1", None),
    ("gendaylit-err-option", "gendaylit", "6 21 12 -q", None),
    ("gendaylit-err-bad-option", "gendaylit", "6 21 12 x", None),
    ("gensurf-err-usage", "gensurf", "m s 1 2", None),
    ("genrev-err-usage", "genrev", "m r t 1", None),
    ("genworm-err-usage", "genworm", "m w t t t", None),
]


def run(program, args, stdin_name):
    stdin = open(os.path.join(INPUTS, stdin_name), "rb") if stdin_name else subprocess.DEVNULL
    try:
        p = subprocess.run(
            [program] + shlex.split(args),
            cwd=INPUTS,
            stdin=stdin,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
        )
    finally:
        if stdin_name:
            stdin.close()
    return p.returncode, p.stdout.decode(), p.stderr.decode()


def random_invocation(rng):
    """A random but valid-looking invocation of one of the generators."""
    program = rng.choice(["genbox", "gendaylit", "genprism", "genrev", "gensky", "gensurf",
                          "genworm", "xform"])
    if program == "genbox":
        size = [rng.uniform(0.05, 20) for _ in range(3)]
        args = ["m", "b"] + ["%.4g" % x for x in size]
        r = rng.random()
        if r < 0.3:
            args += ["-b", "%.3g" % rng.uniform(0.001, min(size) / 2)]
        elif r < 0.7:
            args += ["-r", "%.3g" % rng.uniform(0.001, min(size) / 2),
                     "-n", str(rng.choice([1, 2, 3, 4]))]
            if rng.random() < 0.4:
                args.append("-s")
        if rng.random() < 0.3:
            args.append("-i")
        if rng.random() < 0.2:
            args.append("-o")
    elif program == "genprism":
        n = rng.randint(3, 8)
        angles = sorted(rng.uniform(0, 2 * math.pi) for _ in range(n))
        if rng.random() < 0.5:
            angles.reverse()
        args = ["m", "p", str(n)]
        for a in angles:
            r = rng.uniform(0.5, 3)
            args += ["%.5g" % (r * math.cos(a)), "%.5g" % (r * math.sin(a))]
        if rng.random() < 0.6:
            z = rng.choice([1, -1]) * rng.uniform(0.5, 4)
            args += ["-l", "%.4g" % rng.uniform(-1, 1), "%.4g" % rng.uniform(-1, 1), "%.4g" % z]
        if rng.random() < 0.6:
            args += ["-r", "%.3g" % rng.uniform(0.01, 0.3)]
        args += [o for o in ("-e", "-c") if rng.random() < 0.2]
    elif program == "gensurf":
        terms = ["s", "t", "s*t", "s*s-t", "cos(%d*PI*s)", "sin(%d*PI*t)", "exp(-s*t)",
                 "bezier(0,%d,1,0,s)", "hermite(1,0,%d,1,t)", "bspline(0,1,%d,0,s)"]
        def term():
            x = rng.choice(terms)
            return ("%.3g*" % rng.uniform(-3, 3)) + (x % rng.randint(1, 4) if "%d" in x else x)
        args = ["m", "s", term(), term(), term(), str(rng.randint(1, 6)), str(rng.randint(1, 6))]
        args += [o for o in ("-i", "-o", "-s") if rng.random() < 0.3]
        if rng.random() < 0.2:
            args += ["-e", "valid(s,t)=%.3g-s*t" % rng.uniform(0.2, 1)]
    elif program in ("genworm", "genrev"):
        terms = ["t", "t*t", "cos(%d*PI*t)", "sin(%d*PI*t)", "exp(-t)", "sqrt(t+1)",
                 "bezier(0,%d,1,0,t)", "hermite(1,0,%d,1,t)", "bspline(0,1,%d,0,t)"]
        def curve():
            term = rng.choice(terms)
            return ("%.3g*" % rng.uniform(-3, 3)) + (term % rng.randint(1, 4) if "%d" in term else term)
        radius = rng.choice([".1", ".05+.05*t", "%.3g" % rng.uniform(0.01, 0.3), ".1*(1+%s)" % curve()])
        if program == "genworm":
            args = ["m", "w", curve(), curve(), curve(), radius, str(rng.randint(1, 20))]
        else:
            z = rng.choice(["t", "1-t", curve(), "%.3g" % rng.uniform(0, 1)])
            args = ["m", "v", z, "1+" + curve(), str(rng.randint(1, 20))]
            if rng.random() < 0.4:
                args.append("-s")
    elif program == "gendaylit":
        if rng.random() < 0.25:
            args = ["-ang", "%.4g" % rng.uniform(-10, 95), "%.4g" % rng.uniform(-180, 180)]
        else:
            h = rng.uniform(0, 24)
            args = [str(rng.randint(1, 12)), str(rng.randint(1, 31)),
                    rng.choice(["%.2f" % h, "+%.1f" % h])]
        kind = rng.choice("PWLGE")
        if kind == "P":
            args += ["-P", "%.4g" % rng.uniform(0.5, 13), "%.3g" % rng.uniform(0, 0.7)]
        elif kind in "WG":
            args += ["-" + kind, "%.4g" % rng.uniform(-50, 1100), "%.4g" % rng.uniform(-10, 500)]
        elif kind == "L":
            args += ["-L", "%.5g" % rng.uniform(-1000, 130000), "%.5g" % rng.uniform(-100, 60000)]
        else:
            args += ["-E", "%.4g" % rng.uniform(-10, 1200)]
        for option in rng.sample(["-O", "-s", "+s", "-w", "-g", "-a", "-o", "-m", "-y", "-i",
                                  "-d", "-C", "-c"], rng.randint(0, 4)):
            value = {
                "-O": lambda: str(rng.choice([0, 1, 2, 3])),
                "-g": lambda: "%.3g" % rng.uniform(0, 1),
                "-a": lambda: "%.4g" % rng.uniform(-60, 65),
                "-o": lambda: "%.4g" % rng.uniform(-180, 180),
                "-m": lambda: str(rng.choice([-120, -30, 0, 15, 75, 120])),
                "-y": lambda: str(rng.randint(1950, 2050)),
                "-i": lambda: str(rng.choice([-5, 15.5, 30, 60])),
                "-d": lambda: "%.3g" % rng.uniform(-50, 50),
            }.get(option)
            args += [option, value()] if value else [option]
    elif program == "gensky":
        if rng.random() < 0.2:
            args = ["-ang", "%.4g" % rng.uniform(-10, 95), "%.4g" % rng.uniform(-180, 180)]
        else:
            h = rng.uniform(0, 24)
            hour = rng.choice(["%.2f" % h, "%d:%02d" % (int(h), rng.randint(0, 59)), "+%.1f" % h])
            if not hour.startswith("+") and rng.random() < 0.4:
                hour += rng.choice(["PST", "EST", "CET", "JST", "GMT", "NZDT"])
            args = [str(rng.randint(1, 12)), str(rng.randint(1, 28)), hour]
        args.append(rng.choice(["+s", "-s", "-c", "-u", "+i", "-i"]))
        if rng.random() < 0.3:
            args += ["-y", str(rng.randint(1950, 2050))]
        if rng.random() < 0.4:
            args += ["-a", "%.4g" % rng.uniform(-60, 70), "-o", "%.4g" % rng.uniform(-180, 180)]
    else:
        args = ["-I"] if rng.random() < 0.3 else []
        for _ in range(rng.randint(1, 6)):
            option = rng.choice(["-t", "-rx", "-ry", "-rz", "-s", "-mx", "-my", "-mz", "-i"])
            args.append(option)
            if option == "-t":
                args += ["%.6g" % rng.uniform(-100, 100) for _ in range(3)]
            elif option.startswith("-r"):
                args.append("%.7g" % rng.uniform(-720, 720))
            elif option == "-s":
                args.append("%.5g" % rng.choice([rng.uniform(0.001, 1000), -rng.uniform(0.01, 10)]))
            elif option == "-i":
                args.append(str(rng.randint(0, 5)))
        args.append(rng.choice(["scene.rad", "commands.rad"]))
    return program, args


def fuzz(count, radc):
    """Runs `count` random invocations through the oracle and radc; prints mismatches."""
    rng = random.Random(count)
    radc = os.path.abspath(radc)
    bad = 0
    for _ in range(count):
        program, args = random_invocation(rng)
        want = subprocess.run([program] + args, cwd=INPUTS, stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, stdin=subprocess.DEVNULL)
        got = subprocess.run([radc, program] + args, cwd=INPUTS, stdout=subprocess.PIPE,
                             stderr=subprocess.DEVNULL, stdin=subprocess.DEVNULL)
        same = (want.returncode != 0 and got.returncode != 0) or (
            want.returncode == 0 and got.returncode == 0 and want.stdout == got.stdout)
        if not same:
            bad += 1
            print("differs:", program, shlex.join(args))
    print(f"{count - bad} of {count} random invocations identical")
    return 1 if bad else 0


def main():
    if "--fuzz" in sys.argv[1:]:
        at = sys.argv.index("--fuzz")
        return fuzz(int(sys.argv[at + 1]), sys.argv[at + 2])
    check = "--check" in sys.argv[1:]
    manifest = []
    outputs = {}
    for case_id, program, args, stdin_name in CASES:
        status, out, err = run(program, args, stdin_name)
        manifest.append(
            {"id": case_id, "program": program, "args": shlex.split(args), "stdin": stdin_name,
             "status": status, "stderr": err}
        )
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
