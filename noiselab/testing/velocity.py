"""Assert a video's velocity in velocity units: measured with its standard error, failing in one line."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import special

from .._core import HIDE_ASSERTION_FRAMES, check_band, check_real
from ..analysis import best_velocity, video_spectrum

__all__ = ["VelocityCheck", "assert_velocity"]

_ROUNDING = 1e-6  # px/frame: the least default tolerance (float32 rounding of a video moves its phases that much)


@dataclass(frozen=True)
class VelocityCheck:
    """A measured velocity with its standard errors, in the unit it was asked in.

    Attributes
    ----------
    vx, vy : float
        Measured velocity (x right, y down): px/frame, or deg/s when a ``display`` was given.
    se_vx, se_vy : float
        Their standard errors (same unit).
    tol_vx, tol_vy : float
        Accepted distance of the expected velocity from the measured one, per component (same unit).
    unit : str
        ``"px/frame"`` or ``"deg/s"``.
    cells : int
        Independent spatial-frequency cells the fit used.
    message : str
    """

    vx: float
    vy: float
    se_vx: float
    se_vy: float
    tol_vx: float
    tol_vy: float
    unit: str
    cells: int
    message: str


def _lag_one_cells(spec, band):
    """Lag-one temporal autocorrelation ``R`` of each independent spatial cell, and its frequencies (cycles/px)."""
    t, h, w = spec.shape
    p = np.asarray(spec.power, dtype=np.float64).reshape(t, -1)
    ang = 2 * np.pi * np.fft.fftfreq(t)
    r_lag = (np.exp(1j * ang) @ p).reshape(h, w // 2 + 1)
    fy = np.broadcast_to(np.fft.fftfreq(h)[:, None], r_lag.shape)
    fx = np.broadcast_to(np.fft.rfftfreq(w)[None, :], r_lag.shape)
    # one cell of each mirror pair: the half spectrum's inner columns, and the upper half of its self-mirrored ones
    inner = (fx > 0) & (fx < 0.5)
    edge = ~inner & (fy > 0)  # fftfreq puts an even height's Nyquist row at -0.5: dropped, as the DC row
    keep = inner | edge
    radius = np.hypot(fx * w, fy * w)  # cycles/frame (cycles per width)
    if band is not None:
        lo, hi = check_band("band", band, w / 2.0 * np.sqrt(2))
        keep &= (radius >= lo) & (radius <= hi)
    return r_lag[keep], fx[keep], fy[keep]


def _near_temporal_nyquist(spec):
    """The share of a video's power at temporal frequencies within 1/16 cycle/frame of the Nyquist frequency."""
    t = spec.shape[0]
    per_t = np.asarray(spec.power, dtype=np.float64).reshape(t, -1, spec.power.shape[-1]).sum(axis=1) @ \
        np.asarray(spec.weight, dtype=np.float64).ravel()
    total = float(per_t.sum())
    if total <= 0:
        return 0.0
    return float(per_t[np.abs(np.fft.fftfreq(t)) >= 0.5 - 1.0 / 16].sum()) / total


def _fit(r_lag, fx, fy, v0):
    """Weighted least squares of the lag-one phases on the plane ``phase = -2 pi (vx fx + vy fy)``, with a sandwich covariance."""
    a = np.abs(r_lag)
    use = a > a.max() * 1e-12 if a.size and a.max() > 0 else np.zeros(a.shape, dtype=bool)
    a, rl = a[use], r_lag[use]
    x = 2 * np.pi * np.stack([fx[use], fy[use]], axis=1)
    n = a.size
    if n < 3:
        return None, None, n
    m = x.T @ (a[:, None] * x)
    ev = np.linalg.eigvalsh(m)
    if ev[0] <= 1e-10 * ev[1]:
        return "aperture", None, n
    v = np.asarray(v0, dtype=np.float64)
    for _ in range(8):
        res = np.angle(rl * np.exp(1j * (x @ v)))
        dv = -np.linalg.lstsq(m, x.T @ (a * res), rcond=1e-10)[0]
        v = v + dv
        if np.max(np.abs(dv)) < 1e-13:
            break
    res = np.angle(rl * np.exp(1j * (x @ v)))
    minv = np.linalg.pinv(m, rcond=1e-10)
    score = x * (a * res)[:, None]
    meat = score.T @ score
    cov = minv @ meat @ minv * (n / (n - 2))
    return v, cov, n


