"""Falling snow with no period: Langer & Zhang's tent realised by moving Gabor kernels in (t, y, x).

:func:`noiselab.snow` inverts one periodic block of the tent spectrum: it
tiles in space, loops in time, and any frame costs the whole block. Here every
kernel is a Gabor grating of spatial frequency ``f`` (cycles/px) whose
envelope moves at ``c / |w|`` px/frame (``|w| = 2 pi |f|`` rad/px) along the
fall direction, so its energy lies on the plane ``w_t = -(c / |w|) d . w``
that touches the tent at ``f``: the sum of kernels puts its energy on the
tent. The band is rendered octave by octave (:func:`snow_layers`), each with
kernels sized to its wavelengths. Impulses come from the counter hash (:class:`GaborNoise`), so any frame
and any window is evaluated alone, with the same bits as the same region of
a larger render, at any time (no period short of 2**32 cells).
"""
from __future__ import annotations

import math

import numpy as np

from .._core import (as_generator, check_band, check_int, check_memory, check_real, check_real_sequence, check_shape,
                     float_dtype)
from ..spectral.envelopes import unit_direction_yx
from .noise import GaborNoise
from .spectra import render_layers

__all__ = ["gabor_snow", "snow_layers", "snow_opacity", "motion_cloud_noise", "OPACITY_SIGMAS"]

#: The raw field (variance 1) maps to opacity as ``clip((x / OPACITY_SIGMAS + 1) / 2, 0, 1) ** beta``: a fixed map
#: (a window cannot know a block's extremes), set to the extremes of :func:`noiselab.snow`'s default block, which
#: reach 5.3 standard deviations from the mean (``benchmarks/bench_gabor.md``).
OPACITY_SIGMAS = 5.3


def snow_layers(*, rng=None, c=1.0, band=None, thickness=0.1, direction_yx=(1.0, 0.0), pan_yx=(0.0, 0.0),
                exponent=1.0, width=512, density=4.0, rows=2048):
    """The moving-kernel noises of a snow scene, one per octave of the band, with their weights.

    The band is split into octaves; octave ``k`` is a :class:`GaborNoise` of
    moving kernels whose spatial envelope is a quarter of the octave's low
    edge (kernels shrink with their wavelength, so each octave has as many
    kernels per wavelength), weighted by the square root of the octave's
    share of the power ``|f|**(-2 exponent)``. :func:`gabor_snow` renders
    ``sum_k weight_k * noise_k`` (variance 1).

    Parameters
    ----------
    rng, c, band, thickness, direction_yx, pan_yx, exponent, width, density
        As for :func:`gabor_snow`.
    rows : int
        Kernel frequencies per octave's table.

    Returns
    -------
    list of (float, GaborNoise)
        3-D noises, axis 0 time (frames), axes 1-2 pixels, unit variance each.

    Examples
    --------
    >>> layers = snow_layers(rng=0)
    >>> len(layers), round(sum(w * w for w, _ in layers), 12)     # 16..128 cycles/frame: 3 octaves
    (3, 1.0)
    >>> bool(all(g.velocities_yx[:, 0].min() > 0 for _, g in layers))  # every kernel falls (down the rows)
    True
    """
    width = check_int("width", width, lo=8, hi=1 << 30)
    c = check_real("c (rad/frame)", c, lo=0.0, hi=math.pi)
    lo, hi = check_band("band", (width / 32, width / 4) if band is None else band, width / 2, lo_open=True,
                        width=width)
    thickness = check_real("thickness", thickness, lo=0.0, hi=1.0)
    exponent = check_real("exponent", exponent, lo=-8.0, hi=8.0)
    dx, dy = unit_direction_yx("direction_yx", direction_yx)
    try:
        uy, ux = check_real_sequence("pan_yx", pan_yx, length=2, lo=-1e6, hi=1e6)
    except (TypeError, ValueError) as exc:
        raise type(exc)(f"pan_yx must be a finite pair (uy, ux) in px/frame: {exc}") from None
    rows = check_int("rows", rows, lo=1, hi=1 << 20)
    gen = as_generator(rng)
    k = 2.0 - 2.0 * exponent   # radial density |f|**(k - 1): power |f|**(-2 exponent) on the plane

    def mass(a, b):
        return math.log(b / a) if abs(k) < 1e-12 else (b ** k - a ** k) / k

    edges = [lo / width]
    while edges[-1] * 2.0 < hi / width * (1 - 1e-9):
        edges.append(edges[-1] * 2.0)
    edges.append(hi / width)
    total = mass(edges[0], edges[-1])
    layers = []
    for a, b in zip(edges[:-1], edges[1:]):
        u = gen.random(rows)
        r = a * (b / a) ** u if abs(k) < 1e-12 else (a ** k + u * (b ** k - a ** k)) ** (1.0 / k)
        theta = gen.random(rows) * 2.0 * math.pi
        # each kernel falls at c_m / |w| px/frame along d (c_m spread over c (1 +- thickness)), plus the pan
        cm = c * (1.0 + thickness * (2.0 * gen.random(rows) - 1.0))
        speed = cm / (2.0 * math.pi * r)
        vel = np.stack([speed * dy + uy, speed * dx + ux], axis=1)
        table = np.stack([np.zeros(rows), r * np.sin(theta), r * np.cos(theta)], axis=1)
        # envelopes: a quarter of the octave's low edge in space, 1/64 cycle/frame in time
        s_space = a / 4.0
        s_time = 1.0 / 64.0 if c > 0 or any((uy, ux)) else s_space
        layers.append((math.sqrt(mass(a, b) / total),
                       GaborNoise(table, bandwidth=(s_time, s_space, s_space), velocities_yx=vel, density=density,
                                  rng=gen)))
    return layers


