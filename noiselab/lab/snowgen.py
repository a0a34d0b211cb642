"""Two alternatives to the tent IFFT for falling snow, for the laboratory's comparisons.

- :func:`layered_lattice_snow`: depth layers of band-pass lattice (gradient)
  noise, each translated rigidly at the speed its depth implies; a layer
  centred on ``f`` cycles/frame moves at ``c / |w| = c W / (2 pi f)``
  px/frame, the tent's parallax law sampled at a few depths.
- :func:`particle_snow`: a particle system in the manner of Reeves (1983),
  the method Langer & Zhang argue against: flakes with a depth, a size and a
  speed (both ``1/depth``), splatted as anti-aliased discs.

Both take the same ``shape``, ``band`` (cycles/frame), ``c`` (rad/frame) and
``direction_yx`` as :func:`noiselab.snowfall.snow`, so the three methods render the
same scene and the analysers (:mod:`noiselab.analysis`) can compare them.
"""
from __future__ import annotations

import functools
import math

import numba
import numpy as np

from .._core import (array_order, as_generator, check_band, check_int, check_memory, check_real, check_shape,
                     float_dtype, renamed_parameters)
from ..lattice import LatticeNoise
from ..snowfall import rescale_opacity
from ..spectral.envelopes import unit_direction_yx

__all__ = ["layered_lattice_snow", "particle_snow", "layer_plan", "lattice_peak"]


def _check_scene(shape, c, band, direction_yx):
    shape = check_shape("shape", shape, ndim=3)
    T, H, W = shape
    c = check_real("c (rad/frame)", c, lo=0.0, hi=math.pi)
    if band is None:
        band = (W / 32, W / 4)
    lo, hi = check_band("band", band, W / 2, lo_open=True, width=W)
    return shape, c, (lo, hi), unit_direction_yx("direction_yx", direction_yx)


def lattice_peak(kernel="catmull-rom", basis="gradient") -> float:
    """Power-weighted mean radial frequency of one lattice-noise octave, in cycles per lattice cell.

    Measured once (and cached) on a 512 x 512 grid of 64 x 64 cells with
    :func:`noiselab.analysis.radial_spectrum`; it maps a wanted centre
    frequency to a lattice density. Gradient noise is band-pass (no DC); with
    the Catmull-Rom kernel 80 % of its power lies within a factor 1.9 of
    frequency (the narrowest of the kernels; cubic B-spline: 2.6).

    Parameters
    ----------
    kernel : str, default "catmull-rom"
        A kernel name of :func:`noiselab.lattice.kernel_names`.
    basis : {"value", "gradient"}, default "gradient"

    Returns
    -------
    float
        Cycles per lattice cell.

    Examples
    --------
    >>> 0.4 < lattice_peak("catmull-rom", "gradient") < 0.7
    True
    """
    for name, value in (("kernel", kernel), ("basis", basis)):
        try:
            hash(value)
        except TypeError:
            raise TypeError(f"{name} must be a name (str), got {type(value).__name__}") from None
    return _lattice_peak(kernel, basis)


@functools.lru_cache(maxsize=None)
def _lattice_peak(kernel, basis) -> float:
    from ..analysis import radial_spectrum

    img = LatticeNoise(2, rng=12345, kernel=kernel, basis=basis, period=64).grid((512, 512), [(0, 64), (0, 64)])
    rs = radial_spectrum(img)
    p = rs.power * rs.counts
    return float(np.sum(p * rs.mean_frequency) / np.sum(p) / 64.0)


