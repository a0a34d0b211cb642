"""Motion in the frequency domain: energy on motion planes and tents, the best velocity, speed per band.

Conventions. A video is ``(frames, height, width)``; x right along columns, y
*down* along rows; velocities are ``(vx, vy)`` in pixels/frame with sign
(+vy = down). Angular frequencies: ``w_x = 2 pi k_x / W``, ``w_y = 2 pi k_y / H``
(rad/px), ``w_t = 2 pi k_t / T`` (rad/frame), with numpy's FFT sign (the
same ``exp(-i ...)`` on every axis). Under that convention an image translating
with velocity ``v`` (``I(x, t) = I(x - v t, 0)``) puts all its energy on the
*motion plane* ``w_t = -v . w`` (Watson & Ahumada; Langer & Zhang Eq. 2.8), and
a cell's temporal frequency is periodic: energy predicted past the temporal
Nyquist frequency is found wrapped around, where the sampled video really has
it. Distances to a surface are therefore measured along ``w_t``, modulo the
temporal period, in temporal-frequency cells (cycles/video): ``tol=1`` accepts
the cells within one cell of the surface.

The falling-snow *tent* (Langer & Zhang Eq. 3.3, written there as
``w_t = C w_v / |w|``; with numpy's sign and ``w_v`` measured along the fall
direction, the surface of snow that falls *along* ``d`` is the negative one,
as the motion plane says and the tests check on translating patterns): a
flake layer whose spatial frequency is ``|w|`` rad/px moves at ``c / |w|``
px/frame along the unit fall direction ``d``, so its energy lies on
``w_t = -(c / |w|) d . w``, with ``c`` in rad/frame (``0 <= c <= pi``). A panning
camera adds the image velocity ``pan`` to every layer (the *sheared* tent,
Eq. 4.2): ``w_t = -((c / |w|) d + pan) . w``.

Velocities come from the lag-one temporal autocorrelation of each spatial
frequency, read off the power spectrum in one pass:
``R(k) = sum_kt P(k, kt) exp(2 pi i kt / T)`` equals ``sum_t F_{t+1}(k) conj(F_t(k))``
(circularly in t; the velocity analysers taper time with a Hann window by
default, which gives the wrap-around pair zero weight), whose
phase is ``-w . v`` for a translation. A phase correlation of ``R / |R|``
gives the integer part of ``v`` (no wrap-around ambiguity up to half the
frame), and a weighted least-squares fit of the remaining phase gives the
sub-pixel part; a pure translation, integer or not, is recovered exactly.
"""
from __future__ import annotations

from dataclasses import dataclass

import math

import numpy as np
import scipy.fft

from .._core import array_order, check_memory, check_real
from ._common import check_band, check_tol, check_vector, check_video, frequency_index, half_weight, ref_size
from .spectrum import PowerSpectrum, check_power_range, power_spectrum

__all__ = [
    "motion_energy",
    "tent_energy",
    "sheared_tent_energy",
    "best_velocity",
    "band_speeds",
    "speed_profile",
    "SpeedProfile",
    "octave_bands",
    "video_spectrum",
]


