r"""Fractal sums and turbulence over lattice noise (Phillips 2004, section 3, Eqs. 9 and 10).

.. math::

    \mathrm{fracsum}(x, n) = \sum_{o=0}^{n-1} g^o\, \mathrm{noise}(L^o x), \qquad
    \mathrm{turb}(x, n) = \sum_{o=0}^{n-1} g^o\, |\mathrm{noise}(L^o x)|

with lacunarity ``L = 2`` and gain ``g = 1/2`` by default (the paper's
``2^F`` and ``1/2^F``). A ``LatticeNoise`` with a ``period`` gives a sum that
tiles with the noise's tile and has no shorter period: octave ``o`` takes the
lattice period ``period * L**o`` (``L`` a whole number). ``x`` is either an array of points ``(..., dim_in)`` or
a :class:`noiselab.lattice.Grid` (then the grid path of ``LatticeNoise`` is used,
octave by octave, accumulating into one output array).

Octaves that cannot be seen are skipped, and ``return_octaves=True`` reports
how many were used:

- on a grid, octaves whose lattice is finer than the sampling on every
  sampled axis (more than one lattice cell per sample, i.e. their band lies
  past the sampling Nyquist) add only aliasing;
- octaves whose remaining amplitude ``sum_{k>=o} g^k`` is below the output
  precision (half an ulp of the total amplitude, float64 or float32) cannot
  change the result.

Derivatives: :func:`fractal_gradient` and :func:`turbulence_gradient` give the
exact gradient (Jacobian for vector noise) of the function that
:func:`fractal_sum` and :func:`turbulence` return, with the same octaves. Each
octave contributes ``gain**o lacunarity**o noise'(lacunarity**o x)``: with the
default ``gain * lacunarity = 1`` every octave adds as much slope as the
first, so the gradient of a many-octave sum is rough even where the value is
smooth (the octave count used for the value decides it).
"""
from __future__ import annotations

import math

import numpy as np

from .._core import as_array, check_finite_array, check_int, check_real, check_real_array, dispatch, float_dtype, \
    resolve_workers
from .octaves import callable_sum

__all__ = ["fractal_sum", "turbulence", "octaves_used", "fractal_gradient", "turbulence_gradient"]

# frequencies and amplitude sums are kept below this (well inside float64's 1.8e308,
# so that points, phases and kernel sums scaled by them stay finite)
_LOG_LIMIT = math.log(1e300)


