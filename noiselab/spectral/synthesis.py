"""Spectral synthesis on the real-FFT half spectrum: envelope x random amplitude x random phase, then ``irfftn``.

Conjugacy. A real field's spectrum obeys ``S(-k) = conj(S(k))`` (thesis
Eq. 2.7). On the half spectrum of ``rfftn`` (last axis ``0 .. W//2``) the
constraint is implicit everywhere except on the *self-conjugate planes*: the
``kx = 0`` plane and, for even ``W``, the ``kx = W/2`` (Nyquist) plane. Inside
each plane a cell ``k`` and its mirror ``-k`` (indices modulo the sizes) are
both stored, and ``irfftn`` silently keeps only the Hermitian part of whatever
is there -- a spectrum built carelessly loses half the power on those planes
(MotionClouds' ``ifftn(...).real`` loses it everywhere). Here each mirror pair
gets one random value and its conjugate, and the purely real cells (every index
0 or n/2) get a real value of the same magnitude (random sign), so every cell
keeps exactly its prescribed power and ``rfftn(irfftn(S)) == S`` to float
precision.

Random amplitudes are normalised to ``E[a**2] = 1``, so the expected power of
every cell equals the envelope squared:

- ``"uniform"``: ``a`` uniform on ``[0, sqrt(3)]`` (the thesis's ``rand([0,1])``, rescaled),
- ``"rayleigh"``: complex Gaussian coefficients (a Gaussian random field),
- ``"fixed"``: ``a = 1``, random phase only (``|S|`` equals the envelope exactly).
"""
from __future__ import annotations

import numpy as np
import scipy.fft

from .._validate import as_generator, check_memory, check_real, check_shape, float_dtype
from .envelopes import annulus, power_law
from .frequencies import frequency_vectors, half_spectrum_shape

__all__ = ["synthesize", "spectral_noise", "draw_coefficients", "hermitian_plane", "AMPLITUDES"]

AMPLITUDES = ("uniform", "rayleigh", "fixed")


def _complex_dtype(dtype):
    return np.dtype(np.complex64) if np.dtype(dtype) == np.float32 else np.dtype(np.complex128)


def draw_coefficients(n, rng, amplitude="uniform", dtype=np.float32) -> np.ndarray:
    """``n`` random complex coefficients ``a * exp(i*phi)`` with ``E[|.|**2] = 1`` (see the module notes).

    The draws happen in one fixed order (all amplitudes, then all phases), so
    the same generator state always gives the same values.

    Examples
    --------
    >>> import numpy as np
    >>> z = draw_coefficients(100000, np.random.default_rng(0), "rayleigh")
    >>> z.dtype, round(float(np.mean(np.abs(z) ** 2)), 2)
    (dtype('complex64'), 1.0)
    """
    if amplitude not in AMPLITUDES:
        raise ValueError(f"amplitude must be one of {AMPLITUDES}, got {amplitude!r}")
    fdt = np.dtype(dtype)
    if amplitude == "uniform":
        a = rng.random(n, dtype=np.float64) * np.sqrt(3.0)
    elif amplitude == "rayleigh":
        a = np.sqrt(-np.log1p(-rng.random(n, dtype=np.float64)))
    else:
        a = np.ones(n)
    phi = rng.random(n, dtype=np.float64) * (2 * np.pi)
    out = np.empty(n, dtype=_complex_dtype(fdt))
    out.real = a * np.cos(phi)
    out.imag = a * np.sin(phi)
    return out


def _mirror(a):
    """``a[-k]`` for every index ``k`` (indices modulo each axis length)."""
    for ax in range(a.ndim):
        a = np.roll(np.flip(a, ax), 1, ax)
    return a


