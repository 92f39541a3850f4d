#!/usr/bin/env python3
"""Disk parametrization benchmark (issue 6): every mesh in ../shared/data/disk with LSCM,
L2 ARAP (Liu et al. 2008), L-infinity ARAP, relax and direct strict ARAP (strictmin param),
and CGAL's ARAP_parameterizer_3 (bench/cgal, measured with `strictmin eval --measure arap`).
Writes a JSON file and a markdown table: time, max and L2 (area-weighted RMS) ARAP
distortion, flipped triangles.

  bench/param_table.py --cli build/strictmin --cgal build/bench/cgal_arap_param \
      --out docs/param_table [--lg-iterations 10] [--direct-max-faces 50000] [--meshes a.obj ...]
"""
import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile
import time


def faces_of(path):
    with open(path) as f:
        return sum(1 for line in f if line.startswith("f "))


def run_json(cmd, timeout):
    t0 = time.monotonic()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"error": f"timeout after {timeout} s"}, time.monotonic() - t0
    if p.returncode not in (0, 2):
        return {"error": (p.stderr.strip().splitlines() or ["exit %d" % p.returncode])[-1]}, time.monotonic() - t0
    return json.loads(p.stdout), time.monotonic() - t0


def ours(cli, mesh, method, lg, timeout, tmp):
    out = os.path.join(tmp, f"{method}.obj")
    cmd = [cli, "param", mesh, "--method", method, "--lg-iterations", str(lg), "--summary", "-", "--quiet",
           "-o", out, "--threads", "0"]
    s, wall = run_json(cmd, timeout)
    if "error" in s:
        return {"method": method, "error": s["error"], "time_s": wall}
    return {"method": method, "time_s": s["solver_time_s"] + s.get("init_time_s", 0), "max": s["max_distortion"],
            "l2": s["l2_distortion"], "flips": s["flips"], "boundary_overlap": s["boundary_overlap"],
            "status": s["status"], "lg_iterations": s.get("local_global_iterations"),
            "lower_bound": s.get("lower_bound")}


def cgal(cgal_bin, cli, mesh, timeout, tmp):
    out = os.path.join(tmp, "cgal.obj")
    try:
        p = subprocess.run([cgal_bin, mesh, out], capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"method": "cgal-arap", "error": f"timeout after {timeout} s"}
    if p.returncode != 0:
        return {"method": "cgal-arap", "error": p.stderr.strip()}
    seconds = float(p.stdout.strip().splitlines()[-1])
    s, _ = run_json([cli, "eval", mesh, out, "--measure", "arap", "--summary", "-", "--quiet"], timeout)
    if "error" in s:
        return {"method": "cgal-arap", "error": s["error"], "time_s": seconds}
    return {"method": "cgal-arap", "time_s": seconds, "max": s["max_distortion"], "l2": s["l2_distortion"],
            "flips": s["flipped"], "status": "solved"}


def markdown(rows, methods):
    lines = ["| mesh | faces | " + " | ".join(methods) + " |", "|---|---:|" + "---|" * len(methods)]
    for mesh, faces, runs in rows:
        by = {r["method"]: r for r in runs}
        cells = []
        for m in methods:
            r = by.get(m)
            if r is None:
                cells.append("–")
            elif "error" in r:
                cells.append("failed: " + r["error"][:40])
            else:
                cells.append(f"{r['max']:.3f} / {r['l2']:.4f} / {r['flips']} / {r['time_s']:.1f} s")
        lines.append(f"| {mesh} | {faces} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n\nEach cell: max ARAP / L2 ARAP / flipped triangles / time.\n"


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", required=True)
    ap.add_argument("--cgal", default="")
    ap.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data", "disk"))
    ap.add_argument("--meshes", nargs="*", default=None)
    ap.add_argument("--methods", nargs="*", default=["lscm", "l2", "cgal-arap", "linf", "relax", "direct"])
    ap.add_argument("--lg-iterations", type=int, default=10)
    ap.add_argument("--direct-max-faces", type=int, default=50000)
    ap.add_argument("--timeout", type=float, default=1800)
    ap.add_argument("--out", default="param_table")
    a = ap.parse_args()
    meshes = a.meshes or sorted(glob.glob(os.path.join(a.data, "*.obj")), key=faces_of)
    rows = []
    for mesh in meshes:
        faces = faces_of(mesh)
        runs = []
        with tempfile.TemporaryDirectory() as tmp:
            for m in a.methods:
                if m == "cgal-arap":
                    if a.cgal:
                        runs.append(cgal(a.cgal, a.cli, mesh, a.timeout, tmp))
                    continue
                if m == "direct" and faces > a.direct_max_faces:
                    continue
                runs.append(ours(a.cli, mesh, m, a.lg_iterations, a.timeout, tmp))
                print(os.path.basename(mesh), json.dumps(runs[-1]), file=sys.stderr, flush=True)
        rows.append((os.path.basename(mesh), faces, runs))
        with open(a.out + ".json", "w") as f:
            json.dump({"lg_iterations": a.lg_iterations, "meshes": [{"mesh": m, "faces": n, "runs": r}
                                                                    for m, n, r in rows]}, f, indent=1)
        with open(a.out + ".md", "w") as f:
            f.write(markdown(rows, a.methods))
    print(markdown(rows, a.methods))


if __name__ == "__main__":
    main()
