"""``LatticeNoise``: Phillips' permutation-table lattice noise (Perception 33, 2004, section 2).

The basis (2.1.1): a table of random values on [-1, 0) and one on (0, 1],
reached through a shuffled permutation ("address hashing") table; further
input dimensions nest the permutation, ``P[(P[(P[ix] + iy) mod n] + iz) mod n]``
(2.4.1, the integer lattice); every output component has its own permutation
(2.3.1). The lattice values are smoothed by a tensor-product kernel (2.1.1):
the box-filter (B-spline) family, an interpolating cubic, or the quintic fade.
Classic gradient (Perlin) noise is offered as a second basis.

``LatticeNoise`` holds the noise's state (its parameters and tables) and
delegates the work to one module per part, each readable on its own:

- :mod:`.tables`: the random tables (values, gradients, permutations,
  integer-hash keys);
- :mod:`.points_path`: scattered points in either layout, the kernel and the threads;
- :mod:`.grid_path`: regular grids (the fused kernel in 2-D and 3-D, the
  separable passes in 4-D and up, the points path for 1-D grids and for
  octaves sparser than the grid, windows);
- :mod:`.derivatives`: Jacobians on grids and the shapes of the results;
- :mod:`.checks`: argument and overflow checks; :mod:`.grid`: ``Grid``
  and its coordinates; :mod:`._jit`: every compiled kernel (the engine).
"""
from __future__ import annotations

import copy
import math

import numpy as np

from .._core import as_array, as_generator, check_int, check_real, dispatch, renamed_parameters, resolve_workers
from . import checks, tables
from .derivatives import grid_jacobian, jacobian_views
from .grid import check_grid, grid_coordinates
from .grid_path import render_grid
from .kernels import Kernel, get_kernel
from .points_path import evaluate_points, evaluate_points_jac, output_dtype, prepare_points, shape_out

__all__ = ["LatticeNoise"]


