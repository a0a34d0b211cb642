"""1/f checks: the log-log slope of the radial spectrum over a band, and the energy per octave."""
from __future__ import annotations

import functools
import numbers
from dataclasses import dataclass

import numpy as np

from .._core import REMOVED_IN, check_int, check_real
from ._common import check_band, noise_floor
from .spectrum import as_spectrum, radial_spectrum

__all__ = ["Slope", "spectral_slope", "OctaveEnergy", "octave_energy", "default_band"]


class Slope(float):
    """The amplitude slope (a float) with the details of its fit as attributes.

    Attributes
    ----------
    error : float
        Standard error of the amplitude slope (from the scatter of the bins about the line).
    power_slope, power_error : float
        The same fit for the power spectrum: exactly twice the amplitude values.
    intercept : float
        ``log10`` amplitude of the fitted line at 1 cycle/frame.
    band : tuple
        ``(lo, hi)`` in cycles/frame.
    frequencies, amplitude, counts : ndarray
        The log-spaced bins used (mean frequency, radially averaged amplitude, cells).
    """

    error: float
    power_slope: float
    power_error: float
    intercept: float
    band: tuple
    frequencies: np.ndarray
    amplitude: np.ndarray
    counts: np.ndarray

    def __new__(cls, slope, **attrs):
        obj = super().__new__(cls, slope)
        for k, v in attrs.items():
            setattr(obj, k, v)
        return obj

    def __repr__(self):
        return f"Slope({float(self):.4f} +- {self.error:.4f}, band={self.band})"


def default_band(n_ref: int) -> tuple[float, float]:
    """Default fitting band: 2 cycles/frame to a quarter of the frame size (half the Nyquist frequency)."""
    return (2.0, n_ref / 4.0)


def spectral_slope(field, band=None, *, bins_per_octave=8, window=None, axes=None) -> Slope:
    """Log-log slope of the radially averaged *amplitude* spectrum over ``band`` (1/f gives -1).

    The band is cut into log-spaced bins (``bins_per_octave``); each bin's
    mean power (per cell) is turned into an amplitude ``sqrt(P)`` and the
    line ``log A = a + s log f`` is fitted by least squares weighted by the
    number of cells in each bin (the variance of a bin's log power falls as
    one over its cell count), at the bins' mean cell frequency. The power
    slope is ``2 s``.

    Parameters
    ----------
    field : array_like or PowerSpectrum
        1-, 2- or 3-D field. For a video's spatial slope pass ``axes=(-2, -1)``.
    band : (lo, hi), optional
        In cycles/frame, ``0 < lo < hi <= N/2``; default ``(2, N/4)``.
    bins_per_octave : int
    window : {None, "hann"}
        Use ``"hann"`` for images that are not periodic (photographs): the
        edge discontinuity otherwise adds a 1/f^2 power cross along the axes.
    axes : tuple of int, optional

    Returns
    -------
    Slope
        A float (the amplitude slope) carrying ``error``, ``power_slope``, ...

    Raises
    ------
    ValueError
        If the band holds fewer than 3 non-empty bins, or a bin without power
        (a band-limited field measured outside its pass band): never a NaN.

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(1)
    >>> ky, kx = np.fft.fftfreq(256)[:, None], np.fft.rfftfreq(256)[None, :]
    >>> f = np.hypot(kx, ky); f[0, 0] = 1
    >>> spec = rng.standard_normal(f.shape) + 1j * rng.standard_normal(f.shape)
    >>> img = np.fft.irfft2(spec / f, s=(256, 256))
    >>> round(float(spectral_slope(img, (4, 64))), 1)
    -1.0
    """
    bpo = check_int("bins_per_octave", bins_per_octave, lo=1, hi=64)
    spec = as_spectrum(field, window=window, axes=axes)
    n_ref = spec.shape[spec.axes[-1]]
    if n_ref < 8:
        raise ValueError(f"field of shape {spec.shape} is too small to fit a spectral slope (needs at least 8 samples along an axis)")
    band = default_band(n_ref) if band is None else band
    lo, hi = check_band("band", band, n_ref / 2.0)
    if lo < 1e-3:
        raise ValueError(f"band lower edge {lo:g} cycles/frame is below 1e-3: the lowest frequency a field "
                         "holds is 1 cycle/frame")
    n_bins = max(int(np.ceil(np.log2(hi / lo) * bpo)), 1)
    edges = np.geomspace(lo, hi, n_bins + 1)
    edges[-1] *= 1 + 1e-12  # make the upper edge inclusive
    rs = radial_spectrum(spec, bins=edges, log=True)
    if rs.centers.size < 3:
        raise ValueError(
            f"band ({lo:g}, {hi:g}) cycles/frame holds only {rs.centers.size} non-empty frequency bin(s) "
            f"for a field of shape {spec.shape}; a slope needs at least 3: widen the band or use a larger field"
        )
    dead = rs.power <= noise_floor(spec)
    if np.any(dead):
        empty = rs.mean_frequency[dead]
        raise ValueError(
            f"no power at {empty.min():.3g}..{empty.max():.3g} cycles/frame inside band ({lo:g}, {hi:g}): "
            "the field is band-limited there; choose a band inside its pass band"
        )
    x = np.log10(rs.mean_frequency)
    y = 0.5 * np.log10(rs.power)
    w = rs.counts
    xm = np.sum(w * x) / np.sum(w)
    ym = np.sum(w * y) / np.sum(w)
    sxx = np.sum(w * (x - xm) ** 2)
    slope = float(np.sum(w * (x - xm) * (y - ym)) / sxx)
    intercept = float(ym - slope * xm)
    resid = y - (intercept + slope * x)
    dof = max(x.size - 2, 1)
    error = float(np.sqrt(np.sum(w * resid**2) / dof / sxx))
    return Slope(
        slope,
        error=error,
        power_slope=2.0 * slope,
        power_error=2.0 * error,
        intercept=intercept,
        band=(lo, hi),
        frequencies=rs.mean_frequency,
        amplitude=np.sqrt(rs.power),
        counts=rs.counts,
    )