def layer_plan(shape=(64, 512, 512), *, c=1.0, band=None, layers=8, kernel="catmull-rom", exponent=1.0):
    """The depth layers of :func:`layered_lattice_snow`: centre frequency, lattice cells, speed, amplitude.

    Layers are spaced evenly in log frequency across ``band``; layer ``k`` has
    ``cells_x`` lattice cells across the frame width (a whole number, so that
    it tiles the frame exactly like the periodic IFFT snow), its actual centre
    is ``f_k = cells_x * lattice_peak`` cycles/frame, its speed
    ``c W / (2 pi f_k)`` px/frame and its amplitude ``f_k**(1 - exponent)``
    (equal energy per octave for the 1/f amplitude of the thesis).

    Returns
    -------
    dict of arrays: ``frequency`` (cycles/frame), ``cells_x``, ``cells_y``, ``speed`` (px/frame), ``amplitude``.

    Examples
    --------
    >>> plan = layer_plan((16, 128, 128), c=1.0, layers=4)
    >>> bool(np.all(np.diff(plan["speed"]) < 0))   # deeper (finer) layers are slower
    True
    """
    (T, H, W), c, (lo, hi), _ = _check_scene(shape, c, band, (0.0, 1.0))
    layers = check_int("layers", layers, lo=1, hi=256)
    exponent = check_real("exponent", exponent, lo=-8, hi=8)
    rho = lattice_peak(kernel, "gradient")
    target = np.geomspace(lo, hi, layers) if layers > 1 else np.array([math.sqrt(lo * hi)])
    cells_x = np.maximum(np.rint(target / rho), 2).astype(np.int64)
    cells_y = np.maximum(np.rint(cells_x * H / W), 2).astype(np.int64)
    freq = cells_x * rho
    with np.errstate(divide="ignore"):
        speed = c * W / (2 * np.pi * freq)
    amp = freq ** (1.0 - exponent)
    return {"frequency": freq, "cells_x": cells_x, "cells_y": cells_y, "speed": speed, "amplitude": amp}


@array_order(("direction", "direction_yx"))
@renamed_parameters(seed="rng")
def layered_lattice_snow(shape=(64, 512, 512), *, rng=None, c=1.0, band=None, layers=8, direction_yx=(1.0, 0.0),
                         kernel="catmull-rom", exponent=1.0, beta=1.5, dtype=np.float32, rescale=True, start=0):
    """Falling snow from depth layers of band-pass lattice noise, each translating at its own speed.

    The lattice alternative to the tent IFFT (Langer & Zhang 2003) for the same
    scene: ``layers`` layers of gradient (Perlin) noise, each tiling the frame
    (whole lattice periods across it), centred at frequencies spaced evenly in
    log frequency across ``band``; layer ``k`` translates rigidly along
    ``direction_yx`` at ``c / |w_k|`` px/frame (``|w_k| = 2 pi f_k / W``): speed
    inversely proportional to its spatial frequency, the tent's law sampled at
    ``layers`` depths. Amplitude ``f_k**(1 - exponent)`` per layer gives the
    1/f amplitude spectrum of the thesis for ``exponent=1``. The sum is
    rescaled to [0, 1] and raised to ``beta`` as :func:`noiselab.snowfall.snow` does.

    What it cannot do (measured in ``benchmarks/RESULTS.md``): each layer's
    spectrum is about an octave wide, so frequencies between layer centres
    move at a blend of speeds, and energy leaks past the band edges; and it
    does not loop in time (a layer returns to its start only after
    ``W / speed`` frames).

    Parameters
    ----------
    shape : (T, H, W)
        Frames, height, width.
    rng : int, numpy.random.Generator or None
        Same seed, same bits.
    c : float
        Tent constant in rad/frame, ``0 <= c <= pi``.
    band : (lo, hi), optional
        Band in cycles/frame (per frame width), ``0 < lo < hi <= W/2``;
        default ``(W/32, W/4)`` as for :func:`noiselab.snowfall.snow`.
    layers : int
        Depth layers, 1..256 (more layers: a closer approximation, linear cost).
    direction_yx : (dy, dx)
        Fall direction in array order (y down, x right), as :func:`noiselab.snowfall.snow`;
        ``direction=(dx, dy)`` is the old spelling (refused since 0.4).
    kernel : str
        Lattice kernel (see :mod:`noiselab.lattice.kernels`); Catmull-Rom gives
        the narrowest layer spectrum.
    exponent, beta, dtype, rescale
        As for :func:`noiselab.snowfall.snow`.
    start : int
        Index of the first frame (>= 0). Every frame is computed on its own,
        so with ``rescale=False`` frames ``start .. start+T-1`` are
        bit-identical to the same frames of a longer render: a long video can
        be rendered in pieces of bounded memory (rescale them with one shared
        range, e.g. :func:`noiselab.snowfall.rescale_opacity` with ``lo``/``hi``).

    Returns
    -------
    ndarray, shape (T, H, W), ``dtype``; in [0, 1] unless ``rescale=False``.

    Raises
    ------
    ValueError
        For an impossible shape, ``c`` outside ``[0, pi]``, a band past
        Nyquist, or ``layers`` outside ``[1, 256]``.

    Examples
    --------
    >>> a = layered_lattice_snow((4, 64, 64), rng=0, layers=3)
    >>> a.shape, a.dtype, float(a.min()), float(a.max())
    ((4, 64, 64), dtype('float32'), 0.0, 1.0)
    """
    (T, H, W), c, band, (dx, dy) = _check_scene(shape, c, band, direction_yx)
    beta = check_real("beta", beta, lo=0.0, lo_open=True)
    start = check_int("start", start, lo=0)
    dt = float_dtype(dtype)
    plan = layer_plan((T, H, W), c=c, band=band, layers=layers, kernel=kernel, exponent=exponent)
    check_memory(T * H * W * dt.itemsize + 4 * H * W * 8, f"layered_lattice_snow{(T, H, W)}")
    rng = as_generator(rng)
    layer_seeds = rng.integers(0, 2**63 - 1, size=len(plan["speed"]))
    layers_ = []
    for k in range(len(plan["speed"])):
        nx, ny = int(plan["cells_x"][k]), int(plan["cells_y"][k])
        # axis 0 is y, axis 1 is x; period = cells across the frame: each layer tiles the frame
        noise = LatticeNoise(2, rng=int(layer_seeds[k]), kernel=kernel, basis="gradient", period=(ny, nx))
        # random sub-cell offset per layer, so that layers do not share lattice lines
        layers_.append((noise, nx, ny, float(plan["speed"][k]), float(plan["amplitude"][k]), rng.random(2)))
    out = np.empty((T, H, W), dtype=dt)
    acc = np.empty((H, W), dtype=np.float64)
    # frame by frame: every frame is independent, so memory is the output plus one float64 frame
    for i, t in enumerate(range(start, start + T)):
        acc.fill(0.0)
        for noise, nx, ny, v, amp, phase in layers_:
            # content moves by +v*t along d: sample at (x - d v t)
            y0 = (phase[0] - dy * v * t) * ny / H
            x0 = (phase[1] - dx * v * t) * nx / W
            # reduce to one period so coordinates stay small (exact: the layer is periodic)
            y0 -= math.floor(y0 / ny) * ny
            x0 -= math.floor(x0 / nx) * nx
            acc += amp * noise.grid((H, W), [(y0, y0 + ny), (x0, x0 + nx)])
        out[i] = acc
    if rescale:
        rescale_opacity(out, beta)
    return out


