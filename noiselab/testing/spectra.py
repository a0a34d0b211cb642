"""Assertions about spectra: a power law, a band limit, isotropy, no lattice-axis artefacts."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize, special, stats

from .._core import HIDE_ASSERTION_FRAMES, as_array, check_band, check_real, renamed_parameters
from ..analysis import PowerSpectrum, axis_artefacts, band_energy, power_spectrum
from ._cells import independent_cells, live_band, ring_index

__all__ = [
    "PowerLawCheck", "assert_power_law",
    "BandLimitCheck", "assert_band_limited",
    "IsotropyCheck", "assert_isotropic",
    "AxisCheck", "assert_no_axis_artefacts",
    "check_false_alarm", "two_sided_z",
]

_WINDOWS = (None, "hann")


def check_false_alarm(false_alarm) -> float:
    """``false_alarm`` in ``[1e-12, 0.5]``: the probability that a field holding the property fails."""
    return check_real("false_alarm", false_alarm, lo=1e-12, hi=0.5)


def two_sided_z(false_alarm: float) -> float:
    """The normal quantile a two-sided test at ``false_alarm`` compares ``|estimate - expected| / SE`` with."""
    return float(stats.norm.isf(false_alarm / 2.0))


def _check_window(window):
    if not (window is None or (isinstance(window, str) and window in _WINDOWS)):
        raise ValueError(f"window must be None or 'hann', got {window!r}")
    return window


def _spectrum(name, field, ndim, window):
    if isinstance(field, (str, bytes)) or field is None:
        raise TypeError(f"{name} must be a numeric array, got {type(field).__name__}")
    arr = as_array(name, field)
    nd = arr.ndim
    if nd not in ndim:
        dims = " or ".join(f"{d}-D" for d in ndim)
        raise ValueError(f"{name} must be a {dims} array, got {nd}-D")
    return power_spectrum(arr, window=_check_window(window))


def _band(cells, band, default, what):
    """The band to test: the user's, or the default clipped to where the field has power."""
    __tracebackhide__ = HIDE_ASSERTION_FRAMES  # a failure reports the caller's line and the message
    nyq = cells.n_ref / 2.0
    if band is not None:
        return check_band("band", band, nyq * math.sqrt(len(cells.components)), lo_open=True), "given"
    lo, hi = default(cells.n_ref)
    live = live_band(cells, lo, hi)
    if live is None or live[1] - live[0] < 1:
        raise AssertionError(f"{what}: the field has no power between {lo:g} and {hi:g} cycles/frame "
                             "(the default band); pass band=(lo, hi)")
    return live, f"default: where the field has power within ({lo:g}, {hi:g})"


# ------------------------------------------------------------------------------------------- power law

@dataclass(frozen=True)
class PowerLawCheck:
    """The measured exponent of a power law and how it was judged.

    Attributes
    ----------
    exponent : float
        Measured amplitude exponent: the amplitude spectrum falls as ``f**-exponent``.
    error : float
        Its standard error (Fisher information of the cells' exponential law).
    expected : float
    tolerance : float
        Allowed ``|exponent - expected|``.
    band : (lo, hi)
        Cycles/frame.
    cells : int
        Independent periodogram cells in the band.
    message : str
        What was measured and how the tolerance was derived.
    """

    exponent: float
    error: float
    expected: float
    tolerance: float
    band: tuple
    cells: int
    message: str