def octaves_used(octaves, *, lacunarity=2.0, gain=0.5, spacing=None, frequency=1.0, dtype=np.float64) -> int:
    """How many of ``octaves`` can be seen (see the module docstring).

    Parameters
    ----------
    octaves : int
        Octaves requested.
    lacunarity, gain : float
        Frequency and amplitude ratio between octaves.
    spacing : float or sequence of float, optional
        Sample spacing per axis in input units (for a grid); ``None``: no Nyquist limit.
    frequency : float or sequence of float
        The base noise frequency per axis (lattice cells per input unit).
    dtype : float32 or float64
        Output precision that decides which amplitudes are below resolution.

    Returns
    -------
    int
        The octaves actually summed, at most ``octaves``.

    Raises
    ------
    ValueError
        For ``lacunarity <= 1``, ``gain <= 0`` or a spacing or frequency
        that is not positive and finite.

    Examples
    --------
    >>> octaves_used(60)                       # amplitude 2**-o below float64 resolution
    54
    >>> octaves_used(60, spacing=1 / 1024)     # 1024 samples per lattice cell
    11
    """
    octaves = check_int("octaves", octaves, lo=0, hi=10_000)
    lacunarity = check_real("lacunarity", lacunarity, lo=1.0, lo_open=True)
    gain = check_real("gain", gain, lo=0.0, lo_open=True)
    eps = np.finfo(float_dtype(dtype)).eps / 2
    freq_arr = check_real_array("frequency", frequency, ndim=(0, 1), allow_empty=False)
    if not (freq_arr > 0).all():
        raise ValueError(f"frequency must be > 0 (lattice cells per unit), got {frequency!r}")
    if spacing is not None:
        try:
            sp = np.asarray(spacing, dtype=np.float64)
        except (TypeError, ValueError, OverflowError):
            raise TypeError(f"spacing must be a real number or a sequence of them, got {spacing!r}") from None
        if sp.ndim > 1 or np.isinf(sp).any() or (sp <= 0).any():
            raise ValueError(f"spacing must be > 0 and finite per axis (NaN: an axis with one sample), got {spacing!r}")
    if gain > 1 and octaves > 1 and (octaves - 1) * math.log(gain) + math.log(octaves) > _LOG_LIMIT:
        most = int((_LOG_LIMIT - math.log(octaves)) / math.log(gain)) + 1
        raise ValueError(f"gain={gain:g} over octaves={octaves} overflows: the sum of gain**o passes 1e300; "
                         f"use at most {most} octaves with this gain (or gain <= 1)")
    total = sum(gain ** k for k in range(octaves)) if gain != 1 else float(octaves)
    finest = None  # the fewest lattice cells a sample spans at the base frequency (None: no Nyquist limit)
    if spacing is not None:
        with np.errstate(over="ignore"):
            cells = np.atleast_1d(np.asarray(spacing, dtype=np.float64) * np.asarray(frequency, dtype=np.float64))
        cells = cells[~np.isnan(cells)]  # NaN: an axis with one sample (no spacing)
        finest = float(cells.min()) if cells.size else None
    used = 0
    partial = 0.0
    for o in range(octaves):
        # all of what remains from octave o on is below resolution
        remaining = total - partial
        if o > 0 and remaining <= eps * partial:
            break
        if o > 0 and finest is not None:
            step = lacunarity ** o if o * math.log(lacunarity) < _LOG_LIMIT else math.inf
            # every axis's cells times step > 1 (a product is monotone in each factor; times inf, an axis of
            # 0 cells (an underflow) gives NaN and no longer counts)
            if finest * step > 1.0 if step < math.inf else bool((cells > 0).any()):
                break
        partial += gain ** o
        used += 1
    top = float(np.max(freq_arr))
    if used > 1 and math.log(top) + (used - 1) * math.log(lacunarity) > _LOG_LIMIT:
        most = int((_LOG_LIMIT - math.log(top)) / math.log(lacunarity)) + 1
        raise ValueError(f"lacunarity={lacunarity:g} over {used} visible octaves overflows: frequency * "
                         f"lacunarity**(octaves-1) passes 1e300 lattice cells per unit; use at most {most} octaves "
                         "(octaves), a smaller lacunarity, or a gain that lets the fine octaves fall below resolution")
    return used



def _grid_spacing(shape, ext):
    """Sample spacing per grid axis; NaN (no Nyquist limit) for an axis of one sample or of zero width."""
    steps = np.array([abs(ext[a, 1] - ext[a, 0]) / n if n > 1 else np.nan for a, n in enumerate(shape)])
    steps[steps == 0] = np.nan  # every sample of that axis at one point: nothing to alias along it
    return steps

