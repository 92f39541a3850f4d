#!/usr/bin/env python3
"""Parametrize a disk-topology mesh three ways (L2, L-infinity, the strict minimizer by
relaxation; ARAP in each), write the maps as UV-mapped OBJ files and plot the
three distortion histograms (log scale) to a PNG with matplotlib.

    PYTHONPATH=build/python python3 examples/python/param_histograms.py [MESH.obj] [--out DIR]

Without MESH it takes bimba_1k.obj from the shared test meshes ($STRICTMIN_SHARED_DATA/disk,
by default ../shared/data/disk beside the project) and exits politely when they are absent.
"""
import argparse
import os
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import strictmin  # noqa: E402

HERE = Path(__file__).resolve().parent
DEFAULT_DATA = Path(os.environ.get("STRICTMIN_SHARED_DATA", HERE.parent.parent.parent / "shared" / "data"))


def write_uv_obj(path, V, F, uv):
    """An OBJ with one vt per vertex and 'f a/a b/b c/c' corners: every face has vt indices,
    so `strictmin eval MESH.obj MAP.obj` takes the UVs as the map (docs/formats.md)."""
    with open(path, "w") as f:
        for p in V:
            f.write("v " + " ".join(repr(float(x)) for x in p) + "\n")
        for t in uv:
            f.write(f"vt {float(t[0])!r} {float(t[1])!r}\n")
        for a, b, c in np.asarray(F) + 1:
            f.write(f"f {a}/{a} {b}/{b} {c}/{c}\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mesh", nargs="?", default=str(DEFAULT_DATA / "disk" / "bimba_1k.obj"))
    parser.add_argument("--out", default="param_histograms", help="output folder")
    args = parser.parse_args()
    if not Path(args.mesh).exists():
        print(f"param_histograms: {args.mesh} is not there (the shared test meshes are optional); "
              "give a disk-topology .obj to run the example", file=sys.stderr)
        return 0
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    V, F = strictmin.read_mesh(args.mesh)
    runs = {
        "L2": strictmin.param(V, F, method="l2", measure="arap"),
        "L-infinity": strictmin.param(V, F, method="linf", measure="arap"),
        "strict (relax)": strictmin.param(V, F, method="relax", measure="arap", sweeps=50),
    }
    for name, r in runs.items():
        print(f"{name:15s} {r}")
        path = out / f"{Path(args.mesh).stem}_{name.split()[0].lower().replace('-', '')}.obj"
        write_uv_obj(path, V, F, r.uv)
        print(f"{'':15s} wrote {path}")

    # Log-scale histograms on shared bins: the strict minimizer moves area out of the top bins.
    top = max(r.distortion.max() for r in runs.values())
    low = max(min(r.distortion[r.distortion > 0].min() for r in runs.values()), top * 1e-4)
    bins = np.geomspace(low, top, 40)
    fig, ax = plt.subplots(figsize=(7, 4))
    for name, r in runs.items():
        ax.hist(np.clip(r.distortion, low, None), bins=bins, weights=r.weights / r.weights.sum(), histtype="step",
                linewidth=1.5, label=f"{name}: max {r.max_distortion:.3g}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("ARAP distortion per triangle")
    ax.set_ylabel("fraction of the area")
    ax.set_title(f"{Path(args.mesh).name}: {len(F)} triangles")
    ax.legend(loc="upper left")
    fig.tight_layout()
    png = out / "histograms.png"
    fig.savefig(png, dpi=120)
    print(f"wrote {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
