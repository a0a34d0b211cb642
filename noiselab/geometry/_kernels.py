"""numba kernel for the per-face geometry of a mesh: one pass instead of numpy's gathers and temporaries.

:func:`face_pass` walks the faces once and returns the area-weighted
vertex normal sums, the signed volume, the longest edge and a strided sample of
edge lengths (for the median). numpy
needs three fancy-indexed gathers of the corners, a cross product, three
bincounts and their temporaries for the same (about 10x slower on a 1M-vertex
mesh, see ``benchmarks/bench_mesh.md``). Float64 throughout, the faces in
order, so the result does not depend on anything but the mesh.
"""
from __future__ import annotations

import math

import numba as nb
import numpy as np


@nb.njit(cache=True, nogil=True)
def face_pass(vertices, faces, stride):
    """Area-weighted vertex normal sums (not yet unit: see :func:`unit_rows`), signed volume, longest
    edge, and the edge lengths of every ``stride``-th face (``stride = 0``: none) for a median that
    need not sort millions of edges."""
    n = vertices.shape[0]
    m = faces.shape[0]
    sums = np.zeros((n, 3))
    want_lengths = stride > 0
    sampled = (m + stride - 1) // stride if want_lengths else 0
    lengths = np.empty(3 * sampled)
    longest = 0.0
    volume = 0.0
    for k in range(m):
        i0 = faces[k, 0]
        i1 = faces[k, 1]
        i2 = faces[k, 2]
        ax = vertices[i0, 0]
        ay = vertices[i0, 1]
        az = vertices[i0, 2]
        ux = vertices[i1, 0] - ax
        uy = vertices[i1, 1] - ay
        uz = vertices[i1, 2] - az
        wx = vertices[i2, 0] - ax
        wy = vertices[i2, 1] - ay
        wz = vertices[i2, 2] - az
        cx = uy * wz - uz * wy
        cy = uz * wx - ux * wz
        cz = ux * wy - uy * wx
        volume += ax * cx + ay * cy + az * cz
        for i in (i0, i1, i2):
            sums[i, 0] += cx
            sums[i, 1] += cy
            sums[i, 2] += cz
        if want_lengths:
            dx = wx - ux
            dy = wy - uy
            dz = wz - uz
            l0 = ux * ux + uy * uy + uz * uz
            l1 = wx * wx + wy * wy + wz * wz
            l2 = dx * dx + dy * dy + dz * dz
            longest = max(longest, l0, l1, l2)
            if k % stride == 0:
                j = k // stride
                lengths[3 * j] = math.sqrt(l0)
                lengths[3 * j + 1] = math.sqrt(l1)
                lengths[3 * j + 2] = math.sqrt(l2)
    return sums, volume / 6.0, math.sqrt(longest), lengths


@nb.njit(cache=True, nogil=True)
def unit_rows(sums):
    """Normalise (n, 3) rows in place; rows of (near) zero length become zero."""
    for i in range(sums.shape[0]):
        s = math.sqrt(sums[i, 0] ** 2 + sums[i, 1] ** 2 + sums[i, 2] ** 2)
        if s > 1e-300:
            sums[i, 0] /= s
            sums[i, 1] /= s
            sums[i, 2] /= s
        else:
            sums[i, 0] = 0.0
            sums[i, 1] = 0.0
            sums[i, 2] = 0.0
    return sums
