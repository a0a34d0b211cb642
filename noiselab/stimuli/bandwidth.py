"""Bandwidths as vision papers state them, to and from MotionClouds' ``B_sf`` and ``B_theta``.

Papers give a spatial-frequency bandwidth in octaves, the full width at half
maximum (FWHM), and an orientation bandwidth in degrees, the half width at
half height (HWHM). :func:`motion_cloud` takes MotionClouds' parameters:

- ``B_sf``: the log-Gabor band ``G(f) = exp(-ln(f / sf_0)**2 / (2 s**2))``
  with ``s = ln((sf_0 + B_sf) / sf_0)``. Its amplitude falls to half at
  ``ln(f / sf_0) = +-s sqrt(2 ln 2)``, so the FWHM is
  ``2 s sqrt(2 ln 2) / ln 2`` octaves (``B_sf = sf_0 / 2``: s = ln 1.5, 1.38
  octaves; one octave is ``s = 0.2944``).
- ``B_theta``: the orientation band ``exp((cos(2 d) - 1) / (4 B_theta**2))``
  of the angle ``d`` from ``theta``; its amplitude is half at
  ``sin(d) = B_theta sqrt(2 ln 2)``, so ``B_theta = sin(HWHM) / sqrt(2 ln 2)``.
  From ``B_theta = 1 / sqrt(2 ln 2) = 0.849`` rad up the band never falls to
  half (its least, at 90°, is ``exp(-1 / (2 B_theta**2))``).

Both widths are those of the *amplitude* envelope, as a filter's bandwidth is
stated; the power (its square) is at half where the amplitude is at
``1 / sqrt(2)``: the power's widths are ``1 / sqrt(2)`` of these in octaves
(and ``asin(sin(HWHM) / sqrt(2))`` in orientation).

Where the power lies: MotionClouds' radial envelope is ``G(f) / f`` (a 1/f
spectrum through the band), so the power per octave, ``f**2`` times the
per-frequency density of a 2-D field, is ``G(f)**2`` and peaks at ``sf_0``
exactly; the power per frequency cell peaks lower, at ``sf_0 exp(-s**2)``
(0.848 ``sf_0`` for ``s = ln 1.5``), and the power per unit frequency
(summed over a ring) at ``sf_0 exp(-s**2 / 2)`` (0.921 ``sf_0``). A moving
cloud's speed band is ``B_V |w|`` wide in temporal frequency, so over the
frames each spatial frequency holds power in proportion to ``|w|`` as well:
its spatial spectrum peaks one ``exp(s**2 / 2)`` higher than a still one's.
``tests/test_stimuli.py`` measures these on :func:`cloud_envelope`.
"""
from __future__ import annotations

import math

import numpy as np

from .._core import check_real

__all__ = ["B_sf_from_octaves", "octaves_from_B_sf", "B_theta_from_hwhm", "hwhm_from_B_theta"]

_HALF = math.sqrt(2.0 * math.log(2.0))   # where a Gaussian amplitude is at half: sqrt(2 ln 2) standard deviations


def B_sf_from_octaves(*, sf_0, sf_bandwidth_octaves):
    """MotionClouds' ``B_sf`` for a spatial-frequency bandwidth in octaves (FWHM of the amplitude band).

    Parameters
    ----------
    sf_0 : float
        The band's centre, > 0, in any unit (cycles/pixel for :func:`motion_cloud`).
    sf_bandwidth_octaves : float
        Full width at half maximum of the log-Gabor amplitude band, octaves, in ``(0, 20]``.

    Returns
    -------
    float
        ``B_sf`` in the unit of ``sf_0``: ``sf_0 * (exp(s) - 1)`` with
        ``s = octaves * ln 2 / (2 sqrt(2 ln 2))``.

    Examples
    --------
    >>> round(B_sf_from_octaves(sf_0=0.125, sf_bandwidth_octaves=1.0), 6)        # one octave at 0.125 cycles/pixel
    0.042782
    >>> b = B_sf_from_octaves(sf_0=0.125, sf_bandwidth_octaves=1.5)
    >>> round(octaves_from_B_sf(sf_0=0.125, B_sf=b), 12)
    1.5
    """
    sf_0 = check_real("sf_0", sf_0, lo=0.0, lo_open=True, hi=1e12)
    octaves = check_real("sf_bandwidth_octaves", sf_bandwidth_octaves, lo=0.0, lo_open=True, hi=20.0)
    s = octaves * math.log(2.0) / (2.0 * _HALF)
    return float(sf_0 * math.expm1(s))


def octaves_from_B_sf(*, sf_0, B_sf):
    """The FWHM in octaves of the log-Gabor amplitude band of MotionClouds' ``sf_0`` and ``B_sf``.

    Parameters
    ----------
    sf_0, B_sf : float
        The band's centre and MotionClouds' bandwidth, both > 0, in one unit.

    Returns
    -------
    float
        ``2 s sqrt(2 ln 2) / ln 2`` with ``s = ln((sf_0 + B_sf) / sf_0)``.

    Examples
    --------
    >>> round(octaves_from_B_sf(sf_0=4.0, B_sf=2.0), 4)           # noiselab stimulus's default: 4 and 2 cycles/deg
    1.3775
    """
    sf_0 = check_real("sf_0", sf_0, lo=0.0, lo_open=True, hi=1e12)
    B_sf = check_real("B_sf", B_sf, lo=0.0, lo_open=True, hi=1e12)
    return float(2.0 * math.log1p(B_sf / sf_0) * _HALF / math.log(2.0))


def B_theta_from_hwhm(*, orientation_hwhm_deg):
    """MotionClouds' ``B_theta`` (radians) for an orientation half width at half height in degrees.

    Parameters
    ----------
    orientation_hwhm_deg : float
        Half width at half height of the orientation amplitude band, degrees, in ``(0, 90]``.

    Returns
    -------
    float
        ``sin(HWHM) / sqrt(2 ln 2)`` radians.

    Examples
    --------
    >>> round(B_theta_from_hwhm(orientation_hwhm_deg=15.0), 6)
    0.219821
    >>> round(hwhm_from_B_theta(B_theta=B_theta_from_hwhm(orientation_hwhm_deg=15.0)), 9)
    15.0
    """
    hwhm = check_real("orientation_hwhm_deg", orientation_hwhm_deg, lo=0.0, lo_open=True, hi=90.0)
    return float(math.sin(math.radians(hwhm)) / _HALF)


def hwhm_from_B_theta(*, B_theta=np.inf):
    """The half width at half height in degrees of MotionClouds' orientation band ``B_theta`` (radians).

    Parameters
    ----------
    B_theta : float
        Radians, > 0 (``np.inf``, the default as in :func:`motion_cloud`: every orientation).

    Returns
    -------
    float
        Degrees; ``inf`` from ``B_theta = 1 / sqrt(2 ln 2)`` (0.849 rad) up,
        where the band never falls to half.

    Examples
    --------
    >>> round(hwhm_from_B_theta(B_theta=0.2), 3)
    13.62
    >>> hwhm_from_B_theta(B_theta=1.0)
    inf
    """
    if isinstance(B_theta, (int, float, np.floating)) and B_theta == np.inf:
        return math.inf
    b = check_real("B_theta (radians)", B_theta, lo=0.0, lo_open=True, hi=1e12)
    x = b * _HALF
    return math.inf if x >= 1.0 else float(math.degrees(math.asin(x)))
