"""From a field to the display values that show it at a stated mean luminance and contrast.

:func:`to_display` scales a field's deviations from its mean to luminances
(cd/m²) with the requested mean and contrast, inverts the display's
luminance response and returns integer display values. With ``dither=True``
each pixel takes one of the two display values around its luminance at random
(seeded), with the probability that makes its *expected* luminance the
requested one, so contrasts far below one display step survive on average
(0.004 on an 8-bit display); without dithering it takes the nearer of the two.

A Gaussian field has tails: at a high RMS contrast its extremes leave the
display's range although almost every pixel fits. ``clip=k`` clips the field
at ``k`` standard deviations before the scaling, which then makes the
requested contrast hold for the clipped field; ``full_output=True`` reports
the fraction of samples clipped (:class:`DisplayReport`).
"""
from __future__ import annotations

import math
import numbers
from typing import NamedTuple

import numpy as np

from .._core import as_generator, check_finite_array, check_memory, check_real, renamed_parameters
from .display import Display
from .scramble import _power_of_two_scaled

__all__ = ["to_display", "luminance_for", "CONTRAST_KINDS", "DisplayReport"]

CONTRAST_KINDS = ("rms", "michelson")


class DisplayReport(NamedTuple):
    """What :func:`to_display` did besides the display values (``full_output=True``): clipping and the range asked."""

    clipped_fraction: float   # share of the field's samples clipped at +-clip standard deviations (0.0 without clip)
    clip: float | None        # the clip asked for, in standard deviations (None: none)
    luminance_range: tuple    # (darkest, brightest) luminance requested, cd/m², before display values are chosen


@renamed_parameters(kind="contrast_kind")
def luminance_for(field, *, mean, contrast, contrast_kind="rms", clip=None, aperture=None, full_output=False):
    """The luminance (cd/m², float64) a field is shown at: mean ``mean`` and contrast ``contrast`` exactly.

    The field's own mean is removed and its deviations scaled by one factor:
    ``L = mean * (1 + k * (field - field.mean()))``, with ``k`` such that
    ``std(L) / mean(L) = contrast`` (``contrast_kind="rms"``) or
    ``(max L - min L) / (max L + min L) = contrast`` (``"michelson"``); the
    mean is ``mean`` in both (for a field whose extremes are not symmetric
    about its mean the Michelson midpoint ``(max + min) / 2`` is not the
    mean).

    Parameters
    ----------
    field : array_like
        Any real, finite, non-constant array (image, video, volume).
    mean : float
        Mean luminance, cd/m², > 0.
    contrast : float
        RMS contrast (> 0) or Michelson contrast (in ``(0, 1]``).
    contrast_kind : {"rms", "michelson"}
    clip : float or None
        As :func:`to_display`: None (default) keeps the field as it is; ``k >
        0`` clips its deviations at ``k`` standard deviations first, and the
        clipped field then gets the requested mean and contrast.
    aperture : array_like or None
        As :func:`to_display`: weights in ``[0, 1]`` broadcasting against the
        field; ``L = mean * (1 + w * k * z)`` with the contrast stated inside
        the window (``w``-weighted RMS, or Michelson over ``w > 0``).
    full_output : bool
        False (default): return the luminance. True: ``(luminance, report)``
        with the :class:`DisplayReport` of :func:`to_display` (clipped
        fraction, clip, luminance range).

    Returns
    -------
    ndarray, float64, the shape of ``field``.
    DisplayReport
        Only with ``full_output=True``.

    Raises
    ------
    ValueError
        A constant field, a contrast out of its range, or (RMS) a contrast so
        large that some luminance would be negative (the message names the
        largest RMS contrast, and a ``clip`` that keeps the request).

    Examples
    --------
    >>> import numpy as np
    >>> L = luminance_for(np.array([-1.0, 0.0, 1.0, 0.0]), mean=50.0, contrast=0.5, contrast_kind="michelson")
    >>> L.tolist()
    [25.0, 50.0, 75.0, 50.0]

    Clipped at 3 standard deviations, inside a circle of 12 px on a 32-pixel-per-degree screen:

    >>> from noiselab.stimuli import Display, circular_aperture
    >>> x = np.random.default_rng(0).standard_normal((64, 64))
    >>> w = circular_aperture((64, 64), Display(32.0), diameter_deg=0.375)
    >>> L, report = luminance_for(x, mean=50.0, contrast=0.25, clip=3.0, aperture=w, full_output=True)
    >>> bool(report.clipped_fraction < 0.01), float(L[w == 0].min()) == float(L[w == 0].max()) == 50.0
    (True, True)
    """
    kind = contrast_kind
    if not isinstance(full_output, (bool, np.bool_)):
        raise TypeError(f"full_output must be True or False, got {full_output!r}")
    if clip is not None:
        clip = check_real("clip (standard deviations)", clip, lo=0.0, lo_open=True, hi=1e6)
    w = None if aperture is None else _check_aperture(aperture, np.shape(field))
    fraction, source = 0.0, field
    if clip is not None:
        source, fraction = _clip_sd(field, clip)
    L, sd, zmin = _luminance(source, mean, contrast, kind, w)
    del source
    if kind == "rms" and float(L.min()) < 0:
        hint = ""
        k, frac = _largest_clip(field, mean, contrast, 0.0, np.inf, w)
        if k is not None and clip is None:
            hint = f"; clip={k:g} (standard deviations) keeps it, clipping {100 * frac:.3g} % of the samples"
        largest = -contrast * float(mean) / (float(L.min()) - float(mean))
        raise ValueError(f"contrast (RMS) = {contrast:g} makes the darkest pixel's luminance negative for this "
                         f"field; the largest RMS contrast it allows is {largest:.6g}{hint}")
    if full_output:
        return L, DisplayReport(fraction, clip, (float(L.min()), float(L.max())))
    return L