def _sum(noise, x, octaves, lacunarity, gain, normalize, dtype, return_octaves, spacing, absval, workers=None,
         chunks=None):
    from ..lattice import Grid, LatticeNoise, grid_coordinates
    from ..lattice.checks import octave_periods
    from ..lattice.grid import check_grid

    octaves = check_int("octaves", octaves, lo=1, hi=10_000)
    lacunarity = check_real("lacunarity", lacunarity, lo=1.0, lo_open=True)
    gain = check_real("gain", gain, lo=0.0, lo_open=True)
    workers = resolve_workers(workers)
    is_grid = isinstance(x, Grid)
    if is_grid:
        dim = noise.dim_in if isinstance(noise, LatticeNoise) else len(tuple(np.atleast_1d(x.shape)))
        shape, ext = check_grid(x.shape, x.extent, dim)
        spacing = _grid_spacing(shape, ext)
        out_dtype = float_dtype(np.float64 if dtype is None else dtype)
    else:
        raw = as_array("x", x)
        out_dtype = float_dtype(dtype) if dtype is not None else (
            np.dtype(np.float32) if raw.dtype == np.float32 else np.dtype(np.float64))
        if spacing is not None:
            spacing = check_real("spacing", spacing, lo=0.0, lo_open=True)
    freq = noise.frequency if isinstance(noise, LatticeNoise) else 1.0
    used = octaves_used(octaves, lacunarity=lacunarity, gain=gain, spacing=spacing, frequency=freq, dtype=out_dtype)
    norm = sum(gain ** o for o in range(used)) if normalize else 1.0
    if isinstance(noise, LatticeNoise) and noise.tileable and used > 1:
        # refused now rather than when a chunk is computed: a period per octave needs a whole lacunarity
        octave_periods(noise.period, used, lacunarity, noise.table_size, noise.hash)
    if chunks is not None:
        if not is_grid:
            raise ValueError("chunks= needs x to be a Grid (chunked points: wrap them in dask.array.map_blocks)")
        result = dispatch.chunked("fractal_sum")(noise, shape, ext, chunks, dtype=out_dtype, used=used,
                                                 lacunarity=lacunarity, gain=gain, absval=absval,
                                                 norm=norm if normalize else None)
        return (result, used) if return_octaves else result

    if isinstance(noise, LatticeNoise):
        octave_sum = dict(octaves=used, lacunarity=lacunarity, gain=gain, absval=absval, dtype=out_dtype)
        if is_grid:
            result = noise.evaluate_grid(shape, ext, workers=workers, **octave_sum)
        else:
            result = noise.evaluate(raw, workers=workers, name="x", **octave_sum)
        if normalize:
            result /= np.asarray(norm, dtype=result.dtype)
    else:
        if not callable(noise):
            raise TypeError(f"noise must be a LatticeNoise or a callable on points, got {type(noise).__name__}")
        pts = np.stack(np.meshgrid(*grid_coordinates(shape, ext), indexing="ij"), axis=-1) if is_grid else raw
        result = callable_sum(noise, pts, used, lacunarity, gain, absval, norm, out_dtype)
    return (result, used) if return_octaves else result


def fractal_sum(noise, x, octaves=6, *, lacunarity=2.0, gain=0.5, normalize=False, dtype=None,
                return_octaves=False, spacing=None, workers=None, chunks=None):
    """Fractal sum of octaves (Phillips Eq. 9): ``sum_o gain**o * noise(lacunarity**o * x)``.

    Parameters
    ----------
    noise : LatticeNoise or callable
        The basis noise (any callable on points works, without the fast paths).
    x : array (..., dim_in) or Grid
        Points, or ``noiselab.lattice.Grid(shape, extent)`` for a regular grid.
    octaves : int, default 6
        Octaves requested (>= 1); invisible ones are skipped (module docstring).
    lacunarity : float, default 2
        Frequency ratio between octaves (> 1).
    gain : float, default 0.5
        Amplitude ratio between octaves (> 0).
    normalize : bool, default False
        Divide by ``sum_o gain**o`` so the result lies in [-1, 1] (the paper's
        Eq. 9 is unnormalised: with gain 1/2 it lies in (-2, 2)).
    dtype : float32 or float64, optional
        Output precision (float64 by default; float32 for float32 points).
    return_octaves : bool
        Also return the number of octaves used.
    spacing : float, optional
        Sample spacing of scattered points (e.g. mesh edge length) to skip
        octaves past their Nyquist as on a grid.
    workers : int, optional
        Threads (``LatticeNoise`` only; scipy.fft's meaning, default None:
        scipy's current default, one thread unless a ``scipy.fft.set_workers``
        block says otherwise; -1 every core): scattered points
        split into blocks, a grid into bands of its first axis (see
        :meth:`noiselab.lattice.LatticeNoise.grid`); bit-identical to one
        worker.
    chunks : int, "auto" or one entry per axis, optional
        With a Grid: return a lazy ``dask.array.Array`` in these chunks,
        bit-identical to the in-memory result for any chunking (see
        :meth:`noiselab.lattice.LatticeNoise.grid`; needs ``noiselab[dask]``).

    Returns
    -------
    ndarray (a lazy dask array with ``chunks``), or (array, int) with ``return_octaves``

    Raises
    ------
    ValueError
        For points whose last axis is not ``dim_in``, octaves outside
        ``[1, 10000]``, ``lacunarity <= 1`` or ``gain <= 0``.

    Examples
    --------
    >>> from noiselab.lattice import LatticeNoise, Grid
    >>> noise = LatticeNoise(2, rng=0)
    >>> img, used = fractal_sum(noise, Grid((256, 256), [(0, 4), (0, 4)]), 60, return_octaves=True)
    >>> img.shape, used
    ((256, 256), 7)
    """
    return _sum(noise, x, octaves, lacunarity, gain, normalize, dtype, return_octaves, spacing, False, workers, chunks)


