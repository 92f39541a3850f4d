"""strictmin: maps of triangle and tetrahedral meshes with the least possible worst-case
distortion (Levi & Zorin 2014), on numpy arrays.

    V, F = strictmin.read_mesh("bimba.obj")
    r = strictmin.param(V, F, method="linf")
    print(r, r.summary["max_distortion"])

See docs/python.md for every function, keyword and the result object.
"""

import decimal
import numbers
import os
import sys
import warnings

import numpy as np

from . import _strictmin
from ._result import Result

__version__ = _strictmin.__version__

__all__ = ["blas_kernels", "read_mesh", "write_mesh", "deform", "param", "gparam", "interp", "distortion", "compare", "quads", "Result",
           "Comparison"]

def blas_kernels():
    """The dense kernels under the sparse factorizations, as ``(core, better)``: ``core`` the
    kernel set OpenBLAS runs ("" when the BLAS is not OpenBLAS); ``better`` the set to ask
    for with ``OPENBLAS_CORETYPE=better`` in the environment before Python starts, when
    OpenBLAS fell back to its generic Prescott kernels on a processor with AVX2 or AVX-512
    (the factorizations then run about twice as fast), else None. The strictmin command does
    this by itself."""
    core, better = _strictmin.blas_kernels()
    return core, better


class Comparison(tuple):
    """The strict order of d1 against d2, unpacked as ``order, level = compare(...)``:
    ``order`` -1 (d1 less distorting), 0 (equivalent) or 1 (more distorting); ``level`` the
    index of the first distortion level that differs (-1 when equivalent). Also
    ``value_a`` / ``value_b`` and ``area_a`` / ``area_b``: that level's values and areas."""

    def __new__(cls, order, level, value_a=0.0, value_b=0.0, area_a=0.0, area_b=0.0):
        self = super().__new__(cls, (int(order), int(level)))
        self.value_a, self.value_b, self.area_a, self.area_b = value_a, value_b, area_a, area_b
        return self

    order = property(lambda self: self[0])
    level = property(lambda self: self[1])

    def __reduce__(self):
        return (Comparison, (self[0], self[1], self.value_a, self.value_b, self.area_a, self.area_b))

    def __repr__(self):
        return (f"Comparison(order={self[0]}, level={self[1]}, value_a={self.value_a:.6g}, "
                f"value_b={self.value_b:.6g}, area_a={self.area_a:.6g}, area_b={self.area_b:.6g})")


def _is_real(x):
    """True for one real number: int, float, Fraction, Decimal, numpy's real scalars (not bool)."""
    if isinstance(x, (bool, np.bool_)):
        return False
    return isinstance(x, (numbers.Real, decimal.Decimal))


def _is_index(x):
    return isinstance(x, numbers.Integral) and not isinstance(x, (bool, np.bool_))


def _element_type(a, accepted=_is_real):
    """What an array holds that `accepted` refuses, for messages: 'str (dtype <U3)',
    'complex (dtype complex128)', or the type of an object array's first refused element."""
    if a.dtype.kind == "O":
        return next((type(x).__name__ for x in a.flat if not accepted(x)), "object")
    names = {"U": "str", "S": "bytes", "c": "complex", "b": "bool"}
    return f"{names.get(a.dtype.kind, a.dtype.name)} (dtype {a.dtype})"


def _array(x, name, expected):
    """np.asarray(x); a ValueError naming the argument when x is ragged."""
    try:
        return np.asarray(x)
    except ValueError:
        raise ValueError(f"{name} must be {expected}, got rows of different lengths") from None


def _real_array(x, name):
    """x as a float64 array; TypeError naming the argument unless it holds real numbers."""
    a = _array(x, name, "an array of real numbers")
    if a.dtype.kind in "fiu":
        return np.ascontiguousarray(a, dtype=np.float64)
    if a.dtype.kind == "O" and all(_is_real(v) for v in a.flat):
        return np.ascontiguousarray(a.astype(np.float64))
    raise TypeError(f"{name} must hold real numbers, not {_element_type(a)}")


def _real_number(x, name):
    """x as a float; TypeError naming the argument unless it is one real number."""
    if isinstance(x, np.ndarray) and x.ndim == 0:
        if x.dtype.kind in "fiu":
            return float(x)
        raise TypeError(f"{name} must be a real number, not {_element_type(x)}")
    if not _is_real(x):
        raise TypeError(f"{name} must be a real number, not {type(x).__name__}")
    return float(x)


