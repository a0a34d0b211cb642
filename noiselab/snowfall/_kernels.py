"""Hot loops of the snow renderer (numba, cached): the in-place opacity map and the sparse t-pass."""
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
def rescale_power_into(flat, dst, lo, scale, beta):
    """``dst = clip((flat - lo) * scale, 0, 1) ** beta`` for a ``dst`` apart from ``flat`` (the same arithmetic).

    Not for ``dst is flat``: the two arrays may overlap for all numba knows,
    so the loop is vectorised behind a runtime overlap check, and an
    overlapping pair runs element by element (7x slower than
    :func:`rescale_power` on 16 Mi float32, 2026-11-27).
    """
    one = flat.dtype.type(1.0)
    zero = flat.dtype.type(0.0)
    lo = flat.dtype.type(lo)
    scale = flat.dtype.type(scale)
    b = flat.dtype.type(beta)
    if beta == 1.0:
        for i in range(flat.size):
            v = (flat[i] - lo) * scale
            dst[i] = min(max(v, zero), one)
    elif beta == 1.5:
        for i in range(flat.size):
            v = min(max((flat[i] - lo) * scale, zero), one)
            dst[i] = v * np.sqrt(v)
    else:
        for i in range(flat.size):
            v = min(max((flat[i] - lo) * scale, zero), one)
            dst[i] = v ** b


@njit(cache=True, nogil=True)
def t_pass_scatter(dest, bins, vals, tw, t0, B, k):
    """``B[t, :, :k] = 0``, then ``B[t].flat[dest[e]] += vals[e] * tw[(bins[e] * (t0 + t)) % T]`` over every entry ``e``.

    The t-pass of the sparse columns (an inverse DFT along t, ``tw`` its
    twiddles with the ``1/T``, in ``B``'s precision) for each frame ``t`` of
    the block ``B``, scattered straight into the y-pass input (``dest``: each
    entry's cell ``ky * B.shape[2] + kx``): a column has a few bins, so the
    direct sum costs less than an FFT of the dense ``(T, columns)`` array,
    without that array. Only the first ``k`` columns of each row are zeroed
    (the cells that can carry energy: a wider ``B`` is the x-pass's padded
    input, whose columns past ``k`` stay zero). Each cell sums its entries in
    their order: the same bits whichever block a frame is in and however the
    columns are split.
    """
    nt = B.shape[0]
    T = tw.size
    rot = np.empty(T, dtype=B.dtype)
    zero = B.dtype.type(0)
    for t in range(nt):
        Bt = B[t]
        for y in range(Bt.shape[0]):
            for x in range(k):
                Bt[y, x] = zero
        Bf = Bt.reshape(-1)
        step = (t0 + t) % T
        m = 0
        for b in range(T):  # rot[b] = tw[(b * (t0 + t)) % T], without a division per entry
            rot[b] = tw[m]
            m += step
            if m >= T:
                m -= T
        for e in range(dest.size):
            Bf[dest[e]] += vals[e] * rot[bins[e]]
