"""Amplitude envelopes on broadcast frequency vectors; they combine by multiplication.

Every function takes angular frequencies in **rad/sample** (as returned by
:func:`noiselab.spectral.frequency_vectors`: ``wt`` in rad/frame, ``wy`` and
``wx`` in rad/pixel, each in ``[-pi, pi]``) and returns an array that
broadcasts against them. Their other parameters say their unit in their name
or in their error messages: :func:`annulus`'s ``band_cycles_per_sample``
(cycles/sample, the radius ``|w| / (2*pi)``; ``spectral_noise`` and ``snow``
take bands in cycles/frame, ``W`` times that), ``c`` and ``tol`` in
rad/frame, velocities in px/frame. Pairs of per-axis components are in array
order, like the frequency vectors: ``direction_yx = (dy, dx)``,
``pan_yx = (uy, ux)``, ``velocity_yx = (vy, vx)`` (the old ``(x, y)``
keywords and positions were removed in 0.4: they are a ``TypeError`` naming the new keyword).
Masks are float arrays of 0 and 1, so that
``annulus(...) * power_law(...) * tent(...)`` is the snow envelope.

Sign convention (numpy's FFT, checked by measuring motion in the tests): a
pattern translating with image velocity ``v = (vx, vy)`` pixels/frame has its
energy on the motion plane ``wt = -(vx*wx + vy*wy)`` (Watson & Ahumada, thesis
Eq. 2.8). The thesis writes its tent (Eq. 3.3) without the minus sign, for
its own transform convention; here the signs are chosen so that flakes move
along ``+direction_yx``.

"On a surface" means the frequency cell overlaps it: a cell of temporal
frequency ``wt`` carries energy when ``|wt - surface| <= tol``; pass half
a temporal bin (``pi / T``) for the thesis's "cells overlapping the surface".

Examples
--------
>>> import numpy as np
>>> from noiselab.spectral import frequency_vectors
>>> wt, wy, wx = frequency_vectors((64, 128, 128))
>>> env = annulus(wy, wx, band_cycles_per_sample=(4/128, 32/128)) * power_law(wy, wx) * tent(wt, wy, wx, c=1.0, tol=np.pi/64)
>>> env.shape
(64, 128, 65)
"""
from __future__ import annotations

import math

import numpy as np

from .._core import REMOVED_IN, array_order, check_finite_array, check_real, check_real_sequence, renamed_parameters

__all__ = [
    "radial_frequency",
    "power_law",
    "annulus",
    "motion_plane",
    "optical_snow",
    "nonparallel_optical_snow",
    "tent_surface",
    "tent",
    "thickened_tent",
    "sheared_tent",
    "unit_direction",
    "log_gabor",
    "orientation",
    "speed_envelope",
]


