"""Power spectra: the half-spectrum container, radial averages and the video's (radial, temporal) spectrum.

Normalisation (stated once, used everywhere): for a field ``f`` of ``n``
samples over the transformed axes, the power of frequency cell ``k`` is

    P[k] = |FFT(f - mean(f))[k]|**2 / n**2,

so that the sum of ``P`` over the *full* spectrum equals the mean square of
the mean-removed field, i.e. its variance (Parseval). The DC cell is therefore
zero: analysers measure structure, not the mean level (they report it apart).
With ``window="hann"`` the field is multiplied by a periodic Hann window along
the windowed axes and ``P`` is divided by the window's mean square, so a
stationary field keeps its variance. The spectrum is stored as a real-FFT
*half* spectrum (``scipy.fft.rfftn`` layout: the last transformed axis keeps
``n // 2 + 1`` columns); :attr:`PowerSpectrum.weight` gives each column's
multiplicity (2 for the columns whose conjugate mirror is not stored), so sums
over the half spectrum weighted by it are sums over the full spectrum.
Float32 input is transformed in float32 (half the memory and time of
float64); sums are accumulated in float64.
"""
from __future__ import annotations

from dataclasses import dataclass, field as dc_field
from typing import NamedTuple

import numpy as np
import scipy.fft

from .._core import check_axes, check_int, check_memory, check_real
from ._common import check_band, check_field, frequency_index, half_weight, noise_floor, ref_size

__all__ = [
    "PowerBand",
    "power_band",
    "PowerSpectrum",
    "RadialSpectrum",
    "SpatiotemporalSpectrum",
    "power_spectrum",
    "radial_spectrum",
    "spatiotemporal_spectrum",
    "band_energy",
    "as_spectrum",
]

_WINDOWS = (None, "hann")


