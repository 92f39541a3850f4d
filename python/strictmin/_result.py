"""The result object returned by deform, param, gparam and interp."""

import numpy as np


class Result:
    """A map and its account.

    Attributes: ``positions`` (deform, interp; #V by dim) or ``uv`` (param: #V by 2; gparam: #cut-mesh
    vertices by 2, with ``fuv`` #F by 3 indices into it),
    ``distortion`` (#E, in the measure minimized), ``weights`` (#E rest areas / volumes),
    ``status`` ("solved", "almost-solved", "max-iterations", "stalled", "numerical-error",
    "infeasible"), ``usable``, ``message`` (the stop reason), ``iterations``,
    ``lower_bound`` (certified: no map does better; NaN when the method gives none),
    ``history`` (a list of dicts, one per iteration), ``summary`` (a dict with the keys of
    the command line's ``--summary`` JSON), ``time_s``; param adds ``flips``, ``boundary``,
    ``boundary_overlap`` and ``initial`` (the starting map); gparam adds ``fuv``,
    ``flipped``, ``singularities`` (a list of (vertex, index in quarters)), ``field`` (the
    cross field's #F by 3 directions), ``euler_characteristic``, ``edge_length`` and
    ``seam_error``; interp adds ``t``.
    """

    def __init__(self, fields):
        for key, value in fields.items():
            if isinstance(value, np.ndarray):
                value = np.ascontiguousarray(value)
            setattr(self, key, value)

    @property
    def max_distortion(self):
        return float(self.distortion.max()) if self.distortion.size else 0.0

    def __repr__(self):
        s = self.summary
        parts = [f"task={s.get('task')!r}", f"method={s.get('method')!r}"]
        if "measure" in s:
            parts.append(f"measure={s['measure']!r}")
        if hasattr(self, "t"):
            parts.append(f"t={self.t:g}")
        parts.append(f"status={self.status!r}")
        parts.append(f"max_distortion={self.max_distortion:.6g}")
        if np.isfinite(self.lower_bound):
            parts.append(f"lower_bound={self.lower_bound:.6g}")
        parts.append(f"elements={self.distortion.size}")
        if hasattr(self, "singularities"):
            parts.append(f"singularities={len(self.singularities)}")
        parts.append(f"iterations={self.iterations}")
        return "Result(" + ", ".join(parts) + ")"