@dataclass(frozen=True)
class OctaveEnergy:
    """Power in octave bands.

    Attributes
    ----------
    edges : ndarray
        Octave edges in cycles/frame (``lo * 2**i``).
    energy : ndarray
        Fraction of the field's total power in each octave.
    spread : float
        ``(max - min) / mean`` of the octave energies: 0 when every octave holds
        the same power (a 2-D field with 1/f amplitude).
    """

    edges: np.ndarray
    energy: np.ndarray
    spread: float

    @property
    def db_range(self) -> float:
        """``10 log10(max / min)`` of the octave energies."""
        return float(10 * np.log10(self.energy.max() / self.energy.min())) if self.energy.min() > 0 else float("inf")


def _octave_band(function):
    """``octave_energy``'s old split band (``lo, hi`` by position or keyword): a ``TypeError`` naming ``band=``."""
    @functools.wraps(function)
    def wrapper(field, *args, **kwargs):
        if (args and isinstance(args[0], numbers.Real)) or "lo" in kwargs or "hi" in kwargs:
            raise TypeError(f"octave_energy(): lo and hi were removed in noiselab {REMOVED_IN}; pass band=(lo, hi) "
                            "instead (hi=None: the Nyquist frequency)")
        return function(field, *args, **kwargs)
    return wrapper


@_octave_band
def octave_energy(field, band=None, *, window=None, axes=None) -> OctaveEnergy:
    """Fraction of the power in each octave band ``[lo 2**i, lo 2**(i+1))`` of ``band = (lo, hi)``.

    A 2-D field whose amplitude falls as 1/f puts the same power in every
    octave (the annulus area grows as f while the power per cell falls as
    1/f**2): its ``spread`` is near 0. (In 3-D the equal-energy law is
    amplitude ~ f**-1.5; for a video's spatial spectrum pass ``axes=(-2, -1)``.)

    Parameters
    ----------
    field : array_like or PowerSpectrum
        1-, 2- or 3-D finite field.
    band : (lo, hi), optional
        In cycles/frame: ``lo`` (> 0) the lower edge of the first octave,
        ``hi`` the upper limit (``None``: the Nyquist frequency, N/2).
        Default ``(1, N/2)``.
    window : {None, "hann"}, optional
        Spatial taper before the FFT; ``"hann"`` for fields that do not tile.
    axes : tuple of int, optional
        The axes whose radial frequency counts (default all).

    Returns
    -------
    OctaveEnergy
        ``edges``, ``energy`` (fraction of the total in each octave) and
        ``spread`` (their relative spread; 0 for equal energy per octave).

    Raises
    ------
    ValueError
        For a non-finite field, ``lo <= 0`` or ``hi <= lo``.

    Examples
    --------
    >>> import numpy as np
    >>> ky, kx = np.fft.fftfreq(128)[:, None], np.fft.rfftfreq(128)[None, :]
    >>> f = np.hypot(kx, ky); f[0, 0] = 1
    >>> img = np.fft.irfft2(np.exp(2j * np.pi * np.random.default_rng(0).random(f.shape)) / f, s=(128, 128))
    >>> oe = octave_energy(img, (4, 64))
    >>> len(oe.energy), oe.spread < 0.1
    (4, True)
    """
    spec = as_spectrum(field, window=window, axes=axes)
    n_ref = spec.shape[spec.axes[-1]]
    if band is None:
        band = (1.0, None)
    if isinstance(band, (str, bytes, set, frozenset, dict)) or not hasattr(band, "__len__") or len(band) != 2:
        raise TypeError(f"band must be a (lo, hi) pair in cycles/frame, got {band!r}")
    lo = check_real("band[0] (lo)", band[0], lo=0.0, lo_open=True)
    hi = n_ref / 2.0 if band[1] is None else check_real("band[1] (hi)", band[1], lo=0.0, lo_open=True)
    check_band("band", (lo, hi), n_ref / 2.0)
    n_oct = int(np.floor(np.log2(hi) - np.log2(lo) + 1e-9))  # logs apart: hi / lo overflows for tiny lo
    if n_oct < 1:
        raise ValueError(f"band = ({lo:g}, {hi:g}) cycles/frame spans less than one octave")
    edges = np.ldexp(lo, np.arange(n_oct + 1))  # lo * 2**k exactly, without overflowing 2**k
    bins = edges.copy()
    bins[-1] *= 1 + 1e-12
    rs = radial_spectrum(spec, bins=bins, log=True)
    energy = np.zeros(n_oct)
    # radial_spectrum drops empty bins: put the survivors back in place
    pos = np.searchsorted(edges, rs.centers) - 1
    energy[pos] = rs.energy / rs.total if rs.total > 0 else 0.0
    mean = energy.mean()
    spread = float((energy.max() - energy.min()) / mean) if mean > 0 else float("inf")
    return OctaveEnergy(edges=edges, energy=energy, spread=spread)