def _luminance(field, mean, contrast, kind, w=None):
    """:func:`luminance_for`'s luminance, negative where an RMS contrast asks for it; also the normalised sd and min.

    With an aperture ``w`` (weights in [0, 1] broadcast against the field) the field is centred on its
    ``w``-weighted mean, its contrast is measured with the weights ``w`` (RMS) or over ``w > 0`` (Michelson),
    and its deviations are multiplied by ``w``: ``L = mean * (1 + w * k * z)``.
    """
    f = check_finite_array("field", field)
    if f.size == 0:
        raise ValueError("field is empty")
    mean = check_real("mean (cd/m²)", mean, lo=0.0, lo_open=True, hi=1e12)
    if kind not in CONTRAST_KINDS:
        raise ValueError(f"contrast_kind must be one of {CONTRAST_KINDS}, got {kind!r}")
    if kind == "michelson":
        contrast = check_real("contrast (Michelson)", contrast, lo=0.0, hi=1.0, lo_open=True)
    else:
        contrast = check_real("contrast (RMS)", contrast, lo=0.0, lo_open=True, hi=1e6)
    check_memory(f.size * 8 * 3, f"luminance of a field of shape {f.shape}")
    # scaled by a power of two (exact; the normalisation below undoes it): the mean's sum of a field near
    # float64's largest value would overflow
    z = _power_of_two_scaled(f)[0]
    if w is None:
        z -= z.mean()
        inside = z
    else:
        w = np.broadcast_to(w, z.shape)
        total = float(w.sum())
        z -= float(np.sum(w * z)) / total
        inside = z[w > 0]
    zmin, zmax = float(inside.min()), float(inside.max())
    if zmax - zmin == 0 or not np.isfinite(zmax - zmin):
        raise ValueError("field must vary" + (" inside the aperture" if w is not None else "")
                         + " (a constant field has no contrast to scale)")
    scale = max(abs(zmin), abs(zmax), float(np.max(np.abs(z))))
    z /= scale  # scale-free from here: neither the squares nor the sums overflow
    zmin, zmax = zmin / scale, zmax / scale
    if kind == "rms":
        sd = float(z.std()) if w is None else float(np.sqrt(np.sum(w * z * z) / total))
        if sd == 0:
            raise ValueError("field must vary (its standard deviation is 0 in float64)")
        k = contrast / sd
    else:
        # (Lmax - Lmin) / (Lmax + Lmin) = k d / (2 + k s) = C  =>  k = 2 C / (d - C s); d - C s > 0 as zmin < 0 < zmax
        k = 2.0 * contrast / ((zmax - zmin) - contrast * (zmax + zmin))
    z *= k
    if w is not None:
        z *= w
    z += 1.0
    z *= mean
    if kind == "michelson":
        np.maximum(z, 0.0, out=z)  # (rounding: 1 + k*zmin may be -1e-16 at Michelson contrast 1; exactly it is >= 0)
    return z, sd if kind == "rms" else None, zmin