def turbulence(noise, x, octaves=6, *, lacunarity=2.0, gain=0.5, normalize=False, dtype=None,
               return_octaves=False, spacing=None, workers=None, chunks=None):
    """Turbulence (Phillips Eq. 10): ``sum_o gain**o * |noise(lacunarity**o * x)|``.

    Same parameters as :func:`fractal_sum`; the result is >= 0 (in [0, 1] with
    ``normalize=True``). For vector noise the magnitude is taken per component.

    Parameters
    ----------
    noise, x, octaves, lacunarity, gain, normalize, dtype, return_octaves, spacing, workers, chunks
        As for :func:`fractal_sum`.

    Returns
    -------
    ndarray (a lazy dask array with ``chunks``), or (array, int) with ``return_octaves``
        The turbulence, >= 0, and the number of octaves used.

    Raises
    ------
    ValueError
        For the arguments :func:`fractal_sum` refuses (octaves below 1,
        lacunarity <= 1, gain <= 0, points of the wrong dimension, ...).

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab.lattice import LatticeNoise
    >>> t = turbulence(LatticeNoise(1, rng=0), np.linspace(0, 8, 100), 5)
    >>> bool(t.min() >= 0)
    True
    """
    return _sum(noise, x, octaves, lacunarity, gain, normalize, dtype, return_octaves, spacing, True, workers, chunks)


def _jacobian_sum(noise, x, octaves, lacunarity, gain, normalize, return_value, return_octaves, spacing, absval,
                  workers):
    from ..lattice import Grid, LatticeNoise, grid_coordinates
    from ..lattice.grid import check_grid

    octaves = check_int("octaves", octaves, lo=1, hi=10_000)
    lacunarity = check_real("lacunarity", lacunarity, lo=1.0, lo_open=True)
    gain = check_real("gain", gain, lo=0.0, lo_open=True)
    workers = resolve_workers(workers)
    lattice = isinstance(noise, LatticeNoise)
    if not lattice and not callable(getattr(noise, "jacobian", None)):
        raise TypeError(f"noise must be a LatticeNoise or have a jacobian(points) method, got {type(noise).__name__}")
    is_grid = isinstance(x, Grid)
    if is_grid:
        shape, ext = check_grid(x.shape, x.extent, noise.dim_in)
        spacing = _grid_spacing(shape, ext)
    elif spacing is not None:
        spacing = check_real("spacing", spacing, lo=0.0, lo_open=True)
    freq = noise.frequency if lattice else 1.0
    used = octaves_used(octaves, lacunarity=lacunarity, gain=gain, spacing=spacing, frequency=freq)
    norm = sum(gain ** o for o in range(used)) if normalize else 1.0
    if lattice and is_grid:
        value, jac = noise.evaluate_grid_jacobian(shape, ext, octaves=used, lacunarity=lacunarity, gain=gain,
                                                  absval=absval, return_value=bool(return_value), workers=workers)
    elif lattice:
        value, jac = noise.evaluate_jacobian(as_array("x", x), octaves=used, lacunarity=lacunarity, gain=gain,
                                             absval=absval, workers=workers, name="x")
        value = np.ascontiguousarray(value)
    else:
        pts = np.stack(np.meshgrid(*grid_coordinates(shape, ext), indexing="ij"), axis=-1) if is_grid \
            else check_finite_array("x", x)
        value = jac = None
        with np.errstate(over="ignore", invalid="ignore"):  # an overflow is refused below
            for o in range(used):
                scale = lacunarity ** o
                v, j = noise.jacobian(pts * scale, return_value=True)
                v = np.asarray(v, dtype=np.float64)
                j = np.asarray(j, dtype=np.float64) * (gain ** o * scale)
                if absval:
                    j = j * np.sign(v).reshape(v.shape + (1,) * (j.ndim - v.ndim))
                    v = np.abs(v)
                v = gain ** o * v
                value = v if value is None else value + v
                jac = j if jac is None else jac + j
        jac = jac.reshape(value.shape[:value.ndim - (1 if noise.dim_out > 1 else 0)] + (noise.dim_out, noise.dim_in))
        if not (np.isfinite(value).all() and np.isfinite(jac).all()):
            raise ValueError(f"noise returned NaN or inf (or the octave sum of its derivative overflowed float64) "
                             f"at {int((~np.isfinite(jac)).any(axis=(-2, -1)).sum())} point(s); noise's jacobian "
                             "must be finite")
    if normalize:
        jac = jac / norm
        value = None if value is None else value / norm
    if noise.dim_out == 1:
        jac = jac[..., 0, :]
    result = (value, jac) if return_value else jac
    return (*result, used) if return_octaves and return_value else ((result, used) if return_octaves else result)


