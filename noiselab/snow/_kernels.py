"""Hot loop of the snow renderer (numba, cached): the in-place opacity map."""
from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, nogil=True)
def rescale_power(flat, lo, scale, beta):
    """``flat = clip((flat - lo) * scale, 0, 1) ** beta`` in place (beta 1 and 1.5 without ``pow``)."""
    one = flat.dtype.type(1.0)
    zero = flat.dtype.type(0.0)
    lo = flat.dtype.type(lo)
    scale = flat.dtype.type(scale)
    b = flat.dtype.type(beta)
    if beta == 1.0:
        for i in range(flat.size):
            v = (flat[i] - lo) * scale
            flat[i] = min(max(v, zero), one)
    elif beta == 1.5:
        for i in range(flat.size):
            v = min(max((flat[i] - lo) * scale, zero), one)
            flat[i] = v * np.sqrt(v)
    else:
        for i in range(flat.size):
            v = min(max((flat[i] - lo) * scale, zero), one)
            flat[i] = v ** b


@njit(cache=True, nogil=True)
def scatter_columns(C, t0, ky, kx, B):
    """``B[t] = 0`` then ``B[t, ky[j], kx[j]] = C[t0 + t, j]`` for every frame ``t`` of the block ``B``.

    The y-pass input of one block of frames: the spectrum columns put back at
    their ``(ky, kx)`` cells, zeros elsewhere, in one pass (numpy's fancy
    scatter after a ``zeros`` was slower in a scratch timing, loaded machine).
    """
    nt, H, K = B.shape
    zero = B.dtype.type(0)
    for t in range(nt):
        for i in range(H):
            for k in range(K):
                B[t, i, k] = zero
        for j in range(ky.size):
            B[t, ky[j], kx[j]] = C[t0 + t, j]