def _text(x, name):
    if not isinstance(x, str):
        raise TypeError(f"{name} must be a string, not {type(x).__name__}")
    return x


def _path(path, function):
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"{function}: path must be a str or os.PathLike, not {type(path).__name__}")
    return os.fsdecode(os.fspath(path))


def _vertices(V, name="V"):
    V = _real_array(V, name)
    if V.ndim != 2 or V.shape[1] not in (2, 3):
        raise ValueError(f"{name} must be #V by 2 or 3, got shape {V.shape}")
    return V


def _integers(a, name):
    """An object array of Python ints as int64 (out of range: ValueError); TypeError when
    something else is in it."""
    if not all(_is_index(v) for v in a.flat):
        raise TypeError(f"{name} must hold integer indices, not {_element_type(a, _is_index)}")
    values = [int(v) for v in a.flat]
    if values and (min(values) < -2**31 or max(values) >= 2**31):
        raise ValueError(f"{name}: index {max(values) if max(values) >= 2**31 else min(values)} out of range")
    return np.array(values, dtype=np.int64).reshape(a.shape)


def _indices(F, name="F", ndim=2):
    F = _array(F, name, "an array of integer indices")
    if F.size == 0:
        F = F.astype(np.int32)
    if F.dtype.kind == "O":
        F = _integers(F, name)
    if F.dtype.kind == "f":
        if not np.all(np.isfinite(F)) or np.any(F != np.round(F)):
            raise ValueError(f"{name} must hold integer indices")
    elif F.dtype.kind not in "iu":
        raise TypeError(f"{name} must hold integer indices, not {_element_type(F, _is_index)}")
    if F.ndim != ndim:
        raise ValueError(f"{name} must have {ndim} dimension(s), got shape {F.shape}")
    if F.size and (F.min() < -2**31 or F.max() >= 2**31):
        raise ValueError(f"{name}: index {F.max() if F.max() >= 2**31 else F.min()} out of range")
    return np.ascontiguousarray(F, dtype=np.int32)


def _faces(F):
    F = _indices(F)
    if F.shape[1] not in (3, 4):
        raise ValueError(f"F must be #F by 3 (triangles) or 4 (tets), got shape {F.shape}")
    return F


def _format_record(r):
    """One progress line, as the command line prints it."""
    if r.get("stage") == "gparam":
        return f"gparam {r['message']}"
    if r.get("stage") == "strict":
        line = (f"  strict step {r['step']:3d}  k {r['k']:.8g}  fixed {r['fixed_now']} (total {r['fixed_total']})"
                f"  solves {r['solves']}")
        if r["level_free_vertices"] >= 0:
            line += f"  moving vertices {r['level_free_vertices']}"
        if r.get("pinned_total", 0) > 0:
            line += f"  pinned {r['pinned_total']}"
        if r["level_iterations"] > 0:
            line += f"  {r['level_iterations']} {r.get('level_iteration_unit', 'interior-point iterations')}"
        return line + f"  {r['time_s']:.2f} s"
    labels = {"linf": "  linf  iter", "lp": "  lp    iter", "irls": "  irls  iter", "relax": "  relax sweep",
              "local-global": "local-global iter"}
    line = f"{labels.get(r['stage'], r['stage'])} {r['iteration']:3d}  max {r['max_distortion']:.10g}"
    for name, key, fmt in (("lower bound", "lower_bound", ".10g"), ("gap", "certified_gap", ".2e"),
                           ("relative change", "relative_change", ".2e"), ("largest move", "largest_move", ".2e"),
                           ("decrement", "decrement", ".2e")):
        if not np.isnan(r[key]):
            line += f"  {name} {r[key]:{fmt}}"
    return line + f"  {r['time_s']:.2f} s"


def _progress(progress, verbose):
    if progress is not None and not callable(progress):
        raise TypeError("progress must be callable (it receives one dict per iteration)")
    if not verbose:
        return progress

    def both(record):
        print(_format_record(record), file=sys.stderr)
        if progress is not None:
            progress(record)
    return both


