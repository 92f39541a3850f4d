#!/usr/bin/env python3
"""Disk parametrization benchmark (issue 6): every mesh in ../shared/data/disk with LSCM,
L2 ARAP (Liu et al. 2008), L-infinity ARAP, relax and direct strict ARAP (strictmin param),
and CGAL's ARAP_parameterizer_3 (bench/cgal, measured with `strictmin eval --measure arap`).
Writes a JSON file and a markdown table: time, max and L2 (area-weighted RMS) ARAP
distortion, flipped triangles, and per mesh the verdicts of issue 6:
  - relax vs linf and direct vs linf in the strict order (paper Section 4) on the
    per-element distortion vectors, weighted by the triangles' 3D areas, values within
    1e-4 of the linf maximum equal, areas within 1e-6 of the total equal (as
    tests/test_param.cpp): "<" less distorting (expected), "=" equivalent, ">" more;
    direct is also compared at its own resolution, values within delta-k = 1e-3 equal
    (docs/strict.md: below delta-k it can be more distorting than linf);
  - linf max < L2 ARAP max.

  bench/param_table.py --cli build/strictmin --cgal build/bench/cgal_arap_param \
      --out docs/param_table [--lg-iterations 10] [--direct-max-faces 50000] [--meshes a.obj ...] \
      [--keep DIR] [--threads N] [--timeout S] [--direct-timeout S]

The JSON is rewritten after every run, so a long run can be watched or cut short. The
per-element distortions are kept in --keep DIR (<mesh>.<method>.txt) for the verdicts; runs
split over several invocations (e.g. direct in a second process) are put together with

  bench/param_table.py --merge a.json b.json ... --keep DIR --out docs/param_table

(later files win for the same mesh and method).
"""
import argparse
import glob
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

VALUE_TOL = 1e-4   # of the linf maximum
AREA_TOL = 1e-6    # of the total area
DELTA_K = 1e-3     # strictmin's default --delta-k: direct's own resolution (docs/strict.md)


def faces_of(path):
    with open(path) as f:
        return sum(1 for line in f if line.startswith("f "))


def triangle_areas(path):
    """3D area of each face (fan-triangulated), input order, as strictmin's weights."""
    verts, areas = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                verts.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                idx = [int(t.split("/")[0]) for t in line.split()[1:]]
                idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
                a = 0.0
                p0 = verts[idx[0]]
                for k in range(1, len(idx) - 1):
                    p1, p2 = verts[idx[k]], verts[idx[k + 1]]
                    u = [p1[j] - p0[j] for j in range(3)]
                    v = [p2[j] - p0[j] for j in range(3)]
                    c = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
                    a += 0.5 * math.sqrt(c[0] ** 2 + c[1] ** 2 + c[2] ** 2)
                areas.append(a)
    return areas


def read_values(path):
    with open(path) as f:
        return [float(line) for line in f if line.strip()]


def compare_strict(a, b, w, value_tol, area_tol):
    """Port of strictmin::compare_strict (src/report/strict_order.cpp): the order of a
    relative to b ('<', '=', '>') and the first level where they differ."""
    oa = sorted(range(len(a)), key=lambda i: -a[i])
    ob = sorted(range(len(b)), key=lambda i: -b[i])
    area_eps = area_tol * sum(w)
    ia = ib = 0
    level = 0

    def take(d, o, pos, threshold):
        area = 0.0
        while pos < len(o) and d[o[pos]] >= threshold:
            area += w[o[pos]]
            pos += 1
        return area, pos

    while ia < len(oa) or ib < len(ob):
        za = a[oa[ia]] if ia < len(oa) else -math.inf
        zb = b[ob[ib]] if ib < len(ob) else -math.inf
        if not abs(za - zb) <= value_tol:
            return {"order": "<" if za < zb else ">", "by": "value", "level": level, "value_a": za, "value_b": zb}
        threshold = max(za, zb) - value_tol
        area_a, ia = take(a, oa, ia, threshold)
        area_b, ib = take(b, ob, ib, threshold)
        if abs(area_a - area_b) > area_eps:
            return {"order": "<" if area_a < area_b else ">", "by": "area", "level": level, "value_a": za, "value_b": zb,
                    "area_a": area_a, "area_b": area_b, "area_total": sum(w)}
        level += 1
    return {"order": "=", "level": -1}


def run_json(cmd, timeout):
    t0 = time.monotonic()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"error": f"timeout after {timeout:.0f} s"}, time.monotonic() - t0
    if p.returncode not in (0, 2):
        return {"error": (p.stderr.strip().splitlines() or ["exit %d" % p.returncode])[-1]}, time.monotonic() - t0
    return json.loads(p.stdout), time.monotonic() - t0