def _clip_sd(field, k):
    """The field less its mean, clipped at ``k`` standard deviations (scaled by a power of two), and the fraction clipped."""
    f = check_finite_array("field", field)
    if f.size == 0:
        raise ValueError("field is empty")
    check_memory(f.size * 8 * 2, f"clipping a field of shape {f.shape}")
    z = _power_of_two_scaled(f)[0]
    z -= z.mean()
    lim = k * float(z.std())
    if lim == 0:
        return z, 0.0   # a constant field: _luminance names it
    frac = float(np.count_nonzero(np.abs(z) > lim)) / z.size
    np.clip(z, -lim, lim, out=z)
    return z, frac


def _clipped_range(z, k, contrast, w):
    """The relative luminance range ``(min, max) / mean - 1`` of ``z`` clipped at ``k`` sd and scaled to RMS ``contrast``.

    (As :func:`_luminance` scales it, through the aperture ``w`` when there is one.)
    """
    lim = k * float(z.std())
    c = np.clip(z, -lim, lim)
    if w is None:
        c -= c.mean()
        c *= contrast / float(c.std())
    else:
        c -= float(np.sum(w * c)) / float(w.sum())
        c *= contrast / float(np.sqrt(np.sum(w * c * c) / float(w.sum())))
        c *= w
    return float(c.min()), float(c.max())


def _largest_clip(field, mean, contrast, lo, hi, w=None):
    """The largest ``clip`` (sd, rounded down to 0.01) at which an RMS request fits ``[lo, hi]``, or None; its fraction."""
    z = _clip_sd(field, np.inf)[0]
    sd = float(z.std())
    if w is not None:
        w = np.broadcast_to(w, z.shape)

    def fits(k):
        a, b = _clipped_range(z, k, contrast, w)
        return mean * (1 + a) >= lo and mean * (1 + b) <= hi

    k_lo, k_hi = 0.01, float(np.max(np.abs(z))) / sd
    if not fits(k_lo):
        return None, None
    for _ in range(30):   # the range needed grows with k (more of the tails kept): bisect for the edge
        mid = 0.5 * (k_lo + k_hi)
        k_lo, k_hi = (mid, k_hi) if fits(mid) else (k_lo, mid)
    k = max(0.01, math.floor(k_lo * 100) / 100)
    return k, float(np.count_nonzero(np.abs(z) > k * sd)) / z.size