class LatticeNoise:
    r"""Phillips' lattice noise ``a * noise(F x + phi)`` (Eq. 2) with any input and output dimension.

    Parameters
    ----------
    dim_in : int
        Input dimension d >= 1 (1: a curve of time, 2: an image, 3: solid noise, ...).
    dim_out : int, default 1
        Output components; each has its own permutation table (Phillips 2.3.1).
    rng : int, numpy.random.Generator or None, default 0
        Draws the value tables, the gradients and the permutations (SPEC 7).
        A noise is a fixed function, as Perlin's reference noise and the
        SIMD peers' default seed are, so the default is the int 0 rather
        than ``None``: ``LatticeNoise(3)`` is the same function in every
        process. ``seed=`` is the old spelling (refused since 0.4).
    kernel : str, optional
        ``"box"``, ``"linear"``, ``"quadratic"``, ``"cubic"`` (B-splines of
        order 1-4, i.e. 1-4 box filters), ``"catmull-rom"`` (interpolating
        cubic) or ``"quintic"`` (Perlin's fade); see :mod:`noiselab.lattice.kernels`.
        Default per basis: ``"cubic"`` for value noise (Phillips' smoothest
        B-spline: an interpolating kernel gives value noise its full variance
        at the lattice points only, a visible lattice pattern), ``"quintic"``
        for gradient noise (Perlin's 2002 noise, what a user of gradient noise
        expects: the cubic B-spline spreads each gradient over 4 cells, which
        costs twice the time and leaves a range of about +-0.62 of the bound).
    basis : {"value", "gradient"}, default "value"
        ``"value"``: Phillips' random values. ``"gradient"``: Perlin's gradient
        noise, ``sum_i K(x - i) g_i . (x - i)`` with unit gradients ``g_i``
        (zero at every lattice point for the interpolating kernels: linear,
        catmull-rom, quintic).
    table_size : int, default 256
        Entries n of the permutation table and of each value table (even, >= 2).
    period : int or sequence of int, optional
        Exact lattice period per axis: the noise then tiles with period
        ``period / frequency`` in input units. Without it the noise is
        pseudo-periodic with the table's period n. An octave sum of a noise
        with a period (:meth:`evaluate`, :func:`noiselab.fractal_sum`, ...)
        keeps that tile as its only period: octave ``o`` gets the lattice
        period ``period * lacunarity**o`` (a whole-number lacunarity, and the
        finest octave's period at most ``table_size`` with the table hash,
        2**32 with the integer hash; a ValueError otherwise).
    frequency, phase : float or sequence of dim_in floats
        ``F`` and ``phi`` of Eq. 2 (lattice cells per input unit, and offset in
        lattice cells).
    amplitude : float, default 1
        ``a`` of Eq. 2 (> 0); the output lies in ``[-a, a]``.
    alternation : {"table", "lattice"}, default "table"
        How the negative and positive tables alternate. ``"table"``: they are
        interleaved into one table (even entries from (0, 1], odd from
        [-1, 0)) that the permutation addresses, so every table period holds
        exactly as many positive as negative values at pseudo-random lattice
        points: stationary and isotropic. ``"lattice"``: the literal 1-D
        reading of Phillips' figure 1, the sign alternates with the parity of
        the lattice point (``i_1 + ... + i_d``); this adds a deterministic
        checkerboard of wavelength 2 cells (not stationary, not isotropic).
    hash : {"table", "integer"}, default "table"
        How a lattice point is addressed. ``"table"``: Phillips' nested
        permutation ``P[(P[i] + j) mod n]`` into the value (or gradient)
        table. ``"integer"``: an arithmetic hash of the (period-reduced)
        lattice coordinates and a seed-derived key per component,
        ``mix32(key ^ j_0 M_0 ^ ... ^ j_{d-1} M_{d-1})`` in 32-bit words (see
        :mod:`noiselab.lattice._inthash`): values uniform on [-1, 1), or a
        gradient picked by the word's top bits from a fixed set (1-D: +-1;
        2-D: 8 directions at 45 degrees; 3-D: Perlin's 2002 cube-edge
        directions; 4-D and up: the random unit gradients). No permutation,
        so no 256-cell period (the default period is 2**32 cells per axis, the
        most it allows) and no row/column artefacts of the nested
        permutation; ``alternation`` must be ``"table"``.

    Raises
    ------
    ValueError
        For ``dim_in`` outside ``[1, 32]``, an unknown kernel, basis, hash or
        alternation, an odd or too small ``table_size``, a period below 1,
        or a non-finite frequency, phase or amplitude.

    Notes
    -----
    **Range.** Every component lies in ``[-a, a]`` with no clipping: the sum is
    divided by a bound proved from the kernel. With values ``|v| <= 1`` a
    tensor-product kernel gives ``|sum_i w_i v_i| <= prod_a sum_k |w_k(t_a)|
    <= S**d``, ``S = sup_t sum_k |w_k(t)|``; ``S = 1`` for the non-negative
    kernels and ``S = 5/4`` for Catmull-Rom (``sum |w| = 1 + t (1 - t)``), whose
    overshoot is therefore absorbed by a factor ``(4/5)**d``. Gradient noise is
    divided by ``sqrt(d Q) S**(d - 1/2)`` (:meth:`Kernel.gradient_bound`).

    **Derivatives.** :meth:`gradient`, :meth:`jacobian`, :meth:`gradient_grid`
    and :meth:`jacobian_grid` give the exact derivative in input units for
    the kernels with a continuous first derivative (quadratic, cubic,
    catmull-rom, quintic); see also :func:`noiselab.curl_noise`,
    :func:`noiselab.warp` and :func:`noiselab.fractal.fractal_gradient`.

    **Tables.** ``perms`` (``(dim_out, table_size)`` int64, one permutation
    per component) and ``keys`` (``(dim_out,)`` uint32, the integer hash's
    keys) are read-only arrays whose flag cannot be set back: every path
    (points, grids, derivatives) reads these same arrays, so they cannot
    drift apart after construction. ``values`` and ``gradients`` are read
    where they are, by every path alike.

    **Layout.** Points are ``(..., dim_in)`` by default; ``axis=0`` takes
    them as ``(dim_in, ...)`` (structure of arrays, as SIMD libraries take
    them). Two-dimensional float64 points are read in place in either
    layout, and the result is bit-identical.

    **Evaluation interface.** :meth:`evaluate` and :meth:`evaluate_grid` (and
    their Jacobian twins) sum octaves ``sum_o gain**o b(noise(lacunarity**o x))``
    on points or grids; ``__call__``, :meth:`grid` and the derivative methods
    are their one-octave forms, :mod:`noiselab.fractal` and the dask path call them.

    **Precision.** Coordinates are split in float64 into an integer lattice
    index and an exact fraction (``u - floor(u)`` is exact); the index is
    reduced modulo the period before it becomes an int64 (``fmod`` past 2**52),
    so inputs up to 1e12 and beyond stay continuous, and float32 inputs are
    promoted. The output is float64 (float32 for float32 input unless ``dtype``
    says otherwise); every path computes in float64, and float32 output is
    the float64 result rounded once.

    Examples
    --------
    >>> import numpy as np
    >>> noise = LatticeNoise(2, rng=1)
    >>> v = noise(np.random.default_rng(0).uniform(-8, 8, (1000, 2)))
    >>> v.shape, bool(np.abs(v).max() <= 1)
    ((1000,), True)
    >>> img = noise.grid((64, 64), [(0, 4), (0, 4)])
    >>> img.shape
    (64, 64)
    >>> flow = LatticeNoise(2, 2, rng=1)(np.zeros((5, 2)))
    >>> flow.shape
    (5, 2)
    """

    @renamed_parameters(seed="rng")
    def __init__(self, dim_in, dim_out=1, *, rng=0, kernel=None, basis="value", table_size=256,
                 period=None, frequency=1.0, phase=0.0, amplitude=1.0, alternation="table", hash="table"):
        self.dim_in = d = check_int("dim_in", dim_in, lo=1, hi=32)
        self.dim_out = check_int("dim_out", dim_out, lo=1)
        checks.check_choices(basis, alternation, hash)
        self.kernel: Kernel = get_kernel(checks.default_kernel(basis) if kernel is None else kernel)
        self.basis, self.alternation, self.hash = basis, alternation, hash
        self.table_size = n = checks.check_table_size(table_size)
        # the value tables and one int64 permutation per component, the gradients
        checks.check_large(self.dim_out * n * 8 + n * (d + 4) * 8,
                           f"LatticeNoise(dim_out={self.dim_out}, table_size={n})")
        self.tileable = period is not None
        self.period = checks.check_period(period, d, n, hash, alternation)
        self._pmask = tables.period_masks(self.period)
        self.frequency = checks.per_axis("frequency", frequency, d, lo=0.0, lo_open=True)
        self.phase = checks.per_axis("phase", phase, d)
        self.amplitude = check_real("amplitude", amplitude, lo=0.0, lo_open=True)
        self.rng = rng
        drawn = tables.draw_tables(as_generator(rng), n, d, self.dim_out, hash == "integer")
        # perms and keys are read-only (tables.frozen): every path reads these very arrays
        self.positive, self.negative, self.gradients, self.keys, self.perms = drawn
        self.values = tables.signed_values(self.positive, self.negative, alternation)
        self._mult = tables.axis_multipliers(d)
        self._int_grads = tables.int_gradients(d, self.gradients)  # fixed and small in 1-3-D
        self.bound = self.kernel.value_bound(d) if basis == "value" else self.kernel.gradient_bound(d)
        self.scale = self.amplitude / self.bound  # a * basis / bound, so |output| <= a

    def __repr__(self):
        return (f"LatticeNoise(dim_in={self.dim_in}, dim_out={self.dim_out}, rng={self.rng!r}, "
                f"kernel={self.kernel.name!r}, basis={self.basis!r}, table_size={self.table_size}"
                + (", hash='integer')" if self.hash == "integer" else ")"))

    # ------------------------------------------------- the evaluation interface
    def _octave_arrays(self, octaves, lacunarity, gain):
        """Per-octave frequencies ``(octaves, dim_in)`` and amplitudes, from checked octave parameters."""
        if octaves == 1:  # the noise itself, without the array arithmetic (x * 1.0 is x: the same bits)
            return self.frequency[None], np.array([self.scale])
        with np.errstate(over="ignore"):  # an overflow is refused by the amplitude and reach checks
            freqs = self.frequency[None, :] * (lacunarity ** np.arange(octaves))[:, None]
            amps = self.scale * gain ** np.arange(octaves)
        return freqs, amps

    def _octave_periods(self, octaves, lacunarity):
        """The lattice period of each octave ``(octaves, dim_in)`` of a tileable noise's sum, else None (all
        octaves at ``period``): ``period * lacunarity**o`` (:func:`.checks.octave_periods`)."""
        if not self.tileable or octaves == 1:
            return None
        return checks.octave_periods(self.period, octaves, lacunarity, self.table_size, self.hash)

    def _octave_twins(self, octaves, lacunarity, gain):
        """A tileable noise's octaves as single-octave noises, or None (not tileable, or one octave).

        Octave ``o`` is this noise at frequency ``F L**o`` and amplitude
        ``a g**o`` with the lattice period ``period * L**o``
        (:func:`.checks.octave_periods`): at the base period it would repeat
        ``L**o`` times inside the tile. Each twin is evaluated on its own
        (one octave, float64) and the octaves are added in order, so every
        path, window and chunking gives the same bits. The points kernels
        sum octaves that share one period, hence this loop outside them; the
        grid passes take a period per octave (:func:`.grid_path.render_grid`).
        """
        periods = self._octave_periods(octaves, lacunarity)
        if periods is None:
            return None
        freqs, amps = self._octave_arrays(octaves, lacunarity, gain)
        twins = []
        for o in range(octaves):
            twin = copy.copy(self)
            twin.period, twin._pmask = periods[o], tables.period_masks(periods[o])
            twin.frequency, twin.scale = freqs[o], float(amps[o])
            twin.amplitude = self.amplitude * gain ** o
            twins.append(twin)
        return twins

    @staticmethod
    def _add_octaves(twins, one):
        """``sum one(twin)`` over the twins in order, in float64 (``one`` returns a fresh float64 array)."""
        total = None
        for twin in twins:
            part = one(twin)
            if total is None:
                total = np.array(part, dtype=np.float64)
            else:
                total += part
        return total

    def evaluate(self, points, *, octaves=1, lacunarity=2.0, gain=0.5, absval=False, dtype=None, workers=None,
                 name="points", axis=-1, arithmetic="float64"):
        """The octave sum ``sum_o gain**o b(noise(lacunarity**o x))`` at points ``(..., dim_in)``.

        Parameters
        ----------
        points : array_like, shape (..., dim_in)
            As for ``__call__``.
        octaves, lacunarity, gain : int, float, float; default 1, 2, 0.5
            Octaves summed (>= 1; one is ``__call__``), their frequency (> 1) and amplitude (> 0) ratios.
        absval : bool, default False
            Sum ``|noise|`` (turbulence): ``b = abs``.
        dtype, workers
            As for ``__call__`` (``workers``: scipy.fft's meaning, bit-identical for any count).
        name : str, default "points"
            The points' name in error messages (for callers that take them under another name).
        axis : int, default -1
            The axis of ``points`` that holds the coordinates (0: ``(dim_in, ...)`` columns); the
            other axes, in order, are the result's shape.
        arithmetic : {"float64", "float32"}, default "float64"
            The arithmetic of the sum: "float64" (the result, rounded once to ``dtype``) or "float32"
            (integer-hash values in 1-3-D without a period only, float32 output; anything else is a
            ValueError): each point's lattice index stays exact (the float64 index's bits; computed in
            float32 where that is exact: float32 points, no phase, power-of-two frequencies), its weights,
            hashed values, gradient dots and sums are float32; 1.8-2.3x the speed of "float64" on 1e6 3-D
            float32 points (0.41-0.66x pyfastnoisesimd). Largest difference from "float64" over 1e6 points
            within 1e3 of 0 and of 1e12, 1-3-D, quintic and Catmull-Rom value and gradient noise: 2.8e-6 at
            amplitude 1 (``python benchmarks/bench_limits.py --f32-error``; speed:
            ``benchmarks/bench_limits.md``).

        Returns
        -------
        ndarray ``(...)`` for one component, ``(..., dim_out)`` otherwise

        Examples
        --------
        >>> import numpy as np
        >>> noise = LatticeNoise(2, rng=1)
        >>> x = np.random.default_rng(0).uniform(0, 8, (100, 2))
        >>> bool(np.array_equal(noise.evaluate(x), noise(x)))
        True
        >>> bool(noise.evaluate(x, octaves=4, absval=True).min() >= 0)
        True
        >>> fast = LatticeNoise(2, rng=1, hash="integer").evaluate(x, arithmetic="float32")
        >>> fast.dtype.name, bool(np.abs(fast - LatticeNoise(2, rng=1, hash="integer")(x)).max() < 1e-6)
        ('float32', True)
        """
        octaves, lacunarity, gain = checks.check_octaves(octaves, lacunarity, gain)
        f32 = checks.check_arithmetic(arithmetic, self, dtype)
        return self._sum_at(points, octaves, lacunarity, gain, absval, np.float32 if f32 else dtype, workers, name,
                            axis, f32)

    def _sum_at(self, points, octaves, lacunarity, gain, absval, dtype, workers, name, axis=-1, f32=False):
        """:meth:`evaluate` with checked octave parameters (``__call__`` comes here directly)."""
        workers = resolve_workers(workers)
        twins = self._octave_twins(octaves, lacunarity, gain)
        if twins is not None:
            out_dtype = output_dtype(as_array(name, points).dtype, dtype)
            checks.check_amplitude(self.amplitude * checks.total_gain(octaves, gain), out_dtype,
                                   "amplitude (times the sum of the octaves' gains)")
            total = self._add_octaves(twins, lambda t: t._sum_at(points, 1, 2.0, 0.5, absval, np.float64, workers,
                                                                 name, axis))
            return total.astype(out_dtype, copy=False)
        freqs, amps = self._octave_arrays(octaves, lacunarity, gain)
        raw = as_array(name, points)
        lead, flat = prepare_points(self, raw, name, axis)
        dtype = output_dtype(raw.dtype, dtype)
        checks.check_amplitude(self.amplitude * checks.total_gain(octaves, gain), dtype,
                               "amplitude" if octaves == 1 else "amplitude (times the sum of the octaves' gains)")
        checks.check_large(flat.shape[0] * (self.dim_out * dtype.itemsize + 8 * self.dim_in), "lattice noise")
        return shape_out(evaluate_points(self, flat, freqs, amps, absval, dtype, name, workers, f32), lead,
                         self.dim_out)

    def evaluate_jacobian(self, points, *, octaves=1, lacunarity=2.0, gain=0.5, absval=False, workers=None,
                          name="points", axis=-1):
        """The octave sum and its exact Jacobian at points: ``(value, jacobian)``, computed in one pass.

        Parameters as :meth:`evaluate`; with ``absval`` each octave's
        derivative carries the sign of its value (:func:`noiselab.turbulence_gradient`).
        Needs a kernel with a continuous first derivative (see :meth:`jacobian`).

        Returns
        -------
        value : ndarray ``(...)`` or ``(..., dim_out)``, float64
        jacobian : ndarray ``(..., dim_out, dim_in)``, float64, in output units per input unit
            Both are views of one buffer.

        Examples
        --------
        >>> import numpy as np
        >>> noise = LatticeNoise(3, 2, rng=2, kernel="quintic")
        >>> value, jac = noise.evaluate_jacobian(np.zeros((5, 3)), octaves=3)
        >>> value.shape, jac.shape
        ((5, 2), (5, 2, 3))
        """
        workers = resolve_workers(workers)
        checks.check_differentiable(self.kernel)
        octaves, lacunarity, gain = checks.check_octaves(octaves, lacunarity, gain)
        twins = self._octave_twins(octaves, lacunarity, gain)
        if twins is not None:
            def one(twin):
                value, jac = twin.evaluate_jacobian(points, absval=absval, workers=workers, name=name, axis=axis)
                return np.concatenate([value.reshape(jac.shape[:-1] + (1,)), jac], axis=-1)
            both = self._add_octaves(twins, one)
            return both[..., 0].reshape(both.shape[:-2] + ((self.dim_out,) if self.dim_out > 1 else ())), \
                both[..., 1:]
        freqs, amps = self._octave_arrays(octaves, lacunarity, gain)
        lead, flat = prepare_points(self, points, name, axis)
        checks.check_large(flat.shape[0] * self.dim_out * (self.dim_in + 1) * 8 * 2, "lattice noise jacobian")
        out = evaluate_points_jac(self, flat, freqs, amps, absval, name, workers)
        return jacobian_views(out, lead, self.dim_out, self.dim_in)

    def evaluate_grid(self, shape, extent, *, window=None, octaves=1, lacunarity=2.0, gain=0.5, absval=False,
                      dtype=np.float64, workers=None):
        """:meth:`evaluate` on a regular grid (as :meth:`grid`), by the grid path (:mod:`.grid_path`).

        ``shape``, ``extent``, ``window``, ``dtype`` and ``workers`` as for
        :meth:`grid`; ``octaves``, ``lacunarity``, ``gain`` and ``absval`` as
        for :meth:`evaluate`. Returns the window's shape (``+ (dim_out,)``).

        Examples
        --------
        >>> import numpy as np
        >>> noise = LatticeNoise(2, rng=1)
        >>> img = noise.evaluate_grid((64, 48), [(0, 4), (0, 3)], octaves=5)
        >>> tile = noise.evaluate_grid((64, 48), [(0, 4), (0, 3)], octaves=5, window=[(8, 24), (0, 48)])
        >>> img.shape, bool(np.array_equal(tile, img[8:24]))
        ((64, 48), True)
        """
        octaves, lacunarity, gain = checks.check_octaves(octaves, lacunarity, gain)
        return render_grid(self, shape, extent, dtype=dtype, window=window, octaves=octaves, lacunarity=lacunarity,
                           gain=gain, absval=bool(absval), periods=self._octave_periods(octaves, lacunarity),
                           workers=resolve_workers(workers))

    @renamed_parameters(value="return_value")
    def evaluate_grid_jacobian(self, shape, extent, *, window=None, octaves=1, lacunarity=2.0, gain=0.5,
                               absval=False, return_value=True, workers=None):
        """:meth:`evaluate_jacobian` on a regular grid: ``(value or None, jacobian)``.

        One set of separable grid passes per input axis with the kernel's
        derivative on that axis; ``return_value=False`` skips the value's passes
        (``None`` is returned in its place). Parameters as
        :meth:`evaluate_grid`; the results are float64, the Jacobian of shape
        ``window shape + (dim_out, dim_in)``.

        Examples
        --------
        >>> noise = LatticeNoise(2, rng=3, kernel="quintic")
        >>> value, jac = noise.evaluate_grid_jacobian((32, 16), [(0, 4), (0, 2)], octaves=4)
        >>> value.shape, jac.shape
        ((32, 16), (32, 16, 1, 2))
        """
        octaves, lacunarity, gain = checks.check_octaves(octaves, lacunarity, gain)
        return grid_jacobian(self, shape, extent, window=window, octaves=octaves, lacunarity=lacunarity, gain=gain,
                             absval=bool(absval), value=bool(return_value), periods=self._octave_periods(octaves, lacunarity),
                             workers=resolve_workers(workers))

    # ------------------------------------------------------- the user's calls
    def __call__(self, points, *, dtype=None, workers=None, axis=-1):
        """Evaluate at points of shape ``(..., dim_in)``; returns ``(...)`` or ``(..., dim_out)``.

        For ``dim_in == 1`` an array whose last axis is not 1 (or a scalar) is
        taken as that many scalar inputs. ``axis=0`` takes the points as
        ``(dim_in, ...)`` columns instead (see Notes, Layout; same bits).
        ``dtype`` (float32 or float64) picks
        the output precision; the computation is float64 either way.
        ``workers`` > 1 splits the points into that many contiguous blocks
        evaluated on threads (the kernels release the GIL); every point's
        arithmetic is the same, so the result is bit-identical to one worker.
        """
        return self._sum_at(points, 1, 2.0, 0.5, False, dtype, workers, "points", axis)

    def jacobian(self, points, *, return_value=False, workers=None, axis=-1):
        r"""The exact Jacobian ``d noise_c / d x_a`` at points ``(..., dim_in)``: shape ``(..., dim_out, dim_in)``.

        In input units (:mod:`noiselab.lattice.derivatives`). It needs a kernel
        with a continuous first derivative (``quadratic``, ``cubic``,
        ``catmull-rom``, ``quintic``); ``box`` and ``linear`` raise ValueError.

        Parameters
        ----------
        points : array_like, shape (..., dim_in)
            As for ``__call__`` (for ``dim_in == 1`` a plain array is that many inputs).
        return_value : bool, default False
            Also return the noise values (computed in the same pass), as ``(value, jacobian)``.
        workers : int, optional
            Threads over blocks of points (bit-identical to one worker);
            scipy.fft's meaning (``None``: its current default, one thread
            unless a ``scipy.fft.set_workers`` block says otherwise).
        axis : int, default -1
            The axis of ``points`` that holds the coordinates (as in :meth:`evaluate`).

        Returns
        -------
        ndarray ``(..., dim_out, dim_in)``, or ``(value, jacobian)``

        Notes
        -----
        The result is float64. The value returned with it agrees with
        ``noise(points)`` to rounding (a few ulp; the fast value kernels sum
        in another order). Accuracy against central differences:
        ``tests/test_derivatives.py``.

        Examples
        --------
        >>> import numpy as np
        >>> noise = LatticeNoise(3, 3, rng=2, frequency=2.0)
        >>> noise.jacobian(np.zeros((5, 3))).shape
        (5, 3, 3)
        """
        value, jac = self.evaluate_jacobian(points, workers=workers, axis=axis)
        return (value, jac) if return_value else jac

    def gradient(self, points, *, return_value=False, workers=None, axis=-1):
        """The exact gradient of scalar noise (``dim_out == 1``) at points ``(..., dim_in)``: shape ``(..., dim_in)``.

        :meth:`jacobian` of a one-component noise, without the component
        axis; see there for units, kernels and ``return_value``.

        Examples
        --------
        >>> import numpy as np
        >>> noise = LatticeNoise(2, rng=1, kernel="quintic", frequency=4.0)
        >>> value, grad = noise.gradient(np.array([[0.3, 0.7]]), return_value=True)
        >>> value.shape, grad.shape
        ((1,), (1, 2))
        """
        checks.check_scalar(self.dim_out, "gradient")
        value, jac = self.evaluate_jacobian(points, workers=workers, axis=axis)
        return (value, jac[..., 0, :]) if return_value else jac[..., 0, :]

    def jacobian_grid(self, shape, extent, *, window=None, return_value=False, workers=None):
        """:meth:`jacobian` on a regular grid (as :meth:`grid`): shape ``shape + (dim_out, dim_in)``.

        Evaluated by the grid's separable passes with the kernel's derivative
        on one axis (one set of passes per input axis); agrees with
        :meth:`jacobian` on :meth:`grid_points` to rounding (tested).
        ``window`` and ``workers`` as in :meth:`grid`; ``return_value`` also
        returns :meth:`grid`'s values, as ``(value, jacobian)``.

        Examples
        --------
        >>> noise = LatticeNoise(2, 2, rng=3)
        >>> noise.jacobian_grid((32, 16), [(0, 4), (0, 2)]).shape
        (32, 16, 2, 2)
        """
        val, jac = self.evaluate_grid_jacobian(shape, extent, window=window, return_value=bool(return_value),
                                               workers=workers)
        return (val, jac) if return_value else jac

    def gradient_grid(self, shape, extent, *, window=None, return_value=False, workers=None):
        """:meth:`gradient` on a regular grid (as :meth:`grid`): shape ``shape + (dim_in,)``.

        See :meth:`jacobian_grid`.

        Examples
        --------
        >>> noise = LatticeNoise(2, rng=3, kernel="quintic")
        >>> h, g = noise.gradient_grid((64, 64), [(0, 4), (0, 4)], return_value=True)
        >>> h.shape, g.shape
        ((64, 64), (64, 64, 2))
        """
        checks.check_scalar(self.dim_out, "gradient_grid")
        val, jac = self.evaluate_grid_jacobian(shape, extent, window=window, return_value=bool(return_value),
                                               workers=workers)
        jac = jac[..., 0, :]
        return (val, jac) if return_value else jac

    def grid_points(self, shape, extent):
        """The points ``(*shape, dim_in)`` that :meth:`grid` samples (for the scattered path)."""
        shape, extent = check_grid(shape, extent, self.dim_in)
        checks.check_large(math.prod(shape) * self.dim_in * 8 * 2, f"grid_points{shape}")
        coords = grid_coordinates(shape, extent)
        return np.stack(np.meshgrid(*coords, indexing="ij"), axis=-1) if coords else np.zeros((0,))

    def grid(self, shape, extent, *, dtype=np.float64, window=None, chunks=None, workers=None):
        """Evaluate on a regular grid by separability.

        Parameters
        ----------
        shape : tuple of int
            Samples per input axis (axis order as in ``extent``).
        extent : sequence of (start, stop)
            One pair per input axis, stop excluded (``numpy.arange`` style).
        dtype : float32 or float64
            Output precision (the computation is float64).
        window : sequence of (lo, hi) index pairs, optional
            Evaluate only samples ``lo <= j < hi`` of each axis of the full grid;
            the result is bit-identical to the same slice of the full grid, so a
            huge grid can be rendered in tiles.
        chunks : int, "auto" or one entry per axis, optional
            Return a lazy ``dask.array.Array`` in these chunks (dask's chunk
            syntax; uneven chunks allowed), each chunk rendered by the
            ``window=`` path: bit-identical to the in-memory grid for any
            chunking, and a chunk needs only its own memory. Needs the extra
            ``pip install noiselab[dask]``; see :mod:`noiselab.scale`.
        workers : int, optional
            Threads (scipy.fft's meaning: ``None`` its current default, -1 is every core). The grid's first
            axis is split into that many bands, each a ``window`` of the full
            grid rendered on a pooled thread (the kernels release the GIL), so
            the result is bit-identical for any count. A band gets at least
            2**21 samples x octaves (a 1024² grid of two octaves), so a
            small grid uses fewer threads: below that, a second thread
            measured slower than one. With ``chunks``, dask's scheduler
            places the chunks instead.

        Returns
        -------
        ndarray, shape ``shape`` (or ``shape + (dim_out,)``); a dask array with ``chunks``

        Notes
        -----
        The kernel is applied one axis at a time to the block of lattice values
        the grid covers (:mod:`noiselab.lattice.grid_path`): a sample costs
        ``taps`` multiply-adds in the last pass instead of ``taps**d`` hashed
        lookups; it agrees with the points path to 1e-12 (tested). On a 512 x
        512 grid of 32 cells the fused 2-D kernel ran at 0.9-1.8x
        pyfastnoisesimd's value and Perlin noise with float64 output and
        1.3-2.5x with float32 output (quintic, one and six octaves, three runs
        of ``bench_lattice.py --grid-only``; ``benchmarks/bench_lattice.md``).
        """
        if chunks is not None:
            return dispatch.chunked("lattice_grid")(self, shape, extent, dtype=dtype, chunks=chunks, window=window)
        return self.evaluate_grid(shape, extent, dtype=dtype, window=window, workers=workers)