def hermitian_plane(plane, support=None):
    """Make a self-conjugate plane Hermitian, ``P[-k] = conj(P[k])``, without losing or doubling power.

    Parameters
    ----------
    plane : complex ndarray
        Values on a self-conjugate plane (e.g. ``S[..., 0]``); any number of axes.
    support : bool ndarray, optional
        Where the envelope carries energy (default ``plane != 0``).

    Returns
    -------
    ndarray
        The Hermitian plane. Of each mirror pair the first in C order (the
        *canonical* cell) keeps its value and the other receives its conjugate;
        if only one of the two is in the support, its value is used for both
        (the support becomes symmetric, every supported cell keeps its
        magnitude). Self-conjugate cells become real with their magnitude kept:
        ``|v| * sign(Re v)``.

    Examples
    --------
    >>> import numpy as np
    >>> hermitian_plane(np.array([1 + 1j, 2 + 0j, 0j, 3j]))  # k=1 and k=3 are a mirror pair
    array([1.41421356+0.j, 2.        +0.j, 0.        +0.j, 2.        -0.j])
    """
    plane = np.asarray(plane)
    if plane.ndim == 0:
        v = plane[()]
        return np.asarray(abs(v) * (1.0 if v.real >= 0 else -1.0), dtype=plane.dtype)
    if support is None:
        support = plane != 0
    lin = np.arange(plane.size).reshape(plane.shape)
    lin_m = _mirror(lin)
    canonical = lin < lin_m
    selfconj = lin == lin_m
    mir = _mirror(plane)
    sup_m = _mirror(support)
    # canonical cells: own value, or the mirror's conjugate when only the mirror is supported
    take_mirror = canonical & ~support & sup_m
    out = np.where(take_mirror, np.conj(mir), plane)
    out = np.where(canonical | selfconj, out, np.conj(_mirror(out)))
    sc = out[selfconj]
    out[selfconj] = np.abs(sc) * np.where(sc.real >= 0, 1.0, -1.0)
    return out