@renamed_parameters(seed="rng", kind="contrast_kind")
def to_display(field, display, *, mean, contrast, contrast_kind="rms", dither=True, rng=None, clip=None,
               aperture=None, full_output=False):
    """Integer display values that show ``field`` at mean luminance ``mean`` (cd/m²) and the given contrast.

    Parameters
    ----------
    field : array_like
        Any real, finite, non-constant array: a noise image, a snow video, a
        composite. Its own mean is removed (see :func:`luminance_for`).
    display : Display
        The screen (luminance range, gamma law or measured table, bits).
    mean : float
        Mean luminance, cd/m², inside the display's ``luminance`` range.
    contrast : float
        ``contrast_kind="rms"``: standard deviation over mean of the luminance, > 0.
        ``contrast_kind="michelson"``: ``(max - min) / (max + min)``, in ``(0, 1]``.
    contrast_kind : {"rms", "michelson"}
    dither : bool
        True (default): random dithering between the two display values
        around each requested luminance, with probabilities that make the
        expected luminance of every pixel exactly the requested one. False:
        the display value of the nearer luminance. With ``contrast_kind="michelson"``
        the darkest and the brightest pixel then get the pair of display
        values (each just below or above its request) whose Michelson
        contrast is nearest the request, and every other value is bounded by
        them: the dither cannot widen the contrast by a step (only pixels
        within one step of the two ends lose their exact expectation).
    rng : int, numpy.random.Generator or None
        The dither: each pixel's threshold is uniform and independent of the
        others; consecutive int seeds shift them along a golden-ratio (Weyl)
        sequence, so the average of ``N`` frames dithered with seeds
        ``s .. s+N-1`` is the request to about ``1/N`` of a step at every
        pixel (temporal dithering).
    clip : float or None
        None (default): the field as it is; a request whose extremes leave the
        display is refused. A number ``k > 0``: the field's deviations from
        its mean are first clipped at ``k`` standard deviations, then scaled
        so that the *clipped* field has the requested mean and contrast (the
        RMS contrast is the request exactly, not the request times the
        clipped field's smaller spread). The fraction of samples clipped is
        in the report (``full_output=True``).
    aperture : array_like or None
        None (default): the whole field. Weights in ``[0, 1]`` that broadcast
        against the field (an ``(ny, nx)`` window serves every frame of a
        video), e.g. from :func:`circular_aperture`,
        :func:`raised_cosine_aperture` or :func:`gaussian_aperture`: the
        field is shown as ``L = mean * (1 + w * k * z)``, blending to the
        mean luminance where ``w`` is 0, and its contrast is stated inside
        the window: ``z`` is centred on its ``w``-weighted mean and ``k``
        makes its ``w``-weighted RMS contrast (or its Michelson contrast over
        ``w > 0``) the request. In a hard circle that is the contrast of the
        luminance inside it; in a tapered window it is the carrier's contrast
        where the window is 1 (as "a Gabor of contrast c" states it). The
        mean of ``L`` over the whole frame is ``mean``.
    full_output : bool
        False (default): return the display values. True: return
        ``(values, report)`` with a :class:`DisplayReport` (the clipped
        fraction, the clip, the luminance range requested).

    Returns
    -------
    ndarray
        Display values, uint8 for displays of up to 8 bits, uint16 above;
        ``display.luminance_of(values)`` is the luminance shown.
    DisplayReport
        Only with ``full_output=True``.

    Raises
    ------
    ValueError
        A request the display cannot show: the mean or some pixel's luminance
        outside the display's ``[L_min, L_max]`` (the message gives the range
        needed, the display's, and the largest contrast that fits); a
        contrast out of its range; a constant field; a ``clip`` that is not
        a positive number. For an RMS request the refusal also names the
        largest ``clip=`` that makes it fit and the fraction it clips.
    TypeError
        ``display`` not a :class:`Display`.

    Notes
    -----
    Measured on 8-bit and 10-bit gamma-2.2 displays (``tests/test_stimuli.py``):
    the RMS and Michelson contrast of ``luminance_of(to_display(...))`` are
    within 2 % of the request and the mean within 1 %; at an RMS contrast of
    0.002 (a request about one display step wide) the luminance averaged over
    64 consecutive dither seeds is within 0.2 step of the request at every
    pixel (``benchmarks/bench_stimuli.md``: 0.04 step at 128 x 128).

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab import Display, spectral_noise
    >>> d = Display(32.0, luminance=(0.5, 100.0), gamma=2.2, bits=8)
    >>> x = spectral_noise((128, 128), band=d.band((1, 8), 128), rng=0)
    >>> v = to_display(x, d, mean=40.0, contrast=0.2, rng=1)
    >>> v.dtype, v.shape
    (dtype('uint8'), (128, 128))
    >>> L = d.luminance_of(v)
    >>> round(float(L.mean()), 1), round(float(L.std() / L.mean()), 2)
    (40.0, 0.2)

    A Gaussian 1/f patch at RMS contrast 0.25 around 50 cd/m² needs about
    -1.8 to 103.8 cd/m² (its tails) on a 0.5 to 100 cd/m² display; clipped at 3 standard
    deviations it fits:

    >>> x = spectral_noise((256, 256), exponent=1.0, rng=0)
    >>> v, report = to_display(x, d, mean=50.0, contrast=0.25, clip=3.0, rng=1, full_output=True)
    >>> L = d.luminance_of(v)
    >>> round(float(L.std() / L.mean()), 2), report.clipped_fraction < 0.01
    (0.25, True)
    """
    if not isinstance(display, Display):
        raise TypeError(f"display must be a noiselab.Display, got {type(display).__name__}")
    if not isinstance(dither, (bool, np.bool_)):
        raise TypeError(f"dither must be True or False, got {dither!r}")
    if not isinstance(full_output, (bool, np.bool_)):
        raise TypeError(f"full_output must be True or False, got {full_output!r}")
    if clip is not None:
        clip = check_real("clip (standard deviations)", clip, lo=0.0, lo_open=True, hi=1e6)
    w = None if aperture is None else _check_aperture(aperture, np.shape(field))
    lo, hi = display.luminance
    mean = check_real("mean (cd/m²)", mean, lo=0.0, lo_open=True, hi=1e12)
    if not lo <= mean <= hi:
        raise ValueError(f"mean = {mean:g} cd/m² is outside the display's range [{lo:g}, {hi:g}] cd/m² "
                         f"(luminance=(L_min, L_max))")
    kind = contrast_kind
    fraction = 0.0
    source = field
    if clip is not None:
        source, fraction = _clip_sd(field, clip)
    L = _luminance(source, mean, contrast, kind, w)[0]  # (a negative luminance is out of range below)
    del source
    Lmin, Lmax = float(L.min()), float(L.max())
    # a request that exactly fills the range (e.g. the largest contrast this error reports) may land a rounding
    # past an end: within 1e-9 of the range it is that end, not a refusal
    slack = 1e-9 * (hi - lo)
    if lo - slack <= Lmin < lo or hi < Lmax <= hi + slack:
        L = np.clip(L, lo, hi)
        Lmin, Lmax = max(Lmin, lo), min(Lmax, hi)
    if Lmin < lo or Lmax > hi:
        # the largest contrast that fits scales the deviations down to the nearer limit
        room = min((hi - mean) / (Lmax - mean) if Lmax > mean else np.inf,
                   (mean - lo) / (mean - Lmin) if Lmin < mean else np.inf)
        best = _contrast_of(L, kind, mean, room)
        clipped = "" if clip is None else f" clipped at clip={clip:g} standard deviations"
        hint = "clip=K (standard deviations) clips the field's tails; "
        if kind == "rms":
            k, frac = _largest_clip(field, mean, contrast, lo, hi, w)
            hint = (f"to keep the contrast, clip the field's tails: clip={k:g} (standard deviations) fits, "
                    f"clipping {100 * frac:.3g} % of the samples; " if k is not None else
                    "no clip=K (standard deviations, clipping the field's tails) fits this mean and contrast; ")
        raise ValueError(f"the display cannot show this request: mean {mean:g} cd/m² at {kind} contrast "
                         f"{contrast:g}{clipped} needs luminances [{Lmin:.6g}, {Lmax:.6g}] cd/m², the display's "
                         f"range is [{lo:g}, {hi:g}] (luminance=(L_min, L_max)); {hint}the largest {kind} contrast "
                         f"that fits at this mean is {best:.6g}")
    check_memory(L.size * 8 * 3, f"display values of a field of shape {L.shape}")
    t = display.table
    v0 = np.searchsorted(t, L, side="right") - 1
    np.clip(v0, 0, display.levels - 2, out=v0)
    below = t[v0]
    p = (L - below) / (t[v0 + 1] - below)  # where L lies between the two values, in luminance
    del below
    if dither:
        up = _thresholds(p.shape, rng) < p   # E[luminance] = below + p * step = L exactly
    else:
        up = p >= 0.5    # the nearer luminance
    v0 += up
    if kind == "michelson" and (w is None or abs((Lmax - Lmin) / (Lmax + Lmin) - float(contrast)) < 1e-9):
        # (in a tapered aperture the carrier's extremes may fall where w < 1: then the luminance's own ends do
        # not set the contrast asked for, and are left as they are)
        _michelson_ends(v0, L, t, float(contrast), display.levels)
    values = v0.astype(np.uint8 if display.bits <= 8 else np.uint16)
    if full_output:
        return values, DisplayReport(fraction, clip, (Lmin, Lmax))
    return values


