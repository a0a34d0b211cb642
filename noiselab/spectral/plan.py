"""The spectral plan: internal interface shared by the in-memory and dask paths of :func:`spectral_noise`.

:func:`noiselab.spectral.spectral_noise` fills its half spectrum in memory
(:mod:`noiselab.spectral.synthesis`); ``spectral_noise(..., chunks=)`` fills
the same spectrum slab by slab on dask (:mod:`noiselab.scale.spectral`). Both
build it from the functions here, so the two paths draw the same
coefficients, make the same planes Hermitian and scale by the same gain:

- :func:`noise_plan`: the validated band, the kept block of rows and kx
  columns, each row's kx interval, the power law's reference and the stream key;
- :func:`fill_slab`: the block's slab ``i0:i1`` along its first axis, unscaled,
  with its rows' power (the in-memory fill writes the same rows in groups);
- :func:`hermitian_gain`: the self-conjugate planes made Hermitian and the
  gain that gives the field unit variance;
- :func:`leading_ifft`: the pruned inverse FFT along the leading axes (the
  kept rows back at their indices, then ``ifft``);
- :func:`self_conjugate_columns`, :func:`complex_dtype`, :func:`stream_key`,
  :data:`AMPLITUDE_MODES`, :data:`CHUNK`: the small conventions they share.

The plan (a namespace) holds: ``shape``, ``dt``/``cdt`` (float and complex
dtypes), ``n`` (last axis), ``index`` (kept indices of each leading axis),
``K`` (kept kx columns ``0..K-1``), ``bshape`` (the block's shape), ``q0``,
``q1``, ``wxsq`` (squared angular frequencies of the row axes and of kx),
``kbeg``/``kend``/``counts`` (each row's kx interval and its cell count),
``R``/``Kr`` (rows and row length of the fill), ``weight`` (each kx column's
share of the power), ``sample``, ``exponent``, ``qfloor``, ``inv_qref``,
``key``, ``mode``, ``dc``, ``band``, ``lo``, ``maps`` (each self-conjugate plane's
mirror rows), ``peak`` (the in-memory path's bytes) and ``memo`` (a dict in
which a path keeps what it derives from the geometry, shared by the calls
that share the geometry).

Internal: noiselab's subpackages use these names; users call
:func:`~noiselab.spectral.spectral_noise`.
"""
from __future__ import annotations

import functools
from types import SimpleNamespace

import numpy as np
import scipy.fft

from .._core import as_generator, check_memory, float_dtype
from .._core.validate import check_band
from . import _kernels
from .frequencies import frequency_vectors

__all__ = ["AMPLITUDE_MODES", "CHUNK", "complex_dtype", "self_conjugate_columns", "stream_key", "noise_plan",
           "fill_slab", "hermitian_gain", "leading_ifft"]

AMPLITUDE_MODES = {"uniform": 0, "rayleigh": 1, "fixed": 2}  # amplitude law -> kernel mode
CHUNK = 1 << 14  # coefficients drawn per chunk of rows (their float32 scratch stays in cache; 2**14 measured best)
# below this peak the free-memory check is skipped: it reads /proc and the cgroup files (0.2 ms, 3 % of a 1024^2
# inverse FFT, benchmarks/bench_spectral.md 2026-11-25), and numpy's own MemoryError is as clear for so small a need
CHECK_FROM = 64 << 20


def complex_dtype(dtype):
    """complex64 for float32, complex128 for float64: the dtype of a real field's half spectrum.

    Examples
    --------
    >>> complex_dtype(np.float32)
    dtype('complex64')
    """
    return np.dtype(np.complex64) if np.dtype(dtype) == np.float32 else np.dtype(np.complex128)