def dist_path(keep, mesh, method):
    return os.path.join(keep, f"{os.path.splitext(os.path.basename(mesh))[0]}.{method}.txt")


def ours(cli, mesh, method, lg, timeout, tmp, keep, threads):
    out = os.path.join(tmp, f"{method}.obj")
    cmd = [cli, "param", mesh, "--method", method, "--lg-iterations", str(lg), "--summary", "-", "--quiet",
           "-o", out, "--threads", str(threads)]
    if keep:
        cmd += ["--distortion", dist_path(keep, mesh, method)]
    s, wall = run_json(cmd, timeout)
    if "error" in s:
        return {"method": method, "error": s["error"], "time_s": wall}
    r = {"method": method, "time_s": s["solver_time_s"] + s.get("init_time_s", 0), "wall_s": wall,
         "max": s["max_distortion"], "l2": s["l2_distortion"], "flips": s["flips"],
         "boundary_overlap": s["boundary_overlap"], "status": s["status"],
         "lg_iterations": s.get("local_global_iterations"), "lower_bound": s.get("lower_bound")}
    for k in ("levels", "sweeps", "message"):
        if k in s:
            r[k] = s[k]
    return r


def cgal(cgal_bin, cli, mesh, timeout, tmp, keep):
    """CGAL's ARAP map measured by `strictmin eval`. When CGAL's post-processor refuses
    (ERROR_NON_CONVEX_BORDER: the map is not one-to-one and its UV boundary is not simple),
    the peer writes the unprocessed ARAP map and exits 3: it is measured and marked."""
    out = os.path.join(tmp, "cgal.obj")
    try:
        p = subprocess.run([cgal_bin, "--keep-unprocessed", mesh, out], capture_output=True, text=True,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"method": "cgal-arap", "error": f"timeout after {timeout:.0f} s"}
    err_lines = [ln for ln in p.stderr.strip().splitlines() if ln.strip()]
    if p.returncode not in (0, 3):
        return {"method": "cgal-arap", "error": err_lines[-1] if err_lines else f"exit {p.returncode}"}
    seconds = float(p.stdout.strip().splitlines()[-1])
    cmd = [cli, "eval", mesh, out, "--measure", "arap", "--summary", "-", "--quiet"]
    if keep:
        cmd += ["--distortion", dist_path(keep, mesh, "cgal-arap")]
    s, _ = run_json(cmd, timeout)
    if "error" in s:
        return {"method": "cgal-arap", "error": s["error"], "time_s": seconds}
    r = {"method": "cgal-arap", "time_s": seconds, "max": s["max_distortion"], "l2": s["l2_distortion"],
         "flips": s["flipped"], "status": "solved" if p.returncode == 0 else "not-post-processed",
         "notes": err_lines}
    if any("not one-to-one" in ln for ln in err_lines):
        r["one_to_one"] = False
    elif any("is one-to-one" in ln for ln in err_lines):
        r["one_to_one"] = True
    return r


def verdicts(mesh_path, runs, keep):
    """relax/direct vs linf in the strict order, and linf max < L2 ARAP max."""
    by = {r["method"]: r for r in runs if "error" not in r}
    v = {}
    if "linf" in by and "l2" in by:
        v["linf_below_l2"] = by["linf"]["max"] < by["l2"]["max"]
    if not keep or "linf" not in by or not os.path.exists(dist_path(keep, mesh_path, "linf")):
        return v
    linf = read_values(dist_path(keep, mesh_path, "linf"))
    w = None
    for m in ("relax", "direct"):
        f = dist_path(keep, mesh_path, m)
        if m not in by or not os.path.exists(f):
            continue
        if w is None:
            w = triangle_areas(mesh_path)
        d = read_values(f)
        if len(d) != len(linf) or len(w) != len(linf):
            v[f"{m}_vs_linf"] = {"order": "?", "error": "element counts differ"}
            continue
        v[f"{m}_vs_linf"] = compare_strict(d, linf, w, VALUE_TOL * max(linf), AREA_TOL)
        if m == "direct":
            # direct fixes elements within delta-k of a level at that level, so below delta-k
            # it can be more distorting than linf (docs/strict.md): also compare at delta-k.
            v["direct_vs_linf_delta_k"] = compare_strict(d, linf, w, DELTA_K, AREA_TOL)
    return v


