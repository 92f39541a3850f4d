#!/usr/bin/env python3
"""Figures 10-11 of the paper in spirit: bars bent / twisted by handles at their ends,
ARAP by local-global around l2, linf and relax. Prints, per method, the maximum ARAP
distortion and the mean distortion of the elements near the handles (the 10% of the
length next to each end slab) against the middle 20%: L2 concentrates distortion at the
handles, L-infinity and the strict minimizer spread it along the bar.

  python3 scripts/arap_bars.py [--cli build/strictmin] [--data ../shared/data] [--out DIR]

Inputs: a planar 10 x 1 bar (made here, 80 x 8 cells) whose right end is turned by 180
degrees and laid beside the left end (a U bend), and ../shared/data/tet/bar.mesh whose
end slab (5% of the length) is twisted by 90 degrees about the bar's axis. Writes the
meshes, handles, summaries and per-element distortions to DIR and a JSON table to stdout;
each row has the deform command that made it ("command").
"""
import argparse
import json
import math
import os
import shlex
import subprocess
import sys


def planar_bar(path, nx=80, ny=8):
    with open(path, "w") as f:
        for j in range(ny + 1):
            for i in range(nx + 1):
                f.write(f"v {10.0 * i / nx!r} {1.0 * j / ny!r} 0\n")
        for j in range(ny):
            for i in range(nx):
                a, b = j * (nx + 1) + i + 1, j * (nx + 1) + i + 2
                f.write(f"f {a} {b} {b + nx + 1}\nf {a} {b + nx + 1} {a + nx + 1}\n")


def read_vertices_elements(path):
    V, E = [], []
    with open(path) as f:
        if path.endswith(".obj"):
            for line in f:
                t = line.split()
                if t and t[0] == "v":
                    V.append(tuple(map(float, t[1:4])))
                elif t and t[0] == "f":
                    E.append(tuple(int(x.split("/")[0]) - 1 for x in t[1:4]))
            return V, E
        tokens = f.read().split()
    i = 0
    while i < len(tokens):
        if tokens[i] == "Vertices":
            n = int(tokens[i + 1]); i += 2
            for _ in range(n):
                V.append(tuple(map(float, tokens[i:i + 3]))); i += 4
        elif tokens[i] == "Tetrahedra":
            n = int(tokens[i + 1]); i += 2
            for _ in range(n):
                E.append(tuple(int(x) - 1 for x in tokens[i:i + 4])); i += 5
        else:
            i += 1
    return V, E


def end_handles(V, axis, move, band=0.05):
    lo, hi = min(v[axis] for v in V), max(v[axis] for v in V)
    lines = []
    for i, v in enumerate(V):
        if v[axis] <= lo + band * (hi - lo):
            lines.append((i, v))
        elif v[axis] >= hi - band * (hi - lo):
            lines.append((i, move(v)))
    return lines, lo, hi


def run_case(cli, name, mesh, handles, axis, lo, hi, out, methods, lg_iterations):
    dim = 3 if mesh.endswith(".mesh") else 2
    hpath = os.path.join(out, name + ".handles.txt")
    with open(hpath, "w") as f:
        for i, p in handles:
            f.write(f"{i} " + " ".join(repr(x) for x in p[:dim]) + "\n")
    V, E = read_vertices_elements(mesh)
    length = hi - lo
    pos = [(sum(V[j][axis] for j in e) / len(e) - lo) / length for e in E]  # 0..1 along the bar
    near = [i for i, s in enumerate(pos) if s < 0.15 or s > 0.85]   # next to the 5% slabs
    middle = [i for i, s in enumerate(pos) if 0.4 <= s <= 0.6]
    rows = []
    for m in methods:
        summ = os.path.join(out, f"{name}_{m}.json")
        dist = os.path.join(out, f"{name}_{m}.txt")
        ext = ".mesh" if mesh.endswith(".mesh") else ".obj"
        cmd = [cli, "deform", mesh, "--handles", hpath, "--measure", "arap", "--method", m,
               "--lg-iterations", str(lg_iterations), "-o", os.path.join(out, f"{name}_{m}{ext}"),
               "--summary", summ, "--distortion", dist, "--quiet"]
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode not in (0, 2):
            sys.exit(f"{' '.join(cmd)}: exit {p.returncode}\n{p.stderr}")
        d = [float(x) for x in open(dist).read().split()]
        s = json.load(open(summ))
        rows.append({"case": name, "method": m, "max": max(d),
                     "mean_near_handles": sum(d[i] for i in near) / len(near),
                     "mean_middle": sum(d[i] for i in middle) / len(middle),
                     "max_near_handles": max(d[i] for i in near), "max_middle": max(d[i] for i in middle),
                     "local_global_iterations": s.get("local_global_iterations"), "time_s": s["time_s"],
                     "command": shlex.join(cmd)})  # to re-run it, e.g. with --report DIR for pictures
        print(json.dumps(rows[-1]), file=sys.stderr)
    return rows


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cli", default=os.path.join(here, "..", "build", "strictmin"))
    ap.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data"))
    ap.add_argument("--out", default="arap_bars")
    ap.add_argument("--methods", default="l2,linf,relax")
    ap.add_argument("--lg-iterations", type=int, default=20)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    methods = a.methods.split(",")
    rows = []
    # Planar U bend: the right end turned by 180 degrees and laid above the left end, as a
    # U with legs of (10 - 1.5 pi) / 2 and a half circle of radius 1.5 (centre line).
    bar = os.path.join(a.out, "bar2d.obj")
    planar_bar(bar)
    V, _ = read_vertices_elements(bar)
    radius = 1.5

    def u_bend(v):
        return (10.0 - v[0], 1.0 + 2 * radius - v[1], 0.0)

    handles, lo, hi = end_handles(V, 0, u_bend)
    rows += run_case(a.cli, "bar2d", bar, handles, 0, lo, hi, a.out, methods, a.lg_iterations)
    # Tet bar twisted by 90 degrees about its long axis.
    tet = os.path.join(a.data, "tet", "bar.mesh")
    if os.path.exists(tet):
        V, _ = read_vertices_elements(tet)
        spans = [max(v[k] for v in V) - min(v[k] for v in V) for k in range(3)]
        axis = spans.index(max(spans))
        others = [k for k in range(3) if k != axis]
        centre = [sum(v[k] for v in V) / len(V) for k in range(3)]
        def twist(v, angle=math.pi / 2):
            w = list(v)
            y, z = v[others[0]] - centre[others[0]], v[others[1]] - centre[others[1]]
            w[others[0]] = centre[others[0]] + math.cos(angle) * y - math.sin(angle) * z
            w[others[1]] = centre[others[1]] + math.sin(angle) * y + math.cos(angle) * z
            return tuple(w)
        handles, lo, hi = end_handles(V, axis, twist)
        rows += run_case(a.cli, "tetbar_twist", tet, handles, axis, lo, hi, a.out, methods, a.lg_iterations)
    print(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