# the key of the fixed threshold pattern, and the 64-bit golden-ratio step of the offsets (Weyl sequence)
_DITHER_KEY = 0x5EED_D174
_GOLDEN = 0x9E3779B97F4A7C15


def _thresholds(shape, seed):
    """Dither thresholds, uniform on [0, 1): one fixed random pattern shifted (mod 1) by an offset of ``seed``.

    Each pixel's threshold is uniform for any seed, and the pixels are
    independent within an image. An int seed ``s`` gives the offset
    ``frac(s * golden ratio)`` (exactly, in 64-bit integers): consecutive
    seeds step along a Weyl sequence, so over ``N`` consecutive seeds (the
    frames of a temporal dither) every pixel's thresholds are spread evenly
    and its mean luminance is the request to about ``1/N`` of a step rather
    than ``1/(2 sqrt(N))`` for independent draws. A Generator (or None) seed
    draws the offset from it.
    """
    rng = as_generator(seed)   # checks the seed (and draws the offset when it is not an int)
    if isinstance(seed, numbers.Integral) and not isinstance(seed, (bool, np.bool_)):
        offset = ((int(seed) * _GOLDEN) % (1 << 64)) / float(1 << 64)
    else:
        offset = float(rng.random())
    u = np.random.default_rng(_DITHER_KEY).random(shape)
    u += offset
    u -= np.floor(u)
    return u