def read_mesh(path, *, check_geometry=True):
    """V, F of a mesh file (.obj, .off, .mesh), validated as the command line validates it.

    V is #V by 2 or 3 (float64), F #F by 3 (triangles) or #F by 4 (tets), 0-based (int32).
    ``check_geometry=False`` skips the zero-area/volume and orientation checks, as the command
    line does for a map's image (an interpolation target, a frame or a deformation with
    flipped elements). Raises ValueError naming the file, line and reason; warnings
    (unreferenced vertices) go to the warnings module."""
    V, F, notes = _strictmin.read_mesh(_path(path, "read_mesh"), bool(check_geometry))
    for note in notes:
        warnings.warn(note, stacklevel=2)
    return np.ascontiguousarray(V), np.ascontiguousarray(F)


def write_mesh(path, V, F, uv=None, quality=None):
    """Write a mesh by extension: .obj (with uv: vt and f v/vt), .off, .mesh (tets), or .ply
    (with quality: a per-face `quality` property MeshLab and ParaView colour)."""
    path = _path(path, "write_mesh")
    V = _vertices(V)
    F = _faces(F)
    ext = os.path.splitext(path)[1].lower()
    if uv is not None and ext != ".obj":
        raise ValueError(f"uv is written as an OBJ's vt; {ext or 'a file without extension'} cannot hold it")
    if quality is not None and ext != ".ply":
        raise ValueError(f"quality is written as a PLY's per-face property; {ext or 'a file without extension'} cannot hold it")
    if uv is not None:
        uv = _vertices(uv, "uv")
    if quality is not None:
        quality = _real_array(quality, "quality").reshape(-1)
    _strictmin.write_mesh(path, V, F, uv, quality)


def deform(V, F, handle_indices, handle_positions, method="linf", measure="fd", *, progress=None, verbose=False,
           **options):
    """Deform a planar triangle mesh, a triangle surface in 3D or a tet mesh so that the handle
    vertices reach their positions with the least distortion (method: l2, linf, relax, direct,
    exact, lp, irls; measure: fd, arap, asap, and qc or iso on planar triangles; docs/python.md).
    Options: the command line's flags with underscores
    (gap, max_iterations, sweeps, delta_k, k_min, lg_iterations, start, threads, ...).
    Returns a Result with ``positions``."""
    V = _vertices(V)
    F = _faces(F)
    idx = _indices(_array(handle_indices, "handle_indices", "an array of integer indices").reshape(-1),
                   "handle_indices", ndim=1)
    pos = _real_array(handle_positions, "handle_positions")
    if pos.ndim == 1 and idx.size == 1:
        pos = pos.reshape(1, -1)
    if pos.ndim != 2:
        raise ValueError(f"handle_positions must be #H by dim, got shape {pos.shape}")
    return Result(_strictmin.deform(V, F, idx, pos, _text(method, "method"), _text(measure, "measure"), options,
                                    _progress(progress, verbose)))


def param(V, F, method="linf", measure="arap", init=None, *, progress=None, verbose=False, **options):
    """Parametrize a disk-topology surface (one boundary loop) in the plane with a free
    boundary (method: tutte, lscm, l2, linf, relax, direct, lp, irls; measure: arap, asap,
    fd; init: tutte (None: the default) or lscm, the starting map; method tutte or lscm is
    that map itself, and an init naming the other one is a ValueError). relax starts from
    ``relax_init`` (l2, lp, irls, linf; default linf). Returns a Result with ``uv`` and
    ``warnings`` (flipped triangles, a boundary that crosses itself)."""
    V = _vertices(V)
    F = _faces(F)
    if init is not None:
        options["init"] = init
    return Result(_strictmin.param(V, F, _text(method, "method"), _text(measure, "measure"), options,
                                   _progress(progress, verbose)))