@dataclass(frozen=True, eq=False)
class PowerSpectrum:
    """Half power spectrum of a real field (see the module docstring for the normalisation).

    Attributes
    ----------
    power : ndarray
        ``P`` in ``rfftn`` layout over :attr:`axes` (float32 for float32 input).
        Axes of the field that were not transformed come first, unchanged.
    shape : tuple of int
        Shape of the field.
    axes : tuple of int
        The transformed axes (non-negative), the last one halved.
    window : str or None
        ``"hann"`` or None.
    window_axes : tuple of int
        Axes the window was applied along.
    mean : float
        Mean of the field (removed before the transform).
    """

    power: np.ndarray
    shape: tuple
    axes: tuple
    window: str | None = None
    window_axes: tuple = ()
    mean: float = 0.0
    _cache: dict = dc_field(default_factory=dict, repr=False, compare=False)

    @property
    def weight(self) -> np.ndarray:
        """Multiplicity of each column of the halved axis (broadcastable against :attr:`power`)."""
        w = half_weight(self.shape[self.axes[-1]]).astype(self.power.dtype)
        return w.reshape((-1,) + (1,) * (self.power.ndim - 1 - self.axes[-1]))

    def frequency(self, axis: int) -> np.ndarray:
        """Integer frequency index (cycles per axis length) of a transformed ``axis``, broadcastable against :attr:`power`."""
        axis = axis % len(self.shape)
        if axis not in self.axes:
            raise ValueError(f"axis {axis} was not transformed (transformed axes: {self.axes})")
        k = frequency_index(self.shape[axis], half=axis == self.axes[-1])
        shape = [1] * self.power.ndim
        shape[axis] = k.size
        return k.reshape(shape)

    @property
    def total(self) -> float:
        """Sum of the power over the full spectrum: the variance of the (windowed) field."""
        half = self.axes[-1]
        others = tuple(a for a in range(self.power.ndim) if a != half)
        per_column = np.sum(self.power, axis=others, dtype=np.float64)  # no full-size temporary
        return float(per_column @ half_weight(self.shape[half]))

    def full(self) -> np.ndarray:
        """The full power spectrum in ``fftn`` layout (a new array; for small fields and tests)."""
        if len(self.axes) != len(self.shape):
            raise ValueError("full() needs a spectrum over every axis")
        n = self.shape[-1]
        half = self.power
        mirror_cols = np.arange(n // 2 + 1, n)  # columns not stored: conj of (-k)
        out = np.empty(self.shape, dtype=half.dtype)
        out[..., : n // 2 + 1] = half
        src = n - mirror_cols
        mirrored = half[..., src]
        # negate every other index: k -> (-k) mod n along the leading axes
        for ax in range(half.ndim - 1):
            mirrored = np.roll(np.flip(mirrored, axis=ax), 1, axis=ax)
        out[..., mirror_cols] = mirrored
        return out


def _hann(n: int, dtype) -> np.ndarray:
    # periodic Hann: the window itself tiles without a seam
    return (0.5 - 0.5 * np.cos(2.0 * np.pi * np.arange(n) / n)).astype(dtype)


def check_power_range(name, arr) -> tuple[float, float]:
    """``(min, max)`` of ``arr``; a ValueError naming ``name`` when a value's square would leave float64's range."""
    lo, hi = float(arr.min()), float(arr.max())
    biggest = max(abs(lo), abs(hi))
    if biggest > 1e150:
        raise ValueError(f"{name} values reach {biggest:.3g}: their power (value squared) would overflow float64; "
                         f"|{name}| must stay below 1e150 (rescale it)")
    if biggest < 1e-150:
        raise ValueError(f"{name} values are at most {biggest:.3g} in magnitude: their power (value squared) would "
                         f"underflow float64; |{name}| must reach 1e-150 (rescale it)")
    return lo, hi


def power_spectrum(field, *, window=None, axes=None, window_axes=None, min_size=4, workers=None) -> PowerSpectrum:
    """Power spectrum of a 1-, 2- or 3-D real field, normalised so that Parseval holds.

    Parameters
    ----------
    field : array_like
        Real, finite, non-constant; every axis at least 4 samples.
    window : {None, "hann"}
        Periodic Hann taper for fields that are not periodic (cuts the leakage
        of the edge discontinuity); the power is divided by the window's mean
        square so that a stationary field keeps its variance.
    axes : tuple of int, optional
        Axes to transform (default: all). The others are kept (e.g. ``(-2, -1)``
        for per-frame spectra of a video).
    window_axes : tuple of int, optional
        Axes the window is applied along (default: the transformed axes).
    min_size : int
        Fewest samples accepted along any axis (a video's time axis may
        have 2: :func:`noiselab.analysis.video_spectrum` checks it).
    workers : int, optional
        FFT threads, scipy.fft's meaning (-1: every core; None: scipy's
        default); the result is the same for any count.

    Returns
    -------
    PowerSpectrum
        ``sum(P * weight)`` over the full spectrum equals ``var(field)`` (per
        frame for untransformed axes: their values are summed).

    Examples
    --------
    >>> import numpy as np
    >>> x = np.random.default_rng(0).standard_normal((64, 64))
    >>> spec = power_spectrum(x)
    >>> bool(np.isclose(spec.total, x.var()))
    True
    """
    min_size = check_int("min_size", min_size, lo=1)
    arr = check_field("field", field, min_size=min_size)
    if not (window is None or (isinstance(window, str) and window in _WINDOWS)):
        raise ValueError(f"window must be None or 'hann', got {window!r}")
    nd = arr.ndim
    axes = tuple(range(nd)) if axes is None else check_axes("axes", axes, nd)
    window_axes = axes if window_axes is None else check_axes("window_axes", window_axes, nd)
    lo_val, hi_val = check_power_range("field", arr)
    biggest = max(abs(lo_val), abs(hi_val))
    if arr.dtype == np.float32 and (biggest * np.sqrt(arr.size) > 1e18 or biggest < 1e-15):
        arr = arr.astype(np.float64)  # |FFT|**2 would overflow float32: transform these values in float64
    cdt = np.complex64 if arr.dtype == np.float32 else np.complex128
    # peak: the working copy, the complex half spectrum and the power
    spec_cells = arr.size // arr.shape[axes[-1]] * (arr.shape[axes[-1]] // 2 + 1)
    check_memory(arr.nbytes * 2 + spec_cells * np.dtype(cdt).itemsize, "power_spectrum")
    mean = float(np.mean(arr, dtype=np.float64))
    scale = 1.0
    # Without a window, removing the mean only zeroes the DC cell, so the field is transformed as
    # is (no working copy) unless its mean dwarfs its range, where subtracting first keeps the
    # FFT's rounding (relative to the whole signal) off the fluctuations.
    span = hi_val - lo_val
    if window is None and abs(mean) <= 10 * span:
        work, zero_dc = arr, True
    else:
        work, zero_dc = arr - arr.dtype.type(mean), False
    if window == "hann":
        for ax in window_axes:
            w = _hann(arr.shape[ax], arr.dtype)
            shape = [1] * nd
            shape[ax] = w.size
            work *= w.reshape(shape)
            scale *= float(np.mean(w.astype(np.float64) ** 2))
    spec = scipy.fft.rfftn(work, axes=axes, overwrite_x=work is not arr, workers=workers)
    del work
    if zero_dc:
        spec[tuple(0 if a in axes else slice(None) for a in range(nd))] = 0
    n = int(np.prod([arr.shape[a] for a in axes]))
    norm = 1.0 / (float(n) ** 2 * scale)
    # |X| <= n * max|field|: square after scaling by 1/n when n * max|field| could overflow the square
    prescale = biggest * n > 1e150 if arr.dtype == np.float64 else False
    root = spec.real.dtype.type(np.sqrt(norm))
    power = np.empty(spec.shape, dtype=arr.dtype)
    for i in range(spec.shape[0]) if spec.ndim > 1 else [slice(None)]:
        # |X|^2 one slab at a time: slab-sized temporaries only
        if prescale:
            spec[i] *= root
        power[i] = np.square(spec[i].real)
        power[i] += np.square(spec[i].imag)
        if not prescale:
            power[i] *= power.dtype.type(norm)
    del spec
    return PowerSpectrum(power=power, shape=arr.shape, axes=axes, window=window, window_axes=window_axes if window else (), mean=mean)


def as_spectrum(field, *, window=None, axes=None, window_axes=None, workers=None) -> PowerSpectrum:
    """Return ``field`` if it already is a :class:`PowerSpectrum` (over the same axes), else compute it."""
    if isinstance(field, PowerSpectrum):
        if axes is not None:
            nd = len(field.shape)
            want = tuple(sorted(int(a) % nd for a in axes))
            if want != field.axes:
                raise ValueError(f"the spectrum was computed over axes {field.axes}, this measurement needs {want}")
        return field
    return power_spectrum(field, window=window, axes=axes, window_axes=window_axes, workers=workers)


def _radial_frequency(spec: PowerSpectrum, radial_axes) -> tuple[list, int]:
    """Per-axis frequency components (cycles/frame, broadcastable against the power) and the frame size N."""
    n_ref = ref_size([spec.shape[a] for a in radial_axes])
    return [spec.frequency(a) * (n_ref / spec.shape[a]) for a in radial_axes], n_ref


def _slabs(shape):
    """Slices of the leading axis of a 3-D spectrum (one at a time bounds the temporaries), else everything."""
    return [(i,) for i in range(shape[0])] if len(shape) == 3 and shape[0] > 1 else [()]


def _slab_radius(comps, sl, shape):
    """Radial frequency of the slab ``sl`` (a tuple indexing the leading axis, or ``()``), broadcast to its shape."""
    r2 = 0.0
    for c in comps:
        part = c[sl] if not sl or c.shape[0] > 1 else c[0]
        r2 = r2 + part**2
    sub = shape[len(sl):]
    return np.broadcast_to(np.sqrt(r2), sub)


@dataclass(frozen=True)
class RadialSpectrum:
    """Radially averaged power spectrum.

    Attributes
    ----------
    centers : ndarray
        Bin centres in cycles/frame (arithmetic for linear bins, geometric for log bins).
    edges : ndarray
        Bin edges (cycles/frame), ``len(centers) + 1``.
    power : ndarray
        Mean power per full-spectrum cell in each bin (spectral density; a
        field whose amplitude falls as ``f**-a`` gives ``power ~ f**(-2a)``).
    counts : ndarray
        Number of full-spectrum cells in each bin.
    variance : ndarray
        Variance of the cell power within each bin.
    mean_frequency : ndarray
        Mean radial frequency of the cells in each bin (what a fit should use).
    frame_size : int
        ``N``: cycles/frame = cycles/pixel x N.
    total : float
        Power of the whole field (all cells, inside or outside the bins).

    Empty bins are dropped, so every entry is finite.
    """

    centers: np.ndarray
    edges: np.ndarray
    power: np.ndarray
    counts: np.ndarray
    variance: np.ndarray
    mean_frequency: np.ndarray
    frame_size: int
    total: float

    @property
    def amplitude(self) -> np.ndarray:
        """Radially averaged amplitude ``sqrt(power)``."""
        return np.sqrt(self.power)

    @property
    def energy(self) -> np.ndarray:
        """Power in each bin (``power * counts``); divide by :attr:`total` for fractions."""
        return self.power * self.counts

    @property
    def cycles_per_pixel(self) -> np.ndarray:
        return self.centers / self.frame_size


def _edges(bins, log, fmax, fmin=1.0):
    if bins is None:
        if log:
            octaves = np.log2(fmax / fmin)
            nb = max(int(np.ceil(octaves * 8)), 1)
            return np.geomspace(fmin * (1 - 1e-9), fmax * (1 + 1e-9), nb + 1)
        # one bin per integer frequency: k - 0.5 <= r < k + 0.5, k = 1 .. floor(fmax)
        return np.arange(0.5, np.floor(fmax) + 0.5 + 1e-9, 1.0)
    if np.ndim(bins) == 0:
        nb = check_int("bins", bins, lo=1)
        check_memory(nb * 8 * 8, f"radial_spectrum with bins={nb}")  # edges and the per-bin sums
        if log:
            return np.geomspace(fmin * (1 - 1e-9), fmax * (1 + 1e-9), nb + 1)
        return np.linspace(0.5, fmax, nb + 1)
    if isinstance(bins, (str, bytes, set, frozenset, dict)):
        raise TypeError(f"bins must be an int count or a 1-D array of edges, got {type(bins).__name__}")
    try:
        edges = np.asarray(bins, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError(f"bins must be an int count or a 1-D array of edges, got {bins!r}") from None
    if edges.ndim != 1 or edges.size < 2 or not np.all(np.isfinite(edges)) or np.any(np.diff(edges) <= 0):
        raise ValueError("bins must be an int count or an increasing 1-D array of at least 2 finite edges")
    if edges[0] < 0:
        raise ValueError(f"bins edges must be >= 0 cycles/frame, got {edges[0]:g}")
    return edges


def _bin_index(r, edges):
    """Bin number of each radius (-1 outside the edges)."""
    idx = np.searchsorted(edges, r, side="right") - 1
    idx[(r < edges[0]) | (r >= edges[-1])] = -1
    return idx


def radial_spectrum(field, *, bins=None, log=False, window=None, axes=None, fmax=None, workers=None) -> RadialSpectrum:
    """Radially averaged power spectrum of a 1-, 2- or 3-D field (or of a :class:`PowerSpectrum`).

    Parameters
    ----------
    field : array_like or PowerSpectrum
    bins : int or array_like, optional
        Number of bins, or their edges in cycles/frame. Default: linear bins
        one cycle/frame wide centred on the integers 1 .. fmax; with
        ``log=True``, 8 bins per octave from 1 cycle/frame to ``fmax``.
    log : bool
        Log-spaced bins (geometric centres).
    window : {None, "hann"}
        See :func:`power_spectrum`.
    axes : tuple of int, optional
        Radial axes (default all). Other axes are averaged over, e.g.
        ``axes=(-2, -1)`` gives a video's spatial spectrum averaged over frames.
    fmax : float, optional
        Upper limit in cycles/frame; default ``N / 2`` (the inscribed Nyquist
        circle; the corners beyond it hold an incomplete annulus). At most
        ``N / 2 * sqrt(d)``.
    workers : int, optional
        FFT threads, scipy.fft's meaning (-1: every core); same result for any count.

    Returns
    -------
    RadialSpectrum

    Examples
    --------
    >>> import numpy as np
    >>> y, x = np.mgrid[:64, :64]
    >>> rs = radial_spectrum(np.cos(2 * np.pi * 8 * x / 64))
    >>> float(rs.centers[np.argmax(rs.power)])
    8.0
    """
    spec = as_spectrum(field, window=window, axes=axes, workers=workers)
    radial_axes = spec.axes
    comps, n_ref = _radial_frequency(spec, radial_axes)
    nyq = n_ref / 2.0
    fmax = nyq if fmax is None else check_real("fmax", fmax, lo=1.0, hi=nyq * np.sqrt(len(radial_axes)) + 1e-9)
    edges = _edges(bins, log, fmax)
    nb = edges.size - 1
    # average over the untransformed axes (e.g. frames), keeping them as length-1 axes
    other = tuple(a for a in range(len(spec.shape)) if a not in spec.axes)
    p = spec.power
    if other:
        n_other = int(np.prod([spec.shape[a] for a in other]))
        p = np.sum(p, axis=other, dtype=np.float64, keepdims=True) / n_other
    w_b = np.broadcast_to(spec.weight, p.shape)  # a view: nothing full-size is allocated
    counts = np.zeros(nb)
    s1 = np.zeros(nb)
    s2 = np.zeros(nb)
    sf = np.zeros(nb)
    total = 0.0
    # one slab of the leading axis at a time: a few slab-sized temporaries, never a full-size index array
    for sl in _slabs(p.shape):
        ps, ws = p[sl], w_b[sl]
        rs = _slab_radius(comps, sl, p.shape)
        idx = _bin_index(np.ascontiguousarray(rs), edges)
        keep = idx >= 0
        i = idx[keep]
        w = ws[keep].astype(np.float64)
        pv = ps[keep].astype(np.float64)
        counts += np.bincount(i, weights=w, minlength=nb)
        s1 += np.bincount(i, weights=w * pv, minlength=nb)
        s2 += np.bincount(i, weights=w * pv * pv, minlength=nb)
        sf += np.bincount(i, weights=w * rs[keep], minlength=nb)
        total += float(np.sum(ps * ws, dtype=np.float64))
    ok = counts > 0
    counts, s1, s2, sf = counts[ok], s1[ok], s2[ok], sf[ok]
    mean = s1 / counts
    var = np.maximum(s2 / counts - mean**2, 0.0)
    lo, hi = edges[:-1][ok], edges[1:][ok]
    centers = np.sqrt(lo * hi) if log else 0.5 * (lo + hi)
    return RadialSpectrum(
        centers=centers,
        edges=edges,
        power=mean,
        counts=counts,
        variance=var,
        mean_frequency=sf / counts,
        frame_size=n_ref,
        total=total,
    )


@dataclass(frozen=True)
class SpatiotemporalSpectrum:
    """A video's power as a function of spatial radial frequency and temporal frequency.

    Attributes
    ----------
    centers : ndarray
        Spatial radial bin centres (cycles/frame), shape ``(nb,)``.
    temporal : ndarray
        Temporal frequencies in cycles/video, ascending (``-T//2 .. (T-1)//2``), shape ``(T,)``.
    power : ndarray
        Mean power per cell, shape ``(T, nb)``.
    counts : ndarray
        Full-spectrum cells per spatial bin and temporal frequency, shape ``(nb,)``.
    frame_size : int
    total : float
    """

    centers: np.ndarray
    temporal: np.ndarray
    power: np.ndarray
    counts: np.ndarray
    frame_size: int
    total: float


def spatiotemporal_spectrum(video, *, bins=None, log=False, window=None) -> SpatiotemporalSpectrum:
    """Spatial-radial x temporal-frequency power spectrum of a ``(frames, height, width)`` video.

    One 3-D FFT; each temporal slice is binned radially. Cells stored once for
    a conjugate pair are credited to both ``+w_t`` and ``-w_t`` (their mirror
    has the same radius and the opposite temporal frequency), so a motion
    that is asymmetric in time is kept.

    Parameters
    ----------
    video : array_like (T, H, W)
        A finite grey video (at least 2 frames).
    bins : int or array_like, optional
        Radial bins (count or edges) in cycles/frame; default one per integer frequency.
    log : bool, default False
        Log-spaced radial bins.
    window : {None, "hann"}, optional
        Spatial taper before the FFT.

    Returns
    -------
    SpatiotemporalSpectrum
        ``power`` (temporal x radial), ``temporal`` (cycles/video) and ``centers`` (cycles/frame).

    Raises
    ------
    ValueError
        For an array that is not a finite 3-D video.

    Examples
    --------
    >>> import numpy as np
    >>> t, y, x = np.mgrid[:8, :32, :32]
    >>> st = spatiotemporal_spectrum(np.cos(2 * np.pi * (4 * x / 32 - 2 * t / 8)))
    >>> it, ib = np.unravel_index(np.argmax(st.power), st.power.shape)
    >>> float(abs(st.temporal[it])), float(st.centers[ib])
    (2.0, 4.0)
    """
    spec = as_spectrum(video, window=window)
    if len(spec.shape) != 3:
        raise ValueError(f"video must be 3-D (frames, height, width), got shape {spec.shape}")
    t_len, h, w = spec.shape
    n_ref = ref_size((h, w))
    ky = frequency_index(h)[:, None] * (n_ref / h)
    kx = frequency_index(w, half=True)[None, :] * (n_ref / w)
    r = np.sqrt(ky**2 + kx**2)
    edges = _edges(bins, log, n_ref / 2.0)
    nb = edges.size - 1
    idx = _bin_index(r, edges)
    wcol = half_weight(w)
    keep = idx >= 0
    interior = keep & (wcol[None, :] == 2)
    i_all = idx[keep]
    i_int = idx[interior]
    sums = np.zeros((t_len, nb))
    for it in range(t_len):
        slab = spec.power[it]
        sums[it] += np.bincount(i_all, weights=slab[keep], minlength=nb)
        sums[(-it) % t_len] += np.bincount(i_int, weights=slab[interior], minlength=nb)
    counts = np.bincount(i_all, minlength=nb) + np.bincount(i_int, minlength=nb)
    ok = counts > 0
    lo, hi = edges[:-1][ok], edges[1:][ok]
    order = np.argsort(np.fft.fftfreq(t_len, 1.0 / t_len), kind="stable")
    return SpatiotemporalSpectrum(
        centers=np.sqrt(lo * hi) if log else 0.5 * (lo + hi),
        temporal=np.fft.fftfreq(t_len, 1.0 / t_len)[order],
        power=(sums[:, ok] / counts[ok])[order],
        counts=counts[ok].astype(np.float64),
        frame_size=n_ref,
        total=spec.total,
    )


def band_energy(field, band, *, window=None, axes=None) -> float:
    """Fraction of the field's power whose radial frequency lies in ``band = (lo, hi)`` cycles/frame (lo <= f <= hi).

    For a video pass ``axes=(-2, -1)`` to band-limit the spatial frequency only.

    Parameters
    ----------
    field : array_like or PowerSpectrum
        1-, 2- or 3-D finite field.
    band : (lo, hi)
        In cycles/frame, ``0 <= lo < hi``.
    window : {None, "hann"}, optional
        Spatial taper before the FFT; ``"hann"`` for fields that do not tile.
    axes : tuple of int, optional
        The axes whose radial frequency counts (default all).

    Returns
    -------
    float
        In ``[0, 1]``; 0 for a field without power.

    Raises
    ------
    ValueError
        For a non-finite field or a band that is not ``0 <= lo < hi``.

    Examples
    --------
    >>> import numpy as np
    >>> x = np.cos(2 * np.pi * 8 * np.arange(64) / 64)[None, :] * np.ones((64, 1))
    >>> band_energy(x, (6, 10))
    1.0
    """
    spec = as_spectrum(field, window=window, axes=axes)
    comps, n_ref = _radial_frequency(spec, spec.axes)
    lo, hi = check_band("band", band, n_ref / 2.0 * np.sqrt(len(spec.axes)))
    w_b = np.broadcast_to(spec.weight, spec.power.shape)
    num = 0.0
    for sl in _slabs(spec.power.shape):
        rs = _slab_radius(comps, sl, spec.power.shape)
        inside = (rs >= lo) & (rs <= hi)
        num += float(np.sum(spec.power[sl] * np.where(inside, w_b[sl], 0), dtype=np.float64))
    total = spec.total
    return num / total if total > 0 else 0.0


# the steepest power law a field without a band limit is taken to have: power ~ f**-6 (amplitude 1/f**3);
# power_band's edges must fall by `drop` decades more than it would
_STEEPEST = 6.0


class PowerBand(NamedTuple):
    """Where a field has power (:func:`power_band`): the band and how each edge was found."""

    lo: float                    # cycles/frame: the lower edge, or 1 (the lowest ring) when none was found
    hi: float                    # cycles/frame: the upper edge, or N / 2 (Nyquist) when none was found
    limited: tuple[bool, bool]   # whether a lower / an upper edge was found
    drop: tuple[float, float]    # decades the power falls past each edge (0 where none was found)


def power_band(field, *, drop=1.0, window=None, axes=None, workers=None) -> PowerBand:
    """The band of radial frequencies where a field has power: edges where its spectrum falls off a cliff.

    The radial power spectrum (rings one cycle/frame wide, :func:`radial_spectrum`,
    floored at :func:`noise_floor`) is read outwards from its strongest ring.
    An upper edge is the first ring ``f`` past which *every* ring lies below
    the spectrum's level just inside the edge (the median of the rings in
    ``[f / 1.25, f]``) by ``drop`` decades more than the steepest power law
    taken for a field without a band limit (power ``f**-6``, amplitude
    ``1/f**3``) falls over the same span; a lower edge likewise, inwards
    (rings in ``[f, 1.25 f]``, every ring below ``f``). A band-limited field
    (spectral noise with a band, snow, stimuli) falls by several decades
    within a ring or two onto whatever floor it has (rounding, 8-bit
    quantisation, compression), so its edges are found; a power law
    ``1/f**k`` with ``|k| <= 3`` and no band limit has none and keeps the
    full band ``(1, N / 2)`` (tested for k = -1 .. 3, N = 64 .. 1024, in float
    and quantised to 8 bits).

    Parameters
    ----------
    field : array_like or PowerSpectrum
        A 1-, 2- or 3-D field, or its :func:`power_spectrum` (for a video,
        ``power_spectrum(video, axes=(-2, -1))``: the spatial band).
    drop : float, default 1
        Decades of power (1: a factor of 10) that an edge must fall by, in (0, 30].
    window : {None, "hann"}
        See :func:`power_spectrum`.
    axes : tuple of int, optional
        Radial axes (default all), as in :func:`radial_spectrum`.
    workers : int, optional
        FFT threads, scipy.fft's meaning; the same result for any count.

    Returns
    -------
    PowerBand
        ``(lo, hi)`` in cycles/frame, ``limited`` (an edge found below, above)
        and ``drop`` (decades fallen past each edge, 0 where none).

    Raises
    ------
    ValueError
        For a field that :func:`power_spectrum` refuses, or ``drop`` outside (0, 30].

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab.spectral import spectral_noise
    >>> pb = power_band(spectral_noise((128, 128), exponent=1.0, band=(8, 24), rng=1))
    >>> pb.lo, pb.hi, pb.limited
    (8.0, 24.0, (True, True))
    >>> power_band(spectral_noise((128, 128), exponent=1.0, rng=1)).limited
    (False, False)
    """
    drop = check_real("drop", drop, lo=0.0, lo_open=True, hi=30.0)
    spec = as_spectrum(field, window=window, axes=axes, workers=workers)
    rs = radial_spectrum(spec)
    f = rs.centers
    level = np.log10(np.maximum(rs.power, noise_floor(spec)))
    fmax = float(rs.frame_size) / 2.0
    if f.size < 3:
        return PowerBand(1.0, fmax, (False, False), (0.0, 0.0))
    peak = int(np.argmax(level))
    # the highest level at or beyond each ring, outwards and inwards
    above = np.maximum.accumulate(level[::-1])[::-1]
    below = np.maximum.accumulate(level)
    hi, hi_drop, hi_found = fmax, 0.0, False
    for i in range(peak, f.size - 1):
        near = (f >= f[i] / 1.25) & (f <= f[i])
        inside = float(np.median(level[near]))
        fall = inside - float(above[i + 1])
        if fall - _STEEPEST * np.log10(f[i + 1] / np.median(f[near])) >= drop:
            hi, hi_drop, hi_found = float(f[i]), fall, True
            break
    lo, lo_drop, lo_found = 1.0, 0.0, False
    for i in range(peak, 0, -1):
        near = (f >= f[i]) & (f <= 1.25 * f[i])
        inside = float(np.median(level[near]))
        fall = inside - float(below[i - 1])
        if fall - _STEEPEST * np.log10(np.median(f[near]) / f[i - 1]) >= drop:
            lo, lo_drop, lo_found = float(f[i]), fall, True
            break
    return PowerBand(lo, hi, (lo_found, hi_found), (lo_drop, hi_drop))