def power_law_fit(cells, lo, hi):
    """Whittle's maximum-likelihood exponent of ``S = A f**(-2 alpha)`` over the cells in ``[lo, hi]``.

    Each cell's power is ``S(f) E`` with ``E`` exponential (mean 1), so the
    negative log-likelihood is ``sum(log S + P / S)``; profiling out ``A``
    leaves one dimension. The Fisher information for ``alpha`` is
    ``4 sum (log f - mean log f)**2`` (the cells' exponential law has unit
    information in ``log S``): its inverse, times the window's variance
    factor, is the variance of the estimate. Returns
    ``(alpha, se, n_cells, dead)``, ``dead`` the cells at the rounding floor.
    """
    sel = (cells.radius >= lo) & (cells.radius <= hi)
    p, f = cells.power[sel], cells.radius[sel]
    dead = p <= cells.floor
    n = p.size
    if n < 3 or dead.any():
        return float("nan"), float("nan"), n, f[dead]
    logf, logp = np.log(f), np.log(p)
    sxx = float(np.sum((logf - logf.mean()) ** 2))
    if sxx <= 0:
        return float("nan"), float("nan"), n, f[dead]

    def nll(alpha):  # profile: A(alpha) = mean(P f**(2 alpha)), in logs so that steep spectra cannot overflow
        return n * special.logsumexp(logp + 2 * alpha * logf) - 2 * alpha * float(np.sum(logf))

    res = optimize.minimize_scalar(nll, bounds=(-20.0, 20.0), method="bounded", options={"xatol": 1e-10})
    se = math.sqrt(cells.variance_factor / (4.0 * sxx))
    return float(res.x), se, n, f[dead]


def _exponent_hint(measured, expected, tol):
    """A hint when ``expected`` looks like a power exponent (or half of one) where the amplitude exponent was meant."""
    what = (f"exponent is the AMPLITUDE exponent (amplitude ~ f**-exponent, power ~ f**(-2 exponent)): "
            f"exponent={expected:g} means a power slope of {-2.0 * expected:g}")
    if expected != 0 and abs(measured - expected / 2.0) <= tol:
        return f"; the measured exponent is about half the one given: {what}, and a power slope of " \
               f"{-expected:g} is exponent={expected / 2.0:g}"
    if expected != 0 and abs(measured - 2.0 * expected) <= tol:
        return f"; the measured exponent is about twice the one given: {what}, and this field's power slope is " \
               f"about {-2.0 * measured:.3g}"
    return ""


def _default_slope_band(n_ref):
    # 2 cycles/frame (the lowest rings hold a handful of cells) to a quarter of the frame (half the Nyquist
    # frequency: above it a generator's interpolation and a camera's optics bend the spectrum)
    return 2.0, n_ref / 4.0