def gparam(V, F, method="l2", measure="fd", field=None, edge_length=None, quads=None, *, curvature_alignment=None,
           parallel=False, cones=None, integer_grid=False, grid_guide=None, progress=None, verbose=False,
           **options):
    """Globally parametrize a manifold triangle surface (one component, any genus, closed or
    with boundary loops: the field then follows the boundary and the map's boundary is free;
    integer_grid, parallel, cones and the unit field take closed surfaces only) guided by a
    cross field, with seams as linear constraints (the paper's Appendix A; docs/gparam.md). method: l2, linf, relax, direct, lp, irls; measure: fd (against the
    field) or arap; field: None or "smoothest", "unit" (the smoothest field lowered among unit fields),
    "curvature" (curvature_alignment, default 0.01, says how closely it follows the principal
    directions), or #F by 3 directions; parallel: keep the field's singularities and make it
    parallel between them (the CLI's --parallel); cones: #V integers, each vertex's index in
    quarters (the field with exactly these cones, the CLI's --cones; instead of field);
    edge_length: the surface length that maps to 1 in UV, or quads: about that many unit
    squares (default 1000); integer_grid: round the singular vertices and the seam
    translations to that grid first (the CLI's --integer-grid; the Result then has
    ``integer_error``, ``rounded_singularities``, ``off_grid_translations``, ``grid_guide``, ...);
    grid_guide: with integer_grid, the map the rounding follows, "l2" (default) or "linf" (the
    CLI's --grid-guide). Options: the command line's flags with underscores. Returns a
    Result with ``uv`` (#cut-mesh vertices by 2, the tool's vt) and ``fuv`` (#F by 3 indices
    into uv), ``singularities`` [(vertex, index in quarters)], ``field`` (#F by 3, the field
    used), ``euler_characteristic``, ``boundary_loops``, ``edge_length``, ``seam_error``,
    ``warnings`` (sentences on what the status does not say: full-turn singularities of a
    given field, cones missed)."""
    V = _vertices(V)
    F = _faces(F)
    directions = None
    if field is None:
        field = "smoothest"
    elif not isinstance(field, str):
        directions = np.asarray(field)
        if directions.dtype.kind not in "fiu":
            raise ValueError(f"field must be 'smoothest', 'unit', 'curvature' or #F by 3 directions, "
                             f"got dtype {directions.dtype}")
        directions = np.ascontiguousarray(directions, dtype=np.float64)
        if directions.ndim != 2 or directions.shape[1] != 3:
            raise ValueError(f"field directions must be #F by 3, got shape {directions.shape}")
        field = "given"
    elif field == "given":
        raise ValueError("field takes 'smoothest', 'unit', 'curvature' or a #F by 3 array of directions, not 'given'")
    if edge_length is not None:
        edge_length = _real_number(edge_length, "edge_length")
    if quads is not None:
        if isinstance(quads, bool) or not isinstance(quads, numbers.Integral):
            raise TypeError("quads must be an integer")
        quads = int(quads)
        if not -2**31 <= quads < 2**31:
            raise ValueError(f"quads: {quads} is out of range")
    if curvature_alignment is None:
        curvature_alignment = 0.01
    elif field != "curvature":
        raise ValueError(f"curvature_alignment applies to field='curvature' only (the field is "
                         f"{'from cones' if cones is not None else repr(field)})")
    else:
        curvature_alignment = _real_number(curvature_alignment, "curvature_alignment")
    if not isinstance(parallel, bool):
        raise TypeError("parallel must be True or False")
    if not isinstance(integer_grid, bool):
        raise TypeError("integer_grid must be True or False")
    if grid_guide is None:
        grid_guide = "l2"
    elif not integer_grid:
        raise ValueError("grid_guide applies to integer_grid=True only")
    else:
        grid_guide = _text(grid_guide, "grid_guide")
    if cones is not None:
        cones = np.asarray(cones)
        if cones.size == 0 and cones.ndim == 1:
            cones = cones.astype(np.int64)  # [] is float64 to numpy: let the count be the message
        if cones.dtype.kind not in "iu" or cones.ndim != 1:
            raise ValueError(f"cones must be a 1-D array of integers (indices in quarters), got dtype {cones.dtype}, "
                             f"shape {cones.shape}")
        if cones.size and (cones.min() < -2**31 or cones.max() >= 2**31):
            raise ValueError("cones: an index is out of range")
        cones = [int(q) for q in cones]
    return Result(_strictmin.gparam(V, F, _text(method, "method"), _text(measure, "measure"), field, directions,
                                    edge_length, quads, curvature_alignment, parallel, cones, integer_grid,
                                    grid_guide, options,
                                    _progress(progress, verbose)))


def interp(V, F, V_target, t, method="linf", *, progress=None, verbose=False, **options):
    """Interpolate between two poses of one mesh (same F) at time t in [0, 1] (a float: one
    Result; a list: a list of Results), local-global around the method. Options: pin
    ('centroid' or a vertex), rotation_blend ('auto', 'logarithms' or 'tree': 3D only),
    lg_iterations (0: no local steps), lg_tolerance and the method's options. Returns Results
    with ``positions``, ``t``, ``rotation_jumps``, ``rotation_blend``,
    ``rotation_disagreements`` and ``warnings`` (docs/interp.md, "Limits")."""
    V = _vertices(V)
    F = _faces(F)
    V_target = _vertices(V_target, "V_target")
    single = not isinstance(t, (str, bytes)) and (_is_real(t) or (isinstance(t, np.ndarray) and t.ndim == 0))
    times = [_real_number(t, "t")] if single else _times(t)
    results = [Result(r) for r in _strictmin.interp(V, F, V_target, times, _text(method, "method"), options,
                                                   _progress(progress, verbose))]
    return results[0] if single else results


