"""Gabor noise with a chosen spectrum: the kernels' frequencies sampled from a target (Galerne et al. 2012).

The expected power spectrum of Gabor noise is the frequency table's mean of
Gaussian lobes at ``+-f_m`` (:meth:`GaborNoise.expected_spectrum`). Drawing
the table from a power density ``P`` makes it ``P`` convolved with one lobe
(of width ``bandwidth``), to within the table's sampling: the spectrum of a
spectral field with the same amplitude envelope, blurred by the kernel's
bandwidth. :func:`from_envelope` takes the envelope that
:func:`noiselab.synthesize` takes (angular frequencies in rad/sample; power is
its square), so a spectral field and a Gabor noise are made from one formula.
"""
from __future__ import annotations

import math

import numpy as np

from .._core import as_generator, check_int
from .noise import GaborNoise

__all__ = ["from_envelope", "power_law_layers", "render_layers", "SAMPLES_PER_AXIS"]

#: Frequency cells per axis over [-0.5, 0.5) cycles/sample where the envelope is sampled (2-D, 3-D).
SAMPLES_PER_AXIS = {2: 512, 3: 96}


def from_envelope(envelope, *, dim=2, bandwidth, rows=4096, density=4.0, truncation=0.01, rng=0):
    """Gabor noise whose expected power spectrum is ``envelope**2`` blurred by one kernel lobe.

    The envelope is evaluated on a grid of ``SAMPLES_PER_AXIS[dim]`` cells per
    axis over ``[-0.5, 0.5)`` cycles/sample; ``rows`` kernel frequencies are
    drawn with probability proportional to ``envelope**2`` in each cell, at a
    uniform position inside it (the "by example" construction). The result's
    :meth:`~GaborNoise.expected_spectrum` is exact for the table drawn.

    Parameters
    ----------
    envelope : callable
        ``envelope(*w)`` of ``dim`` broadcast angular frequency arrays in
        rad/sample (array order, as :func:`noiselab.spectral.frequency_vectors`
        gives them), returning the amplitude (>= 0), as for
        :func:`noiselab.synthesize`; for ``dim=3`` the first axis may be time
        (rad/frame), e.g. a MotionClouds envelope.
    dim : {2, 3}
        Dimension of the noise.
    bandwidth : float or sequence of dim floats
        The kernels' envelope width in cycles/sample (see :class:`GaborNoise`):
        the lobe that blurs the target, and ``1 / bandwidth`` the kernel's cell.
    rows : int
        Size of the frequency table, 1 to 2**20.
    density, truncation : float
        As for :class:`GaborNoise`.
    rng : int, numpy.random.Generator or None
        Draws the table, then the hash key. Default 0.

    Returns
    -------
    GaborNoise

    Raises
    ------
    ValueError
        When the envelope is negative, not finite, of the wrong shape or 0 everywhere.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab.spectral import envelopes as E
    >>> env = lambda *w: E.power_law(*w, exponent=1.0) * E.annulus(*w, band_cycles_per_sample=(0.05, 0.2))
    >>> g = from_envelope(env, bandwidth=0.01, rng=0)
    >>> f = np.sqrt((g.frequencies ** 2).sum(axis=1))
    >>> bool(f.min() >= 0.049 and f.max() <= 0.201)
    True
    """
    if dim not in (2, 3) or isinstance(dim, bool):
        raise ValueError(f"dim must be 2 or 3, got {dim!r}")
    rows = check_int("rows", rows, lo=1, hi=1 << 20)
    gen = as_generator(rng)
    table = sample_table(envelope, dim, rows, gen)
    return GaborNoise(table, bandwidth=bandwidth, density=density, truncation=truncation, rng=gen)