@renamed_parameters(tolerance="tol")
def assert_power_law(field, exponent, *, band=None, tol=None, false_alarm=1e-3, window=None) -> PowerLawCheck:
    """Assert that the amplitude spectrum of ``field`` falls as ``f**-exponent`` over ``band``.

    The exponent is measured by Whittle's maximum likelihood over the
    independent periodogram cells of the band (each cell's power is the
    spectrum times an exponential draw: a chi-square with 2 degrees of
    freedom), with its standard error from the Fisher information,
    ``1 / sqrt(4 sum (log f - mean log f)**2)`` (times 35/18 per axis in
    variance with a Hann window, which correlates neighbouring cells). With
    ``tol=None`` the field passes when the estimate lies within
    ``z SE`` of ``exponent``, ``z`` the two-sided normal quantile of
    ``false_alarm``: a Gaussian field whose spectrum truly is that power law
    fails with probability ``false_alarm``.

    Parameters
    ----------
    field : array_like
        1-, 2- or 3-D real field, periodic (or pass ``window="hann"``).
    exponent : float
        The amplitude exponent: 1 for 1/f (pink) images, 0 for white noise;
        the power spectrum falls as ``f**(-2 exponent)``.
    band : (lo, hi), optional
        Cycles/frame (cycles per width of the last axis). Default: from 2
        cycles/frame to a quarter of the width, clipped to where the field
        has power.
    tol : float, optional
        Allowed ``|measured - exponent|``, instead of the statistical one
        (for fields that follow the law only approximately).
    false_alarm : float
        Probability that a field holding the property fails (1e-12 to 0.5).
    window : {None, "hann"}
        Use ``"hann"`` for fields that are not periodic.

    Returns
    -------
    PowerLawCheck

    Raises
    ------
    AssertionError
        If the exponent is off, or the band holds cells without power.
    ValueError, TypeError
        For bad input, naming the parameter.

    Examples
    --------
    >>> import noiselab
    >>> from noiselab.testing import assert_power_law
    >>> img = noiselab.spectral_noise((128, 128), exponent=1.0, rng=0)
    >>> check = assert_power_law(img, 1.0)
    >>> abs(check.exponent - 1) < check.tolerance
    True
    >>> assert_power_law(img, 1.2)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    AssertionError: power law: amplitude exponent 0.98...
    """
    __tracebackhide__ = HIDE_ASSERTION_FRAMES  # a failure reports the caller's line and the message
    spec = _spectrum("field", field, (1, 2, 3), window)
    expected = check_real("exponent", exponent, lo=-20.0, hi=20.0)
    alpha_fa = check_false_alarm(false_alarm)
    given = None if tol is None else check_real("tol", tol, lo=0.0, hi=40.0)
    cells = independent_cells(spec)
    (lo, hi), origin = _band(cells, band, _default_slope_band, "power law")
    est, se, n, dead = power_law_fit(cells, lo, hi)
    where = f"over {lo:g} <= f <= {hi:g} cycles/frame ({origin})"
    if dead.size:
        raise AssertionError(f"power law: no power at {dead.min():.3g}..{dead.max():.3g} cycles/frame {where}: "
                             f"the field is band-limited there, not a power law with exponent {expected:g}")
    if not np.isfinite(est):
        raise AssertionError(f"power law: only {n} independent cell(s) {where}; a slope needs at least 3 at two "
                             "radii: widen the band or use a larger field")
    win = f", x{cells.variance_factor:.3g} in variance for the Hann window" if cells.variance_factor != 1 else ""
    if given is None:
        z = two_sided_z(alpha_fa)
        tol = z * se
        how = (f"within {z:.2f} SE = {tol:.3g} (false_alarm={alpha_fa:g}, two-sided; SE from the Fisher "
               f"information of {n} independent cells, each cell's power chi-square with 2 dof{win})")
    else:
        tol = given
        how = f"within the given tolerance {tol:g} (statistical SE {se:.2g}{win})"
    off = est - expected
    msg = (f"power law: amplitude exponent {est:.4f} +- {se:.4f} (Whittle fit {where}), expected {expected:g} "
           f"{how}: off by {off:+.4f} = {abs(off) / se:.1f} SE")
    if not abs(off) <= tol:
        raise AssertionError(msg + _exponent_hint(est, expected, tol))
    return PowerLawCheck(exponent=est, error=se, expected=expected, tolerance=tol, band=(lo, hi), cells=n,
                         message=msg)


# ------------------------------------------------------------------------------------------- band limit

@dataclass(frozen=True)
class BandLimitCheck:
    """Power outside a band.

    Attributes
    ----------
    leakage : float
        Fraction of the power outside ``band`` (``1 - inside``).
    below, above : float
        Fractions under ``lo`` and over ``hi``.
    max_leakage : float
    band : (lo, hi)
    message : str
    """

    leakage: float
    below: float
    above: float
    max_leakage: float
    band: tuple
    message: str