def self_conjugate_columns(last_n):
    """kx indices of the self-conjugate planes: 0, and W/2 for an even width W > 1.

    Examples
    --------
    >>> self_conjugate_columns(8), self_conjugate_columns(7)
    ([0, 4], [0])
    """
    return [0] + ([last_n // 2] if last_n % 2 == 0 and last_n > 1 else [])


def stream_key(rng):
    """The 64-bit key of a field's coefficient stream: one word of the caller's generator."""
    return np.uint64(rng.integers(0, 2 ** 64, dtype=np.uint64))


def noise_plan(shape, exponent, band, rng, amplitude, dtype, *, normalize="expected", dc=False, check=True):
    """Everything the fill of :func:`spectral_noise`'s spectrum block decides before it allocates the block.

    Validates the band (cycles/frame, ``0 <= lo < hi <= shape[-1]/2``),
    keeps the rows and kx columns the band can reach, each row's kx interval
    ``kbeg:kend``, the power law's reference and the stream key drawn from
    ``seed``. With ``check`` the in-memory path's peak is checked against the
    free memory (the chunked path holds one slab at a time). Returns the plan
    (a namespace; see the module notes). All but the key depends on the
    arguments alone and is kept for the last few argument sets (the same
    arrays for repeated calls: callers read them and never write).

    Examples
    --------
    >>> p = noise_plan((64, 64), 1.0, (2, 16), 0, "rayleigh", np.float32)
    >>> p.bshape, p.K            # the block the band (2..16 cycles/frame) can reach: 33 rows, kx 0..16
    ((33, 17), 17)
    """
    dt = float_dtype(dtype)
    shape = tuple(int(m) for m in shape)
    n = shape[-1]
    if all(m == 1 for m in shape):
        raise ValueError(f"shape {shape} holds no nonzero frequency (a single sample); spectral noise needs "
                         f"an axis of at least 2 samples")
    if band is not None:
        lo, hi = check_band("band", band, n / 2, width=n)
        if dc and lo > 0:
            raise ValueError(f"dc=True keeps the DC term, which a band must then start at: got band[0] = {lo:g} "
                             f"cycles/frame; pass band=(0, hi)")
        band_key = (lo, hi)
    else:
        band_key = None
    geo = _geometry(shape, float(exponent), band_key, dt.str, normalize == "sample", bool(dc))
    if check and geo["peak"] >= CHECK_FROM:  # the in-memory path (the chunked one holds a chunk at a time)
        check_memory(geo["peak"], f"spectral_noise{shape}")
    rng = as_generator(rng)
    return SimpleNamespace(**geo, band=band, key=stream_key(rng), mode=AMPLITUDE_MODES[amplitude])


@functools.lru_cache(maxsize=8)
def _geometry(shape, exponent, band, dtype, sample, dc):
    """:func:`noise_plan`'s fields that do not depend on the random state (``band``: the checked pair or None)."""
    dt = np.dtype(dtype)
    cdt = complex_dtype(dt)
    d = len(shape)
    n = shape[-1]
    if band is None:
        lo, hi = 0.0, 0.5 * np.sqrt(d) + 1.0  # everything, corners included
    else:
        lo, hi = band[0] / n, band[1] / n
    eps = 1e-12  # the tolerance of envelopes.annulus
    lo_e, hi_e = lo * (1 - eps), hi * (1 + eps)
    w = frequency_vectors(shape)
    wsq = [wi.reshape(-1) * wi.reshape(-1) for wi in w]
    # a cell can be in the band only if each of its own axis frequencies is (with a margin for rounding)
    reach = hi_e * (1 + 1e-9)
    index = [np.flatnonzero(np.abs(wi.reshape(-1)) / (2 * np.pi) <= reach) for wi in w[:-1]]
    K = int(np.count_nonzero(np.abs(w[-1].reshape(-1)) / (2 * np.pi) <= reach))
    lead = [wsq[i][index[i]] for i in range(d - 1)]
    lead = [np.zeros(1)] * (2 - len(lead)) + lead
    q0, q1 = lead
    bshape = tuple(ix.size for ix in index) + (K,)
    # the in-memory path: the field's storage (its rows hold the half spectrum first), the last pass's scratch
    # (1 MiB at most) and the fill's per-row scratch
    peak = int(np.prod(shape[:-1])) * 2 * (n // 2 + 1) * dt.itemsize + (1 << 20) + 20 * CHUNK
    wxsq = np.ascontiguousarray(wsq[-1][:K])
    # weight of a half-spectrum cell in the full spectrum's power, halved: 1 where it stands for two cells, 1/2
    # on the self-conjugate planes (sample power: 0 there, their power is added once they are Hermitian)
    weight = np.ones(K, dtype=dt)
    for j in self_conjugate_columns(n):
        if j < K:
            weight[j] = 0 if sample else 0.5
    # the power law relative to its value at the band's loudest end (|e| <= 1, whatever the exponent), and flat
    # below the lowest nonzero frequency of the grid (2*pi / the longest axis): only DC can be there
    wmin2 = (2 * np.pi / max(m for m in shape if m > 1)) ** 2
    qfloor = wmin2 if exponent > 0 else 0.0
    q_lo = max(wmin2, (2 * np.pi * lo_e) ** 2)
    q_hi = min(float(sum(np.max(x) for x in wsq)), (2 * np.pi * hi_e) ** 2)
    inv_qref = 1.0 / (q_lo if exponent >= 0 else q_hi)
    if band is None and d == 3:
        # every cell but DC: fill whole (ky, kx) planes as single rows (|w|**2 = wt**2 + (wy**2 + wx**2)),
        # long loops instead of many short ones (measured 2x faster at 128**3); the first row starts after DC
        wxsq = np.ascontiguousarray((q1[:, None] + wxsq[None, :]).reshape(-1))
        weight = np.tile(weight, q1.size)
        q1 = np.zeros(1)
        R, Kr = q0.size, wxsq.size
        kbeg = np.zeros(R, dtype=np.int64)
        kend = np.full(R, Kr, dtype=np.int64)
        kbeg[0] = 0 if dc else 1
    else:
        R, Kr = q0.size * q1.size, K
        kbeg = np.empty(R, dtype=np.int64)
        kend = np.empty(R, dtype=np.int64)
        if band is None:  # every cell but DC (the first row holds DC: index[i][0] == 0)
            kbeg[:] = 0
            kend[:] = K
            kbeg[0] = 0 if dc else 1
        else:
            _kernels.band_rows(q0, q1, wxsq, lo_e, hi_e, bool(dc), kbeg, kend)
    counts = kend - kbeg
    if not counts.any():
        raise ValueError(f"band ({lo * n:g}, {hi * n:g}) cycles/frame holds no frequency of a "
                         f"{' x '.join(map(str, shape))} grid (frequency steps are 1 cycle/frame along the last "
                         f"axis, {n}/length along the others); widen the band")
    # each self-conjugate plane's mirror rows: -k along the kept indices of each leading axis
    maps = [np.searchsorted(ix, (-ix) % m) for ix, m in zip(index, shape[:-1])]
    maps = [np.zeros(1, dtype=np.int64)] * (2 - len(maps)) + maps
    return dict(shape=shape, dt=dt, cdt=cdt, n=n, index=index, K=K, bshape=bshape, q0=q0, q1=q1, wxsq=wxsq,
                kbeg=kbeg, kend=kend, counts=counts, R=R, Kr=Kr, weight=weight, sample=sample,
                exponent=float(exponent), qfloor=float(qfloor), inv_qref=float(inv_qref), dc=bool(dc), lo=lo,
                maps=maps, peak=peak, memo={})


def fill_slab(p, i0, i1):
    """The block's slab ``i0:i1`` along its first axis, unscaled, and its rows' power (see :func:`hermitian_gain`).

    Every row takes its words of the plan's stream at its own offset, so a
    slab holds the same values as the same rows of the in-memory block.
    2-D and 3-D plans (a 1-D block is one row).

    Examples
    --------
    >>> p = noise_plan((64, 64), 1.0, (2, 16), 0, "rayleigh", np.float32, check=False)
    >>> slab, rowpow = fill_slab(p, 0, 4)
    >>> slab.shape, rowpow.shape
    ((4, 17), (4,))
    """
    rpi = p.R // p.bshape[0]   # fill rows per index of the block's first axis
    r0, r1 = i0 * rpi, i1 * rpi
    slab = np.empty((i1 - i0,) + tuple(p.bshape[1:]), dtype=p.cdt)
    bf = slab.reshape(-1).view(p.dt)
    start = int(p.counts[:r0].sum())
    q0, q1 = p.q0, p.q1
    if len(p.shape) == 2:
        q1 = q1[i0:i1]   # 2-D: q0 is one zero, rows are the first axis itself
    else:
        q0 = q0[i0:i1]   # 3-D: rpi rows per index of the first axis
    rowpow = np.zeros(r1 - r0)
    scratch = np.empty(p.Kr, dtype=p.dt)
    _kernels.fill_power_law(bf, p.Kr, q0, q1, p.wxsq, p.kbeg[r0:r1], p.kend[r0:r1], 0, r1 - r0, p.key, start,
                            p.mode, p.exponent, p.qfloor, p.inv_qref, p.weight, p.sample, rowpow, scratch)
    return slab, rowpow


def hermitian_gain(p, rowpow, planes):
    """Make the self-conjugate ``planes`` (views, in place) Hermitian and return the gain ``g`` of the plan ``p``.

    ``g`` scales the block so that the field has unit variance (expected or
    sample, as the plan says).

    ``rowpow`` holds every kept row's power outside those planes, in the row order of the kept block (the
    in-memory fill and the chunked one hand in the same array, so ``g`` is the same float). The annulus is
    symmetric under k -> -k, and so is the kept block.
    """
    power = 2.0 * float(np.sum(rowpow))  # the same float for any worker count or chunking: one fixed order
    maps = p.maps
    for plane in planes:
        pw = _kernels.hermitian_symmetric_plane(plane.reshape(maps[0].size, maps[1].size), maps[0], maps[1])
        if p.sample:
            power += pw
    if p.sample and p.dc:
        power -= float(np.abs(planes[0].reshape(-1)[0])) ** 2  # the sample variance is about the field's mean
    if not power > 0:
        raise ValueError(f"the band carries no energy to normalise (only DC, where the law is 0 for exponent < 0, "
                         f"or only DC with normalize='sample'; got band={p.band!r}, exponent={p.exponent:g}); "
                         "widen the band")
    # var(field) = sum over the full spectrum of |S|**2 / N**2 (Parseval), DC included in the expected case
    return p.dt.type(np.prod(p.shape, dtype=np.float64) / np.sqrt(power))


def leading_ifft(block, index, shape, *, workers=None, overwrite=True):
    """``ifft`` along every leading axis of a half spectrum ``block``, the kept rows put back at their indices first.

    ``index[ax]`` holds the rows of ``shape[ax]`` that ``block`` keeps; ``overwrite=False`` leaves ``block`` as it is.

    Examples
    --------
    >>> block = np.ones((2, 3), np.complex128)          # rows 0 and 7 of an 8-row half spectrum kept
    >>> leading_ifft(block, [np.array([0, 7])], (8, 4), overwrite=False).shape
    (8, 3)
    """
    B = block
    for ax in range(len(shape) - 1):
        n, ix = shape[ax], index[ax]
        if ix.size < n:
            full_shape = list(B.shape)
            full_shape[ax] = n
            F = np.zeros(full_shape, dtype=B.dtype)
            sl = [slice(None)] * B.ndim
            sl[ax] = ix
            F[tuple(sl)] = B
            B = F
        B = scipy.fft.ifft(B, axis=ax, overwrite_x=overwrite or B is not block, workers=workers)
    return B