def sample_table(envelope, dim, rows, gen):
    """``rows`` frequency vectors (cycles/sample) drawn with probability ``envelope**2`` (see :func:`from_envelope`).

    Parameters
    ----------
    envelope : callable
        ``envelope(*w)`` of ``dim`` angular frequency arrays in rad/sample.
    dim : {2, 3}
        Number of frequency axes.
    rows : int
        How many to draw.
    gen : numpy.random.Generator
        Draws the cells and the positions inside them.

    Returns
    -------
    ndarray, (rows, dim)

    Examples
    --------
    >>> import numpy as np
    >>> t = sample_table(lambda wy, wx: (np.abs(wx) < 0.5) * 1.0, 2, 100, np.random.default_rng(0))
    >>> t.shape, bool(np.all(np.abs(2 * np.pi * t[:, 1]) < 0.52))
    ((100, 2), True)
    """
    if not callable(envelope):
        raise TypeError(f"envelope must be a callable envelope(*w) of rad/sample frequencies, got "
                        f"{type(envelope).__name__}")
    n = SAMPLES_PER_AXIS[dim]
    f = (np.arange(n) - n // 2) / n            # cell starts, cycles/sample
    step = 1.0 / n
    centres = np.meshgrid(*[f + step / 2] * dim, indexing="ij", sparse=True)
    try:
        amp = np.asarray(envelope(*[2.0 * math.pi * c for c in centres]), dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"envelope failed on the frequency grid: {exc}") from None
    shape = (n,) * dim
    if amp.shape != shape:
        try:
            amp = np.broadcast_to(amp, shape)
        except ValueError:
            raise ValueError(f"envelope must return an array broadcastable to {shape}, got {amp.shape}") from None
    if not np.all(np.isfinite(amp)):
        raise ValueError("envelope must be finite on the frequency grid")
    if np.any(amp < 0):
        raise ValueError("envelope must be >= 0 (an amplitude)")
    p = (amp ** 2).ravel()
    total = float(p.sum())
    if not total > 0:
        raise ValueError("envelope is 0 on every frequency of the grid: nothing to sample")
    idx = gen.choice(p.size, size=rows, p=p / total)
    cells = np.stack(np.unravel_index(idx, shape), axis=1)
    return f[cells] + gen.random((rows, dim)) * step


def power_law_layers(*, dim=2, exponent=1.0, band, density=4.0, rows=2048, rng=0):
    """An isotropic power law in a band as octave layers of Gabor noise, with their weights.

    Octave ``k`` of ``band`` (cycles/sample) is a :class:`GaborNoise` whose
    kernels have random directions and radii drawn with the density of the
    power ``|f|**(-2 exponent)`` over the plane (space), and an envelope a
    quarter of the octave's low edge wide (kernels sized to their
    wavelengths); its weight is the square root of the octave's share of the
    power. ``sum_k weight_k * noise_k`` has variance 1 and the power law's
    expected spectrum blurred by each octave's lobe.

    Parameters
    ----------
    dim : {2, 3}
        Dimension of the noise.
    exponent : float
        Amplitude exponent (``dim / 2``: equal energy per octave).
    band : (lo, hi)
        Pass band in cycles/sample, ``0 < lo < hi <= 0.5``.
    density, rows, rng
        As for :func:`from_envelope` (``rows`` per octave).

    Returns
    -------
    list of (float, GaborNoise)

    Examples
    --------
    >>> layers = power_law_layers(band=(1 / 64, 1 / 4))
    >>> len(layers), round(sum(w * w for w, _ in layers), 12)
    (4, 1.0)
    """
    from .._core import check_band, check_real

    if dim not in (2, 3) or isinstance(dim, bool):
        raise ValueError(f"dim must be 2 or 3, got {dim!r}")
    exponent = check_real("exponent", exponent, lo=-8.0, hi=8.0)
    lo, hi = check_band("band", band, 0.5, lo_open=True)
    rows = check_int("rows", rows, lo=1, hi=1 << 20)
    gen = as_generator(rng)
    k = float(dim) - 2.0 * exponent   # radial density |f|**(k - 1)

    def mass(a, b):
        return math.log(b / a) if abs(k) < 1e-12 else (b ** k - a ** k) / k

    edges = [lo]
    while edges[-1] * 2.0 < hi * (1 - 1e-9):
        edges.append(edges[-1] * 2.0)
    edges.append(hi)
    total = mass(lo, hi)
    layers = []
    for a, b in zip(edges[:-1], edges[1:]):
        u = gen.random(rows)
        r = a * (b / a) ** u if abs(k) < 1e-12 else (a ** k + u * (b ** k - a ** k)) ** (1.0 / k)
        d = gen.standard_normal((rows, dim))
        d /= np.linalg.norm(d, axis=1, keepdims=True)
        layers.append((math.sqrt(mass(a, b) / total),
                       GaborNoise(r[:, None] * d, bandwidth=a / 4.0, density=density, rng=gen)))
    return layers


def render_layers(weighted_noises, shape, *, origin=None, dtype=np.float32, workers=None):
    """``sum_k weight_k * noise_k`` on a grid (:meth:`GaborNoise.grid`), summed in float64 in layer order.

    Parameters
    ----------
    weighted_noises : list of (float, GaborNoise)
        From :func:`power_law_layers` or :func:`noiselab.gabor.snow_layers`.
    shape : tuple of ints
        The grid (array order).
    origin : sequence of floats, optional
        Coordinate of the first sample (default zeros).
    dtype : float32 or float64
        Output dtype.
    workers : int, optional
        Threads; the result does not depend on them.

    Returns
    -------
    ndarray, ``shape``

    Examples
    --------
    >>> x = render_layers(power_law_layers(band=(1 / 32, 1 / 4)), (64, 64))
    >>> x.shape, x.dtype
    ((64, 64), dtype('float32'))
    """
    from .._core import float_dtype

    dt = float_dtype(dtype)
    out = None
    for weight, g in weighted_noises:
        x = g.grid(shape, origin=origin, dtype=np.float64, workers=workers)
        out = weight * x if out is None else out + weight * x
    return out.astype(dt, copy=False)