def assert_band_limited(field, band, *, max_leakage=None, window=None, axes=None) -> BandLimitCheck:
    """Assert that at most ``max_leakage`` of the power of ``field`` lies outside ``band``.

    A band limit is not a sampling estimate: a field synthesised inside a
    band has no power outside it whatever its seed, only the rounding of its
    arithmetic. The default ``max_leakage`` is that floor with a wide margin:
    1.4e-6 of the power for float32 fields (``1e8 eps**2``, eps of float32),
    1e-12 for float64 (noiselab's float32 generators leak 1e-12 to 1e-9).

    Parameters
    ----------
    field : array_like or PowerSpectrum
        1-, 2- or 3-D; for the spatial band of a video ``(frames, height, width)`` pass ``axes=(-2, -1)``
        (a :class:`noiselab.analysis.PowerSpectrum` is used as it is).
    band : (lo, hi)
        Cycles/frame, inclusive.
    max_leakage : float, optional
        Allowed fraction of the power outside the band (0 to 1).
    window : {None, "hann"}
    axes : tuple of int, optional
        The axes whose radial frequency is tested (default: all).

    Returns
    -------
    BandLimitCheck

    Raises
    ------
    AssertionError
        If more than ``max_leakage`` of the power lies outside ``band``.
    ValueError, TypeError
        For bad input, naming the parameter.

    Examples
    --------
    >>> import noiselab
    >>> from noiselab.testing import assert_band_limited
    >>> img = noiselab.spectral_noise((128, 128), band=(8, 32), rng=0)
    >>> assert_band_limited(img, (8, 32)).leakage < 1e-9
    True
    >>> assert_band_limited(img, (8, 16))
    Traceback (most recent call last):
    ...
    AssertionError: band limit: ...
    """
    __tracebackhide__ = HIDE_ASSERTION_FRAMES  # a failure reports the caller's line and the message
    if isinstance(field, PowerSpectrum):
        spec = field  # computed once for several checks
    else:
        spec = power_spectrum(field, window=_check_window(window), axes=axes)
    if max_leakage is None:
        max_leakage = 1.4e-6 if spec.power.dtype == np.float32 else 1e-12
        how = f"default {max_leakage:g}: the rounding floor of {spec.power.dtype} arithmetic with a wide margin"
    else:
        max_leakage = check_real("max_leakage", max_leakage, lo=0.0, hi=1.0)
        how = f"given max_leakage {max_leakage:g}"
    inside = band_energy(spec, band)  # validates band
    lo, hi = band[0], band[1]
    below = band_energy(spec, (float(lo) * 1e-9, float(lo) * (1 - 1e-9)))
    leak = max(0.0, 1.0 - inside)
    above = max(0.0, leak - below)
    msg = (f"band limit: {leak:.3g} of the power lies outside {float(lo):g} <= f <= {float(hi):g} cycles/frame "
           f"({below:.3g} below, {above:.3g} above), allowed {how}")
    if not leak <= max_leakage:
        raise AssertionError(msg)
    return BandLimitCheck(leakage=leak, below=below, above=above, max_leakage=max_leakage,
                          band=(float(lo), float(hi)), message=msg)


# ------------------------------------------------------------------------------------------- isotropy

@dataclass(frozen=True)
class IsotropyCheck:
    """Orientation modulation of the power and its test.

    Attributes
    ----------
    depth2, depth4 : float
        Fitted relative modulation of the power, ``1 + depth2 cos 2(theta - phi2) + depth4 cos 4(theta - phi4)``:
        one preferred orientation (``depth2``) and an axis cross (``depth4``).
    angle2 : float
        ``phi2`` in degrees (wave-vector angle of the stronger orientation).
    statistic : float
        The score statistic, chi-square with 4 dof for an isotropic Gaussian field.
    threshold : float
        Its ``1 - false_alarm`` quantile (what it was compared with unless ``tol`` was given).
    error : float
        Standard error of each modulation component.
    cells : int
    band : (lo, hi)
    message : str
    """

    depth2: float
    depth4: float
    angle2: float
    statistic: float
    threshold: float
    error: float
    cells: int
    band: tuple
    message: str