def _michelson_ends(v, L, t, contrast, levels):
    """Fix the two pixels that set the Michelson contrast, in place, to the display values nearest the request.

    Of the values just below and just above the darkest and the brightest
    requested luminance, the pair whose Michelson contrast is nearest
    ``contrast`` goes to those two pixels, and every other value is bounded
    by it, so neither dithering nor rounding widens or narrows the contrast
    by a step (only pixels within one step of the two ends lose their exact
    expected luminance).
    """
    flat = L.reshape(-1)
    i_lo, i_hi = int(np.argmin(flat)), int(np.argmax(flat))
    e = np.clip(np.searchsorted(t, [flat[i_lo], flat[i_hi]], side="right") - 1, 0, levels - 2)
    best = None
    for lo_v in (int(e[0]), int(e[0]) + 1):
        for hi_v in (int(e[1]), int(e[1]) + 1):
            if hi_v <= lo_v:
                continue
            err = abs((t[hi_v] - t[lo_v]) / (t[hi_v] + t[lo_v]) - contrast)
            if best is None or err < best[0]:
                best = (err, lo_v, hi_v)
    if best is None:
        return
    _, lo_v, hi_v = best
    np.clip(v, lo_v, hi_v, out=v)
    vf = v.reshape(-1)
    vf[i_lo], vf[i_hi] = lo_v, hi_v


def _check_aperture(aperture, shape):
    """An aperture: finite weights in [0, 1], not all 0, that broadcast to the field's ``shape`` (float64)."""
    w = check_finite_array("aperture", aperture).astype(np.float64)
    try:
        ok = np.broadcast_shapes(w.shape, shape) == tuple(shape)
    except ValueError:
        ok = False
    if not ok:
        raise ValueError(f"aperture must broadcast against the field's shape {tuple(shape)} (e.g. the frames' "
                         f"(ny, nx)), got shape {w.shape}")
    if w.size and (w.min() < 0 or w.max() > 1):
        raise ValueError(f"aperture must hold weights in [0, 1], got [{w.min():.6g}, {w.max():.6g}]")
    if not np.any(w > 0):
        raise ValueError("aperture is 0 everywhere: nothing of the field would be shown")
    return w


def _contrast_of(L, kind, mean, room):
    """The contrast of ``mean + room * (L - mean)`` (a request scaled down by ``room``), in ``kind``."""
    if kind == "rms":
        return float(room * L.std() / mean)
    a, b = mean + room * (float(L.max()) - mean), mean + room * (float(L.min()) - mean)
    return (a - b) / (a + b)