def _times(t):
    """interp's sequence of times as floats; TypeError naming t (or its item) otherwise."""
    if isinstance(t, (str, bytes)):
        raise TypeError(f"t must be a number or a sequence of numbers in [0, 1], not a string ({t!r})")
    try:
        items = list(t)
    except TypeError:
        raise TypeError(f"t must be a number or a sequence of numbers in [0, 1], not {type(t).__name__}") from None
    return [_real_number(x, f"t[{i}]") for i, x in enumerate(items)]


def distortion(V, F, U, measure="arap"):
    """Per-element distortion of the map sending vertex i of (V, F) to U[i] (a deformation,
    #V by dim, or a UV layout, #V by 2), or corner j of element e to U[e * corners + j]
    (seamed layouts). measure: fd, arap, asap, qc (sigma1/sigma2), iso."""
    V = _vertices(V)
    F = _faces(F)
    U = _vertices(U, "U")
    return np.ascontiguousarray(_strictmin.distortion(V, F, U, _text(measure, "measure"))["distortion"])


def quads(V, F, uv, fuv, tolerance=1e-6, fill_holes=False):
    """The quad mesh of an integer-grid map (gparam with integer_grid=True: its ``uv`` and
    ``fuv``; the command line's ``strictmin quads``; docs/gparam.md, "Quad meshes"): one quad
    per unit square of UV. Returns a dict: ``V`` (#vertices by 3, on the surface), ``Q``
    (#quads by 4, counter-clockwise), ``uv`` / ``quv`` (each quad's integer corners),
    ``vertex_face`` and ``vertex_barycentric`` (where each vertex lies on (V, F)),
    ``complete`` (every square a quad, closed, the surface's Euler characteristic) and
    ``summary`` (the command line's keys: holes, dropped_squares, valences, ...). Squares next
    to flipped triangles are left out as holes (complete is then False). tolerance: UV units,
    how far a seam translation or a cone may be from the grid. fill_holes: fill the holes with
    the grid's squares where their boundary allows (the CLI's --fill-holes; status "filled",
    the inner vertices placed by averaging, ``vertex_face`` -1). ValueError when the map is not
    an integer-grid map."""
    V = _vertices(V)
    F = _faces(F)
    uv = _real_array(uv, "uv")
    if uv.ndim != 2 or uv.shape[1] != 2:
        raise ValueError(f"uv must be #UV by 2, got shape {uv.shape}")
    fuv = _indices(fuv, "fuv")
    tolerance = _real_number(tolerance, "tolerance")
    if not isinstance(fill_holes, bool):
        raise TypeError("fill_holes must be True or False")
    return _strictmin.quads(V, F, uv, fuv, tolerance, fill_holes)


def element_weights(V, F):
    """Rest areas (triangles) or volumes (tets), the weights of the strict order."""
    V = _vertices(V)
    F = _faces(F)
    return np.ascontiguousarray(_strictmin.distortion(V, F, V, "fd")["weights"])


def compare(d1, d2, weights=None, value_tolerance=1e-6, area_tolerance=1e-9):
    """The strict order of two distortion vectors of one mesh (paper Section 4): a
    Comparison whose ``order`` is -1 when d1 is less distorting, 0 equivalent, 1 more, and
    ``level`` the first differing level (-1 when equivalent). weights: the elements' areas
    (default: all 1)."""
    d1 = _real_array(d1, "d1").reshape(-1)
    d2 = _real_array(d2, "d2").reshape(-1)
    w = np.ones_like(d1) if weights is None else _real_array(weights, "weights").reshape(-1)
    value_tolerance = _real_number(value_tolerance, "value_tolerance")
    area_tolerance = _real_number(area_tolerance, "area_tolerance")
    if not (value_tolerance >= 0 and area_tolerance >= 0):  # also refuses nan
        raise ValueError(f"value_tolerance and area_tolerance must be >= 0, got {value_tolerance} and {area_tolerance}")
    return Comparison(*_strictmin.compare(d1, d2, w, value_tolerance, area_tolerance))