def video_spectrum(video, *, window=None, remove_static=False, workers=None) -> PowerSpectrum:
    """The 3-D power spectrum the motion analysers share (``window`` tapers time only).

    Compute it once and pass it to several analysers instead of the video to
    pay for one FFT. ``remove_static=True`` subtracts each pixel's temporal
    mean first (one more copy of the video): a still background composited
    under moving snow then no longer pulls every band's velocity towards
    zero. (The kt = 0 plane alone would not do with a window: a tapered
    still leaks into the neighbouring temporal bins.) ``workers``: FFT
    threads, scipy.fft's meaning (-1: every core); same result for any count.

    Parameters
    ----------
    video : array_like (T, H, W)
        A finite grey video of at least 2 frames.
    window : {None, "hann"}, optional
        Temporal taper.
    remove_static : bool, default False
        Subtract each pixel's temporal mean first.
    workers : int, optional
        FFT threads.

    Returns
    -------
    PowerSpectrum
        To pass to :func:`best_velocity`, :func:`band_speeds`, :func:`speed_profile`, ...

    Raises
    ------
    ValueError
        For a video that is not a finite 3-D array.

    Examples
    --------
    >>> import numpy as np
    >>> video = np.random.default_rng(0).random((8, 16, 16))
    >>> spec = video_spectrum(video, window="hann")
    >>> best_velocity(spec).shape
    (2,)
    """
    if isinstance(video, PowerSpectrum):
        if len(video.shape) != 3 or video.axes != (0, 1, 2):
            raise ValueError("motion analysers need the 3-D spectrum of a (frames, height, width) video")
        if video.shape[0] < 2:
            raise ValueError("motion analysers need at least 2 frames")
        return video
    if window not in (None, "hann"):
        raise ValueError(f"window must be None or 'hann', got {window!r}")
    arr = check_video("video", video)
    check_power_range("video", arr)  # named here: power_spectrum would call it a field
    if remove_static:
        scale = float(np.max(np.abs(arr)))
        arr = arr - np.mean(arr, axis=0, dtype=np.float64).astype(arr.dtype)
        if float(np.max(np.abs(arr))) <= 64 * np.finfo(arr.dtype).eps * scale:  # rounding only
            raise ValueError("the video does not change in time: nothing is left once its static part is removed")
    return power_spectrum(arr, window=window, window_axes=(0,), min_size=1, workers=workers)