def fmt_verdict(c):
    if c is None:
        return "–"
    o = c["order"]
    if o == "=" or o == "?":
        return o
    if c.get("by") == "value":
        return f"{o} (level {c['level']}: {c['value_a']:.4f} vs {c['value_b']:.4f})"
    share = lambda x: f"{100 * x / c['area_total']:.3g}%"
    return f"{o} (level {c['level']} at {max(c['value_a'], c['value_b']):.4f}: {share(c['area_a'])} vs " \
           f"{share(c['area_b'])} of the area)"


def markdown(rows, methods):
    names = {"lscm": "LSCM", "l2": "L2 ARAP", "cgal-arap": "CGAL ARAP", "linf": "linf ARAP", "relax": "relax",
             "direct": "direct"}
    lines = ["| mesh | faces | " + " | ".join(names.get(m, m) for m in methods) +
             " | linf max < L2 max | relax vs linf | direct vs linf |",
             "|---|---:|" + "---|" * (len(methods) + 3)]
    for row in rows:
        by = {r["method"]: r for r in row["runs"]}
        cells = []
        for m in methods:
            r = by.get(m)
            if r is None:
                cells.append("–")
            elif "error" in r:
                cells.append("failed: " + r["error"][:60])
            else:
                marks = [] if r["status"] == "solved" else [r["status"]]
                if r.get("boundary_overlap"):
                    marks.append("boundary overlaps")
                if r.get("one_to_one") is False:
                    marks.append("not 1-to-1")
                st = f" ({', '.join(marks)})" if marks else ""
                t = r["time_s"]
                ts = f"{t:.2f}" if t < 1 else f"{t:.1f}" if t < 100 else f"{t:.0f}"
                cells.append(f"{r['max']:.3f} / {r['l2']:.3f} / {r['flips']} / {ts}{st}")
        v = row.get("verdicts", {})
        below = v.get("linf_below_l2")
        cells.append("–" if below is None else ("yes" if below else "**no**"))
        cells.append(fmt_verdict(v.get("relax_vs_linf")))
        direct = fmt_verdict(v.get("direct_vs_linf"))
        if v.get("direct_vs_linf_delta_k"):
            direct += f"; at delta-k {DELTA_K:g}: " + fmt_verdict(v["direct_vs_linf_delta_k"])
        cells.append(direct)
        lines.append(f"| {row['mesh']} | {row['faces']:,} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + ("\n\nEach cell: max ARAP / L2 (area-weighted RMS) ARAP / flipped triangles / "
                               "seconds; (boundary overlaps): the UV boundary crosses itself (strictmin's test); (not 1-to-1): "
                               "CGAL's own is_one_to_one_mapping fails on its result. Strict order of relax "
                               "(direct) relative to linf: < less distorting, = equivalent, > more distorting, "
                               "with the first level that differs: values within 1e-4 of the linf maximum and areas within "
                               "1e-6 of the total count as equal; for direct also at its own resolution, values "
                               "within delta-k = 1e-3.\n")


def write(out, meta, rows, methods):
    with open(out + ".json", "w") as f:
        json.dump(dict(meta, meshes=rows), f, indent=1)
    with open(out + ".md", "w") as f:
        f.write(markdown(rows, methods))


def fail(message):
    """A clear message on stderr and exit 1 (bad input: no traceback)."""
    sys.exit(f"param_table.py: {message}")


def load_run(path):
    """One earlier run's JSON (a dict with "meshes")."""
    try:
        with open(path) as f:
            j = json.load(f)
    except OSError as e:
        fail(f"--merge {path}: cannot open: {e.strerror}")
    except ValueError as e:
        fail(f"--merge {path}: not JSON: {e}")
    if not isinstance(j, dict) or not isinstance(j.get("meshes"), list):
        fail(f"--merge {path}: not a param_table.py JSON (no \"meshes\" list)")
    return j


def merge(a):
    rows, meta, methods = {}, {}, []
    for path in a.merge:
        j = load_run(path)
        for k, val in j.items():
            if k != "meshes":
                meta.setdefault(k, val)
        for row in j["meshes"]:
            cur = rows.setdefault(row["mesh"], {"mesh": row["mesh"], "faces": row["faces"],
                                                "path": row.get("path"), "runs": [], "stored_verdicts": {}})
            cur["stored_verdicts"].update(row.get("verdicts", {}))  # later files win, as for the runs
            for r in row["runs"]:
                cur["runs"] = [x for x in cur["runs"] if x["method"] != r["method"]] + [r]
                if r["method"] not in methods:
                    methods.append(r["method"])
    order = [m for m in ["lscm", "l2", "cgal-arap", "linf", "relax", "direct"] if m in methods]
    out_rows = sorted(rows.values(), key=lambda r: r["faces"])
    for row in out_rows:
        row["runs"].sort(key=lambda r: order.index(r["method"]))
        # Verdicts recomputed where the distortion files (--keep) and the mesh are there; the
        # stored ones otherwise (a merge without --keep must not lose them).
        stored = row.pop("stored_verdicts")
        path = row["path"]
        computed = verdicts(path, row["runs"], a.keep) if path and os.path.exists(path) else {}
        row["verdicts"] = dict(stored, **computed)
    meta["methods"] = order
    meta["merged_from"] = a.merge
    write(a.out, meta, out_rows, order)
    print(markdown(out_rows, order))


