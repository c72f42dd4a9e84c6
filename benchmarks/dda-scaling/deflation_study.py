#!/usr/bin/python3
"""Would a two-level preconditioner or a local solve cut the CG work of the
DDA's linear solves? Measured on the engine's own matrices (section 20 of
README.md).

usage: deflation_study.py CENTROIDS SYSTEM.bin [SYSTEM.bin ...]
       [--sizes 4,8,16] [--patches]

Inputs are written by the engine built with dump-systems.patch (temporary
instrumentation, not part of main):
  ROCKDDA_DUMP=DIR ROCKDDA_DUMP_FROM=A ROCKDDA_DUMP_TO=B rockdda scene.prm
writes DIR/cent0.txt (the blocks' initial centroids, m) and the solves A to
B - 1 as DIR/sysK.bin: int32 n, int32 m, float64 tolerance, the n diagonal
6x6 blocks, the m pairs (int32 i, int32 j, K_ij), f and the starting x
(blocks column-major).

For each system it runs preconditioned CG to the engine's tolerance (the
same stopping test, r^T M^-1 r <= tol^2 f^T M^-1 f) from the engine's
starting x with
  - the block D-ILU M = (P + L) P^-1 (P + U) of linear_solver.cc in the
    natural block order (no subdomains);
  - the same D-ILU inside a two-level "A-DEF2" preconditioner (Tang,
    Nabben, Vuik & Erlangga 2009, J. Sci. Comput. 39: 340-370):
    M2 = (I - Q K) M^-1 + Q, Q = Z (Z^T K Z)^-1 Z^T, with Z the rigid
    motions (2 translations, 1 rotation about the aggregate's centroid) of
    aggregates of SIZE blocks grown by breadth-first search over the block
    graph;
  - with --patches: the D-ILU CG after an exact solve of the residual on a
    patch around the blocks holding 99 % of |r0|^2, grown by 1 to 6 rings
    of neighbours (a one-shot additive-Schwarz correction).
It prints the CG iterations of each.
"""
import argparse
import struct
from collections import deque

import numpy as np
import scipy.sparse as sp
from scipy.linalg import cho_factor, cho_solve
from scipy.sparse.linalg import splu, spsolve

D = 6


def load(path):
    b = open(path, "rb").read()
    n, m = struct.unpack_from("ii", b, 0)
    tol, = struct.unpack_from("d", b, 8)
    off = 16
    diag = np.frombuffer(b, np.float64, n * D * D, off).reshape(
        n, D, D).transpose(0, 2, 1).copy()
    off += 8 * n * D * D
    pairs, blocks = [], np.empty((m, D, D))
    for k in range(m):
        pairs.append(struct.unpack_from("ii", b, off))
        off += 8
        blocks[k] = np.frombuffer(b, np.float64, D * D, off).reshape(D, D).T
        off += 8 * D * D
    f = np.frombuffer(b, np.float64, n * D, off).copy()
    x0 = np.frombuffer(b, np.float64, n * D, off + 8 * n * D).copy()
    return n, tol, diag, pairs, blocks, f, x0


def block_csr(n, entries):
    """CSR matrix of the (row block, column block, 6x6) entries."""
    I, J = np.meshgrid(np.arange(D), np.arange(D), indexing="ij")
    rows, cols, vals = [], [], []
    for i, j, A in entries:
        rows.append(D * i + I.ravel())
        cols.append(D * j + J.ravel())
        vals.append(A.ravel())
    return sp.csr_matrix((np.concatenate(vals),
                          (np.concatenate(rows), np.concatenate(cols))),
                         shape=(D * n, D * n))


def matrix(n, diag, pairs, blocks):
    entries = [(i, i, diag[i]) for i in range(n)]
    for (i, j), A in zip(pairs, blocks):
        entries += [(i, j, A), (j, i, A.T)]
    return block_csr(n, entries)


def dilu(n, diag, pairs, blocks):
    """The block D-ILU, applied as r -> (P + U)^-1 P (P + L)^-1 r."""
    lower = {}
    for (i, j), A in zip(pairs, blocks):
        a, b, Kab = (i, j, A) if i < j else (j, i, A.T)
        lower.setdefault(b, []).append((a, Kab))
    P, Pinv = diag.copy(), np.empty_like(diag)
    for b in range(n):
        for a, Kab in lower.get(b, []):
            P[b] -= Kab.T @ Pinv[a] @ Kab
        Pinv[b] = np.linalg.inv(P[b])
    entries = [(i, i, P[i]) for i in range(n)]
    entries += [(b, a, Kab.T) for b, lst in lower.items() for a, Kab in lst]
    PL = block_csr(n, entries)
    lo = splu(PL.tocsc(), permc_spec="NATURAL", diag_pivot_thresh=0.)
    up = splu(PL.T.tocsc(), permc_spec="NATURAL", diag_pivot_thresh=0.)
    Pd = sp.block_diag(list(P)).tocsr()
    return lambda r: up.solve(Pd @ lo.solve(r))


