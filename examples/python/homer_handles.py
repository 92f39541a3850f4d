"""Handles for a 3D surface deformation (the README's and docs/arap.md's homer example):
the feet held (vertices within 3% of the height from the bottom), the head turned by 0.5 rad
about the vertical axis through the centroid and moved sideways by a tenth of the height
(vertices within 3% from the top). Writes 'vertex x y z' lines (docs/formats.md) to stdout.

    python3 examples/python/homer_handles.py ../shared/data/closed/homer.obj > homer_handles.txt
"""
import math
import sys


USAGE = "usage: homer_handles.py MESH.obj > handles.txt"


def read_vertices(path):
    """The OBJ's 'v x y z' vertices; exits with a message when there are none."""
    V = []
    try:
        with open(path) as f:
            for number, line in enumerate(f, 1):
                t = line.split()
                if t and t[0] == "v":
                    if len(t) < 4:
                        sys.exit(f"homer_handles.py: {path}:{number}: a vertex needs x y z")
                    try:
                        V.append(tuple(float(x) for x in t[1:4]))
                    except ValueError:
                        sys.exit(f"homer_handles.py: {path}:{number}: not a number in {line.strip()!r}")
    except OSError as e:
        sys.exit(f"homer_handles.py: {path}: {e.strerror}")
    except UnicodeDecodeError:
        sys.exit(f"homer_handles.py: {path}: not a text OBJ file")
    if not V:
        sys.exit(f"homer_handles.py: {path}: no vertices ('v x y z' lines): not an OBJ mesh?")
    return V


def main(path):
    V = read_vertices(path)
    ys = [v[1] for v in V]
    lo, hi = min(ys), max(ys)
    h = hi - lo
    c = [sum(v[k] for v in V) / len(V) for k in range(3)]
    cos, sin = math.cos(0.5), math.sin(0.5)
    for i, (x, y, z) in enumerate(V):
        if y < lo + 0.03 * h:
            print(f"{i} {x!r} {y!r} {z!r}")
        elif y > hi - 0.03 * h:
            dx, dz = x - c[0], z - c[2]  # a turn about the y axis through the centroid
            print(f"{i} {c[0] + cos * dx + sin * dz + 0.1 * h!r} {y!r} {c[2] - sin * dx + cos * dz!r}")


if __name__ == "__main__":
    if len(sys.argv) == 2 and sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip() + "\n\n" + USAGE)
        sys.exit(0)
    if len(sys.argv) != 2:
        sys.exit(USAGE)
    main(sys.argv[1])