class _Grid:
    """Broadcast spatial frequency vectors of the half spectrum of a video (no meshgrids kept)."""

    def __init__(self, shape):
        t, h, w = shape
        self.t, self.h, self.w = t, h, w
        self.n_ref = ref_size((h, w))
        self.ky = frequency_index(h)[:, None]
        self.kx = frequency_index(w, half=True)[None, :]
        self.wy = 2 * np.pi * self.ky / h  # rad/px
        self.wx = 2 * np.pi * self.kx / w
        self.r = np.hypot(self.kx * (self.n_ref / w), self.ky * (self.n_ref / h))  # cycles/frame
        self.weight = np.broadcast_to(half_weight(w)[None, :], (h, w // 2 + 1))
        self.kt = frequency_index(t)

    def band_mask(self, band):
        if band is None:
            return self.r > 0
        lo, hi = check_band("band", band, self.n_ref / 2.0 * np.sqrt(2))
        return (self.r >= lo) & (self.r <= hi) & (self.r > 0)


def _surface_energy(spec: PowerSpectrum, grid: _Grid, kt_pred: np.ndarray, region: np.ndarray, tol: float) -> float:
    """Fraction of the total power in ``region`` (spatial cells) within ``tol`` temporal cells of ``kt_pred`` (cycles/video).

    The temporal bins within ``tol`` of a cell's surface point are the
    integers ``b`` with ``|b - kt_pred| <= tol`` (read at ``b mod T``: the
    temporal axis is periodic), at most ``2 tol + 1`` of them: the power is
    gathered there directly instead of testing every bin of every cell.
    """
    t = grid.t
    total = spec.total
    if total <= 0:
        raise ValueError("the video has no power (constant after removing its mean)")
    shape = region.shape
    cells = np.flatnonzero(region)
    p2 = spec.power.reshape(t, -1)
    wgt = np.broadcast_to(grid.weight, shape).ravel()[cells]
    tolc = np.broadcast_to(np.asarray(tol, dtype=np.float64), shape).ravel()[cells]
    on = 0.0
    full = 2 * tolc + 1 >= t  # every temporal bin of these cells is within tol
    if full.any():
        on += float(np.sum(p2[:, cells[full]], dtype=np.float64, axis=0) @ wgt[full])
        cells, wgt, tolc = cells[~full], wgt[~full], tolc[~full]
    if cells.size:
        kp = np.broadcast_to(kt_pred, shape).ravel()[np.flatnonzero(region)][~full]
        base = np.floor(kp - tolc - 1e-9).astype(np.int64)
        for j in range(int(np.ceil(2 * tolc.max())) + 2):
            b = base + j
            ok = np.abs(b - kp) <= tolc + 1e-9
            if ok.any():
                on += float(np.sum(p2[np.mod(b[ok], t), cells[ok]] * wgt[ok], dtype=np.float64))
    return on / total


@array_order(("velocity", "velocity_yx"), positional=("velocity",))
def motion_energy(video, *, velocity_yx=(0.0, 0.0), tol=1.0, band=None, window=None) -> float:
    """Fraction of a video's spectral power on the motion plane ``w_t = -v·w`` of ``velocity_yx = (vy, vx)``.

    Parameters
    ----------
    video : array_like or PowerSpectrum
        ``(frames, height, width)``; or its :func:`video_spectrum`.
    velocity_yx : (vy, vx)
        Pixels/frame in array order (+y down the rows, +x right).
        ``velocity=(vx, vy)`` (also by position) is the old spelling, refused since 0.4.
    tol : float
        Accepted distance from the plane along ``w_t``, in temporal-frequency
        cells (cycles/video), modulo the temporal period.
    band : (lo, hi), optional
        Count only spatial frequencies in this band (cycles/frame); the
        fraction is still of the *total* power.
    window : {None, "hann"}
        Temporal taper for videos that do not loop (spreads a plane over about
        two cells: use ``tol >= 1.5``).

    Returns
    -------
    float in [0, 1]; 1 for an image translating at ``velocity_yx`` (integer or
    sub-pixel, when the translation loops over the video).

    Examples
    --------
    >>> import numpy as np
    >>> img = np.random.default_rng(0).random((32, 32))
    >>> video = np.stack([np.roll(img, (t, 2 * t), axis=(0, 1)) for t in range(32)])  # loops after 32 frames
    >>> round(motion_energy(video, velocity_yx=(1, 2), tol=0.5), 6)
    1.0
    """
    spec = video_spectrum(video, window=window)
    v = check_vector("velocity_yx", velocity_yx, order="yx")
    tol = check_tol("tol", tol)
    g = _Grid(spec.shape)
    kt_pred = -g.t * (v[0] * g.kx / g.w + v[1] * g.ky / g.h)
    region = np.ones(g.r.shape, dtype=bool) if band is None else g.band_mask(band)
    return _surface_energy(spec, g, kt_pred, region, tol)


def _tent_kt(g: _Grid, c, direction, pan):
    d = direction / np.hypot(*direction)
    wmag = np.hypot(g.wx, g.wy)
    along = d[0] * g.wx + d[1] * g.wy
    with np.errstate(invalid="ignore", divide="ignore"):
        wt = -c * np.where(wmag > 0, along / np.where(wmag > 0, wmag, 1.0), 0.0)
    wt = wt - (pan[0] * g.wx + pan[1] * g.wy)
    return wt * g.t / (2 * np.pi)


@array_order(("direction", "direction_yx"), ("pan", "pan_yx"), positional=("direction",))
def tent_energy(video, c, band, *, direction_yx=(1.0, 0.0), pan_yx=(0.0, 0.0), thickness=0.1, tol=0.5, window=None,
                workers=None) -> float:
    """Fraction of a video's power on the falling-snow tent inside ``band``.

    The tent (Langer & Zhang Eq. 3.3, numpy's FFT sign): ``w_t = -(c / |w|) d . w``,
    i.e. the layer of spatial frequency ``|w|`` rad/px moves at ``c / |w|``
    px/frame along the unit fall direction ``d`` (default ``direction_yx=(1, 0)``:
    straight down). With ``pan_yx`` (px/frame) the sheared tent ``w_t = -((c / |w|) d + pan) . w``.

    Parameters
    ----------
    video : array_like or PowerSpectrum
    c : float
        Tent constant in rad/frame, ``0 <= c <= pi`` (``c = 0``: frozen snow).
        The speed at a band edge of ``f`` cycles/frame on an ``N``-pixel frame is
        ``c N / (2 pi f)`` px/frame.
    band : (lo, hi)
        Spatial band in cycles/frame; only cells with ``lo <= f <= hi`` count.
    direction_yx : (dy, dx)
        Fall direction in array order (+y down, +x right), any length.
        ``direction=(dx, dy)`` (also by position) is the old spelling, refused since 0.4.
    pan_yx : (uy, ux)
        Camera pan as an image velocity in px/frame, array order (sheared
        tent). ``pan=(ux, uy)`` is the old spelling, refused since 0.4.
    thickness : float
        Relative thickness of the tent (thesis 3.2.1), in [0, 1]: ``c`` spread over
        ``c (1 +- thickness)``, i.e. a half-width of ``thickness c |d . w| / |w|``
        rad/frame added to ``tol``. The default 0.1 is ``noiselab.snow``'s.
    tol : float
        Distance along ``w_t`` in temporal-frequency cells beyond the
        thickness. The default 1/2 accepts the bins that overlap the
        (thickened) surface, exactly the cells ``noiselab.snow`` fills.
    window : {None, "hann"}
    workers : int, optional
        FFT threads, scipy.fft's meaning (-1: every core); same result for any count.

    Returns
    -------
    float in [0, 1]: power on the tent within the band over the total power.

    Examples
    --------
    >>> import numpy as np
    >>> t, y, x = np.mgrid[:16, :32, :32].astype(float)
    >>> # one layer at 4 cycles/frame moving down at c / |w| px/frame
    >>> c = np.pi / 4; w = 2 * np.pi * 4 / 32; v = c / w
    >>> video = np.cos(2 * np.pi * 4 * (y - v * t) / 32)
    >>> round(tent_energy(video, c, (2, 8), thickness=0), 6)
    1.0
    """
    spec = video_spectrum(video, window=window, workers=workers)
    c = check_real("c", c, lo=0.0, hi=np.pi)
    d = check_vector("direction_yx", direction_yx, nonzero=True, order="yx")
    p = check_vector("pan_yx", pan_yx, order="yx")
    thickness = check_real("thickness", thickness, lo=0.0, hi=1.0)
    tol = check_tol("tol", tol)
    g = _Grid(spec.shape)
    check_band("band", band, g.n_ref / 2.0)
    dh = d / np.hypot(*d)
    wmag = np.hypot(g.wx, g.wy)
    along = np.abs(dh[0] * g.wx + dh[1] * g.wy) / np.where(wmag > 0, wmag, 1.0)
    tol_cells = tol + thickness * c * along * g.t / (2 * np.pi)
    return _surface_energy(spec, g, _tent_kt(g, c, d, p), g.band_mask(band), tol_cells)


@array_order(("direction", "direction_yx"), ("pan", "pan_yx"), positional=("direction", "pan"))
def sheared_tent_energy(video, c, band, *, direction_yx=(1.0, 0.0), pan_yx=(0.0, 0.0), thickness=0.1, tol=0.5,
                        window=None) -> float:
    """Fraction of the power on the sheared tent of a panning camera (see :func:`tent_energy`).

    Parameters
    ----------
    video, c, band, direction_yx, thickness, tol, window
        As for :func:`tent_energy`.
    pan_yx : (uy, ux), default (0, 0)
        The camera's pan in px/frame, array order (thesis Eq. 4.2).

    Returns
    -------
    float
        In ``[0, 1]``.

    Raises
    ------
    ValueError
        For the arguments :func:`tent_energy` refuses, or a non-finite pan.

    Examples
    --------
    >>> from noiselab.snowfall import snow
    >>> video = snow((16, 64, 64), rng=0, c=1.0, band=(4, 16), pan_yx=(0.0, 1.0))
    >>> sheared_tent_energy(video, 1.0, (4, 16), pan_yx=(0.0, 1.0)) > 0.9
    True
    """
    return tent_energy(video, c, band, direction_yx=direction_yx, pan_yx=pan_yx, thickness=thickness, tol=tol,
                       window=window)


def _lag_one(spec: PowerSpectrum) -> np.ndarray:
    """``R(k) = sum_kt P(k, kt) exp(2 pi i kt / T)``: the lag-one temporal autocorrelation of each spatial frequency."""
    t = spec.shape[0]
    if t < 4:
        # two frames give +-pi phases (no sign); a Hann taper leaves a 3-frame video two weighted frames
        raise ValueError(f"a velocity needs a video of at least 4 frames, got {t}")
    ang = 2 * np.pi * frequency_index(t) / t
    p2 = spec.power.reshape(t, -1)
    re = np.cos(ang).astype(p2.dtype) @ p2
    im = np.sin(ang).astype(p2.dtype) @ p2
    return (re.astype(np.float64) + 1j * im.astype(np.float64)).reshape(spec.power.shape[1:])


def _fit_velocity(r_lag, g: _Grid, region):
    """Velocity (vx, vy) and coherence from the lag-one phases in ``region``."""
    mag = np.abs(r_lag)
    use = region & (mag > mag.max() * 1e-12) if mag.max() > 0 else region & False
    if not use.any():
        return None, 0.0
    # integer part: phase correlation over the region
    norm = np.where(use, r_lag / np.where(use, mag, 1.0), 0.0)
    surface = scipy.fft.irfft2(norm, s=(g.h, g.w))
    iy, ix = np.unravel_index(np.argmax(surface), surface.shape)
    v = np.array([ix - g.w if ix >= g.w / 2 else ix, iy - g.h if iy >= g.h / 2 else iy], dtype=np.float64)
    a = (mag * g.weight)[use]
    wx = np.broadcast_to(g.wx, use.shape)[use]
    wy = np.broadcast_to(g.wy, use.shape)[use]
    rl = r_lag[use]
    m = np.array([[np.sum(a * wx * wx), np.sum(a * wx * wy)], [np.sum(a * wx * wy), np.sum(a * wy * wy)]])
    for _ in range(4):
        phi = np.angle(rl * np.exp(1j * (wx * v[0] + wy * v[1])))
        b = -np.array([np.sum(a * wx * phi), np.sum(a * wy * phi)])
        # lstsq: a one-dimensional pattern (aperture problem) gets its normal velocity
        dv = np.linalg.lstsq(m, b, rcond=1e-10)[0]
        v = v + dv
        if np.max(np.abs(dv)) < 1e-12:
            break
    coherence = float(np.abs(np.sum(a * rl / np.abs(rl) * np.exp(1j * (wx * v[0] + wy * v[1])))) / np.sum(a))
    return v, coherence


def best_velocity(video, *, band=None, window="hann", remove_static=False) -> np.ndarray:
    """The single velocity ``(vx, vy)`` (px/frame, +y down) that best explains the video's motion.

    Weighted by power over the spatial frequencies in ``band`` (default all);
    exact for a pure translation (integer or sub-pixel per frame), up to half
    the frame per frame. For a mixture (falling snow) it is the power-weighted
    compromise; see :func:`band_speeds` for the speed of each band.
    The default temporal Hann window gives the wrap-around pair (last frame
    to first) zero weight, so a video need not loop; every other pair of
    consecutive frames keeps the exact phase of its step. ``remove_static``:
    see :func:`video_spectrum`.

    Parameters
    ----------
    video : array_like (T, H, W) or PowerSpectrum
        A finite grey video of at least 2 frames (or its :func:`video_spectrum`).
    band : (lo, hi), optional
        Spatial frequencies counted, in cycles/frame (default all).
    window : {"hann", None}, default "hann"
        Temporal taper.
    remove_static : bool, default False
        Subtract each pixel's temporal mean first.

    Returns
    -------
    ndarray (2,)
        ``(vx, vy)`` in px/frame, x right, y down.

    Raises
    ------
    ValueError
        For a video that is not finite and 3-D, or a band that is empty or past Nyquist.

    Examples
    --------
    >>> import numpy as np
    >>> img = np.random.default_rng(0).random((32, 32))
    >>> video = np.stack([np.roll(img, (3 * t, -t), axis=(0, 1)) for t in range(8)])
    >>> best_velocity(video).round(6).tolist()
    [-1.0, 3.0]
    """
    spec = video_spectrum(video, window=window, remove_static=remove_static)
    g = _Grid(spec.shape)
    v, _ = _fit_velocity(_lag_one(spec), g, g.band_mask(band))
    if v is None:
        raise ValueError("the video has no moving power in the band: cannot estimate a velocity")
    return v


def octave_bands(lo, hi, per_octave=2):
    """Log-spaced bands ``[(f0, f1), (f1, f2), ...]`` from ``lo`` to ``hi`` cycles/frame, ``per_octave`` per octave.

    Parameters
    ----------
    lo, hi : float
        Limits in cycles/frame, ``0 < lo < hi``.
    per_octave : int, default 2
        Bands per octave (>= 1).

    Returns
    -------
    list of (float, float)
        Contiguous bands covering ``[lo, hi]``.

    Raises
    ------
    ValueError
        For ``lo <= 0``, ``hi <= lo`` or ``per_octave < 1``.

    Examples
    --------
    >>> [(round(lo, 6), round(hi, 6)) for lo, hi in octave_bands(4, 16, per_octave=1)]
    [(4.0, 8.0), (8.0, 16.0)]
    """
    lo = check_real("lo", lo, lo=0.0, lo_open=True)
    hi = check_real("hi", hi, lo=lo, lo_open=True)
    per_octave = check_real("per_octave", per_octave, lo=0.0, lo_open=True)
    count = (math.log2(hi) - math.log2(lo)) * per_octave  # logs apart: hi / lo overflows for tiny lo
    check_memory(count * 200, f"octave_bands with {count:.3g} bands")  # a list of tuples of two floats
    n = max(int(round(count)), 1)
    e = np.geomspace(lo, hi, n + 1)
    return [(float(e[i]), float(e[i + 1])) for i in range(n)]


def _check_bands(bands, fmax):
    if isinstance(bands, np.ndarray):
        bands = bands.tolist()
    try:
        bands = list(bands)
    except TypeError:
        raise TypeError("bands must be a sequence of (lo, hi) pairs in cycles/frame") from None
    if not bands:
        raise ValueError("bands is empty: give at least one (lo, hi) pair")
    return [check_band(f"bands[{i}]", b, fmax) for i, b in enumerate(bands)]


@dataclass(frozen=True)
class SpeedProfile:
    """Speed of each spatial-frequency band (the motion-parallax curve).

    Attributes
    ----------
    bands : ndarray, shape (n, 2)
        Band edges in cycles/frame.
    centers : ndarray
        Radial frequency each band's velocity refers to (cycles/frame):
        ``sum P f**2 / sum P f`` over the band, the frequency the weighted
        fit effectively measures (for speeds ``c / |w|`` it returns exactly
        ``c / |w|`` at this centre when the band's power is isotropic).
    velocity : ndarray, shape (n, 2)
        ``(vx, vy)`` px/frame per band (+y down).
    coherence : ndarray
        How well one velocity explains the band, 1 for a pure translation.
    energy : ndarray
        Fraction of the total power in each band.
    frame_size : int
    """

    bands: np.ndarray
    centers: np.ndarray
    velocity: np.ndarray
    coherence: np.ndarray
    energy: np.ndarray
    frame_size: int

    @property
    def speed(self) -> np.ndarray:
        return np.hypot(self.velocity[:, 0], self.velocity[:, 1])

    @property
    def parallax(self) -> np.ndarray:
        """``speed x |w|`` with ``|w| = 2 pi f / N`` rad/px at the band centre: constant (= c) on a tent."""
        return self.speed * 2 * np.pi * self.centers / self.frame_size


def speed_profile(video, bands=None, *, window="hann", min_energy=1e-3, per_octave=2,
                  remove_static=False, workers=None) -> SpeedProfile:
    """Velocity per spatial-frequency band, with band centres, coherence and energy.

    ``bands`` default: ``per_octave`` bands per octave from 2 cycles/frame to
    Nyquist, keeping only those holding at least ``min_energy`` of the power. Explicit
    bands must all hold power (else ``ValueError`` naming the band). ``workers``:
    FFT threads, scipy.fft's meaning (-1: every core); same result for any count.

    Parameters
    ----------
    video : array_like (T, H, W) or PowerSpectrum
        A finite grey video (or its :func:`video_spectrum`).
    bands : sequence of (lo, hi), optional
        Spatial-frequency bands in cycles/frame (default: see above).
    window : {"hann", None}, default "hann"
        Temporal taper.
    min_energy : float, default 0.001
        Smallest share of the power a default band must hold to be kept.
    per_octave : int, default 2
        Default bands per octave.
    remove_static : bool, default False
        Subtract each pixel's temporal mean first.
    workers : int, optional
        FFT threads.

    Returns
    -------
    SpeedProfile
        ``bands``, ``centers``, ``velocity`` (px/frame per band), ``coherence``, ``energy``.

    Raises
    ------
    ValueError
        For a video that is not finite and 3-D, or an explicit band without power.

    Examples
    --------
    >>> from noiselab.snowfall import snow
    >>> profile = speed_profile(snow((16, 64, 64), rng=0, c=1.0, band=(4, 16)), [(4, 8), (8, 16)])
    >>> bool(profile.velocity[0, 1] > profile.velocity[1, 1] > 0)   # near (low-frequency) flakes fall faster
    True
    """
    spec = video_spectrum(video, window=window, remove_static=remove_static, workers=workers)
    g = _Grid(spec.shape)
    explicit = bands is not None
    min_energy = check_real("min_energy", min_energy, lo=0.0, hi=1.0)
    if explicit:
        bands = _check_bands(bands, g.n_ref / 2.0 * np.sqrt(2))
    else:
        bands = octave_bands(2.0, g.n_ref / 2.0, per_octave)
    r_lag = _lag_one(spec)
    # power of each spatial cell summed over w_t = R at lag zero
    p0 = np.sum(spec.power, axis=0, dtype=np.float64) * g.weight
    total = spec.total
    out_b, out_c, out_v, out_coh, out_e = [], [], [], [], []
    for i, (lo, hi) in enumerate(bands):
        region = (g.r >= lo) & (g.r <= hi) & (g.r > 0)
        e = float(np.sum(p0[region]) / total) if total > 0 else 0.0
        if not explicit and e < min_energy:
            continue
        v, coh = _fit_velocity(r_lag, g, region)
        if v is None or e <= 0:
            raise ValueError(f"band {i} ({lo:g}, {hi:g}) cycles/frame holds no power: cannot estimate its speed")
        out_b.append((lo, hi))
        # the frequency the fit measures: it weighs each cell's phase -w.v by P |w|^2, so for speeds
        # that vary as 1/|w| it returns c / (sum P |w|^2 / sum P |w|)
        rr = g.r[region]
        out_c.append(float(np.sum(p0[region] * rr**2) / np.sum(p0[region] * rr)))
        out_v.append(v)
        out_coh.append(coh)
        out_e.append(e)
    if not out_b:
        raise ValueError("no band holds enough power to estimate a speed")
    return SpeedProfile(
        bands=np.array(out_b),
        centers=np.array(out_c),
        velocity=np.array(out_v),
        coherence=np.array(out_coh),
        energy=np.array(out_e),
        frame_size=g.n_ref,
    )


def band_speeds(video, bands, *, window="hann", remove_static=False, workers=None) -> np.ndarray:
    """Velocity ``(vx, vy)`` in px/frame of each spatial-frequency band: an array of shape ``(len(bands), 2)``.

    ``bands`` is a sequence of ``(lo, hi)`` pairs in cycles/frame (see
    :func:`octave_bands`). For falling snow with tent constant ``c`` the
    speed of a band near ``f`` cycles/frame is ``c N / (2 pi f)``: speed x
    frequency is constant (motion parallax). ``workers``: FFT threads,
    scipy.fft's meaning (-1: every core); same result for any count.

    Parameters
    ----------
    video : array_like (T, H, W) or PowerSpectrum
        A finite grey video (or its :func:`video_spectrum`).
    bands : sequence of (lo, hi)
        Spatial-frequency bands in cycles/frame.
    window : {"hann", None}, default "hann"
        Temporal taper.
    remove_static : bool, default False
        Subtract each pixel's temporal mean first.
    workers : int, optional
        FFT threads.

    Returns
    -------
    ndarray (len(bands), 2)
        ``(vx, vy)`` per band in px/frame.

    Raises
    ------
    ValueError
        For a video that is not finite and 3-D, or a band holding no power
        (named in the message).

    Examples
    --------
    >>> import numpy as np
    >>> t, y, x = np.mgrid[:32, :64, :64].astype(float)
    >>> slow = np.cos(2 * np.pi * (16 * x + 16 * y) / 64 - 2 * np.pi * 16 * 0.5 * t / 64)
    >>> fast = np.cos(2 * np.pi * 4 * y / 64 - 2 * np.pi * 4 * 2.0 * t / 64)
    >>> band_speeds(slow + fast, [(2, 8), (16, 32)]).round(6).tolist()
    [[0.0, 2.0], [0.25, 0.25]]
    """
    return speed_profile(video, bands, window=window, remove_static=remove_static, workers=workers).velocity
