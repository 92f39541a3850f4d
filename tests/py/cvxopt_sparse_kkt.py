"""A sparse KKT solver for CVXOPT's SOCP method, so that the cross-check reaches problems of a
few thousand elements (CVXOPT's built-in solvers for second-order cones factorise dense
matrices: 128 s for 1,238 triangles, 250 s for 2,048).

CVXOPT's algorithm (steps, scalings, stopping) is unchanged: this only solves its Newton
systems, as its documentation allows (`kktsolver` argument, "Exploiting Structure"). Without
equality constraints the system

    [ 0   G'    ] [ ux ]   [ bx ]
    [ G  -W'W   ] [ uz ] = [ bz ]

reduces to H ux = bx + G' (W'W)^-1 bz with H = (W^-T G)' (W^-T G), and W uz = W^-T (G ux - bz).
For a second-order cone CVXOPT's scaling is W = beta (2 v v' - J), J = diag(1, -1, ..., -1),
symmetric, with W^-1 = (2 J v v' J - J) / beta. Every cone here has the same dimension q and
touches only a few columns (k and its element's vertex coordinates), so each cone's block of G
is kept dense (q x c, c its columns) and H is assembled from per-cone c x c blocks and
factorised by CHOLMOD (cvxopt.cholmod).
"""
import numpy as np
from cvxopt import cholmod, matrix, spmatrix


class ConeBlocks:
    """G as dense per-cone blocks: G_e = blocks[e] (q x c) on the columns cols[e] (padding: -1)."""

    def __init__(self, cone_rows, q, nv):
        # cone_rows[e]: list of (row within the cone 0..q-1, column, value)
        self.q = q
        self.nv = nv
        columns = [sorted({j for _, j, _ in rows}) for rows in cone_rows]
        c = max(1, max(len(cs) for cs in columns))
        E = len(cone_rows)
        self.cols = -np.ones((E, c), dtype=np.int64)
        self.blocks = np.zeros((E, q, c))
        for e, rows in enumerate(cone_rows):
            where = {j: i for i, j in enumerate(columns[e])}
            self.cols[e, :len(columns[e])] = columns[e]
            for r, j, v in rows:
                self.blocks[e, r, where[j]] += v
        self.used = self.cols >= 0
        self.safe_cols = np.where(self.used, self.cols, 0)
        ii = np.broadcast_to(self.safe_cols[:, :, None], (E, c, c))
        jj = np.broadcast_to(self.safe_cols[:, None, :], (E, c, c))
        mask = self.used[:, :, None] & self.used[:, None, :]
        self.h_rows = ii[mask].tolist()
        self.h_cols = jj[mask].tolist()
        self.h_mask = mask

    def kktsolver(self, W):
        if W["d"].size[0] or W["r"]:
            raise ValueError("sparse KKT: only second-order cones are handled")
        q, E = self.q, len(W["v"])
        v = np.array([np.array(vk).ravel() for vk in W["v"]])  # E x q
        beta = np.array(W["beta"], dtype=float)
        jdiag = -np.ones(q)
        jdiag[0] = 1.0
        jv = v * jdiag
        winv = (2.0 * jv[:, :, None] * jv[:, None, :] - np.diag(jdiag)[None, :, :]) / beta[:, None, None]
        wg = np.einsum("eij,ejc->eic", winv, self.blocks)  # W^-T G, per cone
        hblocks = np.einsum("eic,eid->ecd", wg, wg)
        values = hblocks[self.h_mask]
        H = spmatrix(values.tolist(), self.h_rows, self.h_cols, (self.nv, self.nv))
        F = cholmod.symbolic(H)
        # Near the optimum H can lose definiteness to round-off: then a small multiple of the
        # identity is added (CVXOPT's iterative refinement removes its effect on the step).
        shift = 0.0
        scale = max(abs(values).max(), 1e-300)
        for attempt in range(8):
            try:
                cholmod.numeric(H if shift == 0 else H + spmatrix([float(shift)] * self.nv, list(range(self.nv)), list(range(self.nv))), F)
                break
            except ArithmeticError:
                shift = scale * (1e-14 if shift == 0 else 100 * shift / scale)
        else:
            raise ArithmeticError("sparse KKT: H is not positive definite")

        def solve(x, y, z):
            bz = np.array(z).ravel().reshape(E, q)
            wz = np.einsum("eij,ej->ei", winv, bz)  # W^-T bz (W is symmetric)
            rhs = np.array(x).ravel().copy()
            contrib = np.einsum("eic,ei->ec", wg, wz)  # G' (W'W)^-1 bz = (W^-T G)' W^-T bz
            np.add.at(rhs, self.safe_cols[self.used], contrib[self.used])
            u = matrix(rhs)
            cholmod.solve(F, u)
            ux = np.array(u).ravel()
            gx = np.einsum("eic,ec->ei", wg, np.where(self.used, ux[self.safe_cols], 0.0))
            x[:] = matrix(ux)
            z[:] = matrix((gx - wz).ravel())

        return solve
