"""The measures a noise is judged by: band leakage and aliasing, slices of volumes, envelope error,
variance and range, periods, lattice-axis artefacts and motion per band.

Each function measures one property the procedural-noise literature asks of a
noise (Lagae et al. 2010, "A survey of procedural noise functions"; Cook &
DeRose 2005, "Wavelet noise"; Ulichney 1987 for :func:`ring_anisotropy`) on
any array, so that every generator (spectral, lattice, a peer's) is measured
with the same instrument. Frequencies are in cycles/frame (see
:mod:`noiselab.analysis`); power fractions are of the field's variance.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.fft

from .._core import array_order, as_array, check_int, check_real, check_real_sequence, keyword_only
from ._common import check_band, check_field, half_weight, noise_floor
from .spectrum import PowerSpectrum, _radial_frequency, _slabs, as_spectrum, power_spectrum

__all__ = [
    "BandLeakage",
    "band_leakage",
    "SliceLeakage",
    "slice_leakage",
    "shell_slice_below",
    "EnvelopeError",
    "envelope_error",
    "ValueStatistics",
    "value_statistics",
    "Period",
    "detect_period",
    "AxisArtefacts",
    "axis_artefacts",
    "variance_striping",
    "BandMotion",
    "tent_energy_per_band",
]


# --------------------------------------------------------------------------- band leakage and aliasing

@dataclass(frozen=True)
class BandLeakage:
    """Where a field's power lies against a requested band: below, inside, above it, and past the output's Nyquist.

    Attributes
    ----------
    band : (lo, hi)
        The requested band (cycles/frame).
    nyquist : float
        The output's Nyquist frequency per axis (cycles/frame): the field's own
        Nyquist divided by ``oversample``.
    below, inside, above : float
        Fractions of the power with radial frequency under ``lo``, within
        ``[lo, hi]`` and over ``hi``, counting only cells inside the output's
        Nyquist cube.
    aliased : float
        Fraction of the power past the output's Nyquist on any axis: what
        sampling the noise at the output's rate folds back onto lower
        frequencies (0 unless ``oversample > 1``).
    edges : ndarray
        Octave edges ``lo * 2**k`` (cycles/frame) covering every cell with power.
    octaves : ndarray
        Fraction of the power in each octave (all of it, aliased or not).
    octaves_aliased : ndarray
        The part of each octave that is past the output's Nyquist.
    """

    band: tuple
    nyquist: float
    below: float
    inside: float
    above: float
    aliased: float
    edges: np.ndarray
    octaves: np.ndarray
    octaves_aliased: np.ndarray

    @property
    def outside(self) -> float:
        """Power outside the requested band, aliasing included (``1 - inside``)."""
        return self.below + self.above + self.aliased


def _cell_frequencies(spec: PowerSpectrum):
    comps, n_ref = _radial_frequency(spec, spec.axes)
    return comps, n_ref


def band_leakage(field, band, *, oversample=1, window=None) -> BandLeakage:
    """Power outside a requested band, per octave, and above the output's Nyquist (aliasing).

    To measure aliasing, evaluate the noise ``oversample`` times more densely
    over the *same* domain as the output (a lattice noise at any points; a
    fractal sum with the same octaves) and pass that field: the power past
    the output's Nyquist frequency on any axis is what sampling at the
    output's rate would fold back (a square/cubic Nyquist region, as the
    sampling grid folds each axis separately).

    Parameters
    ----------
    field : array_like or PowerSpectrum
        1-, 2- or 3-D, sampled ``oversample`` times denser than the output.
    band : (lo, hi)
        Requested band in cycles/frame.
    oversample : int
        How many times denser than the output ``field`` is sampled (1: no
        aliasing measurement).
    window : {None, "hann"}
        See :func:`noiselab.analysis.power_spectrum` (use "hann" for a field that does not tile).

    Returns
    -------
    BandLeakage

    Examples
    --------
    >>> import numpy as np
    >>> white = np.random.default_rng(0).standard_normal((256, 256))   # 2x denser than a 128 x 128 output
    >>> round(band_leakage(white, (1, 64), oversample=2).aliased, 2)      # 3/4 of white noise is past Nyquist
    0.75
    """
    oversample = check_int("oversample", oversample, lo=1, hi=64)
    spec = as_spectrum(field, window=window)
    comps, n_ref = _cell_frequencies(spec)
    nyq_field = n_ref / 2.0
    nyq = nyq_field / oversample
    lo, hi = check_band("band", band, nyq * np.sqrt(len(spec.axes)))
    fmax = nyq_field * np.sqrt(len(spec.axes))
    # lo = m * 2**e exactly: r / lo = (r / m) * 2**-e, so log2(r / lo) = log2(r / m) - e without forming r / lo
    # (which overflows for a subnormal lo); the edges lo * 2**k are ldexp's exact scalings
    lo_m, lo_e = np.frexp(lo)
    k_lo = int(np.floor(np.log2(min(1.0, lo) / lo_m) - lo_e)) - 1
    k_hi = int(np.ceil(np.log2(fmax / lo_m) - lo_e)) + 1
    edges = np.ldexp(lo, np.arange(k_lo, k_hi + 1))
    nb = edges.size - 1
    octs = np.zeros(nb)
    octs_al = np.zeros(nb)
    below = inside = above = aliased = 0.0
    w_b = np.broadcast_to(spec.weight, spec.power.shape)
    for sl in _slabs(spec.power.shape):
        parts = []
        for c in comps:
            part = c[sl] if (sl and c.shape[0] > 1) else (c[0] if sl else c)
            parts.append(part)
        sub = spec.power[sl].shape
        r = np.broadcast_to(np.sqrt(sum(p**2 for p in parts)), sub)
        # share of each cell's weight that the output keeps: 0 past its Nyquist on any axis; an even
        # output's Nyquist frequency is one cell, +nyq (the -nyq cell of a full axis is its alias, and the
        # +nyq column of the halved axis, weight 2, stands for both)
        keep = np.ones(sub)
        if oversample > 1:
            for a, part in zip(spec.axes, parts):
                part = np.broadcast_to(part, sub)
                at = np.isclose(np.abs(part), nyq, rtol=1e-12, atol=0)
                f = np.where(np.abs(part) > nyq * (1 + 1e-12), 0.0, 1.0)
                if a == spec.axes[-1]:
                    f = np.where(at, 0.5, f)
                else:
                    f = np.where(at & (part < 0), 0.0, f)
                keep = keep * f
        e = (spec.power[sl] * w_b[sl]).astype(np.float64)
        kept = e * keep
        aliased += float((e - kept).sum())
        below += float(kept[r < lo].sum())
        inside += float(kept[(r >= lo) & (r <= hi)].sum())
        above += float(kept[r > hi].sum())
        pos = r > 0
        idx = np.clip(np.floor(np.log2(r[pos] / lo_m) - lo_e).astype(np.int64) - k_lo, 0, nb - 1)
        octs += np.bincount(idx, weights=e[pos], minlength=nb)
        octs_al += np.bincount(idx, weights=(e - kept)[pos], minlength=nb)
    total = below + inside + above + aliased
    if total <= 0:
        raise ValueError("field has no power: nothing to measure")
    return BandLeakage(band=(lo, hi), nyquist=nyq, below=below / total, inside=inside / total, above=above / total,
                       aliased=aliased / total, edges=edges, octaves=octs / total, octaves_aliased=octs_al / total)


# --------------------------------------------------------------------------- slices of a volume

@dataclass(frozen=True)
class SliceLeakage:
    """A volume's band-limitedness against that of its 2-D slices (Cook & DeRose's point).

    Attributes
    ----------
    band : (lo, hi)
    volume : BandLeakage
        Of the 3-D volume (radial frequency in 3-D).
    slices : BandLeakage
        Of the 2-D slices perpendicular to ``axis``, their spectra averaged.
    added_below : float
        ``slices.below - volume.below``: the power slicing brings under ``lo``
        (every 3-D frequency ``k`` projects onto the slice at ``|k_xy| <= |k|``).
    """

    band: tuple
    volume: BandLeakage
    slices: BandLeakage
    added_below: float


def slice_leakage(volume, band, *, axis=0, window=None) -> SliceLeakage:
    """Band-limitedness of the 2-D slices of a 3-D noise against the volume's own.

    A slice through a band-limited volume is not band-limited: a frequency
    ``k`` of the volume appears in the slice at its projection ``k_xy``,
    anywhere from 0 to ``|k|``, so power the volume holds only in
    ``[lo, hi]`` spreads under ``lo`` in the slice (Cook & DeRose 2005, who
    make the point about Perlin noise). For a volume whose power per cell is
    ``|k|**(-2 * exponent)`` in the shell, :func:`shell_slice_below` gives
    the expected fraction under ``lo``.

    Parameters
    ----------
    volume : array_like
        3-D field ``(depth, height, width)``.
    band : (lo, hi)
        Cycles/frame (per the last axis' length; the other two axes should have the same length).
    axis : int
        Axis the slices are perpendicular to.
    window : {None, "hann"}

    Returns
    -------
    SliceLeakage

    Examples
    --------
    >>> import noiselab
    >>> vol = noiselab.spectral_noise((64, 64, 64), exponent=0.0, band=(8, 16), rng=0)
    >>> s = slice_leakage(vol, (8, 16))
    >>> round(s.volume.below, 6), round(s.slices.below, 2)   # none under 8 in 3-D, a quarter in 2-D
    (0.0, 0.24)
    >>> round(shell_slice_below(8, 16), 2)   # the continuous law (the 64**3 grid's own cells give 0.245)
    0.26
    """
    arr = check_field("volume", volume, ndim=3)
    axis = check_int("axis", axis, lo=-3, hi=2) % 3
    vol = band_leakage(power_spectrum(arr, window=window), band)
    others = tuple(a for a in range(3) if a != axis)
    sl = band_leakage(power_spectrum(arr, window=window, axes=others), band)
    return SliceLeakage(band=vol.band, volume=vol, slices=sl, added_below=sl.below - vol.below)


def shell_slice_below(lo, hi, exponent=0.0) -> float:
    """Expected fraction of a 2-D slice's power under ``lo`` for a 3-D power law ``|k|**(-2 exponent)`` in ``[lo, hi]``.

    A sphere of radius ``k`` projects onto a plane with the fraction
    ``1 - sqrt(1 - lo**2 / k**2)`` of its area inside radius ``lo`` (its two
    caps), so the fraction is ``int k**(2 - 2e) (1 - sqrt(1 - lo**2/k**2)) dk
    / int k**(2 - 2e) dk`` over ``[lo, hi]``. For a flat spectrum in closed
    form: ``(hi**3 - (hi**2 - lo**2)**1.5 - lo**3) / (hi**3 - lo**3)``.

    Parameters
    ----------
    lo, hi : float
        The power law's band, ``0 < lo < hi``.
    exponent : float, default 0
        Amplitude exponent ``e`` (power ``|k|**(-2 e)``).

    Returns
    -------
    float
        In ``[0, 1]``.

    Raises
    ------
    ValueError
        For ``lo <= 0`` or ``hi <= lo``.

    Examples
    --------
    >>> round(shell_slice_below(8, 16), 4)
    0.2577
    """
    from scipy.integrate import quad

    lo = check_real("lo", lo, lo=0.0, lo_open=True)
    hi = check_real("hi", hi, lo=lo, lo_open=True)
    e = check_real("exponent", exponent, lo=-8, hi=8)
    # k = lo * exp(t), t in [0, L]: dk = k dt, so both integrands carry exp(q t), q = 3 - 2 e, which is
    # divided by exp(q M) (M = L if q > 0, else 0) so that it stays <= 1 for any band (hi / lo up to 1e600)
    span = math.log(hi) - math.log(lo)
    q = 3.0 - 2.0 * e
    top = span if q > 0 else 0.0
    # 1 - sqrt(1 - x) = x / (1 + sqrt(1 - x)), x = exp(-2 t): no cancellation for large t
    cap = lambda t: math.exp(-2 * t) / (1 + math.sqrt(max(-math.expm1(-2 * t), 0.0)))  # noqa: E731
    # the mass sits within a few units of t = 0 or t = span: split there, so a wide band is not under-sampled
    cuts = sorted({0.0, span, *(c for d in (0.25, 1.0, 4.0, 16.0, 64.0) for c in (d, span - d) if 0 < c < span)})
    num = sum(quad(lambda t: math.exp(q * (t - top)) * cap(t), a, b, limit=200)[0] for a, b in zip(cuts, cuts[1:]))
    if q == 0:
        den = span
    else:
        den = -math.expm1(-q * span) / q if q > 0 else math.expm1(q * span) / q
    return float(min(max(num / den, 0.0), 1.0))


# --------------------------------------------------------------------------- envelope error

@dataclass(frozen=True)
class EnvelopeError:
    """A measured spectrum against a target envelope, in dB, with the overall gain removed.

    Attributes
    ----------
    target_level : ndarray
        Mean target power per cell of each group of cells (groups of equal
        target level, lowest first).
    db : ndarray
        ``10 log10(measured / (gain * target))`` per group.
    counts : ndarray
        Full-spectrum cells per group.
    rms_db, max_db : float
        Cell-weighted RMS and largest absolute value of :attr:`db`.
    noise_db : float
        What a field drawn exactly from the target would give on average:
        the cell-weighted RMS of ``4.34 / sqrt(cells)`` dB (a periodogram
        cell of a Gaussian field has an exponential spread, sd = mean).
    gain_db : float
        Measured over target power inside the support, in dB (the normalisation, removed above).
    outside : float
        Fraction of the measured power where the target is zero (below ``support`` x its peak).
    """

    target_level: np.ndarray
    db: np.ndarray
    counts: np.ndarray
    rms_db: float
    max_db: float
    noise_db: float
    gain_db: float
    outside: float


def _real_target(t) -> np.ndarray:
    """A target (power per cell) as a real float64 array; its finiteness is checked once DC is set aside."""
    t = as_array("target", t)
    if t.dtype.kind not in "biuf":
        raise TypeError(f"target must be real power per cell (an array or a callable returning one), got dtype "
                        f"{t.dtype}")
    return t.astype(np.float64, copy=False)


def _target_half(target, spec: PowerSpectrum) -> np.ndarray:
    shape = spec.power.shape
    if callable(target):
        comps, _ = _radial_frequency(spec, spec.axes)
        r = np.sqrt(sum(c.astype(np.float64) ** 2 for c in comps))
        try:
            with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
                t = target(np.broadcast_to(r, shape))
        except (ValueError, TypeError) as exc:
            raise type(exc)(f"target must be a callable of the radial frequency (an array of shape {shape}, "
                            f"cycles/frame) returning the power there; calling it raised: {exc}") from exc
        t = _real_target(t)
        try:
            t = np.broadcast_to(t.astype(np.float64, copy=False), shape)
        except ValueError:
            raise ValueError(f"target(f) must return an array of the frequencies' shape {shape} (or one that "
                             f"broadcasts to it), got shape {t.shape}") from None
    else:
        t = _real_target(target)
        if t.shape == tuple(spec.shape) and t.shape != shape:
            t = t[..., : shape[-1]]  # a full fftn-layout target: keep the rfftn half
        if t.shape != shape:
            raise ValueError(f"target must be a callable of the radial frequency or an array of the half-spectrum shape "
                             f"{shape} (or the full shape {tuple(spec.shape)}), got shape {t.shape}")
    t = np.array(t, dtype=np.float64)
    t[tuple(0 if a in spec.axes else slice(None) for a in range(t.ndim))] = 0.0  # DC: the mean is not compared
    if not np.all(np.isfinite(t)):
        raise ValueError("target must be finite at every frequency but DC")
    if np.any(t < 0):
        raise ValueError("target power must be >= 0")
    return t


def envelope_error(field, target, *, groups=16, support=1e-6, window=None) -> EnvelopeError:
    """Error of a field's power spectrum against a target envelope (power per cell), in dB.

    Cells are pooled by target level (``groups`` groups of about equal cell
    count, by quantiles of the target), so the comparison works for any
    envelope in any dimension: a radial power law, snow's tent in
    (t, y, x), a lattice kernel's separable spectrum. Each group's mean
    measured power is compared with its mean target power after removing
    one overall gain (the ratio of the totals), so the normalisation does not
    count; :attr:`EnvelopeError.noise_db` says what sampling alone gives.

    Parameters
    ----------
    field : array_like or PowerSpectrum
    target : callable or ndarray
        ``target(f)`` of the radial frequency in cycles/frame (over all the
        spectrum's axes), or the expected power per cell as an array in
        ``rfftn`` layout (or full ``fftn`` layout) of the field's shape.
    groups : int
        Number of target-level groups.
    support : float in [0, 1)
        Cells whose target is at most ``support`` x the target's peak are outside the envelope.
    window : {None, "hann"}

    Returns
    -------
    EnvelopeError

    Examples
    --------
    >>> import noiselab
    >>> x = noiselab.spectral_noise((256, 256), exponent=1.0, band=(4, 128), rng=0)
    >>> err = envelope_error(x, lambda f: np.where((f >= 4) & (f <= 128), f ** -2.0, 0.0))
    >>> bool(err.rms_db < 2 * err.noise_db), err.outside < 1e-9
    (True, True)
    """
    groups = check_int("groups", groups, lo=1, hi=1000)
    support = check_real("support", support, lo=0.0, hi=1.0, hi_open=True)
    spec = as_spectrum(field, window=window)
    t = _target_half(target, spec)
    w = np.broadcast_to(spec.weight, spec.power.shape).astype(np.float64)
    p = spec.power.astype(np.float64)
    peak = float(t.max())
    if peak <= 0:
        raise ValueError("target is zero everywhere: no envelope to compare with")
    t = t / peak  # the comparison removes the gain: in units of the peak no sum of the target can overflow
    inside = t > support
    total = float(np.sum(p * w))
    if total <= 0:
        raise ValueError("field has no power: nothing to compare")
    outside = float(np.sum((p * w)[~inside])) / total
    tv, pv, wv = t[inside], p[inside], w[inside]
    order = np.argsort(tv, kind="stable")
    tv, pv, wv = tv[order], pv[order], wv[order]
    cw = np.cumsum(wv)
    gid = np.minimum((cw - 0.5 * wv) / cw[-1] * groups, groups - 1).astype(np.int64)
    # cells of equal target level stay in one group
    _, first = np.unique(tv, return_index=True)
    gid = np.maximum.accumulate(np.repeat(gid[first], np.diff(np.append(first, tv.size))))
    cnt = np.bincount(gid, weights=wv)
    keep = cnt > 0
    cnt = cnt[keep]
    tm = np.bincount(gid, weights=wv * tv)[keep] / cnt
    pm = np.bincount(gid, weights=wv * pv)[keep] / cnt
    gain = float(np.sum(cnt * pm) / np.sum(cnt * tm))
    with np.errstate(divide="ignore"):
        db = 10 * np.log10(pm / (gain * tm))
    fw = cnt / cnt.sum()
    return EnvelopeError(target_level=tm * peak, db=db, counts=cnt, rms_db=float(np.sqrt(np.sum(fw * db**2))),
                         max_db=float(np.max(np.abs(db))), noise_db=float(np.sqrt(np.sum(fw * (10 / np.log(10)) ** 2 / cnt))),
                         gain_db=float(10 * np.log10(gain) - 10 * np.log10(peak)), outside=outside)


# --------------------------------------------------------------------------- variance and range

@dataclass(frozen=True)
class ValueStatistics:
    """Empirical variance and range of a field against the analytic ones.

    Attributes
    ----------
    mean, variance, min, max : float
        Of the field.
    expected_variance : float or None
        The analytic variance given.
    variance_ratio : float or None
        ``variance / expected_variance``.
    bounds : (lo, hi) or None
        The analytic range given.
    within_bounds : bool or None
        Whether every value lies in ``bounds``.
    range_used : float or None
        ``(max - min) / (hi - lo)``: how much of the guaranteed range the field
        reaches (lattice noise divides by a worst-case bound, so well under 1).
    range_sd : float
        ``(max - min) / sd``.
    """

    mean: float
    variance: float
    min: float
    max: float
    expected_variance: float | None
    variance_ratio: float | None
    bounds: tuple | None
    within_bounds: bool | None
    range_used: float | None
    range_sd: float


def value_statistics(field, *, variance=None, bounds=None) -> ValueStatistics:
    """Mean, variance and range of a field, against an analytic variance and range when given.

    Parameters
    ----------
    field : array_like
        Values with ``1e-150 <= max|field| <= 1e150`` (its variance must fit float64).
    variance : float, optional
        The analytic (expected) variance (> 0; the ratio to it must fit float64).
    bounds : (lo, hi), optional
        The analytic range.

    Returns
    -------
    ValueStatistics

    Examples
    --------
    >>> import numpy as np
    >>> u = np.random.default_rng(0).uniform(-1, 1, 100_000)
    >>> s = value_statistics(u, variance=1 / 3, bounds=(-1, 1))
    >>> round(s.variance_ratio, 2), s.within_bounds, round(s.range_used, 3)
    (1.0, True, 1.0)
    """
    arr = check_field("field", field, min_size=1)
    lo_v, hi_v = float(arr.min()), float(arr.max())
    biggest = max(abs(lo_v), abs(hi_v))
    if not 1e-150 <= biggest <= 1e150:
        raise ValueError(f"field values reach {biggest:.3g} in magnitude: their variance would "
                         f"{'overflow' if biggest > 1 else 'underflow'} float64; |field| must reach 1e-150 and stay "
                         "below 1e150 (rescale it)")
    var = float(np.var(arr, dtype=np.float64))
    ratio = None
    if variance is not None:
        variance = check_real("variance", variance, lo=0.0, lo_open=True)
        with np.errstate(over="ignore"):
            ratio = float(np.float64(var) / variance)
        if not math.isfinite(ratio):
            raise ValueError(f"variance must be in ({var / np.finfo(np.float64).max:.3g}, inf) for this field (variance {var:.3g}): "
                             f"the ratio to {variance:.3g} overflows float64")
    within = used = None
    if bounds is not None:
        b0, b1 = check_real_sequence("bounds", bounds, length=2)
        if not b1 > b0:
            raise ValueError(f"bounds must have lo < hi, got ({b0:g}, {b1:g})")
        bounds = (b0, b1)
        within = bool(lo_v >= b0 and hi_v <= b1)
        with np.errstate(over="ignore", divide="ignore"):  # b1 - b0 > 0 (gradual underflow), maybe inf (used 0)
            used = float(np.float64(hi_v - lo_v) / (np.float64(b1) - np.float64(b0)))
        if not math.isfinite(used):
            raise ValueError(f"bounds ({b0:g}, {b1:g}) are too narrow for the field's range ({lo_v:g}, {hi_v:g}): "
                             "the ratio of the widths overflows float64")
    return ValueStatistics(mean=float(np.mean(arr, dtype=np.float64)), variance=var, min=lo_v, max=hi_v,
                           expected_variance=variance, variance_ratio=ratio, bounds=bounds, within_bounds=within,
                           range_used=used, range_sd=float((hi_v - lo_v) / np.sqrt(var)))


# --------------------------------------------------------------------------- periods

@dataclass(frozen=True)
class Period:
    """The shortest lag after which a field repeats along an axis.

    Attributes
    ----------
    period : int or None
        Smallest lag (samples) whose normalised difference is at most ``tol``;
        None if the field does not repeat within ``max_lag``.
    difference : float
        ``mean((x[L:] - x[:-L])**2) / (2 var)`` at that lag (0 for an exact
        repeat, about 1 for unrelated samples); at the best lag if none repeats.
    best_lag : int
        Lag of the smallest difference.
    """

    period: int | None
    difference: float
    best_lag: int


@keyword_only("axis")
def detect_period(field, *, axis=-1, tol=1e-6, max_lag=None, min_lag=1) -> Period:
    """Detect an exact repeat along one axis (a lattice's table period, an FFT field's domain).

    For every lag ``L`` from ``min_lag`` to ``max_lag`` (default: half the
    axis, so the repeat is seen at least twice over) the mean squared
    difference between the field and itself shifted by ``L`` along ``axis``,
    over the overlap and every other axis, divided by twice the variance: 0
    for an exact repeat, about 1 for uncorrelated samples. All lags come from
    one zero-padded FFT correlation.

    Parameters
    ----------
    field : array_like
        1-, 2- or 3-D.
    axis : int
    tol : float
        Largest normalised difference counted as a repeat (float rounding
        makes an exact repeat ~1e-14, not 0).
    max_lag, min_lag : int, optional

    Returns
    -------
    Period

    Examples
    --------
    >>> import numpy as np
    >>> x = np.random.default_rng(0).standard_normal(100)
    >>> detect_period(np.tile(x, 3)).period
    100
    >>> print(detect_period(x).period)
    None
    """
    arr = check_field("field", field, min_size=1).astype(np.float64)
    arr = arr / np.max(np.abs(arr))  # scale-free: scaled to |x| <= 1, the squares neither overflow nor underflow
    axis = check_int("axis", axis, lo=-arr.ndim, hi=arr.ndim - 1) % arr.ndim
    n = arr.shape[axis]
    if n < 4:
        raise ValueError(f"field has {n} samples along axis {axis}; detecting a period needs at least 4")
    max_lag = n // 2 if max_lag is None else check_int("max_lag", max_lag, lo=1, hi=n - 1)
    min_lag = check_int("min_lag", min_lag, lo=1, hi=max_lag)
    tol = check_real("tol", tol, lo=0.0)
    x = np.moveaxis(arr, axis, -1)
    x = x - x.mean()
    x = x.reshape(-1, n)
    var = float(np.mean(x**2))
    size = scipy.fft.next_fast_len(2 * n, real=True)
    f = scipy.fft.rfft(x, size, axis=-1)
    corr = scipy.fft.irfft(np.sum(np.abs(f) ** 2, axis=0), size)[:n]  # sum over rows of x[i] x[i + L]
    sq = np.cumsum(np.sum(x**2, axis=0))
    lags = np.arange(min_lag, max_lag + 1)
    head = sq[n - 1 - lags]                       # sum of x[:n-L]**2
    tail = sq[-1] - sq[lags - 1]                  # sum of x[L:]**2
    overlap = (n - lags) * x.shape[0]
    diff = np.maximum(head + tail - 2 * corr[lags], 0.0) / overlap / (2 * var)
    hit = np.nonzero(diff <= tol)[0]
    best = int(np.argmin(diff))
    if hit.size:
        return Period(period=int(lags[hit[0]]), difference=float(diff[hit[0]]), best_lag=int(lags[best]))
    return Period(period=None, difference=float(diff[best]), best_lag=int(lags[best]))


# --------------------------------------------------------------------------- lattice-axis artefacts

@dataclass(frozen=True)
class AxisArtefacts:
    """Signatures of an axis-aligned lattice in an image.

    Attributes
    ----------
    axis_power : float
        Fraction of the band's power on the two frequency axes (``kx = 0`` or ``ky = 0``).
    axis_excess : float
        Mean over the band's axis cells of their power over their ring's
        mean power off the axes (each cell whitened by its ring): 1 for an
        isotropic field (about ``1 +- 1/sqrt(cells)``), above 1 where a
        lattice's energy runs along its axes (its spectrum's tails past the
        lattice frequency), below 1 where its separable main lobe is narrower
        along the axes than along the diagonals.
    row_mean_spread, column_mean_spread : float
        Standard deviation of the row means (column means) over the field's
        standard deviation.
    mean_spread_excess : float
        The variance of the row and column means (the power on the axes, all
        radii, not whitened: the lowest rings dominate it) over what an
        isotropic field of the same radial spectrum gives.
    """

    axis_power: float
    axis_excess: float
    row_mean_spread: float
    column_mean_spread: float
    mean_spread_excess: float


def axis_artefacts(image, band=None, *, window=None) -> AxisArtefacts:
    """Power on the frequency axes and spread of the row and column means, against an isotropic field's.

    The variance of the column means of an image is exactly the power on its
    ``ky = 0`` frequency axis (and the row means' that on ``kx = 0``), so the
    two views agree; both are compared with the power the same cells would
    hold if each had the mean power of its ring (computed off the axes), so
    a steep spectrum does not pass for an artefact.

    Parameters
    ----------
    image : array_like
        2-D.
    band : (lo, hi), optional
        Cycles/frame for :attr:`AxisArtefacts.axis_power` and ``axis_excess``; default ``(1, N/2)``.
    window : {None, "hann"}
        Use "hann" for a field that does not tile (its edge jump puts a cross on the axes).

    Returns
    -------
    AxisArtefacts

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> round(axis_artefacts(rng.standard_normal((256, 256))).axis_excess, 1)
    1.0
    >>> striped = rng.standard_normal((256, 256)) + rng.standard_normal((1, 256))   # every row the same profile added
    >>> axis_artefacts(striped).axis_excess > 50
    True
    """
    arr = check_field("image", image, ndim=2)
    spec = power_spectrum(arr, window=window)
    h, w = arr.shape
    n_ref = w
    ky = np.fft.fftfreq(h, 1.0 / h)[:, None] * (n_ref / h)
    kx = np.arange(w // 2 + 1, dtype=np.float64)[None, :] * (n_ref / w)
    r = np.broadcast_to(np.hypot(kx, ky), spec.power.shape)
    lo, hi = check_band("band", (1.0, n_ref / 2.0) if band is None else band, n_ref / 2.0 * np.sqrt(2))
    weight = np.broadcast_to(half_weight(w)[None, :], r.shape)
    p = spec.power.astype(np.float64)
    on_axis = np.broadcast_to((kx == 0) | (ky == 0), r.shape) & (r > 0)
    ring = np.rint(r).astype(np.int64)
    nring = int(ring.max()) + 1
    off = ~on_axis & (r > 0)
    cnt = np.bincount(ring[off], weights=weight[off], minlength=nring)
    ring_mean = np.divide(np.bincount(ring[off], weights=(weight * p)[off], minlength=nring), cnt,
                          out=np.zeros(nring), where=cnt > 0)
    expected = ring_mean[ring]
    e = weight * p
    inband = (r >= lo) & (r <= hi)
    band_total = float(e[inband].sum())
    if band_total <= 0:
        raise ValueError(f"the image has no power in band ({lo:g}, {hi:g}) cycles/frame")
    # rings with no power off the axes (at the rounding floor) give no reference: left out
    sel = on_axis & inband & (expected > noise_floor(spec))
    # each axis cell against its own ring (whitened), so the few lowest rings of a steep spectrum do not decide
    excess = float(np.sum((weight * p / np.where(expected > 0, expected, 1.0))[sel]) / np.sum(weight[sel])) \
        if sel.any() else float("nan")
    exp_all = float((weight * expected)[on_axis & (expected > noise_floor(spec))].sum())
    sd = float(np.std(arr, dtype=np.float64))
    rows = np.mean(arr, axis=1, dtype=np.float64)
    cols = np.mean(arr, axis=0, dtype=np.float64)
    return AxisArtefacts(axis_power=float(e[on_axis & inband].sum()) / band_total, axis_excess=excess,
                         row_mean_spread=float(rows.std()) / sd, column_mean_spread=float(cols.std()) / sd,
                         mean_spread_excess=float(e[on_axis & (expected > noise_floor(spec))].sum()) / exp_all if exp_all > 0 else float("inf"))


def variance_striping(field, period, *, axis=-1, phases=None) -> float:
    """Depth of the variance's modulation with position in a lattice cell: (max - min) / mean.

    Lattice noise is not stationary: its variance depends on where a point
    sits in its cell (value noise with the linear kernel has the value
    tables' variance at lattice points and half of it mid-cell), which shows
    as stripes along the lattice's rows and columns. The field's squared
    deviation is averaged over every sample of the same phase
    ``(i mod period) / period`` along ``axis`` (all other axes pooled); a
    stationary field gives a flat profile (depth near 0, up to sampling
    noise).

    Parameters
    ----------
    field : array_like
    period : float
        Samples per lattice cell along ``axis`` (need not be an integer).
    axis : int
    phases : int, optional
        Phase bins; default ``round(period)`` (one per sample for an integer period), at most 64.

    Returns
    -------
    float
        ``(max - min) / mean`` of the phase-folded variance profile.

    Examples
    --------
    >>> import noiselab
    >>> line = noiselab.LatticeNoise(1, rng=0, kernel="linear", table_size=1 << 16).grid((1 << 18,), [(0, 1 << 14)])
    >>> abs(variance_striping(line, 16) - 0.75) < 0.05   # (1 - 1/2) / (2/3): linear value noise
    True
    """
    arr = check_field("field", field, min_size=1).astype(np.float64)
    arr = arr / np.max(np.abs(arr))  # scale-free: scaled to |x| <= 1, the squares neither overflow nor underflow
    axis = check_int("axis", axis, lo=-arr.ndim, hi=arr.ndim - 1) % arr.ndim
    period = check_real("period", period, lo=2.0, hi=arr.shape[axis] / 2)
    nph = int(round(period)) if phases is None else check_int("phases", phases, lo=2)
    nph = min(max(nph, 2), 64)
    dev2 = np.moveaxis((arr - arr.mean()) ** 2, axis, -1).reshape(-1, arr.shape[axis]).mean(axis=0)
    ph = np.floor(np.mod(np.arange(arr.shape[axis]) / period, 1.0) * nph).astype(np.int64) % nph
    prof = np.bincount(ph, weights=dev2, minlength=nph) / np.maximum(np.bincount(ph, minlength=nph), 1)
    return float((prof.max() - prof.min()) / prof.mean())


# --------------------------------------------------------------------------- motion per band

@dataclass(frozen=True)
class BandMotion:
    """The share of each band's power on the tent (snow) or motion plane.

    Attributes
    ----------
    bands : ndarray
        ``(n, 2)`` band edges in cycles/frame.
    fraction : ndarray
        Power on the surface within each band over all the power in that band.
    share : ndarray
        Each band's share of the video's power.
    """

    bands: np.ndarray
    fraction: np.ndarray
    share: np.ndarray


@array_order(("direction", "direction_yx"), positional=("direction",))
def tent_energy_per_band(video, c, band, *, direction_yx=(1.0, 0.0), per_octave=1, thickness=0.1, tol=0.5,
                         window=None) -> BandMotion:
    """Fraction of each band's power on the falling-snow tent (:func:`noiselab.analysis.tent_energy`, band by band).

    With ``c = 0`` the tent is the still plane ``w_t = 0``; for a single
    rigid motion use :func:`noiselab.analysis.motion_energy` per band.
    ``band`` is split into ``per_octave`` bands per octave
    (:func:`noiselab.analysis.octave_bands`); a band holding no power (no
    frequency cell of the video, or none with power) has fraction 0 and share
    0. A ``band`` holding no spatial frequency of the video at all is a
    ValueError.

    Parameters
    ----------
    video : array_like (T, H, W)
        A finite grey video.
    c : float
        Tent constant in rad/frame (``0 <= c <= pi``).
    band : (lo, hi)
        Spatial band in cycles/frame, split into ``per_octave`` bands per octave.
    direction_yx : (dy, dx), default (1, 0)
        Fall direction in array order (y down, x right); ``direction=(dx, dy)``
        (also by position) is the old spelling, refused since 0.4.
    per_octave : int, default 1
        Bands per octave.
    thickness, tol, window
        As for :func:`noiselab.analysis.tent_energy`.

    Returns
    -------
    BandMotion
        Per band: its limits, the fraction of its power on the tent, its share of the total power.

    Raises
    ------
    ValueError
        For a video that is not finite and 3-D, ``c`` outside ``[0, pi]``, or
        a band holding no spatial frequency of the video.

    Examples
    --------
    >>> import numpy as np
    >>> t, y, x = np.mgrid[:16, :32, :32].astype(float)
    >>> c = np.pi / 4; w = 2 * np.pi * 3 / 32
    >>> falling = np.cos(2 * np.pi * 3 * (y - c / w * t) / 32)   # 3 cycles/frame at c / |w| px/frame
    >>> still = np.cos(2 * np.pi * 6 * y / 32)                    # 6 cycles/frame, not moving
    >>> tent_energy_per_band(falling + still, c, (2, 8), thickness=0).fraction.round(6).tolist()
    [1.0, 0.0]
    """
    from .motion import _Grid, octave_bands, tent_energy, video_spectrum

    spec = video_spectrum(video, window=window)
    g = _Grid(spec.shape)
    lo, hi = check_band("band", band, g.n_ref / 2.0)
    per_octave = check_int("per_octave", per_octave, lo=1, hi=16)
    bands = octave_bands(lo, hi, per_octave)
    # power of each spatial cell summed over temporal frequency, weighted for the unstored mirror columns
    spatial = np.sum(spec.power, axis=0, dtype=np.float64) * g.weight
    total = spec.total
    if not g.band_mask((lo, hi)).any():
        raise ValueError(f"band ({lo:g}, {hi:g}) cycles/frame holds no spatial frequency of this video (its "
                         f"nonzero ones run from {float(g.r[g.r > 0].min()):g} to {float(g.r.max()):g} cycles/frame)")
    frac, share = [], []
    for b in bands:
        s = float(spatial[g.band_mask(b)].sum()) / total if total > 0 else 0.0
        # a sub-band without power (no cell in it, or none with power) has nothing to measure: fraction 0
        on = tent_energy(spec, c, b, direction_yx=direction_yx, thickness=thickness, tol=tol) if s > 0 else 0.0
        frac.append(on / s if s > 0 else 0.0)
        share.append(s)
    return BandMotion(bands=np.array(bands), fraction=np.array(frac), share=np.array(share))
