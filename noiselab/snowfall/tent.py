"""The tent spectrum, built sparsely, and the pruned inverse FFT that turns it into video.

What is exploited
-----------------
Only the cells on the (thickened, sheared) tent inside the annulus band carry
energy. For the default 64 x 512 x 512 scene that is the ~25 000 spatial
frequencies of the band in the half plane (19 % of the 512 x 257 spatial
cells), each with one to a few temporal bins: about 1 % of the 8.4 million
half-spectrum cells. So:

1. **Sparse build.** Loop (vectorised) over the band's spatial cells only; for
   each, compute the tent's temporal frequency and place energy in the few
   temporal bins that overlap the thickened surface. Random numbers are drawn
   for those cells only.
2. **Pruned inverse FFT.** The inverse 3-D FFT is three passes of 1-D
   transforms. Along t, each (ky, kx) column holds energy in a few temporal
   bins only (2.3 on average for the default scene), so the t-pass is a
   direct sum over those bins, evaluated frame by frame while the frame's
   y-pass input is scattered (:class:`ColumnSpectra`: no ``(T, columns)``
   array, which held 12 MiB beside a 64 MiB video); along y, only the kx
   columns inside the band (``kx <= hi``: about half); the last pass
   (``irfft`` along x, complex-to-real) is the full one, written straight
   into the output a few rows at a time. This beats a bare ``irfftn`` of the
   same output (figures in ``benchmarks/bench_snow.md``).

The tent itself is :func:`noiselab.spectral.envelopes.tent_surface` (its
unchecked form ``tent_surface_terms``), evaluated at the band's spatial
cells only, with the amplitude of
:func:`~noiselab.spectral.envelopes.power_law`: the cells that carry energy
are the cells of ``thickened_tent(..., tol=pi/T) * annulus(...)``
(tested). :func:`y_pass`, :func:`tent_columns`, :func:`tent_coefficients`,
:func:`self_conjugate_planes` and :func:`column_spectra` are the internal interface shared by the
in-memory and dask paths (:mod:`noiselab.scale.spectral`).

Units: spatial frequencies in cycles/pixel internally (band limits are given in
cycles/frame = cycles per frame width); angular frequencies ``w`` in rad/px
and ``wt`` in rad/frame; ``c`` in rad/frame; speeds in px/frame.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.fft

from .._core import check_int, check_real, resolve_workers, thread_pool
from .._core.validate import check_band
from ..spectral import draw_coefficients, hermitian_plane
from ..spectral.envelopes import tent_surface_terms, unit_direction
from ..spectral.plan import complex_dtype, self_conjugate_columns
from . import _kernels

try:  # scipy.fft's own pocketfft binding: its c2c and c2r write into a given array (scipy.fft's functions allocate)
    from scipy.fft._pocketfft import pypocketfft as _pocketfft
except ImportError:  # another scipy layout: the public functions and a copy, the same transforms and bits
    _pocketfft = None

__all__ = ["TentColumns", "ColumnSpectra", "tent_columns", "largest_c", "tent_coefficients", "self_conjugate_planes",
           "column_spectra", "assemble", "to_half_spectrum", "ifft_columns", "irfft_rows", "y_pass", "pruned_irfftn",
           "flake_speeds"]

@dataclass
class TentColumns:
    """The tent spectrum in sparse form: band cells (columns) and their temporal bins."""

    shape: tuple          # (T, H, W) of the video
    ky: np.ndarray        # row index 0..H-1 of each column
    kx: np.ndarray        # column index 0..W//2 of each column
    entry_col: np.ndarray  # column of each energy-carrying cell
    entry_bin: np.ndarray  # temporal bin index 0..T-1 of each cell
    weight: np.ndarray     # envelope amplitude of each cell (1/f, split over the column's bins)
    peak_wt: float         # largest |temporal frequency| (rad/frame) the thickened tent reaches
    dropped: int           # cells dropped for temporal aliasing (on_alias="drop")

    @property
    def n_cells(self) -> int:
        return int(self.entry_col.size)


def _band_columns(H, W, lo_cpp, hi_cpp):
    """(ky index, kx index, fy, fx) of the half-plane spatial cells with lo <= |f| <= hi cycles/px, DC excluded."""
    fy_all = scipy.fft.fftfreq(H)
    fx_all = scipy.fft.rfftfreq(W)
    eps = 1e-12
    rows = np.flatnonzero(np.abs(fy_all) <= hi_cpp * (1 + eps))
    cols = np.flatnonzero(fx_all <= hi_cpp * (1 + eps))
    fy = fy_all[rows][:, None]
    fx = fx_all[cols][None, :]
    r = np.hypot(fy, fx)
    mask = (r >= lo_cpp * (1 - eps)) & (r <= hi_cpp * (1 + eps)) & (r > 0)
    ri, ci = np.nonzero(mask)
    return rows[ri], cols[ci], fy_all[rows[ri]], fx_all[cols[ci]]


def largest_c(a, b, thickness):
    """Largest tent constant c keeping ``|c*a + b| + thickness*c*|a| <= pi`` on every column (None if no c >= 0 works)."""
    sgn = np.where(a < 0, -1.0, 1.0)
    a = a * sgn
    b = b * sgn
    if np.any(np.abs(b[a == 0]) > np.pi):
        return None
    pos = a > 0
    if not pos.any():
        return np.pi
    cmax = float(np.min((np.pi - b[pos]) / (a[pos] * (1 + thickness))))
    # lower bounds (pan pushing the other way faster than the tent can compensate)
    if thickness < 1:
        need = -(np.pi + b[pos]) / ((1 - thickness) * a[pos])
        cmin = float(np.max(need, initial=0.0))
    else:
        cmin = 0.0 if np.all(np.pi + b[pos] >= 0) else np.inf
    if cmax < max(cmin, 0.0):
        return None
    return min(cmax, np.pi)


def _peak(c, a, b, thickness):
    return float(np.max(np.abs(c * a + b) + thickness * c * np.abs(a), initial=0.0))


def tent_columns(shape, *, c, band, thickness, direction, pan, exponent, on_alias="raise") -> TentColumns:
    """Build the sparse tent spectrum's geometry (no random numbers yet); see the module notes.

    A cell ``(kt, ky, kx)`` carries energy when its temporal bin overlaps the
    thickened tent: ``|kt - x| <= 1/2 + hw`` in bin units, with
    ``x = wt_tent * T / (2*pi)`` and ``hw`` the thickness half-width. The
    column's 1/f amplitude is split evenly over its bins so the spatial
    spectrum does not depend on the thickness.
    """
    T, H, W = shape
    lo, hi = check_band("band", band, W / 2, width=W)
    ky, kx, fy, fx = _band_columns(H, W, lo / W, hi / W)
    if ky.size == 0:
        raise ValueError(
            f"band ({lo:g}, {hi:g}) cycles/frame holds no spatial frequency of a {H} x {W} frame "
            f"(frequency steps are 1 cycle/frame across the width, W/H across the height); widen the band"
        )
    w = (2 * np.pi * fy, 2 * np.pi * fx)   # rad/px
    # the envelope's tent_surface at the band's cells: s (rad/frame), its slope a = (d . w)/|w| and b = pan . w
    s, a, b, r = tent_surface_terms(*w, c, unit_direction(direction), (float(pan[0]), float(pan[1])))
    half = thickness * c * np.abs(a)    # thickened half-width, rad/frame
    peak = float(np.max(np.abs(s) + half))
    dropped = 0
    if T > 1 and peak > np.pi * (1 + 1e-9) and on_alias == "raise":
        cmax = largest_c(a, b, thickness)
        msg = (
            f"temporal aliasing: c={c:g} rad/frame with thickness={thickness:g} and pan_yx={(pan[1], pan[0])} puts energy at "
            f"{peak:.4g} rad/frame, past the temporal Nyquist frequency pi={np.pi:.4f} rad/frame; that motion would "
            f"wrap around and reverse. "
        )
        if cmax is not None:
            msg += f"Largest allowed c for this band, thickness and pan is {cmax:.6g} rad/frame"
        else:
            msg += "No c works with this pan"
        if any(pan):
            lam_lo, lam_hi = 0.0, 1.0
            if _peak(c, a, b * 0, thickness) <= np.pi:
                for _ in range(60):
                    mid = 0.5 * (lam_lo + lam_hi)
                    if _peak(c, a, b * mid, thickness) <= np.pi:
                        lam_lo = mid
                    else:
                        lam_hi = mid
                msg += f"; largest pan speed along this pan direction for c={c:g} is {lam_lo * float(np.hypot(*pan)):.6g} px/frame"
        msg += "; or pass on_alias='drop' to drop the wrapped cells."
        raise ValueError(msg)

    if T == 1:
        # a still: the single temporal bin (DC) overlaps every surface
        entry_col = np.arange(ky.size)
        entry_n = np.zeros(ky.size, dtype=np.int64)
    else:
        x = s * (T / (2 * np.pi))
        hw = half * (T / (2 * np.pi))
        n_lo = np.ceil(x - 0.5 - hw).astype(np.int64)
        n_hi = np.floor(x + 0.5 + hw).astype(np.int64)
        total = int((n_hi - n_lo + 1).sum())
        # bins beyond Nyquist (|n| > T/2): with the surface inside Nyquist these
        # are only the half-bin overlap at |wt| = pi for odd T; otherwise
        # (on_alias="drop") they are the cells that would wrap around
        n_lo = np.maximum(n_lo, -(T // 2))
        n_hi = np.minimum(n_hi, T // 2)
        if on_alias == "drop":
            dropped = total - int(np.maximum(n_hi - n_lo + 1, 0).sum())
        if T % 2 == 0:
            # +T/2 and -T/2 are one bin: keep it once
            n_hi = np.where((n_lo == -(T // 2)) & (n_hi == T // 2), n_hi - 1, n_hi)
        counts = np.maximum(n_hi - n_lo + 1, 0)
        entry_col = np.repeat(np.arange(ky.size), counts)
        starts = np.cumsum(counts) - counts
        entry_n = n_lo[entry_col] + (np.arange(entry_col.size) - starts[entry_col])
    entry_bin = np.mod(entry_n, T)
    count = np.bincount(entry_col, minlength=ky.size)
    amp = r ** (-float(exponent))  # envelopes.power_law at the columns (tested equal; DC is not a column)
    weight = amp[entry_col] / np.sqrt(count[entry_col])
    return TentColumns((T, H, W), ky, kx, entry_col, entry_bin, weight, peak, dropped)


def tent_coefficients(cols: TentColumns, rng, amplitude, dtype):
    """The random coefficients of the tent's cells, weighted (one per cell, in ``cols``' entry order)."""
    coef = draw_coefficients(cols.n_cells, rng, amplitude, dtype)
    coef *= cols.weight.astype(coef.real.dtype)
    return coef


def self_conjugate_planes(cols: TentColumns, coef, cdt):
    """The tent's columns on the self-conjugate planes (kx = 0 and W/2), made Hermitian: ``(columns, (T, m) values)``.

    Within one such plane every column has its own ky, so each plane is filled from ``coef`` alone.
    """
    T, H, W = cols.shape
    out_cols, out_vals = [], []
    for j in self_conjugate_columns(W):
        pc = np.flatnonzero(cols.kx == j)
        if pc.size == 0:
            continue
        inp = np.isin(cols.entry_col, pc)
        P = np.zeros((T, H), dtype=cdt)
        sup = np.zeros((T, H), dtype=bool)
        P[cols.entry_bin[inp], cols.ky[cols.entry_col[inp]]] = coef[inp]
        sup[cols.entry_bin[inp], cols.ky[cols.entry_col[inp]]] = True
        P = hermitian_plane(P, sup)
        out_cols.append(pc)
        out_vals.append(P[:, cols.ky[pc]])
    if not out_cols:
        return np.zeros(0, dtype=np.int64), np.zeros((T, 0), dtype=cdt)
    return np.concatenate(out_cols), np.concatenate(out_vals, axis=1)


@dataclass
class ColumnSpectra:
    """The temporal spectrum of every tent column, sparse (compressed by column).

    Column ``j`` holds ``vals[ptr[j]:ptr[j+1]]`` at the temporal bins
    ``bins[ptr[j]:ptr[j+1]]`` (increasing, ``0 .. T-1``); every other bin is
    0. :func:`y_pass` evaluates its inverse DFT along t frame by frame.
    """

    T: int
    ptr: np.ndarray   # (columns + 1,) int64
    bins: np.ndarray  # (entries,) int64
    vals: np.ndarray  # (entries,) complex64 or complex128

    @property
    def n_columns(self) -> int:
        return int(self.ptr.size - 1)

    def prepare(self, ky, kx, K):
        """``(dest, tw)`` for :func:`y_pass`: each entry's cell ``ky * K + kx`` of a frame of width ``K``, and
        ``exp(2j*pi*m/T) / T`` (``ifft``'s kernel and normalisation, ``m = 0 .. T-1``) in the values' precision."""
        col = np.repeat(np.arange(self.n_columns), np.diff(self.ptr))
        dest = (np.asarray(ky, dtype=np.int64)[col] * int(K) + np.asarray(kx, dtype=np.int64)[col])
        tw = (np.exp(2j * np.pi * np.arange(self.T) / self.T) / self.T).astype(self.vals.dtype)
        return dest, tw

    def take(self, sel):
        """The columns ``sel`` (an index array), in that order, as a new :class:`ColumnSpectra`."""
        sel = np.asarray(sel, dtype=np.int64)
        lens = self.ptr[sel + 1] - self.ptr[sel]
        ptr = np.zeros(sel.size + 1, dtype=np.int64)
        np.cumsum(lens, out=ptr[1:])
        idx = np.repeat(self.ptr[sel] - ptr[:-1], lens) + np.arange(int(ptr[-1]), dtype=np.int64)
        return ColumnSpectra(self.T, ptr, self.bins[idx], self.vals[idx])

    def dense(self):
        """The ``(T, columns)`` array (for tests and small cases)."""
        C = np.zeros((self.T, self.n_columns), dtype=self.vals.dtype)
        C[self.bins, np.repeat(np.arange(self.n_columns), np.diff(self.ptr))] = self.vals
        return C


def column_spectra(cols: TentColumns, coef, plane_cols, plane_vals):
    """The :class:`ColumnSpectra` of the tent: ``coef`` on its cells, the self-conjugate planes' columns replaced.

    ``plane_cols``/``plane_vals`` come from :func:`self_conjugate_planes`
    (whole columns, Hermitian; their nonzero bins are kept).
    """
    T = cols.shape[0]
    n = cols.ky.size
    keep = ~np.isin(cols.entry_col, plane_cols)
    pb, pc = np.nonzero(plane_vals)
    col = np.concatenate([cols.entry_col[keep], np.asarray(plane_cols, dtype=np.int64)[pc]]).astype(np.int64)
    bins = np.concatenate([cols.entry_bin[keep], pb]).astype(np.int64)
    vals = np.concatenate([coef[keep], plane_vals[pb, pc]])
    # by column, then bin (distinct keys: one sort of one int64 array; the stable sort, a radix sort for
    # integers, takes a twentieth of the default one's time on these nearly sorted keys)
    order = np.argsort(col * T + bins, kind="stable")
    ptr = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(np.bincount(col, minlength=n), out=ptr[1:])
    return ColumnSpectra(T, ptr, bins[order], np.ascontiguousarray(vals[order]))


def assemble(cols: TentColumns, rng, amplitude, dtype):
    """Random coefficients on the tent cells, Hermitian on the self-conjugate planes: the :class:`ColumnSpectra`."""
    cdt = complex_dtype(dtype)
    coef = tent_coefficients(cols, rng, amplitude, dtype)
    plane_cols, plane_vals = self_conjugate_planes(cols, coef, cdt)
    return column_spectra(cols, coef, plane_cols, plane_vals)


def to_half_spectrum(spec: ColumnSpectra, cols: TentColumns):
    """Scatter the columns' spectra into the dense ``rfftn`` half spectrum ``(T, H, W//2 + 1)``."""
    T, H, W = cols.shape
    S = np.zeros((T, H, W // 2 + 1), dtype=spec.vals.dtype)
    col = np.repeat(np.arange(spec.n_columns), np.diff(spec.ptr))
    S[spec.bins, cols.ky[col], cols.kx[col]] = spec.vals
    return S


def ifft_columns(B, k):
    """``B[:, :, :k] = ifft(B[:, :, :k], axis=1)`` in place (one thread): the y-pass on the first ``k`` columns.

    ``B``: a C-contiguous complex ``(frames, H, width)`` block. Through
    pocketfft's own binding (the transform that ``scipy.fft.ifft`` runs)
    straight on the strided columns, so a padded block needs no copy.
    """
    view = B[:, :, :k]
    if _pocketfft is not None:
        _pocketfft.c2c(view, (1,), False, 2, view, 1)
    else:
        view[...] = scipy.fft.ifft(view, axis=1, workers=1)
    return B


def irfft_rows(P, n, out):
    """``out[...] = irfft(P, n, axis=-1)`` (one thread): ``P`` complex ``(rows, n//2 + 1)``, ``out`` real ``(rows, n)``.

    pocketfft's complex-to-real transform (what ``scipy.fft.irfft`` runs,
    the same bits) written straight into ``out``: no zero-padded copy of the
    input and no output array to copy from.
    """
    if _pocketfft is not None:
        _pocketfft.c2r(P, (P.ndim - 1,), n, False, 2, out, 1)
    else:
        out[...] = scipy.fft.irfft(P, n=n, axis=-1, workers=1)
    return out


def y_pass(spec: ColumnSpectra, t0, ky, kx, B, prep=None, k=None):
    """The t- and y-passes of a block of frames: ``B`` (``(frames, H, width)``) for frames ``t0 ..`` of ``spec``.

    Evaluates every column's inverse DFT along t at the block's frames (a
    sum over its few bins, in ``B``'s precision), scatters the values to
    their ``(ky[j], kx[j])`` cells of ``B``, zeros elsewhere in the first
    ``k`` columns (default: all of them), then inverse-transforms those ``k``
    columns along y, in place (one thread); returns ``B``. Columns past ``k``
    (no tent column there) are left as they are: a block of width
    ``W//2 + 1`` zeroed once is the x-pass's input as it stands.
    ``prep``: ``spec.prepare(ky, kx, B.shape[2])``, computed if not given
    (pass it when calling block after block). The in-memory renderer (:func:`pruned_irfftn`) and the chunked one
    (:mod:`noiselab.scale.spectral`) compute every block with it, so their
    bits agree.

    Examples
    --------
    >>> import numpy as np
    >>> spec = ColumnSpectra(2, np.array([0, 1]), np.array([0]), np.array([2.0 + 0j]))  # one column, DC only
    >>> B = y_pass(spec, 0, np.array([0]), np.array([1]), np.empty((2, 4, 2), np.complex128))
    >>> B[0, :, 1].real                                      # 2 / T along t, then ky = 0 along y: 1/H
    array([0.25, 0.25, 0.25, 0.25])
    """
    k = B.shape[2] if k is None else int(k)
    dest, tw = spec.prepare(ky, kx, B.shape[2]) if prep is None else prep
    _kernels.t_pass_scatter(dest, spec.bins, spec.vals, tw, t0, B, k)
    return ifft_columns(B, k)


def pruned_irfftn(spec: ColumnSpectra, cols: TentColumns, out, *, chunk_bytes=1 << 18, bar=None, workers=None):
    """``irfftn`` of the sparse columns into ``out`` (T, H, W), transforming only what carries energy.

    Equal to ``scipy.fft.irfftn(to_half_spectrum(spec, cols), s=(T, H, W))``
    to float precision (tested). Returns the output's minimum and maximum,
    taken block by block while the block is in cache.

    Each block of frames (about ``chunk_bytes``, one frame at the least) gets its
    t-pass (a direct sum over each column's few bins) and is scattered to its
    ``(ky, kx)`` cells, transformed along y on the band's kx columns and
    along x (complex-to-real) straight into ``out``, the blocks shared among
    ``workers`` threads. Each thread keeps one block of width ``W//2 + 1``,
    zeroed once: the t- and y-passes fill its first ``K`` columns, the rest
    stays zero, so the x-pass reads it as it is. A block is computed the same
    way whichever thread takes it, so the bits do not depend on ``workers``;
    the only full-size array is ``out`` (plus one block per thread).
    """
    import queue

    nw = resolve_workers(workers)
    T, H, W = cols.shape
    K = int(cols.kx.max()) + 1
    Wh = W // 2 + 1
    ky = cols.ky.astype(np.int64)
    kx = cols.kx.astype(np.int64)
    prep = spec.prepare(ky, kx, Wh)
    item = spec.vals.itemsize
    tc = int(max(1, min(T, chunk_bytes // max(1, H * Wh * item))))
    blocks = [(t0, min(T, t0 + tc)) for t0 in range(0, T, tc)]
    rows = int(max(1, min(H, chunk_bytes // max(1, W * out.itemsize))))
    threaded = not (nw <= 1 or len(blocks) <= 1 or T * H * W < (1 << 16))
    n_buf = min(nw, len(blocks)) if threaded else 1
    scratch = queue.SimpleQueue()
    for _ in range(n_buf):  # one padded block per thread, zeroed once (columns K.. stay zero)
        scratch.put(np.zeros((tc, H, Wh), dtype=spec.vals.dtype))

    def render(blk):
        t0, t1 = blk
        P = scratch.get()
        try:
            B = y_pass(spec, t0, ky, kx, P[:t1 - t0], prep, K)
            # x-pass a slab of rows at a time, straight into out; min and max while the slab is in cache
            blo, bhi = np.inf, -np.inf
            for t in range(t1 - t0):
                for y0 in range(0, H, rows):
                    slab = irfft_rows(B[t, y0:y0 + rows], W, out[t0 + t, y0:y0 + rows])
                    blo, bhi = min(blo, float(slab.min())), max(bhi, float(slab.max()))
        finally:
            scratch.put(P)
        return blo, bhi, t1 - t0

    lo, hi = np.inf, -np.inf
    results = thread_pool(n_buf).map(render, blocks) if threaded else map(render, blocks)
    for blo, bhi, n in results:  # in block order, whichever thread finished first
        lo, hi = min(lo, blo), max(hi, bhi)
        if bar is not None:
            bar.update(n)
    return lo, hi


def flake_speeds(c=1.0, band=None, width=512, height=None):
    """Image speeds (px/frame) of the nearest and the farthest flakes: ``c / |w|`` at the band's ends.

    A flake at spatial frequency ``f`` cycles/frame (``|w| = 2*pi*f/width``
    rad/px) moves at ``c/|w| = c*width/(2*pi*f)`` px/frame. The nearest
    (largest, lowest-frequency) flakes are at ``band[0]``, the farthest at
    ``band[1]``. ``c`` is in ``[0, pi]`` rad/frame as for
    :func:`noiselab.snow.snow`, ``width`` (px) an int >= 1; ``height`` (an int
    >= 1 or None) is accepted for symmetry with ``snow``'s shape and does not
    change the speeds.

    Parameters
    ----------
    c : float, default 1
        Tent constant in rad/frame, ``0 <= c <= pi``.
    band : (lo, hi), optional
        Band in cycles/frame, ``0 < lo < hi <= width / 2``; default
        ``(width / 32, width / 4)``, as :func:`noiselab.snow.snow`.
    width : int, default 512
        Frame width in pixels (>= 1).
    height : int, optional
        Accepted for symmetry with ``snow``'s shape (>= 1); no effect.

    Returns
    -------
    near, far : float
        Speeds in px/frame of the flakes at ``band[0]`` and at ``band[1]``.

    Raises
    ------
    ValueError
        For ``c`` outside ``[0, pi]``, a width or height below 1, or a band
        outside ``(0, width / 2]`` (or so low that the speed overflows).

    Examples
    --------
    >>> near, far = flake_speeds(1.0, (16, 128), 512)
    >>> round(near, 3), round(far, 3)
    (5.093, 0.637)
    """
    c = check_real("c (rad/frame)", c, lo=0, hi=np.pi)
    width = check_int("width", width, lo=1)
    if height is not None:
        check_int("height", height, lo=1)
    if band is None:
        band = (width / 32, width / 4)
    lo, hi = check_band("band", band, width / 2, width=width)
    near = np.inf if lo == 0 else c * width / (2 * np.pi * lo)
    far = c * width / (2 * np.pi * hi)
    if lo > 0 and not math.isfinite(near) or not math.isfinite(far):
        raise ValueError(f"band ({lo:g}, {hi:g}) cycles/frame is so low that the speed c * width / (2 pi f) "
                         "overflows float64")
    return float(near), float(far)