def orientation_modulation(cells, lo, hi, min_cells=12):
    """Fit of the whitened cells' power to ``1 + b . (cos 2t, sin 2t, cos 4t, sin 4t)``, ring by ring.

    Each cell is divided by a smooth radial level (the ring medians over
    ``ln 2``, interpolated in log-log at the cell's radius: a steep spectrum
    is whitened within its rings too), then by its ring's median over
    ``ln 2`` -- medians, so that the few cells of a grating or a stripe
    pattern keep their excess instead of raising their ring's level. The
    orientation vectors ``a`` are centred ring by ring (a ring's scale then
    cannot leak into ``b``). For an isotropic Gaussian field the whitened
    power ``z`` is exponential over a median estimate of its scale:
    variance ``v = 1 + 6.2 / m`` for a ring of ``m`` cells (the delta method:
    the median of ``m`` exponentials has variance ``1 / m``, over
    ``ln(2)**2``, and ``E[1/s**2] = 1 + 3 var(s)``). The weighted least
    squares ``b = M**-1 u``, ``u = sum a z / v``, ``M = sum a a^T / v``, and the
    score statistic ``T = u^T M**-1 u`` is chi-square with 4 dof for many
    cells (divided by the window's variance factor; :func:`isotropy_null`
    for few). Returns ``(b, T, M, n, geometry)`` or None.
    """
    kx, ky = cells.components[-1], cells.components[-2]
    sel = (cells.radius >= lo) & (cells.radius <= hi)
    ring = ring_index(cells.radius[sel])
    _, inv, cnt = np.unique(ring, return_inverse=True, return_counts=True)
    sel_idx = np.flatnonzero(sel)[(cnt >= min_cells)[inv]]
    if sel_idx.size < 8:
        return None
    r, p = cells.radius[sel_idx], cells.power[sel_idx]
    ring = ring_index(r)
    _, inv, cnt = np.unique(ring, return_inverse=True, return_counts=True)
    v = (1.0 + 6.2 / cnt)[inv]
    theta = np.arctan2(ky[sel_idx], kx[sel_idx])
    a = np.stack([np.cos(2 * theta), np.sin(2 * theta), np.cos(4 * theta), np.sin(4 * theta)], axis=1)
    a -= (np.stack([np.bincount(inv, weights=a[:, j]) for j in range(4)], axis=1) / cnt[:, None])[inv]
    aw = a / v[:, None]
    m = aw.T @ a
    order = np.argsort(inv, kind="stable")
    ends = np.cumsum(cnt)
    mean_r = np.bincount(inv, weights=r) / cnt
    geometry = dict(inv=inv, aw=aw, minv=np.linalg.inv(m), order=order, key=hash((r.tobytes(), theta.tobytes())),
                    bounds=list(zip(np.concatenate([[0], ends[:-1]]), ends)),
                    interp=_loglog_weights(np.log(r), np.log(mean_r)))
    if cnt.size < 2 or not np.all(_ring_medians(p, geometry) > 0):
        return None  # rings without power carry no orientation
    b, stat = _modulation(p, geometry)
    return b, float(stat) / cells.variance_factor, m, int(p.size), geometry


def _ring_medians(x, geometry):
    """Median of each ring's cells, for every row of ``x`` (cells along the last axis)."""
    order, bounds = geometry["order"], geometry["bounds"]
    xs = x[..., order]
    return np.stack([np.median(xs[..., i:j], axis=-1) for i, j in bounds], axis=-1)


def _loglog_weights(x, xp):
    """Index and weight of the piecewise-linear ``y(x)`` through ``(xp, y)``, extended past both ends.

    The line is linear in the knots' ``y``: ``y(x) = (1 - w) y[i] + w y[i + 1]``
    (``w`` outside ``[0, 1]`` past the ends, along the end segments: flat ends,
    as ``np.interp`` gives, would leave the inner half of the first ring and the
    outer half of the last unwhitened, where a steep spectrum's tilt lines up
    with the grid's angles).
    """
    i = np.clip(np.searchsorted(xp, x) - 1, 0, xp.size - 2)
    w = (x - xp[i]) / (xp[i + 1] - xp[i])
    return i, w


def _modulation(p, geometry):
    """``(b, T)`` of the cells' power ``p`` (one row per draw allowed) for the cells' geometry.

    See :func:`orientation_modulation`; the rings must all have power (the
    caller checks that the ring medians are positive).
    """
    inv, aw, minv = geometry["inv"], geometry["aw"], geometry["minv"]
    i, w = geometry["interp"]
    ln2 = np.log(2.0)
    logmed = np.log(np.maximum(_ring_medians(p, geometry), 1e-300) / ln2)
    level = np.exp((1 - w) * logmed[..., i] + w * logmed[..., i + 1])
    q = p / level
    qmed = _ring_medians(q, geometry) / ln2
    z = q / np.maximum(qmed, 1e-300)[..., inv]
    u = z @ aw
    b = u @ minv
    return b, np.sum(u * b, axis=-1)