@numba.njit(parallel=True, cache=True)
def _splat(x0, y0, vx, vy, radius, opacity, nsub, T, H, W, trans):
    n = x0.shape[0]
    for t in numba.prange(T):
        for i in range(n):
            r = radius[i]
            ext = r + 0.5
            k_n = nsub[i]
            # the disc's centre at the middle of the frame and how far it moves during the shutter
            cx = (x0[i] + vx[i] * t) % W
            cy = (y0[i] + vy[i] * t) % H
            half_x = 0.5 * vx[i] if k_n > 1 else 0.0
            half_y = 0.5 * vy[i] if k_n > 1 else 0.0
            ylo = int(math.floor(cy - ext - abs(half_y)))
            yhi = int(math.ceil(cy + ext + abs(half_y)))
            xlo = int(math.floor(cx - ext - abs(half_x)))
            xhi = int(math.ceil(cx + ext + abs(half_x)))
            for iy in range(ylo, yhi + 1):
                yy = iy % H
                for ix in range(xlo, xhi + 1):
                    # coverage of the pixel by the disc (a one-pixel linear ramp at the edge),
                    # averaged over k_n instants of an open shutter of one frame (k_n = 1: no blur)
                    acc = 0.0
                    for k in range(k_n):
                        s = (k + 0.5) / k_n - 0.5 if k_n > 1 else 0.0
                        ddx = ix - (cx + 2.0 * half_x * s)
                        ddy = iy - (cy + 2.0 * half_y * s)
                        cov = r + 0.5 - math.sqrt(ddx * ddx + ddy * ddy)
                        if cov > 0.0:
                            acc += cov if cov < 1.0 else 1.0
                    if acc > 0.0:
                        trans[t, yy, ix % W] *= 1.0 - opacity * acc / k_n
    return trans


