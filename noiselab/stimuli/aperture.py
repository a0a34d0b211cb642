"""Apertures: the window a stimulus is seen through, on the mean luminance.

A vision experiment shows its noise in a circular window, a circular window
with a raised-cosine edge, or a Gaussian envelope, on a background at the mean
luminance. Each function here returns that window as an ``(ny, nx)`` array of
weights in ``[0, 1]`` (1: the stimulus at full contrast, 0: the mean
luminance), sized in degrees of visual angle on a :class:`Display` and centred
on the frame (at pixel ``((ny - 1) / 2, (nx - 1) / 2)``). Pass it to
:func:`to_display` as ``aperture=``: the field is shown as
``L = mean * (1 + w * k * z)``, so it blends to the mean luminance where the
window falls to 0, and its contrast is stated inside the window.
"""
from __future__ import annotations

import numpy as np

from .._core import check_memory, check_real, check_shape
from .display import Display

__all__ = ["circular_aperture", "raised_cosine_aperture", "gaussian_aperture"]


def _radius_deg(shape, display):
    """Each pixel's distance from the frame's centre, in degrees (float64, ``(ny, nx)``)."""
    if not isinstance(display, Display):
        raise TypeError(f"display must be a noiselab.Display, got {type(display).__name__}")
    shape = check_shape("shape", shape, ndim={2, 3})
    ny, nx = shape[-2:]
    check_memory(ny * nx * 8 * 3, f"an aperture of {ny} x {nx} pixels")
    y = (np.arange(ny) - (ny - 1) / 2.0)[:, None]
    x = (np.arange(nx) - (nx - 1) / 2.0)[None, :]
    return np.hypot(y, x) / display.pixels_per_degree


def _diameter(diameter_deg):
    return check_real("diameter_deg", diameter_deg, lo=0.0, lo_open=True, hi=1e6)


def circular_aperture(shape, display, *, diameter_deg) -> np.ndarray:
    """A hard-edged circular window: 1 within ``diameter_deg / 2`` degrees of the centre, 0 outside.

    Parameters
    ----------
    shape : tuple of int
        ``(ny, nx)`` or a video's ``(T, ny, nx)`` (the window is the frames' one).
    display : Display
        Gives the pixels per degree.
    diameter_deg : float
        The window's diameter in degrees of visual angle, > 0.

    Returns
    -------
    ndarray, float64, ``(ny, nx)``, values 0 and 1.

    Raises
    ------
    ValueError
        A bad shape or a diameter that is not a positive number.

    Examples
    --------
    >>> from noiselab import Display
    >>> w = circular_aperture((64, 64), Display(32.0), diameter_deg=1.0)   # 32 px across
    >>> int(w.sum()), float(w[32, 32]), float(w[0, 0])
    (812, 1.0, 0.0)
    """
    r = _radius_deg(shape, display)
    return (r <= _diameter(diameter_deg) / 2.0).astype(np.float64)


def raised_cosine_aperture(shape, display, *, diameter_deg, ramp_deg) -> np.ndarray:
    """A circular window whose edge falls from 1 to 0 as half a cosine period over ``ramp_deg`` degrees.

    The window is 1 out to the radius ``diameter_deg / 2 - ramp_deg``, falls
    as ``(1 + cos(pi * (r - r0) / ramp_deg)) / 2`` across the ramp and is 0
    from the radius ``diameter_deg / 2`` on: the whole stimulus, ramp included,
    lies within the stated diameter (its value is 0.5 at ``ramp_deg / 2``
    inside the edge).

    Parameters
    ----------
    shape : tuple of int
        ``(ny, nx)`` or ``(T, ny, nx)``.
    display : Display
        Gives the pixels per degree.
    diameter_deg : float
        Outer diameter in degrees, > 0.
    ramp_deg : float
        Width of the cosine edge in degrees, ``0 < ramp_deg <= diameter_deg / 2``.

    Returns
    -------
    ndarray, float64, ``(ny, nx)``, values in [0, 1].

    Raises
    ------
    ValueError
        A bad shape, diameter or ramp (the message names it and its range).

    Examples
    --------
    >>> from noiselab import Display
    >>> w = raised_cosine_aperture((65, 65), Display(32.0), diameter_deg=2.0, ramp_deg=0.5)
    >>> float(w[32, 32]), float(w[32, 32 + 24]), float(w[32, 32 + 32])   # centre, mid-ramp, edge
    (1.0, 0.5, 0.0)
    """
    d = _diameter(diameter_deg)
    ramp = check_real("ramp_deg", ramp_deg, lo=0.0, lo_open=True, hi=d / 2.0)
    r = _radius_deg(shape, display)
    r0 = d / 2.0 - ramp
    t = np.clip((r - r0) / ramp, 0.0, 1.0)
    return 0.5 * (1.0 + np.cos(np.pi * t))


def gaussian_aperture(shape, display, *, sigma_deg) -> np.ndarray:
    """A Gaussian envelope ``exp(-r**2 / (2 sigma_deg**2))``, 1 at the centre, ``r`` in degrees.

    Parameters
    ----------
    shape : tuple of int
        ``(ny, nx)`` or ``(T, ny, nx)``.
    display : Display
        Gives the pixels per degree.
    sigma_deg : float
        The envelope's standard deviation in degrees, > 0 (its full width at
        half maximum is ``2 sqrt(2 ln 2) sigma_deg``, 2.355 sigma).

    Returns
    -------
    ndarray, float64, ``(ny, nx)``, values in (0, 1].

    Raises
    ------
    ValueError
        A bad shape or a sigma that is not a positive number.

    Examples
    --------
    >>> from noiselab import Display
    >>> w = gaussian_aperture((65, 65), Display(32.0), sigma_deg=0.5)     # sigma 16 px
    >>> float(w[32, 32]), round(float(w[32, 48]), 4)                      # centre, one sigma out
    (1.0, 0.6065)
    """
    sigma = check_real("sigma_deg", sigma_deg, lo=0.0, lo_open=True, hi=1e6)
    r = _radius_deg(shape, display)
    return np.exp(-0.5 * (r / sigma) ** 2)
