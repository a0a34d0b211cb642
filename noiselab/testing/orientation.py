"""Assert a field's orientation (degrees) and centre spatial frequency (cycles/pixel or cycles/deg).

Both are power-weighted means over the independent periodogram cells of the
field (:func:`noiselab.testing._cells.independent_cells`: one cell of each
mirror pair, each an exponential draw of mean ``S(k)`` for a stationary
Gaussian field), judged with their standard errors:

- orientation: half the angle of ``R = sum_k P(k) exp(2 i phi_k)`` (the
  axial mean of the wave vectors' directions ``phi_k``, x right, y down);
- centre frequency: ``exp(sum_k P(k) ln f_k / sum_k P(k))``, the geometric
  mean of the frequency weighted by power, which for a band symmetric in log
  frequency (log-Gabor, MotionClouds) is where the power per octave peaks.

Each is the root of an estimating equation ``sum_k P(k) g_k(theta) = 0``, so
its variance is ``sum_k Var P(k) g_k**2 / (sum_k P(k) g_k')**2`` (the delta
method), with ``Var P(k) = S(k)**2`` estimated by ``P(k)**2 / 2`` (the
exponential law: ``E P**2 = 2 S**2``) and multiplied by 35/18 per axis a
Hann window tapers.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import special

from .._core import HIDE_ASSERTION_FRAMES, as_array, check_band, check_real
from ..analysis import power_spectrum
from ._cells import independent_cells

__all__ = ["OrientationCheck", "FrequencyCheck", "assert_orientation", "assert_centre_frequency"]


@dataclass(frozen=True)
class OrientationCheck:
    """A measured orientation with its standard error, in degrees.

    Attributes
    ----------
    orientation_deg : float
        Measured orientation of the wave vectors in ``[0, 180)``: 0 for
        vertical stripes, turning clockwise on the screen (y down), as
        PsychoPy's ``ori`` and :func:`noiselab.stimuli.motion_cloud`'s
        ``theta``.
    se : float
        Its standard error, degrees.
    tol : float
        Accepted distance of the expected orientation, degrees.
    modulation : float
        ``|R| / sum P``: 0 for an isotropic field, 1 for a grating.
    cells : int
        Independent cells the mean used.
    message : str
    """

    orientation_deg: float
    se: float
    tol: float
    modulation: float
    cells: int
    message: str


@dataclass(frozen=True)
class FrequencyCheck:
    """A measured centre spatial frequency with its standard error.

    Attributes
    ----------
    sf_0 : float
        Power-weighted geometric mean of the spatial frequency: cycles/pixel,
        or cycles/deg when a ``display`` was given.
    se_octaves : float
        Its standard error, octaves.
    tol_octaves : float
        Accepted distance of the expected frequency, octaves.
    unit : str
        ``"cycles/px"`` or ``"cycles/deg"``.
    cells : int
    message : str
    """

    sf_0: float
    se_octaves: float
    tol_octaves: float
    unit: str
    cells: int
    message: str


def _spatial_cells(name, field, band, window):
    """Power, spatial frequency components (cycles/frame: cycles per width) and the variance factor of the cells."""
    if isinstance(field, (str, bytes)) or field is None:
        raise TypeError(f"{name} must be a numeric array, got {type(field).__name__}")
    arr = as_array(name, field)
    if arr.ndim not in (2, 3):
        raise ValueError(f"{name} must be an image (height, width) or a video (frames, height, width), got "
                         f"{arr.ndim}-D")
    if window not in (None, "hann"):
        raise ValueError(f"window must be None or 'hann', got {window!r}")
    # a video: every 3-D cell is independent; its spatial frequency is what the orientation and centre read
    cells = independent_cells(power_spectrum(arr, window=window))
    cy, cx = cells.components[-2], cells.components[-1]
    r = np.hypot(cy, cx)
    keep = r > 0
    if band is not None:
        lo, hi = check_band("band", band, cells.n_ref / 2.0 * math.sqrt(2.0))
        keep &= (r >= lo) & (r <= hi)
    p = cells.power[keep]
    return p, cy[keep], cx[keep], r[keep], cells.variance_factor, cells.n_ref


def _z(false_alarm):
    return float(-special.ndtri(false_alarm / 2))   # two-sided


def assert_orientation(field, *, orientation_deg, tol=None, false_alarm=1e-3, band=None,
                       window=None) -> OrientationCheck:
    """Assert that a field's power is oriented at ``orientation_deg``: measured ± standard error against expected.

    The orientation is half the angle of ``R = sum_k P(k) exp(2 i phi_k)``
    over the field's independent periodogram cells (``phi_k`` the direction
    of the wave vector, x right, y down; for a video, the spatial frequency of
    every spatio-temporal cell), its standard error
    ``sqrt(sum_k P(k)**2 sin(2 (phi_k - theta))**2 / 2) / (2 |R|)`` (the delta
    method with the exponential law of a Gaussian field's cells). The
    angle convention is that of :func:`noiselab.stimuli.motion_cloud`'s
    ``theta`` and of PsychoPy's ``ori`` for a grating: 0 is a vertical
    grating (waves along x) and a positive angle turns the stripes clockwise
    on the screen; orientations are axial (``theta`` and ``theta + 180`` are
    one). For an orientation band symmetric about its centre (MotionClouds'
    ``B_theta`` band) the expected value is that centre.

    ``benchmarks/bench_orientation.md`` counts the false alarms at the true
    orientation, and the misses at an offset, on MotionClouds' and noiselab's
    clouds across bandwidths (128 x 128 px, HWHM 5 to 45 degrees: at
    ``false_alarm`` 1e-3, 0 or 1 failure in 200 at the truth; 5 degrees off
    fails all 200 up to 15 degrees HWHM, and 42 to 50 % at 45 degrees, whose
    standard error is 1.5 degrees). The standard errors hold for Gaussian
    fields (noiselab's); MotionClouds' ``random_cloud`` has heavier-tailed
    cells (its measurements scatter 1.2 standard errors). A field whose power
    lies in a few cells (a pure grating) is judged unmeasurable: the law
    needs many cells.

    Parameters
    ----------
    field : array_like
        An image ``(height, width)`` or a video ``(frames, height, width)``,
        finite, stationary (a periodic field; pass ``window="hann"`` for one
        that does not tile, whose edges otherwise add power along the axes).
    orientation_deg : float
        Expected orientation, degrees (any real; read modulo 180).
    tol : float, optional
        Accepted distance in degrees (0 to 90). Default: ``z`` standard
        errors with ``z`` the two-sided normal quantile of ``false_alarm``.
    false_alarm : float
        Probability that a field oriented at ``orientation_deg`` fails the
        default tolerance (1e-12 to 0.5), default 1e-3; also the level of the
        test that the field is oriented at all.
    band : (lo, hi), optional
        Spatial band in cycles/frame (default all).
    window : {None, "hann"}

    Returns
    -------
    OrientationCheck

    Raises
    ------
    AssertionError
        In one line, ``measured orientation …±…° against expected …°``; or if
        the field has no measurable orientation (its modulation ``|R|`` is
        within the sampling noise of an isotropic field at ``false_alarm``).
    ValueError, TypeError
        For bad input, naming the parameter.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab.stimuli import motion_cloud
    >>> z = motion_cloud((128, 128), sf_0=0.125, B_sf=0.05, theta=np.radians(30), B_theta=0.2, rng=1)
    >>> check = assert_orientation(z, orientation_deg=30)
    >>> abs(check.orientation_deg - 30) < 3 * check.se
    True
    >>> assert_orientation(z, orientation_deg=36)
    Traceback (most recent call last):
    ...
    AssertionError: measured orientation 29...±...° against expected 36° ...
    """
    __tracebackhide__ = HIDE_ASSERTION_FRAMES  # a failure reports the caller's line and the message
    expected = check_real("orientation_deg", orientation_deg, lo=-1e6, hi=1e6)
    if tol is not None:
        tol = check_real("tol (degrees)", tol, lo=0.0, hi=90.0)
    false_alarm = check_real("false_alarm", false_alarm, lo=1e-12, hi=0.5)
    p, cy, cx, _, factor, _ = _spatial_cells("field", field, band, window)
    n = p.size
    total = float(p.sum())
    if n < 3 or total <= 0:
        raise AssertionError(f"no power to measure an orientation from (expected {expected:g}°; {n} cells)")
    phi = np.arctan2(cy, cx)
    r = complex(np.sum(p * np.exp(2j * phi)))
    # under isotropy Re R and Im R are each about N(0, sum P**2 / 4): a Rayleigh test of the modulation
    null_var = factor * float(np.sum(p * p)) / 4.0
    p_isotropic = math.exp(-abs(r) ** 2 / (2.0 * null_var)) if null_var > 0 else 1.0
    modulation = abs(r) / total
    if p_isotropic > false_alarm:
        raise AssertionError(f"the field has no measurable orientation (modulation |R|/P {modulation:.3g}, as "
                             f"likely as {p_isotropic:.2g} from an isotropic field); expected {expected:g}°")
    theta = 0.5 * math.atan2(r.imag, r.real)
    s = np.sin(2.0 * (phi - theta))
    se = math.degrees(math.sqrt(factor * float(np.sum(p * p * s * s)) / 2.0) / (2.0 * abs(r)))
    measured = math.degrees(theta) % 180.0
    if tol is None:
        z = _z(false_alarm)
        tol_used = min(z * se, 90.0)
        how = f"default tolerance {z:.3g} standard errors, false-alarm rate {false_alarm:g}"
    else:
        tol_used, how = tol, f"given tol {tol:g}°"
    off = (measured - expected + 90.0) % 180.0 - 90.0
    msg = (f"measured orientation {measured:.4g}±{se:.2g}° against expected {expected:g}° (accepted "
           f"±{tol_used:.2g}°: {how}; modulation {modulation:.3g}; {n} cells; 0° = vertical stripes, clockwise "
           "with y down, as PsychoPy's ori)")
    if abs(off) > tol_used:
        raise AssertionError(msg)
    return OrientationCheck(orientation_deg=measured, se=se, tol=tol_used, modulation=modulation, cells=n,
                            message=msg)


def assert_centre_frequency(field, *, sf_0, tol=None, display=None, false_alarm=1e-3, band=None,
                            window=None) -> FrequencyCheck:
    """Assert a field's centre spatial frequency: measured ± standard error against ``sf_0``.

    The centre is the power-weighted geometric mean of the spatial frequency,
    ``exp(sum_k P(k) ln f_k / sum_k P(k))`` over the independent periodogram
    cells (for a video, over every spatio-temporal cell, by its spatial
    frequency), with the standard error
    ``sqrt(sum_k P(k)**2 (ln f_k - ln f_c)**2 / 2) / sum_k P(k)`` in natural
    log units (the delta method with the exponential law of a Gaussian
    field's cells), reported in octaves.

    Where that lies for MotionClouds' log-Gabor band (``sf_0``, ``B_sf``,
    ``s = ln((sf_0 + B_sf) / sf_0)``): a still cloud's power per unit log
    frequency is ``exp(-ln(f / sf_0)**2 / s**2)``, symmetric about
    ``sf_0``, so its centre *and* the peak of its power per octave are
    ``sf_0``; a drifting cloud's speed band is ``B_V |f|`` wide in temporal
    frequency, which weights the power by ``f`` and moves the centre of a
    video to ``sf_0 exp(s**2 / 2)`` (:mod:`noiselab.stimuli.bandwidth`). The
    power per frequency cell peaks lower, at ``sf_0 exp(-s**2)``: a "peak"
    read off a periodogram's brightest cell is not ``sf_0``. Bands cut by the
    Nyquist frequency or reaching the lowest cells shift the centre; pass
    ``band=`` to measure inside a band.

    ``benchmarks/bench_orientation.md`` counts the false alarms at the true
    centre and the misses at an offset on MotionClouds' and noiselab's clouds
    (128 x 128 px, 0.5 to 2 octaves: at ``false_alarm`` 1e-3, at most 2
    failures in 200 at the truth; 5 % off fails all 200 up to one octave,
    79 to 92 % at two octaves; 10 % off fails every field).

    Parameters
    ----------
    field : array_like
        An image ``(height, width)`` or a video ``(frames, height, width)``, finite, stationary.
    sf_0 : float
        Expected centre, cycles/pixel (> 0, up to 0.75), or cycles/deg when
        ``display`` is given.
    tol : float, optional
        Accepted distance in octaves (0 to 10). Default: ``z`` standard
        errors with ``z`` the two-sided normal quantile of ``false_alarm``.
    display : noiselab.Display, optional
        Read ``sf_0`` (and report the measurement) in cycles/deg through
        ``display.cycles_per_pixel`` / ``display.cycles_per_degree``.
    false_alarm : float
        Probability that a field centred at ``sf_0`` fails the default
        tolerance (1e-12 to 0.5), default 1e-3.
    band : (lo, hi), optional
        Spatial band in cycles/frame (default all).
    window : {None, "hann"}

    Returns
    -------
    FrequencyCheck

    Raises
    ------
    AssertionError
        In one line: ``measured centre frequency …±… cycles/px (±… octaves)
        against expected …``.
    ValueError, TypeError
        For bad input, naming the parameter.

    Examples
    --------
    >>> from noiselab import Display
    >>> from noiselab.stimuli import motion_cloud
    >>> d = Display(32.0)
    >>> z = motion_cloud((128, 128), sf_0=d.cycles_per_pixel(4.0), B_sf=d.cycles_per_pixel(1.0), rng=2)
    >>> check = assert_centre_frequency(z, sf_0=4.0, display=d)
    >>> check.unit, abs(check.sf_0 - 4.0) < 0.2
    ('cycles/deg', True)
    >>> assert_centre_frequency(z, sf_0=4.4, display=d)
    Traceback (most recent call last):
    ...
    AssertionError: measured centre frequency 3.9...±... cycles/deg (±... octaves) against expected 4.4 ...
    """
    __tracebackhide__ = HIDE_ASSERTION_FRAMES  # a failure reports the caller's line and the message
    if display is None:
        unit = "cycles/px"
        expected = check_real("sf_0 (cycles/pixel)", sf_0, lo=0.0, lo_open=True, hi=0.75)
        expected_px = expected
        to_unit = float
    else:
        if not (callable(getattr(display, "cycles_per_pixel", None))
                and callable(getattr(display, "cycles_per_degree", None))):
            raise TypeError(f"display must be a noiselab.Display (with cycles_per_pixel, cycles_per_degree), got "
                            f"{type(display).__name__}")
        unit = "cycles/deg"
        expected = check_real("sf_0 (cycles/deg)", sf_0, lo=0.0, lo_open=True, hi=1e6)
        expected_px = float(display.cycles_per_pixel(expected))
        to_unit = display.cycles_per_degree
    if tol is not None:
        tol = check_real("tol (octaves)", tol, lo=0.0, hi=10.0)
    false_alarm = check_real("false_alarm", false_alarm, lo=1e-12, hi=0.5)
    p, _, _, r, factor, n_ref = _spatial_cells("field", field, band, window)
    n = p.size
    total = float(p.sum())
    if n < 3 or total <= 0:
        raise AssertionError(f"no power to measure a centre frequency from (expected {expected:g} {unit}; "
                             f"{n} cells)")
    lnf = np.log(r / n_ref)   # cycles/pixel
    mu = float(np.sum(p * lnf)) / total
    d = lnf - mu
    se_ln = math.sqrt(factor * float(np.sum(p * p * d * d)) / 2.0) / total
    se_oct = se_ln / math.log(2.0)
    measured = float(to_unit(math.exp(mu)))
    if tol is None:
        z = _z(false_alarm)
        tol_used = z * se_oct
        how = f"default tolerance {z:.3g} standard errors, false-alarm rate {false_alarm:g}"
    else:
        tol_used, how = tol, f"given tol {tol:g} octaves"
    off = (mu - math.log(expected_px)) / math.log(2.0)
    msg = (f"measured centre frequency {measured:.4g}±{measured * se_ln:.2g} {unit} (±{se_oct:.2g} octaves) "
           f"against expected {expected:g} {unit}, {off:+.3g} octaves off (accepted ±{tol_used:.2g} octaves: "
           f"{how}; {n} cells; the power-weighted geometric mean of the frequency)")
    if abs(off) > tol_used:
        raise AssertionError(msg)
    return FrequencyCheck(sf_0=measured, se_octaves=se_oct, tol_octaves=tol_used, unit=unit, cells=n, message=msg)