def assert_velocity(video, *, vx, vy, tol=None, display=None, false_alarm=1e-3, band=None,
                    window="hann") -> VelocityCheck:
    """Assert that a video moves at ``(vx, vy)``: measured velocity ± standard error against the expected one.

    The velocity is the weighted least-squares fit of the motion plane
    ``w_t = -(vx wx + vy wy)`` to the video's spectrum: for every spatial
    frequency ``w`` the lag-one temporal autocorrelation
    ``R(w) = sum_wt P(w, wt) exp(i wt)`` has the phase ``-(vx wx + vy wy)``
    (exactly for a translation; on average for a motion cloud, whose power
    spreads symmetrically about the plane at any speed bandwidth ``B_V``),
    so the phases are regressed on the plane with weights ``|R|`` (the start
    and the integer part of the phases come from
    :func:`noiselab.analysis.best_velocity`). The spatial frequencies of a
    stationary field are independent, so the standard errors are the
    heteroscedasticity-consistent (sandwich) ones of that regression over the
    independent cells (one of each mirror pair). The default tolerance is
    ``z`` standard errors per component with ``z`` the two-sided normal
    quantile of ``false_alarm / 2`` (both components): a video truly moving
    at ``(vx, vy)`` fails with probability about ``false_alarm``
    (the tolerance is never below 1e-6 px/frame, for rounding)
    (``benchmarks/bench_velocity.md`` counts it on motion clouds).

    A cloud whose speed band reaches the temporal Nyquist frequency reads
    slow: MotionClouds and :func:`noiselab.stimuli.motion_cloud` draw the
    band ``exp(-(ft + v.f)**2 / (2 (B_V |f|)**2))`` on the grid's temporal
    frequencies ``[-1/2, 1/2)``, so where ``|v.f| + 2 B_V |f|`` passes 1/2 it
    is cut (not wrapped) and each such cell's circular mean moves towards 0.
    At (vx, vy) = (1, 0.5) px/frame with ``sf_0`` 0.15, ``B_sf`` 0.1
    cycles/px the fit reads about 1 % slow at ``B_V`` 0.5 and 5 % slow at
    ``B_V`` 1 (at 32 x 64 x 64 px as at 64 x 128 x 128: the size does not
    matter, the band does), enough to fail at the true velocity; with
    ``sf_0`` 0.125, ``B_sf`` 0.05 the bias is at most 0.5 % and within the
    standard errors. Measuring within ``band=(1, N / 2 / (|v| + 2 B_V))``
    cycles/frame removes it (``python3 benchmarks/bench_velocity_bias.py``,
    ``benchmarks/bench_velocity_bias.md``); a failure says how much of the
    video's power lies near the temporal Nyquist frequency.

    Unlike :func:`assert_motion` (a fraction of the power within a number of
    temporal-frequency cells of the plane, which a broad speed bandwidth
    never reaches), the tolerance here is a velocity.

    Parameters
    ----------
    video : array_like
        ``(frames, height, width)``, at least 4 frames, finite.
    vx, vy : float
        Expected velocity, x right and y down: px/frame, or deg/s when
        ``display`` is given.
    tol : float, optional
        Accepted distance per component, in the unit of ``vx`` (>= 0).
        Default: derived from the standard errors at ``false_alarm``.
    display : noiselab.Display, optional
        Read ``vx``, ``vy``, ``tol`` (and report the measurement) in deg/s
        through ``display.px_per_frame`` / ``display.deg_per_second``.
    false_alarm : float
        Probability that a video moving at ``(vx, vy)`` fails the default
        tolerance (1e-12 to 0.5), default 1e-3.
    band : (lo, hi), optional
        Spatial band in cycles/frame (default all).
    window : {"hann", None}
        Temporal taper (default ``"hann"``: the video need not loop).

    Returns
    -------
    VelocityCheck

    Raises
    ------
    AssertionError
        If ``(vx, vy)`` lies outside the tolerance of the measurement, in one
        line: ``measured vx=…±…, vy=…±… px/frame against expected …``; or if
        the video has no moving power, or all of it along one orientation (a
        grating, whose velocity along its stripes is undefined).
    ValueError, TypeError
        For bad input, naming the parameter.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab.testing import assert_velocity
    >>> img = np.random.default_rng(0).random((32, 32))
    >>> video = np.stack([np.roll(img, (t, 2 * t), axis=(0, 1)) for t in range(16)])  # vx=2, vy=1
    >>> check = assert_velocity(video, vx=2, vy=1)
    >>> round(check.vx, 6), round(check.vy, 6)
    (2.0, 1.0)
    >>> assert_velocity(video, vx=2.1, vy=1)
    Traceback (most recent call last):
    ...
    AssertionError: measured vx=2±..., vy=1±... px/frame against expected vx=2.1, vy=1 ...
    """
    __tracebackhide__ = HIDE_ASSERTION_FRAMES  # a failure reports the caller's line and the message
    vx = check_real("vx", vx)
    vy = check_real("vy", vy)
    if tol is not None:
        tol = check_real("tol", tol, lo=0.0)
    false_alarm = check_real("false_alarm", false_alarm, lo=1e-12, hi=0.5)
    if window not in (None, "hann"):
        raise ValueError(f"window must be None or 'hann', got {window!r}")
    if display is None:
        unit, from_px = "px/frame", (lambda s: s)
    else:
        if not (callable(getattr(display, "px_per_frame", None)) and callable(getattr(display, "deg_per_second", None))):
            raise TypeError(f"display must be a noiselab.Display (with px_per_frame, deg_per_second), got "
                            f"{type(display).__name__}")
        unit, from_px = "deg/s", display.deg_per_second
    spec = video_spectrum(video, window=window)
    if spec.shape[0] < 4:
        raise ValueError(f"video must have at least 4 frames to measure a velocity, got {spec.shape[0]}")
    r_lag, fx, fy = _lag_one_cells(spec, band)
    try:
        v0 = best_velocity(spec, band=band)
    except ValueError:
        v0 = None
    fit = (None, None, 0) if v0 is None else _fit(r_lag, fx, fy, v0)
    v, cov, n = fit
    if isinstance(v, str):
        raise AssertionError(f"the video's moving power lies along one orientation (a grating): only the velocity "
                             f"normal to its stripes is defined, not (vx, vy) = ({vx:g}, {vy:g}) {unit} "
                             "(the aperture problem)")
    if v is None:
        raise AssertionError(f"no moving power to measure a velocity from (expected vx={vx:g}, vy={vy:g} {unit})")
    se = np.sqrt(np.maximum(np.diag(cov), 0.0))
    mx, my = float(from_px(float(v[0]))), float(from_px(float(v[1])))
    sx, sy = abs(float(from_px(float(se[0])))), abs(float(from_px(float(se[1]))))
    if tol is None:
        z = float(-special.ndtri(false_alarm / 4))  # two-sided, two components
        floor = abs(float(from_px(_ROUNDING)))  # an exact translation has standard errors of 1e-17
        tx, ty = max(z * sx, floor), max(z * sy, floor)
        how = f"default tolerance {z:.3g} standard errors, false-alarm rate {false_alarm:g} over both components"
    else:
        tx = ty = tol
        how = f"given tol {tol:g} {unit}"
    msg = (f"measured vx={mx:.4g}±{sx:.2g}, vy={my:.4g}±{sy:.2g} {unit} against expected vx={vx:g}, vy={vy:g} "
           f"(accepted ±{tx:.2g}, ±{ty:.2g}: {how}; {n} spatial cells)")
    if not (abs(mx - vx) <= tx and abs(my - vy) <= ty):
        near = _near_temporal_nyquist(spec)
        if near > 1e-3:
            msg += (f"; {100 * near:.2g} % of the power lies within 1/16 cycle/frame of the temporal Nyquist "
                    "frequency, where a speed band is cut and reads slow: band=(lo, hi) below "
                    "N / 2 / (|v| + 2 B_V) cycles/frame measures where it fits")
        raise AssertionError(msg)
    return VelocityCheck(vx=mx, vy=my, se_vx=sx, se_vy=sy, tol_vx=tx, tol_vy=ty, unit=unit, cells=n, message=msg)