# below this many cells the score statistic's tail is heavier than chi-square's (exponential cells, small
# rings, medians): its null moments are then simulated and matched by a scaled chi-square
SMALL_SAMPLE_CELLS = 4000
NULL_DRAWS = 4000


def isotropy_null(geometry, variance_factor):
    """``(scale, dof)`` of the scaled chi-square ``scale * chi2(dof)`` that the score statistic follows.

    Chi-square with 4 dof (scale 1) for many cells; for fewer than
    ``SMALL_SAMPLE_CELLS`` cells the first two moments of the statistic are
    simulated with exponential cells on the same frequency grid
    (``NULL_DRAWS`` draws, a fixed seed: the result is repeatable) and matched
    (Satterthwaite): ``scale = var / (2 mean)``, ``dof = 2 mean**2 / var``.
    """
    n = geometry["inv"].size
    if n >= SMALL_SAMPLE_CELLS:
        return 1.0, 4.0
    key = (geometry["key"], variance_factor)
    if key not in _NULL_CACHE:
        if len(_NULL_CACHE) >= 64:
            _NULL_CACHE.pop(next(iter(_NULL_CACHE)))
        _NULL_CACHE[key] = _simulated_null(geometry, variance_factor)
    return _NULL_CACHE[key]


_NULL_CACHE: dict = {}  # one simulation per frequency grid and band (every seed of a test shares it)