def gabor_snow(shape=(64, 512, 512), *, origin=(0, 0, 0), rng=None, c=1.0, band=None, thickness=0.1,
               direction_yx=(1.0, 0.0), pan_yx=(0.0, 0.0), beta=1.5, exponent=1.0, width=512, density=4.0,
               dtype=np.float32, rescale=True, workers=None, chunks=None):
    """Falling-snow opacity with no period, any window of an endless (t, y, x) scene (sparse Gabor noise).

    The scene is :func:`noiselab.snow`'s (Langer & Zhang's tent, 1/f
    amplitude in an annulus band, opacity ``** beta``), realised by moving
    Gabor kernels rather than one periodic block; ``origin`` is the
    ``(t, y, x)`` of the window's first sample, so a window of frame 10**6
    costs what a window of frame 0 does, and equals the same region of any
    larger render to the bit.

    Parameters
    ----------
    shape : (T, H, W)
        Frames, rows, columns of the window.
    origin : (t, y, x) ints
        Frame, row and column of the window's first sample (any integers).
    rng : int, numpy.random.Generator or None
        The random state: the scene (kernel table and hash key). The same int,
        the same scene.
    c : float
        Tent constant in rad/frame, ``0 <= c <= pi`` (:func:`noiselab.snow`'s).
    band : (lo, hi), optional
        Spatial band in cycles/frame of a ``width``-pixel frame; default
        ``(width/32, width/4)``, 16..128 at 512 px.
    thickness : float
        The tent constant of each kernel is drawn in ``c (1 +- thickness)``, in [0, 1].
    direction_yx : (dy, dx)
        Fall direction in array order, any length; default straight down.
    pan_yx : (uy, ux)
        Camera pan in px/frame added to every kernel's velocity.
    beta : float
        Opacity exponent (thesis: 1.5).
    exponent : float
        Amplitude ``1/|f|**exponent`` (1: the thesis's 1/f).
    width : int
        The frame width in px that cycles/frame refer to (the scene's scale;
        not the window's width), default 512.
    density : float
        Impulses per kernel cell (:class:`GaborNoise`).
    dtype : float32 or float64
        Output dtype.
    rescale : bool
        ``False`` returns the raw field (zero mean, variance 1).
    workers : int, optional
        Threads (scipy.fft's meaning); the result does not depend on them.
    chunks : int, "auto" or one entry per axis, optional
        Return a lazy ``dask.array.Array`` in these chunks (dask's chunk
        syntax), each chunk the window of its samples: bit-identical to the
        in-memory result for any chunking (needs ``noiselab[dask]``).

    Returns
    -------
    ndarray, shape (T, H, W), ``dtype``
        Opacity ``clip((x / OPACITY_SIGMAS + 1) / 2, 0, 1) ** beta`` in [0, 1]
        (a fixed map: windows agree), or the raw field.

    Examples
    --------
    >>> import numpy as np
    >>> a = gabor_snow((4, 32, 32), rng=0)
    >>> a.shape, a.dtype, bool(0 <= a.min() and a.max() <= 1)
    ((4, 32, 32), dtype('float32'), True)
    >>> far = gabor_snow((2, 16, 16), origin=(10**6, 8, 8), rng=0)
    >>> bool(np.array_equal(far, gabor_snow((3, 32, 32), origin=(10**6, 0, 0), rng=0)[:2, 8:24, 8:24]))
    True
    """
    shape = check_shape("shape", shape, ndim=3)
    origin = check_real_sequence("origin", origin, length=3, lo=-2.0 ** 40, hi=2.0 ** 40)
    if any(o != math.floor(o) for o in origin):
        raise ValueError(f"origin must be whole samples (t, y, x), got {origin}")
    beta = check_real("beta", beta, lo=0.0, lo_open=True)
    dt = float_dtype(dtype)
    layers = snow_layers(rng=rng, c=c, band=band, thickness=thickness, direction_yx=direction_yx, pan_yx=pan_yx,
                         exponent=exponent, width=width, density=density)
    if chunks is not None:
        from .._core import dispatch

        return dispatch.chunked("gabor_snow")(layers, shape, origin=origin, beta=beta, dtype=dt, rescale=rescale,
                                              chunks=chunks)
    # the float64 sum, one layer's float64 grid and its scratch, and the output
    check_memory(int(np.prod(shape, dtype=np.float64)) * (3 * 8 + dt.itemsize), f"gabor_snow{shape}")
    # in octave order, one float64 sum: every window adds the same terms in the same order
    x = render_layers(layers, shape, origin=origin, dtype=np.float64, workers=workers)
    return snow_opacity(x, beta=beta, dtype=dt) if rescale else x.astype(dt, copy=False)


