#!/usr/bin/env python3
"""A Teichmueller-like set-up (paper Figure 15): the unit square on an N x N grid, every
boundary vertex fixed where it is, and two interior landmarks turned about the centre.
Writes square.obj and handles.txt ('vertex x y' lines, 0-based) into the given folder.

    python3 examples/teichmuller/make_square.py [N=24] [OUT=.]   (N >= 4)"""
import math
import os
import sys

USAGE = "usage: make_square.py [N=24] [OUT=.]   (N: cells per side, an integer >= 4)"
if len(sys.argv) > 1 and sys.argv[1] in ("-h", "--help"):
    print(__doc__)
    sys.exit(0)
if len(sys.argv) > 3:
    sys.exit(USAGE)
try:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 24
except ValueError:
    sys.exit(f"make_square.py: N {sys.argv[1]!r}: not an integer\n{USAGE}")
if n < 4:  # the landmarks at 1/4 and 3/4 must be interior vertices
    sys.exit(f"make_square.py: N {n}: must be >= 4\n{USAGE}")
out = sys.argv[2] if len(sys.argv) > 2 else "."
try:
    os.makedirs(out, exist_ok=True)
except OSError as e:
    sys.exit(f"make_square.py: output folder {out}: {e.strerror}")
V = [(i / n, j / n) for j in range(n + 1) for i in range(n + 1)]
F = []
for j in range(n):
    for i in range(n):
        a, b, c, d = j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i
        F += [(a, b, c), (a, c, d)]
with open(os.path.join(out, "square.obj"), "w") as f:
    for x, y in V:
        f.write("v %.17g %.17g 0\n" % (x, y))
    for a, b, c in F:
        f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))
# Landmarks at (1/4, 1/2) and (3/4, 1/2) (grid vertices when n is a multiple of 4), turned
# by 40 degrees about the centre.
angle = math.radians(40)
with open(os.path.join(out, "handles.txt"), "w") as f:
    f.write("# boundary fixed; two interior landmarks turned by 40 degrees about the centre\n")
    for v, (x, y) in enumerate(V):
        if x in (0, 1) or y in (0, 1) or min(x, 1 - x) < 1e-12 or min(y, 1 - y) < 1e-12:
            f.write("%d %.17g %.17g\n" % (v, x, y))
    for (x, y) in [(0.25, 0.5), (0.75, 0.5)]:
        i, j = round(x * n), round(y * n)
        v = j * (n + 1) + i
        dx, dy = x - 0.5, y - 0.5
        f.write("%d %.17g %.17g\n" % (v, 0.5 + math.cos(angle) * dx - math.sin(angle) * dy,
                                      0.5 + math.sin(angle) * dx + math.cos(angle) * dy))