def check_program(flag, path):
    """A program flag's value must run: an executable file, or a name on PATH."""
    if os.sep in path:
        if not (os.path.isfile(path) and os.access(path, os.X_OK)):
            fail(f"{flag} {path}: no such executable program")
    elif shutil.which(path) is None:
        fail(f"{flag} {path}: not found on PATH")


def check_inputs(a):
    """Everything that can be checked before the first solve (which may take minutes)."""
    folder = os.path.dirname(a.out)
    if folder and not os.path.isdir(folder):
        fail(f"--out {a.out}: no folder {folder}")
    if a.merge is not None:
        return
    if not a.cli:
        fail("--cli is required (the strictmin program)")
    check_program("--cli", a.cli)
    if a.cgal and "cgal-arap" in a.methods:
        check_program("--cgal", a.cgal)
    for m in a.meshes or []:
        if not os.path.isfile(m):
            fail(f"--meshes {m}: no such file")
    if a.keep:
        try:
            os.makedirs(a.keep, exist_ok=True)
        except OSError as e:
            fail(f"--keep {a.keep}: cannot create: {e.strerror}")


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", default="")
    ap.add_argument("--cgal", default="")
    ap.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data", "disk"))
    ap.add_argument("--meshes", nargs="*", default=None)
    ap.add_argument("--methods", nargs="*", default=["lscm", "l2", "cgal-arap", "linf", "relax", "direct"])
    ap.add_argument("--lg-iterations", type=int, default=10)
    ap.add_argument("--direct-max-faces", type=int, default=50000)
    ap.add_argument("--timeout", type=float, default=1800)
    ap.add_argument("--direct-timeout", type=float, default=None, help="default: --timeout")
    ap.add_argument("--threads", type=int, default=0, help="strictmin --threads (0: all cores)")
    ap.add_argument("--keep", default="", help="folder for the per-element distortions (verdicts)")
    ap.add_argument("--merge", nargs="*", default=None, help="put together JSON outputs of earlier runs")
    ap.add_argument("--out", default="param_table")
    a = ap.parse_args()
    if a.merge is not None and not a.merge:
        fail("--merge: no JSON files given")
    check_inputs(a)
    if a.merge:
        return merge(a)
    meshes = a.meshes or sorted(glob.glob(os.path.join(a.data, "*.obj")), key=faces_of)
    if not meshes:
        fail(f"no meshes: none given (--meshes) and no .obj in --data {a.data}")
    meta = {"lg_iterations": a.lg_iterations, "threads": a.threads, "methods": a.methods,
            "direct_max_faces": a.direct_max_faces, "started": time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime())}
    rows = []
    for mesh in meshes:
        faces = faces_of(mesh)
        row = {"mesh": os.path.splitext(os.path.basename(mesh))[0], "faces": faces,
               "path": os.path.abspath(mesh), "runs": []}
        rows.append(row)
        with tempfile.TemporaryDirectory() as tmp:
            for m in a.methods:
                if m == "cgal-arap":
                    if not a.cgal:
                        continue
                    row["runs"].append(cgal(a.cgal, a.cli, mesh, a.timeout, tmp, a.keep))
                elif m == "direct" and faces > a.direct_max_faces:
                    continue
                else:
                    timeout = a.direct_timeout if (m == "direct" and a.direct_timeout) else a.timeout
                    row["runs"].append(ours(a.cli, mesh, m, a.lg_iterations, timeout, tmp, a.keep, a.threads))
                row["runs"][-1]["finished"] = time.strftime("%H:%M:%S", time.gmtime())
                print(row["mesh"], json.dumps(row["runs"][-1]), file=sys.stderr, flush=True)
                row["verdicts"] = verdicts(mesh, row["runs"], a.keep)
                meta["finished"] = time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime())
                write(a.out, meta, rows, a.methods)
    print(markdown(rows, a.methods))


if __name__ == "__main__":
    main()