def _hermitian_half_spectrum(spec, support, last_n):
    """Apply :func:`hermitian_plane` to the kx = 0 (and, for even ``last_n``, Nyquist) planes in place."""
    planes = [0] + ([last_n // 2] if last_n % 2 == 0 and last_n > 1 else [])
    if last_n == 1:
        planes = [0]
    for j in planes:
        spec[..., j] = hermitian_plane(spec[..., j], support[..., j])
    return spec


def synthesize(shape, envelope, *, seed=None, amplitude="uniform", dtype=np.float32, return_spectrum=False):
    """Real random field with the given amplitude envelope: ``irfftn(envelope * a * exp(i*phi))``.

    Parameters
    ----------
    shape : tuple of int
        Shape of the real output, 1 to 3 axes (or more), e.g. ``(T, H, W)``.
    envelope : callable or ndarray
        ``envelope(*w)`` receives the broadcast frequency vectors of
        :func:`frequency_vectors` (rad/sample, one per axis) and returns the
        amplitude, broadcastable to the half spectrum ``(..., W//2 + 1)``; or
        that amplitude array itself. Must be finite and non-negative.
    seed : int or numpy.random.Generator
        Random phases and amplitudes (drawn only on the envelope's support).
    amplitude : {"uniform", "rayleigh", "fixed"}
        Distribution of the random amplitude (``E[a**2] = 1``).
    dtype : float32 or float64
        Output dtype (the spectrum is complex64 or complex128).
    return_spectrum : bool
        Also return the half spectrum ``S`` with ``rfftn(field) == S``.

    Returns
    -------
    field : ndarray
        ``irfftn(S, shape)``, zero mean when the envelope is 0 at DC.
    spectrum : ndarray, only with ``return_spectrum``.

    Examples
    --------
    >>> import numpy as np, scipy.fft
    >>> from noiselab.spectral import envelopes as E
    >>> f, S = synthesize((32, 32), lambda wy, wx: E.annulus(wy, wx, lo=0.05, hi=0.3),
    ...                   seed=1, dtype=np.float64, return_spectrum=True)
    >>> bool(np.allclose(scipy.fft.rfftn(f), S))
    True
    """
    shape = check_shape("shape", shape)
    dt = float_dtype(dtype)
    cdt = _complex_dtype(dt)
    hshape = half_spectrum_shape(shape)
    n_out = int(np.prod(shape))
    check_memory(n_out * dt.itemsize + 3 * int(np.prod(hshape)) * cdt.itemsize, f"synthesize{shape}")
    if callable(envelope):
        env = envelope(*frequency_vectors(shape))
    else:
        env = envelope
    env = np.broadcast_to(np.asarray(env, dtype=float), hshape)
    if not np.all(np.isfinite(env)):
        raise ValueError("envelope must be finite everywhere (an infinite amplitude at DC? multiply by an annulus)")
    if np.any(env < 0):
        raise ValueError("envelope must be non-negative (it is an amplitude)")
    rng = as_generator(seed)
    support = env > 0
    spec = np.zeros(hshape, dtype=cdt)
    idx = np.flatnonzero(support)
    coef = draw_coefficients(idx.size, rng, amplitude, dt)
    spec.reshape(-1)[idx] = coef * env.reshape(-1)[idx].astype(dt)
    _hermitian_half_spectrum(spec, support, shape[-1])
    field = scipy.fft.irfftn(spec, s=shape)
    if field.dtype != dt:
        field = field.astype(dt)
    return (field, spec) if return_spectrum else field


def spectral_noise(shape, *, exponent=1.0, band=None, seed=None, amplitude="rayleigh", dtype=np.float32):
    """Isotropic band-limited ``1/f**exponent`` noise in 1, 2 or 3 dimensions, zero mean and unit variance.

    Parameters
    ----------
    shape : int or tuple of int
        ``(n,)``, ``(H, W)`` or ``(D, H, W)``; isotropic in samples (pixels).
    exponent : float
        Amplitude falls as ``f**-exponent`` (1: pink/"1/f"; 2: brown). In 2-D,
        ``exponent=1`` gives equal energy per octave.
    band : (lo, hi), optional
        Pass band in cycles per frame along the last axis (cycles per
        ``shape[-1]`` samples), inclusive; ``hi`` at most the Nyquist frequency
        ``shape[-1]/2``. Default: everything but DC.
    seed : int or numpy.random.Generator
    amplitude : {"rayleigh", "uniform", "fixed"}
        Default: complex Gaussian coefficients, i.e. a Gaussian field.
    dtype : float32 or float64

    Examples
    --------
    >>> x = spectral_noise((64, 64), exponent=1.0, band=(2, 16), seed=0)
    >>> x.shape, x.dtype, round(float(x.std()), 3)
    ((64, 64), dtype('float32'), 1.0)
    """
    shape = check_shape("shape", shape, ndim={1, 2, 3})
    exponent = check_real("exponent", exponent, lo=-8, hi=8)
    n = shape[-1]
    if band is None:
        lo, hi = 0.0, 0.5 * np.sqrt(len(shape)) + 1.0  # everything, corners included
    else:
        lo, hi = _check_band(band, n)
        lo, hi = lo / n, hi / n

    def envelope(*w):
        return annulus(*w, lo=lo, hi=hi) * power_law(*w, exponent=exponent)

    field = synthesize(shape, envelope, seed=seed, amplitude=amplitude, dtype=dtype)
    field -= field.mean(dtype=np.float64)
    sd = float(field.std(dtype=np.float64))
    if sd > 0:
        field *= field.dtype.type(1.0 / sd)
    return field


def _check_band(band, n):
    """Validate a pass band ``(lo, hi)`` in cycles/frame for frames of ``n`` samples; return floats."""
    try:
        lo, hi = band
    except (TypeError, ValueError):
        raise ValueError(f"band must be a pair (lo, hi) in cycles/frame, got {band!r}") from None
    nyq = n / 2
    lo = check_real("band[0] (cycles/frame)", lo, lo=0)
    hi = check_real("band[1] (cycles/frame)", hi, lo=0)
    if hi > nyq * (1 + 1e-12):
        raise ValueError(
            f"band[1] = {hi:g} cycles/frame is past the Nyquist frequency {nyq:g} cycles/frame "
            f"(0.5 cycles/pixel for frames {n} pixels wide); allowed band is 0 <= lo < hi <= {nyq:g}"
        )
    if not lo < hi:
        raise ValueError(f"band is empty: need lo < hi, got lo={lo:g}, hi={hi:g} cycles/frame")
    return lo, hi