def snow_opacity(field, *, beta=1.5, dtype=np.float32):
    """The fixed opacity map of :func:`gabor_snow`: ``clip((x / OPACITY_SIGMAS + 1) / 2, 0, 1) ** beta``.

    Pointwise, so a window of a field maps to the same window of its opacity
    (the chunked path applies it chunk by chunk). ``field`` is float64 and is
    overwritten.

    Examples
    --------
    >>> import numpy as np
    >>> snow_opacity(np.array([-100.0, 0.0, 100.0]), beta=1.0).tolist()
    [0.0, 0.5, 1.0]
    """
    beta = check_real("beta", beta, lo=0.0, lo_open=True)
    x = field
    if not (isinstance(x, np.ndarray) and x.dtype == np.float64):
        raise TypeError(f"field must be a float64 numpy array (it is overwritten), got "
                        f"{type(x).__name__}{'' if not isinstance(x, np.ndarray) else ' of ' + str(x.dtype)}")
    np.multiply(x, 0.5 / OPACITY_SIGMAS, out=x)
    np.add(x, 0.5, out=x)
    np.clip(x, 0.0, 1.0, out=x)
    np.power(x, beta, out=x)
    return x.astype(float_dtype(dtype), copy=False)


def motion_cloud_noise(*, sf_0, B_sf, theta=0.0, B_theta=np.inf, V_X=0.0, V_Y=0.0, B_V=0.5, density=4.0, rows=4096,
                       rng=None):
    """A Motion Cloud (Leon et al. 2012) as moving Gabor kernels: any window of an endless (t, y, x) scene.

    MotionClouds' envelope (:func:`noiselab.stimuli.motion_cloud`'s parameters):
    spatial frequencies from the log-Gabor ring times ``1/f`` and the orientation
    band (power = envelope squared, drawn as :func:`from_envelope` draws them), and
    each kernel's velocity ``V + B_V z f/|f|`` with ``z`` standard normal: the
    energy of a kernel of frequency ``f`` lies on the plane ``f_t = -v . f``, spread
    around the motion plane of ``V`` by ``B_V |f|``, as MotionClouds' speed envelope
    ``exp(-(w_t + V . w)**2 / (2 (B_V |w|)**2))``.

    Parameters
    ----------
    sf_0, B_sf : float
        Peak spatial frequency and its bandwidth, cycles/pixel (``0 < sf_0 <= 0.5``, ``B_sf > 0``).
    theta, B_theta : float
        Orientation (radians, waves along x at 0) and its bandwidth (``np.inf``: every orientation).
    V_X, V_Y : float
        The cloud's velocity, px/frame (x right, y down).
    B_V : float
        Speed bandwidth, px/frame (>= 0).
    density, rows, rng
        As for :func:`gabor_snow` and :func:`from_envelope`.

    Returns
    -------
    GaborNoise
        3-D (t, y, x), moving kernels, unit variance: render with ``.grid(shape, origin=(t, y, x))``.

    Examples
    --------
    >>> g = motion_cloud_noise(sf_0=0.125, B_sf=0.05, V_X=1.0, rng=0)
    >>> v = g.grid((4, 32, 32), origin=(10**6, 0, 0))
    >>> v.shape, g.dim
    ((4, 32, 32), 3)
    """
    from ..spectral import envelopes as E
    from .spectra import sample_table

    sf_0 = check_real("sf_0 (cycles/pixel)", sf_0, lo=0.0, hi=0.5, lo_open=True)
    B_sf = check_real("B_sf (cycles/pixel)", B_sf, lo=0.0, lo_open=True, hi=1e6)
    theta = check_real("theta", theta)
    if not (isinstance(B_theta, (int, float, np.floating)) and B_theta == np.inf):
        B_theta = check_real("B_theta (radians)", B_theta, lo=1e-6, hi=1e6)
    V_X = check_real("V_X (px/frame)", V_X, lo=-1e6, hi=1e6)
    V_Y = check_real("V_Y (px/frame)", V_Y, lo=-1e6, hi=1e6)
    B_V = check_real("B_V (px/frame)", B_V, lo=0.0, hi=1e6)
    rows = check_int("rows", rows, lo=1, hi=1 << 20)
    gen = as_generator(rng)

    def env(wy, wx):
        fr = np.hypot(wy, wx) / (2 * math.pi)
        inv = np.where(fr > 0, 1.0 / np.where(fr > 0, fr, 1.0), 0.0)
        return E.orientation(wy, wx, theta=theta, B_theta=B_theta) * inv * E.log_gabor(wy, wx, sf_0=sf_0, B_sf=B_sf)

    table = sample_table(env, 2, rows, gen)
    r = np.hypot(table[:, 0], table[:, 1])
    unit = table / np.maximum(r, 1e-12)[:, None]
    z = gen.standard_normal(rows) * B_V
    vel = np.array([V_Y, V_X])[None, :] + z[:, None] * unit
    s_space = max(min(sf_0, B_sf) / 4.0, 1.0 / 1024.0)
    return GaborNoise(np.concatenate([np.zeros((rows, 1)), table], axis=1), bandwidth=(1.0 / 64.0, s_space, s_space),
                      velocities_yx=vel, density=density, rng=gen)