def neighbours(n, pairs):
    adj = [[] for _ in range(n)]
    for i, j in pairs:
        adj[i].append(j)
        adj[j].append(i)
    return adj


def rigid_modes(n, adj, centroids, size):
    """Z: the rigid motions of aggregates of `size` blocks (BFS)."""
    agg, na = -np.ones(n, int), 0
    for s in range(n):
        if agg[s] >= 0:
            continue
        queue, agg[s], count = deque([s]), na, 1
        while queue and count < size:
            for v in adj[queue.popleft()]:
                if agg[v] < 0 and count < size:
                    agg[v], count = na, count + 1
                    queue.append(v)
        na += 1
    c, cnt = np.zeros((na, 2)), np.zeros(na)
    np.add.at(c, agg, centroids)
    np.add.at(cnt, agg, 1)
    c /= cnt[:, None]
    rows, cols, vals = [], [], []
    for i in range(n):
        a = agg[i]
        dx, dy = centroids[i] - c[a]
        rows += [D * i, D * i + 1, D * i, D * i + 1, D * i + 2]
        cols += [3 * a, 3 * a + 1, 3 * a + 2, 3 * a + 2, 3 * a + 2]
        vals += [1., 1., -dy, dx, 1.]
    return sp.csr_matrix((vals, (rows, cols)), shape=(D * n, 3 * na)), na


def pcg(K, f, x, M, tol, apply=None, maxit=5000):
    apply = apply or M
    x = x.copy()
    bnorm = f @ M(f)
    r = f - K @ x
    z = apply(r)
    p, rz, it = z.copy(), r @ z, 0
    while rz > tol * tol * bnorm and it < maxit:
        q = K @ p
        a = rz / (p @ q)
        x += a * p
        r -= a * q
        z = apply(r)
        rz_new = r @ z
        p = z + (rz_new / rz) * p
        rz, it = rz_new, it + 1
    return x, it


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("centroids")
    ap.add_argument("systems", nargs="+")
    ap.add_argument("--sizes", default="4,8,16")
    ap.add_argument("--patches", action="store_true")
    args = ap.parse_args()
    centroids = np.loadtxt(args.centroids)
    for path in args.systems:
        n, tol, diag, pairs, blocks, f, x0 = load(path)
        K = matrix(n, diag, pairs, blocks)
        M = dilu(n, diag, pairs, blocks)
        adj = neighbours(n, pairs)
        out = [path, "%d blocks" % n,
               "D-ILU %d" % pcg(K, f, x0, M, tol)[1],
               "(from 0: %d)" % pcg(K, f, 0 * f, M, tol)[1]]
        for size in [int(v) for v in args.sizes.split(",")]:
            Z, na = rigid_modes(n, adj, centroids, size)
            E = cho_factor((Z.T @ (K @ Z)).toarray())
            Q = lambda v: Z @ cho_solve(E, Z.T @ v)
            adef2 = lambda r: (lambda z: z - Q(K @ z))(M(r)) + Q(r)
            x1 = x0 + Q(f - K @ x0)
            out.append("two-level, aggregates of %d (%d coarse unknowns) %d"
                       % (size, 3 * na, pcg(K, f, x1, M, tol, adef2)[1]))
        if args.patches:
            r = f - K @ x0
            rb = (r.reshape(n, D) ** 2).sum(axis=1)
            order = np.argsort(rb)[::-1]
            held = np.searchsorted(np.cumsum(rb[order]) / rb.sum(), .99) + 1
            patch = set(order[:held])
            out.append("|r0|^2 99 %% in %d blocks" % held)
            for ring in range(1, 7):
                patch |= {v for u in patch for v in adj[u]}
                if ring in (1, 2, 4, 6):
                    idx = np.concatenate(
                        [np.arange(D * b, D * b + D) for b in sorted(patch)])
                    x1 = x0.copy()
                    x1[idx] += spsolve(K[idx][:, idx].tocsc(), r[idx])
                    out.append("patch of %d rings (%d blocks) %d"
                               % (ring, len(patch),
                                  pcg(K, f, x1, M, tol)[1]))
        print("; ".join(out), flush=True)


if __name__ == "__main__":
    main()