def _simulated_null(geometry, variance_factor):
    n = geometry["inv"].size
    rng = np.random.default_rng(n)
    per_chunk = max(1, 2_000_000 // n)  # draws per chunk: at most 2e6 cells (16 MB) at a time
    sims = []
    for start in range(0, NULL_DRAWS, per_chunk):
        draws = rng.exponential(size=(min(per_chunk, NULL_DRAWS - start), n))
        sims.append(_modulation(draws, geometry)[1] / variance_factor)
    sims = np.concatenate(sims)
    mean, var = float(sims.mean()), float(sims.var(ddof=1))
    return var / (2 * mean), 2 * mean**2 / var


@renamed_parameters(tolerance="tol")
def assert_isotropic(field, *, band=None, tol=None, false_alarm=1e-3, window=None) -> IsotropyCheck:
    """Assert that no orientation dominates the spectrum of an image.

    Every independent cell of the band is whitened by the field's radial
    spectrum (a smooth level, then its ring's median) and the whitened power is
    fitted with ``1 + depth2 cos 2(theta - phi2) + depth4 cos 4(theta - phi4)``:
    ``depth2`` sees one preferred orientation (oriented texture, stripes,
    motion streaks), ``depth4`` an axis-aligned cross (a lattice). For an
    isotropic Gaussian field the cells are exponential with variance 1, and
    the score statistic ``T`` of the four components is chi-square with 4
    degrees of freedom (below 4000 cells its tail is heavier: a scaled
    chi-square whose two moments are simulated with exponential cells on the
    same grid, 4000 draws, once per grid); the field fails when ``T`` exceeds
    its ``1 - false_alarm`` quantile. The depths are reported as the effect size
    (a 5 % anisotropy is ``depth2 = 0.05``); their standard error is about
    ``sqrt(2 / cells)``.

    Parameters
    ----------
    field : array_like
        2-D image (for a video, pass a frame).
    band : (lo, hi), optional
        Cycles/frame; default from 2 cycles/frame to Nyquist (N/2), clipped to
        where the image has power.
    tol : float, optional
        Largest allowed modulation depth (``max(depth2, depth4)``) instead of
        the statistical test (for fields that are not Gaussian, or to accept a
        known small anisotropy).
    false_alarm : float
        Probability that an isotropic Gaussian field fails.
    window : {None, "hann"}

    Returns
    -------
    IsotropyCheck

    Raises
    ------
    AssertionError
        If an orientation (or the axes) dominates.
    ValueError, TypeError
        For bad input, naming the parameter.

    Examples
    --------
    >>> import numpy as np, noiselab
    >>> from noiselab.testing import assert_isotropic
    >>> img = noiselab.spectral_noise((128, 128), exponent=1.0, rng=1)
    >>> assert_isotropic(img).depth2 < 0.1
    True
    >>> stripes = img + np.sin(2 * np.pi * 8 * np.arange(128) / 128)
    >>> assert_isotropic(stripes)
    Traceback (most recent call last):
    ...
    AssertionError: isotropy: ...
    """
    __tracebackhide__ = HIDE_ASSERTION_FRAMES  # a failure reports the caller's line and the message
    spec = _spectrum("field", field, (2,), window)
    alpha_fa = check_false_alarm(false_alarm)
    tol = None if tol is None else check_real("tol", tol, lo=0.0, hi=1e6)
    cells = independent_cells(spec)
    (lo, hi), origin = _band(cells, band, lambda n: (2.0, n / 2.0), "isotropy")
    fit = orientation_modulation(cells, lo, hi)
    where = f"over {lo:g} <= f <= {hi:g} cycles/frame ({origin})"
    if fit is None:
        raise AssertionError(f"isotropy: too few cells {where} to measure orientation (rings of at least 8 cells)")
    b, stat, m, n, geometry = fit
    depth2, depth4 = float(np.hypot(b[0], b[1])), float(np.hypot(b[2], b[3]))
    angle2 = float(np.rad2deg(np.arctan2(b[1], b[0])) / 2.0) % 180.0
    se = float(np.sqrt(cells.variance_factor * np.mean(np.diag(np.linalg.inv(m)))))
    measured = (f"orientation modulation of the power {depth2:.3%} (2-fold, at {angle2:.0f} deg) and {depth4:.3%} "
                f"(4-fold, axes) +- {se:.2%} each, {where}, from {n} independent cells")
    scale, dof = isotropy_null(geometry, cells.variance_factor)
    thr = float(scale * stats.chi2.isf(alpha_fa, dof))
    law = ("chi-square with 4 dof" if dof == 4.0 else
           f"{scale:.2f} x chi-square with {dof:.1f} dof, moments simulated for {n} exponential cells")
    if tol is None:
        ok = stat <= thr
        how = (f"score statistic {stat:.1f}, allowed {thr:.1f}: the 1 - false_alarm quantile (false_alarm="
               f"{alpha_fa:g}) of its law for exponential (Gaussian-field) cells, {law}")
    else:
        ok = max(depth2, depth4) <= tol
        how = f"allowed depth {tol:g} (given tolerance; score statistic {stat:.1f})"
    msg = f"isotropy: {measured}; {how}"
    if not ok:
        raise AssertionError(msg)
    return IsotropyCheck(depth2=depth2, depth4=depth4, angle2=angle2, statistic=stat, threshold=thr, error=se,
                         cells=n, band=(lo, hi), message=msg)


# ------------------------------------------------------------------------------------------- lattice axes

@dataclass(frozen=True)
class AxisCheck:
    """Power on the frequency axes against the rest of each ring.

    Attributes
    ----------
    axis_excess : float
        :attr:`noiselab.analysis.AxisArtefacts.axis_excess`: mean whitened power of the axis cells (1 when isotropic).
    interval : (lo, hi)
        The range it had to fall in.
    cells : int
        Independent axis cells in the band.
    band : (lo, hi)
    message : str
    """

    axis_excess: float
    interval: tuple
    cells: int
    band: tuple
    message: str


def axis_null(cells, lo, hi):
    """Mean and variance of ``axis_excess`` for a Gaussian field without artefacts, and the axis-cell count.

    Each axis cell is ``X / Y``: ``X`` exponential, ``Y`` the mean of the
    ``m`` off-axis cells of its ring (Gamma with shape ``m``, scale ``1/m``);
    ``E[1/Y] = m/(m-1)``, ``E[1/Y**2] = m**2 / ((m-1)(m-2))``, and cells of one
    ring share ``Y`` (hence a covariance).
    """
    kx, ky = cells.components[-1], cells.components[-2]
    on = (kx == 0) | (ky == 0)
    ring = ring_index(cells.radius)
    n_ring = int(ring.max()) + 1
    m = np.bincount(ring[~on], minlength=n_ring).astype(np.float64)
    inb = on & (cells.radius >= lo) & (cells.radius <= hi)
    k = np.bincount(ring[inb], minlength=n_ring).astype(np.float64)
    use = (k > 0) & (m > 2)
    k, m = k[use], m[use]
    n = float(k.sum())
    if n == 0:
        return None
    e1 = m / (m - 1)
    e2 = m**2 / ((m - 1) * (m - 2))
    mean = float(np.sum(k * e1)) / n
    var = float(np.sum(k * (2 * e2 - e1**2) + k * (k - 1) * (e2 - e1**2))) / n**2
    return mean, var, int(n)


def assert_no_axis_artefacts(field, *, band=None, false_alarm=1e-3, window=None) -> AxisCheck:
    """Assert that the frequency axes of an image hold what the rest of each ring holds (no lattice cross).

    Measures :func:`noiselab.analysis.axis_artefacts`' ``axis_excess``: the
    mean power of the axis cells (``kx = 0`` or ``ky = 0``), each divided by
    its ring's mean power off the axes. An axis-aligned lattice puts its
    spectral tails on the axes (excess above 1) or a separable main lobe
    that is narrower there (below 1). For a Gaussian field without
    artefacts each axis cell is an exponential over a Gamma ring mean; the
    excess then has a known mean and variance (:func:`axis_null`), and the
    field fails outside the two-sided ``false_alarm`` interval of a Gamma law
    matched to them.

    Parameters
    ----------
    field : array_like
        2-D image, periodic (or pass ``window="hann"``: a non-periodic
        image's edge jump itself puts a cross on the axes).
    band : (lo, hi), optional
        Cycles/frame; default (2, N/2).
    false_alarm : float
    window : {None, "hann"}

    Returns
    -------
    AxisCheck

    Raises
    ------
    AssertionError
        If the axes hold too much or too little power.
    ValueError, TypeError
        For bad input, naming the parameter.

    Examples
    --------
    >>> import numpy as np, noiselab
    >>> from noiselab.testing import assert_no_axis_artefacts
    >>> img = noiselab.spectral_noise((128, 128), exponent=1.0, rng=2)
    >>> 0.5 < assert_no_axis_artefacts(img).axis_excess < 1.5
    True
    >>> rows = img + 0.3 * np.random.default_rng(0).standard_normal((1, 128))   # every row the same profile
    >>> assert_no_axis_artefacts(rows)
    Traceback (most recent call last):
    ...
    AssertionError: axis artefacts: ...
    """
    __tracebackhide__ = HIDE_ASSERTION_FRAMES  # a failure reports the caller's line and the message
    spec = _spectrum("field", field, (2,), window)
    alpha_fa = check_false_alarm(false_alarm)
    cells = independent_cells(spec)
    (lo, hi), origin = _band(cells, band, lambda n: (2.0, n / 2.0), "axis artefacts")
    null = axis_null(cells, lo, hi)
    where = f"over {lo:g} <= f <= {hi:g} cycles/frame ({origin})"
    if null is None:
        raise AssertionError(f"axis artefacts: no axis cell {where}")
    mean, var, n = null
    var *= cells.variance_factor
    excess = axis_artefacts(np.asarray(field), (lo, hi), window=window).axis_excess
    shape, scale = mean**2 / var, var / mean
    interval = (float(stats.gamma.ppf(alpha_fa / 2, shape, scale=scale)),
                float(stats.gamma.isf(alpha_fa / 2, shape, scale=scale)))
    msg = (f"axis artefacts: the {n} independent cells on the frequency axes {where} hold {excess:.3f} times their "
           f"rings' mean power off the axes; allowed {interval[0]:.3f}..{interval[1]:.3f} (false_alarm="
           f"{alpha_fa:g}, two-sided: exponential cells over Gamma ring means, mean {mean:.3f}, SD {math.sqrt(var):.3f})")
    if not (interval[0] <= excess <= interval[1]):
        raise AssertionError(msg)
    return AxisCheck(axis_excess=float(excess), interval=interval, cells=n, band=(lo, hi), message=msg)