@array_order(("direction", "direction_yx"))
@renamed_parameters(seed="rng")
def particle_snow(shape=(64, 512, 512), *, rng=None, c=1.0, band=None, flakes=None, direction_yx=(1.0, 0.0),
                  opacity=0.9, motion_blur=False, dtype=np.float32, return_flakes=False):
    """Falling snow as a particle system (Reeves 1983): flakes with depth, size and speed, splatted as discs.

    Each flake has a depth ``z`` in ``[1, hi/lo]`` drawn for a uniform density
    in the viewing volume (``p(z) ~ z**2``: far flakes outnumber near ones),
    a diameter ``D = W / (2 lo z)`` px (a disc of diameter ``D`` is matched to
    the frequency ``f = W / (2 D)`` cycles/frame, so ``band`` maps to
    diameters ``W/(2 hi) .. W/(2 lo)``) and a speed ``c W / (2 pi f) = c D / pi``
    px/frame along ``direction_yx``: the tent's parallax law, flake by flake.
    Flakes wrap around the frame (a torus, like the periodic IFFT snow) and
    are splatted as anti-aliased discs; white flakes of opacity ``opacity``
    composite by the over operator, ``alpha = 1 - prod(1 - opacity * coverage)``,
    whose result does not depend on the drawing order. With ``motion_blur``
    each flake's coverage is averaged over a shutter open for the whole frame
    (sampled every half pixel of its path), Reeves' streaks: the total
    coverage of a flake is unchanged, spread along its motion.

    Parameters
    ----------
    shape : (T, H, W)
        Frames, height, width.
    rng : int, numpy.random.Generator or None
        Same seed, same bits (frames are rendered in parallel, each by one thread).
    c : float
        Tent constant in rad/frame, ``0 <= c <= pi``.
    band : (lo, hi), optional
        Band in cycles/frame, ``0 < lo < hi <= W/2``; default ``(W/32, W/4)``.
    flakes : int, optional
        Number of flakes, 1..10**8; default ``H * W / 16`` (16384 at 512 x
        512), which gives a mean opacity near that of :func:`noiselab.snowfall.snow`
        with the default band (about 0.35; see ``benchmarks/RESULTS.md``).
    direction_yx : (dy, dx)
        Fall direction in array order (y down, x right), as :func:`noiselab.snowfall.snow`;
        ``direction=(dx, dy)`` is the old spelling (refused since 0.4).
    opacity : float
        Opacity of a flake's core, in (0, 1].
    motion_blur : bool
        Average each flake over the frame's shutter interval (slower by about
        the flake's speed in half pixels per frame).
    dtype : float32 or float64
    return_flakes : bool
        Also return the flakes: a dict of arrays ``x``, ``y`` (px at frame 0),
        ``depth``, ``diameter`` (px) and ``speed`` (px/frame).

    Returns
    -------
    ndarray (T, H, W) in [0, 1], or (ndarray, dict) with ``return_flakes``.

    Raises
    ------
    ValueError
        For an impossible shape, ``c`` outside ``[0, pi]`` or a band past Nyquist.

    Examples
    --------
    >>> a, fl = particle_snow((4, 64, 64), rng=0, flakes=50, return_flakes=True)
    >>> a.shape, bool(0 <= a.min() and a.max() <= 1), len(fl["speed"])
    ((4, 64, 64), True, 50)
    """
    (T, H, W), c, (lo, hi), (dx, dy) = _check_scene(shape, c, band, direction_yx)
    opacity = check_real("opacity", opacity, lo=0.0, hi=1.0, lo_open=True)
    if flakes is None:
        flakes = max(1, H * W // 16)
    n = check_int("flakes", flakes, lo=1, hi=10**8)
    dt = float_dtype(dtype)
    check_memory(T * H * W * dt.itemsize + n * 64, f"particle_snow{(T, H, W)} with {n} flakes")
    rng = as_generator(rng)
    zmax = hi / lo
    u = rng.random(n)
    depth = (1.0 + u * (zmax**3 - 1.0)) ** (1.0 / 3.0)  # inverse CDF of p(z) ~ z**2 on [1, zmax]
    x = rng.random(n) * W
    y = rng.random(n) * H
    diameter = W / (2.0 * lo * depth)
    speed = c * diameter / math.pi
    # transmittance, in the output's dtype and in place: memory is the output itself
    trans = np.ones((T, H, W), dtype=dt)
    if motion_blur:
        nsub = np.maximum(1, np.ceil(2.0 * speed)).astype(np.int64)  # a sample every half pixel of the path
    else:
        nsub = np.ones(n, dtype=np.int64)
    _splat(x, y, speed * dx, speed * dy, diameter / 2.0, opacity, nsub, T, H, W, trans)
    out = np.subtract(dt.type(1), trans, out=trans)
    np.clip(out, 0.0, 1.0, out=out)
    if return_flakes:
        return out, {"x": x, "y": y, "depth": depth, "diameter": diameter, "speed": speed}
    return out
