"""Phase scrambling and amplitude swapping: an image's (video's, volume's) amplitude spectrum with other phases.

Both work on the real-FFT half spectrum (``scipy.fft.rfftn`` over ``axes``),
so the output is real by construction: the new phases are those of a white
Gaussian field's spectrum, which obey the conjugacy constraint
``phi(-k) = -phi(k)`` exactly (the self-conjugate cells get 0 or pi: they
stay real). The DC term (the mean) is kept as it is, sign included.
"""
from __future__ import annotations

import numpy as np
import scipy.fft

from .._core import as_generator, check_axes, check_finite_array, check_memory, renamed_parameters

__all__ = ["phase_scramble", "amplitude_swap"]


def _field(name, x):
    """A finite real array of at least one element, as float32 or float64 (the FFT's working precision)."""
    arr = check_finite_array(name, x)
    if arr.size == 0:
        raise ValueError(f"{name} is empty (shape {arr.shape})")
    if arr.ndim == 0:
        raise ValueError(f"{name} must have at least one axis, got a scalar")
    return arr.astype(np.float32 if arr.dtype == np.float32 else np.float64, copy=False)


def _power_of_two_scaled(arr):
    """``(arr / m, m)`` in float64 with ``m`` a power of two within 2x of ``max|arr|`` (the scaled field is below 2).

    The spectra of fields near float64's largest value overflow (a sum of
    N values); both operations are linear in the amplitude, so they run on
    the scaled field and the result is scaled back. A power of two keeps every
    value's bits: the scaling is exact.
    """
    peak = float(np.max(np.abs(arr)))
    m = 1.0 if peak == 0.0 else float(np.ldexp(1.0, int(np.frexp(peak)[1]) - 1))   # 2**1024 would overflow
    return arr.astype(np.float64) / m, m


def _scaled_back(y, m, dtype, name):
    """``y * m`` as ``dtype``, or a ValueError naming ``name`` when that passes the dtype's range."""
    with np.errstate(over="ignore"):
        out = (y * m).astype(dtype, copy=False)
    if not np.all(np.isfinite(out)):
        raise ValueError(f"{name}'s values are too large: the result passes {np.dtype(dtype).name}'s range "
                         f"(largest |{name}| about {m:.3g}; scale {name} down, the operation is linear)")
    return out


def _axes(axes, ndim):
    return tuple(range(ndim)) if axes is None else check_axes("axes", axes, ndim)


def _dc_index(shape, axes):
    """Index of the DC cells (index 0 along every transformed axis) in a half spectrum."""
    return tuple(0 if i in axes else slice(None) for i in range(len(shape)))


@renamed_parameters(seed="rng")
def phase_scramble(x, *, rng=None, axes=None, workers=None) -> np.ndarray:
    """``x`` with its amplitude spectrum kept and its phases replaced by random ones (real output).

    Parameters
    ----------
    x : array_like
        An image ``(H, W)``, a video ``(T, H, W)`` or any real array.
    rng : int, numpy.random.Generator or None
        The random phases: those of the spectrum of a white Gaussian field of
        ``x``'s shape drawn from ``seed``.
    axes : int or tuple of int, optional
        The axes transformed (default all: a video's x-y-t spectrum is kept
        and its motion scrambled). ``axes=(1, 2)`` on a video keeps each
        frame's 2-D amplitude spectrum and scrambles each frame independently.
    workers : int, optional
        scipy.fft's threads.

    Returns
    -------
    ndarray
        Float32 for float32 input, else float64; ``|rfftn(out, axes)|`` equals
        ``|rfftn(x, axes)|`` to float rounding (1e-12 relative in float64,
        checked in ``tests/test_stimuli.py``) and the mean (each slice's
        along the other axes) is kept, sign included.

    Examples
    --------
    >>> import numpy as np, scipy.fft
    >>> img = np.random.default_rng(0).random((64, 64))
    >>> s = phase_scramble(img, rng=1)
    >>> bool(np.allclose(np.abs(scipy.fft.rfftn(s)), np.abs(scipy.fft.rfftn(img))))
    True
    >>> round(float(s.mean() - img.mean()), 12)
    0.0
    """
    arr = _field("x", x)
    ax = _axes(axes, arr.ndim)
    check_memory(arr.size * 8 * 6, f"phase_scramble of shape {arr.shape}")
    rng = as_generator(rng)
    noise = rng.standard_normal(arr.shape)
    P = scipy.fft.rfftn(noise, axes=ax, workers=workers)
    del noise
    mag = np.abs(P)
    # phases of a real field's spectrum: conjugate-symmetric by construction; |P| = 0 has probability 0
    phase = np.divide(P, mag, out=np.ones_like(P), where=mag > 0)
    scaled, m = _power_of_two_scaled(arr)
    S = scipy.fft.rfftn(scaled, axes=ax, workers=workers)
    out = np.abs(S) * phase
    dc = _dc_index(S.shape, ax)
    out[dc] = S[dc]  # the mean, sign included (a random phase of 0 or pi would flip it)
    shape = [arr.shape[i] for i in ax]
    return _scaled_back(scipy.fft.irfftn(out, s=shape, axes=ax, workers=workers), m, arr.dtype, "x")


def amplitude_swap(amplitude_from, phase_from, *, axes=None, workers=None) -> np.ndarray:
    """The amplitude spectrum of ``amplitude_from`` with the phases of ``phase_from`` (real output).

    Parameters
    ----------
    amplitude_from, phase_from : array_like
        Real arrays of one shape.
    axes : int or tuple of int, optional
        The axes transformed (default all).
    workers : int, optional
        scipy.fft's threads.

    Returns
    -------
    ndarray
        Float32 when both inputs are float32, else float64; its amplitude
        spectrum is ``amplitude_from``'s and its DC term (mean)
        ``amplitude_from``'s, sign included; every other cell has
        ``phase_from``'s phase (0 where ``phase_from`` has no energy).

    Examples
    --------
    >>> import numpy as np, scipy.fft
    >>> rng = np.random.default_rng(0)
    >>> a, p = rng.random((32, 32)), rng.random((32, 32))
    >>> s = amplitude_swap(a, p)
    >>> bool(np.allclose(np.abs(scipy.fft.rfftn(s)), np.abs(scipy.fft.rfftn(a))))
    True
    """
    a = _field("amplitude_from", amplitude_from)
    p = _field("phase_from", phase_from)
    if a.shape != p.shape:
        raise ValueError(f"amplitude_from and phase_from must have one shape, got {a.shape} and {p.shape}")
    ax = _axes(axes, a.ndim)
    check_memory(a.size * 8 * 6, f"amplitude_swap of shape {a.shape}")
    a_scaled, m = _power_of_two_scaled(a)
    A = scipy.fft.rfftn(a_scaled, axes=ax, workers=workers)
    P = scipy.fft.rfftn(_power_of_two_scaled(p)[0], axes=ax, workers=workers)   # only its phases count
    mag = np.abs(P)
    phase = np.divide(P, mag, out=np.zeros_like(P), where=mag > 0)
    out = np.abs(A) * phase
    dc = _dc_index(A.shape, ax)
    out[dc] = A[dc]
    dt = np.float32 if a.dtype == np.float32 and p.dtype == np.float32 else np.float64
    shape = [a.shape[i] for i in ax]
    return _scaled_back(scipy.fft.irfftn(out, s=shape, axes=ax, workers=workers), m, dt, "amplitude_from")