def fractal_gradient(noise, x, octaves=6, *, lacunarity=2.0, gain=0.5, normalize=False, return_value=False,
                     return_octaves=False, spacing=None, workers=None):
    r"""Exact gradient of :func:`fractal_sum`: ``sum_o gain**o lacunarity**o noise'(lacunarity**o x)``.

    Parameters
    ----------
    noise : LatticeNoise, or an object with ``jacobian(points, return_value=True)`` and ``dim_in``/``dim_out``
        The basis noise (a C1 kernel: see :meth:`LatticeNoise.jacobian`), or
        e.g. a :func:`noiselab.warp` of one.
    x : array (..., dim_in) or Grid
        Points, or a ``Grid`` (then the grid path is used).
    octaves, lacunarity, gain, normalize, spacing, workers
        As for :func:`fractal_sum`; the same octaves are used, so this is the
        derivative of the function :func:`fractal_sum` returns.
    return_value : bool
        Also return the fractal sum (computed in the same pass), as ``(value, gradient)``.
    return_octaves : bool
        Also return the number of octaves used (last).

    Returns
    -------
    ndarray ``(..., dim_in)`` for scalar noise, ``(..., dim_out, dim_in)`` for vector noise
    (with ``value`` first and the octave count last when asked for).

    Raises
    ------
    ValueError
        For the arguments :func:`fractal_sum` refuses, or a kernel without a
        continuous first derivative (box, linear).

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab.lattice import LatticeNoise
    >>> noise = LatticeNoise(2, rng=0)
    >>> fractal_gradient(noise, np.zeros((3, 2)), 4).shape
    (3, 2)
    """
    return _jacobian_sum(noise, x, octaves, lacunarity, gain, normalize, return_value, return_octaves, spacing,
                         False, workers)


def turbulence_gradient(noise, x, octaves=6, *, lacunarity=2.0, gain=0.5, normalize=False, return_value=False,
                        return_octaves=False, spacing=None, workers=None):
    r"""Gradient of :func:`turbulence` where it is differentiable: ``sum_o gain**o lacunarity**o sign(n_o) n_o'``.

    ``n_o = noise(lacunarity**o x)``. Turbulence has a crease wherever an
    octave crosses zero (``|n|`` has a corner there): on the crease the
    derivative does not exist, and this function returns the octave's term
    with ``sign(0) = 0``, i.e. the average of the two one-sided derivatives.
    Off the zero sets (almost everywhere) it is the exact gradient. Same
    parameters and returns as :func:`fractal_gradient`.

    Parameters
    ----------
    noise, x, octaves, lacunarity, gain, normalize, return_value, return_octaves, spacing, workers
        As for :func:`fractal_gradient`.

    Returns
    -------
    ndarray (..., dim_in) or (..., dim_out, dim_in)
        The gradient (Jacobian for vector noise); with ``return_value`` first
        the turbulence itself, with ``return_octaves`` last the octaves used.

    Raises
    ------
    ValueError
        For the arguments :func:`fractal_gradient` refuses, or a kernel
        without a continuous first derivative (box, linear).

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab.lattice import LatticeNoise
    >>> v, g = turbulence_gradient(LatticeNoise(1, rng=0), np.linspace(0.1, 8, 100), 5, return_value=True)
    >>> v.shape, g.shape
    ((100,), (100, 1))
    """
    return _jacobian_sum(noise, x, octaves, lacunarity, gain, normalize, return_value, return_octaves, spacing,
                         True, workers)