def unit_direction_yx(name, direction_yx) -> tuple[float, float]:
    """A fall direction given in array order ``(dy, dx)``, as the unit ``(dx, dy)`` of :func:`unit_direction`.

    Errors name ``name`` and the array order.
    """
    if isinstance(direction_yx, (str, bytes, set, frozenset, dict)) or not hasattr(direction_yx, "__len__"):
        raise TypeError(f"{name} must be a pair (dy, dx) of real numbers, got {direction_yx!r}")
    if len(direction_yx) != 2:
        raise ValueError(f"{name} must be a pair (dy, dx), got {direction_yx!r}")
    try:
        d = np.asarray(direction_yx, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise TypeError(f"{name} must be a pair (dy, dx) of real numbers, got {direction_yx!r}") from None
    if not np.all(np.isfinite(d)):
        raise ValueError(f"{name} must be finite, got {direction_yx!r}")
    if not np.any(d):
        raise ValueError(f"{name} must be a non-zero vector (dy, dx), got {direction_yx!r}")
    return unit_direction((d[1], d[0]))


def unit_direction(direction) -> tuple[float, float]:
    """``direction = (dx, dy)`` in image coordinates (x right, y down), normalised to unit length.

    Raises ``ValueError`` for a zero, non-finite or wrongly sized vector.
    """
    if isinstance(direction, (str, bytes, set, frozenset, dict)):
        raise TypeError(f"direction must be a pair (dx, dy) of real numbers, got {type(direction).__name__}")
    try:
        d = np.asarray(direction, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise TypeError(f"direction must be a pair (dx, dy) of real numbers, got {direction!r}") from None
    if d.shape != (2,):
        raise ValueError(f"direction must be a pair (dx, dy), got {direction!r}")
    if not np.all(np.isfinite(d)):
        raise ValueError(f"direction must be finite, got {direction!r}")
    m = float(np.max(np.abs(d)))
    if m == 0:
        raise ValueError("direction must be a non-zero vector (dx, dy)")
    d = d / m  # scaled first: hypot of (1e308, 1e308) overflows, of (5e-324, 0) loses the direction
    n = float(np.hypot(*d))
    return float(d[0] / n), float(d[1] / n)


def _frequencies(w, names=None):
    """Check that each frequency array is real and finite (naming it) and that they broadcast together."""
    out = []
    for i, wi in enumerate(w):
        name = names[i] if names else f"w[{i}]"
        if isinstance(wi, (str, bytes)) or wi is None:
            raise TypeError(f"{name} must be a real array of angular frequencies (rad/sample), got {type(wi).__name__}")
        try:
            arr = np.asarray(wi)
        except (TypeError, ValueError):
            raise TypeError(f"{name} must be a real array of angular frequencies (rad/sample)") from None
        if arr.dtype.kind not in "biuf":
            check_finite_array(name, arr)  # raises the TypeError naming it
        if arr.dtype.kind in "biu" or arr.dtype.itemsize < 8:
            arr = arr.astype(np.float64)  # integer products wrap, float32/16 squares overflow at 1.8e19
        if arr.size:
            lo, hi = float(arr.min()), float(arr.max())  # two passes check both the range and finiteness
            if not (-_BOUND <= lo and hi <= _BOUND):    # (NaN fails both comparisons)
                check_finite_array(name, arr)           # NaN or inf: the message counts them
                raise ValueError(f"{name} must hold angular frequencies within +-1e100 rad/sample (they lie in "
                                 f"[-pi, pi]); got values up to {max(abs(lo), abs(hi)):.3g}")
        out.append(arr)
    try:
        np.broadcast_shapes(*(a.shape for a in out))
    except ValueError:
        shapes = ", ".join(str(a.shape) for a in out)
        raise ValueError(f"the frequency arrays must broadcast together, got shapes {shapes}") from None
    return out


# parameters and frequencies stay within +-1e100 so that their products and sums cannot overflow
_BOUND = 1e100


def _tolerance(tol):
    return check_real("tol (rad/frame)", tol, lo=0.0, hi=_BOUND)


def _pair(name, value):
    return check_real_sequence(name, value, length=2, lo=-_BOUND, hi=_BOUND)


def radial_frequency(*w):
    """``sqrt(sum(w_i**2))`` of broadcast frequency vectors (same units as the inputs).

    Every ``w_i`` must be a finite real array (or number); a ``ValueError``
    or ``TypeError`` names the one that is not.
    """
    if not w:
        raise ValueError("radial_frequency needs at least one frequency array w")
    return _radial(_frequencies(w))


def _radial(w):
    """``sqrt(sum(w_i**2))`` of frequency arrays already checked by :func:`_frequencies`."""
    r2 = 0
    for wi in w:
        r2 = r2 + wi * wi
    return np.sqrt(r2)


def power_law(*w, exponent=1.0):
    """Amplitude ``|w|**(-exponent)`` (thesis 3.2.3: ``exponent=1`` is 1/f), 0 at DC.

    With ``exponent=1`` in two dimensions every octave carries the same energy
    (Field 1987). The radius is taken in the units of ``w`` (rad/sample).
    ``exponent`` is any finite real; a ``ValueError`` says so when
    ``|w|**(-exponent)`` leaves float64's range for the given frequencies.
    """
    exponent = check_real("exponent", exponent)
    r = radial_frequency(*w)
    pos = r > 0
    with np.errstate(divide="ignore", over="ignore", under="ignore"):
        a = np.where(pos, r, 1.0) ** (-exponent)
    if np.ndim(a) == 0:
        a = np.where(pos, a, 0.0)
    else:
        a[~pos] = 0.0  # DC (in place: one pass less than a second np.where)
    if not np.isfinite(a).all():
        rmin = float(np.min(r[pos])) if np.any(pos) else 0.0
        raise ValueError(f"exponent={exponent:g} makes |w|**(-exponent) overflow float64 at |w| = {rmin:g} rad/sample; "
                         "use a smaller exponent (or drop the lowest frequencies)")
    return a


def annulus(*w, band_cycles_per_sample=None, **deprecated):
    """Band limit (thesis 3.2.2): 1 where ``lo <= |w| / (2*pi) <= hi`` cycles/sample, else 0; DC never.

    Parameters
    ----------
    *w : arrays
        Angular frequencies in rad/sample (:func:`noiselab.spectral.frequency_vectors`).
    band_cycles_per_sample : (lo, hi)
        The band in cycles/sample (cycles/pixel), ``0 <= lo <= hi``: the
        radius ``|w| / (2*pi)``. A band of ``(lo, hi)`` cycles/frame, as
        ``spectral_noise`` and ``snow`` take it, on frames ``W`` samples wide
        is ``(lo / W, hi / W)`` here. (The earlier keywords ``lo=`` and
        ``hi=`` were removed in 0.4: they are a ``TypeError`` naming this one.)

    Examples
    --------
    >>> import numpy as np
    >>> w = 2 * np.pi * np.array([0.0, 0.1, 0.2, 0.3])
    >>> annulus(w, band_cycles_per_sample=(0.1, 0.2))
    array([0., 1., 1., 0.])
    """
    lo, hi = _annulus_band(band_cycles_per_sample, deprecated)
    f = radial_frequency(*w) / (2 * np.pi)
    eps = 1e-12
    return ((f >= lo * (1 - eps)) & (f <= hi * (1 + eps)) & (f > 0)).astype(float)


def _annulus_band(band, deprecated):
    """``annulus``'s band, from ``band_cycles_per_sample`` or the deprecated ``lo=``/``hi=`` keywords, checked."""
    unknown = sorted(set(deprecated) - {"lo", "hi"})
    if unknown:
        raise TypeError(f"annulus() got an unexpected keyword argument {unknown[0]!r}; the band is "
                        "band_cycles_per_sample=(lo, hi)")
    if deprecated:
        raise TypeError(f"annulus(): lo= and hi= were removed in noiselab {REMOVED_IN}; pass "
                        "band_cycles_per_sample=(lo, hi), the same unit (cycles/sample)")
    if band is None:
        raise TypeError("annulus needs band_cycles_per_sample=(lo, hi), the band in cycles/sample")
    lo, hi = check_real_sequence("band_cycles_per_sample", band, length=2, lo=0.0, hi=_BOUND)
    if lo > hi:
        raise ValueError(f"annulus needs lo <= hi (cycles/sample), got band_cycles_per_sample=({lo:g}, {hi:g})")
    return lo, hi


def _pair_yx(name, value):
    """A checked pair given in array order ``(y, x)``, returned as ``(x, y)`` for the formulas below."""
    y, x = _pair(name, value)
    return x, y


@array_order(("velocity", "velocity_yx"), positional=("velocity",))
@renamed_parameters(tolerance="tol")
def motion_plane(wt, wy, wx, *, velocity_yx, tol):
    """Energy on the motion plane ``wt = -(vx*wx + vy*wy)`` (Eq. 2.8), ``velocity_yx = (vy, vx)`` px/frame."""
    wt, wy, wx = _frequencies((wt, wy, wx), ("wt", "wy", "wx"))
    vx, vy = _pair_yx("velocity_yx (px/frame)", velocity_yx)
    tol = _tolerance(tol)
    return (np.abs(wt + vx * wx + vy * wy) <= tol).astype(float)


@array_order(("direction", "direction_yx"), positional=("direction", "speeds"))
@renamed_parameters(tolerance="tol")
def optical_snow(wt, wy, wx, *, direction_yx, speeds, tol):
    """Parallel optical snow (Eq. 2.12): motion planes ``wt = -s*(d . w)`` for ``s`` in ``speeds = (smin, smax)`` px/frame.

    ``direction_yx = (dy, dx)``, array order.

    The family of planes fills a wedge around the line ``d . w = 0``; a cell
    is kept when it lies within ``tol`` of one of the planes.
    """
    return nonparallel_optical_snow(wt, wy, wx, direction_yx=direction_yx, speeds=speeds, pan_yx=(0.0, 0.0), tol=tol)


@array_order(("direction", "direction_yx"), ("pan", "pan_yx"), positional=("direction", "speeds", "pan"))
@renamed_parameters(tolerance="tol")
def nonparallel_optical_snow(wt, wy, wx, *, direction_yx, speeds, pan_yx, tol):
    """Non-parallel optical snow (Eq. 2.14): velocities ``u + s*d``, ``s`` in ``speeds``, ``u = pan`` px/frame.

    ``direction_yx = (dy, dx)`` and ``pan_yx = (uy, ux)``, array order.
    """
    wt, wy, wx = _frequencies((wt, wy, wx), ("wt", "wy", "wx"))
    dx, dy = unit_direction_yx("direction_yx", direction_yx)
    smin, smax = sorted(_pair("speeds (px/frame)", speeds))
    ux, uy = _pair_yx("pan_yx (px/frame)", pan_yx)
    tol = _tolerance(tol)
    wv = dx * wx + dy * wy
    base = wt + ux * wx + uy * wy  # = -s * wv on the family
    lo = -np.maximum(smin * wv, smax * wv)
    hi = -np.minimum(smin * wv, smax * wv)
    return ((base >= lo - tol) & (base <= hi + tol)).astype(float)


@array_order(("direction", "direction_yx"), ("pan", "pan_yx"), positional=("direction", "pan"))
def tent_surface(wy, wx, c, *, direction_yx=(1.0, 0.0), pan_yx=(0.0, 0.0)):
    """Temporal frequency (rad/frame) of the (sheared) tent: ``wt = -c*(d·w)/|w| - pan·w``.

    ``c`` is the thesis's tent constant in rad/frame; a flake at spatial
    frequency ``|w|`` rad/px moves along ``d`` (``direction_yx = (dy, dx)``,
    array order) at ``c/|w|`` px/frame, plus the pan velocity
    (``pan_yx = (uy, ux)``). At DC the tent term is taken as 0.

    Examples
    --------
    >>> import numpy as np
    >>> w = 2 * np.pi * 16 / 512          # 16 cycles/frame at 512 px, straight down the image
    >>> float(tent_surface(w, 0.0, c=1.0))  # wt = -c: the flake moves at c/|w| = 5.09 px/frame
    -1.0
    """
    wy, wx = _frequencies((wy, wx), ("wy", "wx"))
    c = check_real("c (rad/frame)", c, lo=-_BOUND, hi=_BOUND)
    direction = unit_direction_yx("direction_yx", direction_yx)
    pan = _pair_yx("pan_yx (px/frame)", pan_yx)
    return tent_surface_terms(wy, wx, c, direction, pan)[0]


def tent_surface_terms(wy, wx, c, direction, pan):
    """:func:`tent_surface` and its two terms, for checked input (internal interface shared with ``noiselab.snow``).

    ``wy``, ``wx``: finite float64 arrays (rad/px); ``c`` a float;
    ``direction`` a unit vector and ``pan`` a pair of floats (px/frame), both
    in the formulas' (x, y) order (an internal interface): nothing
    is checked (:func:`tent_surface` checks, then calls this). Returns
    ``(wt, a, b, r)``: the surface ``wt = -c*a - b`` (rad/frame), its slope
    in ``c``, ``a = (d . w)/|w|`` (0 at DC), the pan's shear ``b = pan . w``
    and the radius ``r = |w|`` (rad/px). ``noiselab.snow`` evaluates the tent
    here at its band's cells only: its thickness is ``thickness * c * |a|``,
    its amplitude ``r**-exponent``.

    Examples
    --------
    >>> import numpy as np
    >>> wt, a, b, r = tent_surface_terms(np.array([0.2]), np.array([0.0]), 1.0, (0.0, 1.0), (0.5, 0.0))
    >>> float(wt[0]), float(a[0]), float(b[0])
    (-1.0, 1.0, 0.0)
    """
    dx, dy = direction
    ux, uy = pan
    r = _radial((wy, wx))
    wv = dx * wx + dy * wy
    pos = r > 0
    a = np.where(pos, wv / np.where(pos, r, 1.0), 0.0)  # (no division by 0: DC divides by 1)
    b = ux * wx + uy * wy
    return -c * a - b, a, b, r


@array_order(("direction", "direction_yx"), positional=("direction",))
@renamed_parameters(tolerance="tol")
def tent(wt, wy, wx, c, *, direction_yx=(1.0, 0.0), tol):
    """The thin tent (Eq. 3.3), cells within ``tol`` rad/frame of :func:`tent_surface`."""
    wt, wy, wx = _frequencies((wt, wy, wx), ("wt", "wy", "wx"))
    tol = _tolerance(tol)
    return (np.abs(wt - tent_surface(wy, wx, c, direction_yx=direction_yx)) <= tol).astype(float)


@array_order(("direction", "direction_yx"), ("pan", "pan_yx"), positional=("direction", "pan"))
@renamed_parameters(tolerance="tol")
def thickened_tent(wt, wy, wx, c, *, direction_yx=(1.0, 0.0), pan_yx=(0.0, 0.0), thickness, tol):
    """Thickened (and optionally sheared) tent (thesis 3.2.1): a small range of tent constants.

    The tent is spread over the constants ``c*(1 - thickness) .. c*(1 + thickness)``
    (the sketch's "a small range of constants c"), i.e. a range of flake speeds
    at each spatial frequency, so the half-width in ``wt`` is
    ``thickness*c*|d . w|/|w|``: zero on the ridge ``d . w = 0`` (patterns that
    do not move), and ``c = 0`` stays frozen snow.
    """
    wt, wy, wx = _frequencies((wt, wy, wx), ("wt", "wy", "wx"))
    c = check_real("c (rad/frame)", c, lo=-_BOUND, hi=_BOUND)
    thickness = check_real("thickness", thickness, lo=0.0, hi=1.0)
    tol = _tolerance(tol)
    dx, dy = unit_direction_yx("direction_yx", direction_yx)
    r = _radial((wy, wx))
    wv = dx * wx + dy * wy
    pos = r > 0
    ratio = np.where(pos, np.abs(wv) / np.where(pos, r, 1.0), 0.0)  # (no division by 0: DC divides by 1)
    half = thickness * abs(c) * ratio
    surface = tent_surface(wy, wx, c, direction_yx=direction_yx, pan_yx=pan_yx)
    return (np.abs(wt - surface) <= tol + half).astype(float)


@array_order(("direction", "direction_yx"), ("pan", "pan_yx"), positional=("direction", "pan"))
@renamed_parameters(tolerance="tol")
def sheared_tent(wt, wy, wx, c, *, direction_yx=(1.0, 0.0), pan_yx=(0.0, 0.0), tol):
    """Sheared tent for a panning camera (Eq. 4.2/4.3, any pan vector): tent plus the plane ``-pan . w``.

    ``pan_yx = (uy, ux)`` is the image velocity (px/frame, array order) the
    camera adds to every flake: a camera panning right makes the world, snow
    included, drift left, ``pan_yx = (0, -s)``.
    """
    wt, wy, wx = _frequencies((wt, wy, wx), ("wt", "wy", "wx"))
    tol = _tolerance(tol)
    return (np.abs(wt - tent_surface(wy, wx, c, direction_yx=direction_yx, pan_yx=pan_yx)) <= tol).astype(float)


# ---------------------------------------------------------------- MotionClouds' envelopes (Leon et al. 2012)
# Same formulas as MotionClouds' envelope_radial (log-Gabor), envelope_orientation and envelope_speed, in
# frequency units that cancel (cycles/sample = rad/sample / 2 pi), each divided by its peak so that a narrow
# orientation band (exp(1 / (4 B_theta**2)) is 1e43 at B_theta = 0.05) cannot overflow.


def log_gabor(*w, sf_0, B_sf):
    """Log-Gabor radial band: ``exp(-ln(f / sf_0)**2 / (2 ln((sf_0 + B_sf) / sf_0)**2))``, 0 at DC.

    ``f = |w| / (2*pi)`` is the radial frequency in cycles/sample over the
    given axes (pass the spatial ones). MotionClouds' ``envelope_radial``
    (``loggabor=True``) is this times ``1/f``.

    Parameters
    ----------
    *w : arrays
        Angular frequencies in rad/sample (:func:`noiselab.spectral.frequency_vectors`).
    sf_0 : float
        Peak frequency in cycles/sample (cycles/pixel), in ``(0, 0.5]``;
        :meth:`noiselab.Display.cycles_per_pixel` converts from cycles/deg.
    B_sf : float
        Bandwidth in cycles/sample, > 0: the band's log-width is
        ``ln((sf_0 + B_sf) / sf_0)`` (``B_sf = sf_0`` is one octave's
        standard deviation).

    Examples
    --------
    >>> import numpy as np
    >>> w = 2 * np.pi * np.array([0.0, 0.0625, 0.125, 0.25])
    >>> log_gabor(w, sf_0=0.125, B_sf=0.125).round(3).tolist()
    [0.0, 0.607, 1.0, 0.607]
    """
    sf_0 = check_real("sf_0 (cycles/sample)", sf_0, lo=0.0, hi=0.5, lo_open=True)
    B_sf = check_real("B_sf (cycles/sample)", B_sf, lo=0.0, hi=_BOUND, lo_open=True)
    f = radial_frequency(*w) / (2 * np.pi)
    log_sf0 = math.log(sf_0)
    width2 = (math.log(sf_0 + B_sf) - log_sf0) ** 2  # (logs apart: B_sf / sf_0 may overflow)
    pos = f > 0
    with np.errstate(divide="ignore", over="ignore", under="ignore"):
        out = np.exp(-0.5 * (np.log(np.where(pos, f, 1.0)) - log_sf0) ** 2 / width2)
    return np.where(pos, out, 0.0)


def orientation(wy, wx, *, theta, B_theta):
    """Orientation band (von Mises): ``exp((cos(2 (angle - theta)) - 1) / (4 B_theta**2))``, peak 1.

    ``angle = arctan2(wy, wx)`` is the direction of the wave vector with y
    down the rows (MotionClouds' ``arctan2(fy, fx)`` on its ``(x, y)``
    arrays): ``theta = 0`` keeps waves along x (vertical stripes),
    ``theta = pi/2`` waves along y (horizontal stripes). ``B_theta`` (radians)
    is about the standard deviation for narrow bands; ``np.inf`` is flat.

    Parameters
    ----------
    wy, wx : arrays
        Angular frequencies (rad/pixel) along y (rows) and x (columns).
    theta : float
        Mean orientation in radians.
    B_theta : float
        Bandwidth in radians, ``>= 1e-6`` (narrower than any grid's angular
        resolution), or ``np.inf`` (every orientation).

    Examples
    --------
    >>> import numpy as np
    >>> float(orientation(np.array(0.0), np.array(1.0), theta=0.0, B_theta=0.2))
    1.0
    >>> float(orientation(np.array(1.0), np.array(0.0), theta=0.0, B_theta=0.2))   # 90 degrees off: exp(-1/(2*0.04))
    3.7266531720786777e-06
    """
    wy, wx = _frequencies((wy, wx), ("wy", "wx"))
    theta = check_real("theta (radians)", theta, lo=-_BOUND, hi=_BOUND)
    if isinstance(B_theta, (int, float, np.floating)) and B_theta == np.inf:
        return np.ones(np.broadcast_shapes(wy.shape, wx.shape))
    B_theta = check_real("B_theta (radians)", B_theta, lo=1e-6, hi=_BOUND)
    angle = np.arctan2(wy, wx)
    with np.errstate(under="ignore"):
        return np.exp((np.cos(2 * (angle - theta)) - 1.0) / (4.0 * B_theta ** 2))


@array_order(("velocity", "velocity_yx"))
def speed_envelope(wt, wy, wx, *, velocity_yx, B_V):
    """Gaussian band around the motion plane: ``exp(-(wt + vx wx + vy wy)**2 / (2 (B_V |w|)**2))``.

    MotionClouds' ``envelope_speed``: energy near the plane of the velocity
    ``velocity_yx = (vy, vx)`` px/frame, array order (the sign convention of :func:`motion_plane`), with
    a thickness ``B_V`` (px/frame) that scales with the spatial radius
    ``|w| = sqrt(wx**2 + wy**2)``. At ``|w| = 0`` the value is 1.
    ``B_V = 0`` keeps only the ``wt = 0`` plane (a frozen texture);
    ``B_V = np.inf`` every temporal frequency.

    Examples
    --------
    >>> import numpy as np
    >>> wt, wx = np.array([-0.5, 0.0]), np.array([0.5, 0.5])
    >>> speed_envelope(wt, np.zeros(2), wx, velocity_yx=(0.0, 1.0), B_V=0.5).round(3).tolist()
    [1.0, 0.135]
    """
    wt, wy, wx = _frequencies((wt, wy, wx), ("wt", "wy", "wx"))
    vx, vy = _pair_yx("velocity_yx (px/frame)", velocity_yx)
    shape = np.broadcast_shapes(wt.shape, wy.shape, wx.shape)
    if isinstance(B_V, (int, float, np.floating)) and B_V == np.inf:
        return np.ones(shape)
    B_V = check_real("B_V (px/frame)", B_V, lo=0.0, hi=_BOUND)
    if B_V == 0:
        return np.broadcast_to((wt == 0).astype(float), shape).copy()
    r = _radial((wy, wx))
    pos = r > 0
    d = wt + vx * wx + vy * wy
    with np.errstate(over="ignore", under="ignore", divide="ignore", invalid="ignore"):
        q = d / (B_V * np.where(pos, r, 1.0))   # a tiny B_V: inf off the plane (weight 0), 0/0 on it (weight 1)
        out = np.where(d == 0, 1.0, np.exp(-0.5 * q * q))
    return np.broadcast_to(np.where(pos, out, 1.0), shape).copy()
