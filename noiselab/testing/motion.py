"""Assertions about motion: energy on the motion plane of a velocity, or on Langer & Zhang's tent."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._core import HIDE_ASSERTION_FRAMES, array_order, check_real
from ..analysis import motion_energy, tent_energy, video_spectrum

__all__ = ["MotionCheck", "assert_motion", "assert_tent"]


@dataclass(frozen=True)
class MotionCheck:
    """Energy on a motion surface.

    Attributes
    ----------
    energy : float
        Fraction of the video's power on the surface (within ``tol`` temporal cells).
    opposite : float
        The same fraction for the opposite motion (``-velocity``, or the tent falling up): what a sign error gives.
    chance : float
        The fraction a video whose power is spread evenly over temporal frequency would put there: ``(2 tol + 1) / T``.
    min_energy : float
    message : str
    """

    energy: float
    opposite: float
    chance: float
    min_energy: float
    message: str


_WHY = ("a deterministic fraction of the spectrum: a video that moves so has all its power there whatever its "
        "seed, up to its temporal bandwidth")


def _judge(what, energy, opposite, chance, min_energy, given, extra=""):
    __tracebackhide__ = HIDE_ASSERTION_FRAMES  # a failure reports the caller's line and the message
    how = f"given min_energy {min_energy:g}" if given else f"default min_energy {min_energy:g} ({_WHY})"
    msg = (f"{what}: {energy:.6g} of the power lies on it (the opposite motion: {opposite:.3g}; chance for power "
           f"spread evenly over temporal frequency: {chance:.3g}){extra}; required at least {how}")
    if not energy >= min_energy:
        raise AssertionError(msg)
    return MotionCheck(energy=energy, opposite=opposite, chance=chance, min_energy=min_energy, message=msg)


def _min_energy(min_energy):
    if min_energy is None:
        return 0.9, False
    return check_real("min_energy", min_energy, lo=0.0, hi=1.0), True


@array_order(("velocity", "velocity_yx"), positional=("velocity",))
def assert_motion(video, *, velocity_yx, min_energy=None, tol=1.0, band=None, window=None) -> MotionCheck:
    """Assert that a video's power lies on the motion plane of ``velocity_yx`` (px/frame): it moves that way.

    An image translating with velocity ``v`` puts all its power on the plane
    ``w_t = -v . w`` (:func:`noiselab.analysis.motion_energy`); a motion
    cloud with a speed bandwidth spreads it around the plane. The fraction
    within ``tol`` temporal-frequency cells of the plane is a property of
    the spectrum, not a sampling estimate (every seed of a translating video
    gives 1), so the threshold is a stated fraction: ``min_energy`` (default
    0.9). The message reports the fraction for ``-velocity_yx`` (a sign
    error) and the chance level ``(2 tol + 1) / frames``.

    ``tol`` is a distance in temporal-frequency cells (``1 / frames``
    cycles/frame each), not a velocity: a cell is a velocity step of
    ``1 / (frames |w|)`` px/frame at spatial frequency ``|w|`` (cycles/px),
    so the same ``tol`` accepts a wide range of velocities at low spatial
    frequencies and few at high ones, and a cloud with a broad speed
    bandwidth puts less than ``min_energy`` within it at its true velocity
    (a 128 x 128 x 64 ``motion_cloud`` with ``B_V=0.5``, ``sf_0=0.125``:
    ``tests/test_testing.py``). To check a velocity in px/frame or deg/s
    with a standard error, use :func:`assert_velocity`.

    Parameters
    ----------
    video : array_like
        ``(frames, height, width)``, looping in time (or pass ``window="hann"`` and ``tol >= 1.5``).
    velocity_yx : (vy, vx)
        Pixels/frame in array order, y down, x right. ``velocity=(vx, vy)``
        (also by position) is the old spelling, refused since 0.4.
    min_energy : float, optional
        Fraction of the power required on the plane (0 to 1); default 0.9.
    tol : float
        Accepted distance from the plane in temporal-frequency cells.
    band : (lo, hi), optional
        Spatial band in cycles/frame (the fraction is still of the total power).
    window : {None, "hann"}

    Returns
    -------
    MotionCheck

    Raises
    ------
    AssertionError
        If less than ``min_energy`` of the power lies on the plane.
    ValueError, TypeError
        For bad input, naming the parameter.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab.testing import assert_motion
    >>> img = np.random.default_rng(0).random((32, 32))
    >>> video = np.stack([np.roll(img, (t, 2 * t), axis=(0, 1)) for t in range(32)])  # (vy, vx) = (1, 2)
    >>> round(assert_motion(video, velocity_yx=(1, 2)).energy, 6)
    1.0
    >>> assert_motion(video, velocity_yx=(-1, -2))
    Traceback (most recent call last):
    ...
    AssertionError: motion at (vy, vx) = (-1, -2) px/frame ...
    """
    __tracebackhide__ = HIDE_ASSERTION_FRAMES  # a failure reports the caller's line and the message
    spec = video_spectrum(video, window=window)
    min_energy, given = _min_energy(min_energy)
    energy = motion_energy(spec, velocity_yx=velocity_yx, tol=tol, band=band)
    vy, vx = float(velocity_yx[0]), float(velocity_yx[1])
    opposite = motion_energy(spec, velocity_yx=(-vy, -vx), tol=tol, band=band)
    chance = min(1.0, (2 * float(tol) + 1) / spec.shape[0])
    where = "" if band is None else f" in the spatial band {band[0]:g}..{band[1]:g} cycles/frame"
    return _judge(f"motion at (vy, vx) = ({vy:g}, {vx:g}) px/frame{where} (plane w_t = -v.w, within {float(tol):g} "
                  "temporal cells)", energy, opposite, chance, min_energy, given)


@array_order(("direction", "direction_yx"), ("pan", "pan_yx"))
def assert_tent(video, c, band, *, direction_yx=(1.0, 0.0), pan_yx=(0.0, 0.0), thickness=0.1, tol=0.5, min_energy=None,
                window=None) -> MotionCheck:
    """Assert that a video's power inside ``band`` lies on Langer & Zhang's falling-snow tent.

    The tent ``w_t = -((c / |w|) d + pan) . w`` (:func:`noiselab.analysis.tent_energy`):
    layers whose speed is inversely proportional to their spatial frequency,
    falling along ``direction_yx``, with ``c`` in rad/frame. Like
    :func:`assert_motion` the fraction is a property of the spectrum; the
    default ``min_energy`` is 0.9 (noiselab's raw snow puts 1 - 1e-6 there, its
    alpha matte 0.98).

    Parameters
    ----------
    video : array_like
        ``(frames, height, width)``.
    c : float
        Rad/frame, ``0 <= c <= pi``.
    band : (lo, hi)
        Spatial band, cycles/frame.
    direction_yx, pan_yx : (y, x)
        Fall direction (unit or not) and camera pan (px/frame), array order.
        ``direction=``/``pan=`` in (x, y) order are the old spellings, refused since 0.4.
    thickness, tol : float
        See :func:`noiselab.analysis.tent_energy`.
    min_energy : float, optional
        Default 0.9.
    window : {None, "hann"}

    Returns
    -------
    MotionCheck
        ``opposite`` is the fraction on the tent of snow falling the other way.

    Raises
    ------
    AssertionError
        If less than ``min_energy`` of the power lies on the tent.
    ValueError, TypeError
        For bad input, naming the parameter.

    Examples
    --------
    >>> import noiselab
    >>> from noiselab.testing import assert_tent
    >>> snow = noiselab.snow((16, 64, 64), rng=1, c=1.0, rescale=False)
    >>> assert_tent(snow, 1.0, (2, 16)).energy > 0.999
    True
    """
    __tracebackhide__ = HIDE_ASSERTION_FRAMES  # a failure reports the caller's line and the message
    spec = video_spectrum(video, window=window)
    min_energy, given = _min_energy(min_energy)
    energy = tent_energy(spec, c, band, direction_yx=direction_yx, pan_yx=pan_yx, thickness=thickness, tol=tol)
    d = np.asarray(direction_yx, dtype=np.float64)
    opposite = tent_energy(spec, c, band, direction_yx=(-d[0], -d[1]), pan_yx=pan_yx, thickness=thickness, tol=tol)
    chance = min(1.0, (2 * float(tol) + 1) / spec.shape[0])  # a thin tent's
    return _judge(f"tent c={float(c):g} rad/frame falling along (y, x) = ({d[0]:g}, {d[1]:g}), pan (y, x) = "
                  f"({float(pan_yx[0]):g}, {float(pan_yx[1]):g}) px/frame, in the band {float(band[0]):g}..{float(band[1]):g} cycles/frame",
                  energy, opposite, chance, min_energy, given)
