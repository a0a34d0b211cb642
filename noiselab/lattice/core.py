"""``LatticeNoise``: Phillips' permutation-table lattice noise (Perception 33, 2004, section 2).

The basis (2.1.1): a table of random values on [-1, 0) and one on (0, 1],
reached through a shuffled permutation ("address hashing") table; further
input dimensions nest the permutation, ``P[(P[(P[ix] + iy) mod n] + iz) mod n]``
(2.4.1, the integer lattice); every output component has its own permutation
(2.3.1). The lattice values are smoothed by a tensor-product kernel (2.1.1):
the box-filter (B-spline) family, an interpolating cubic, or the quintic fade.
Classic gradient (Perlin) noise is offered as a second basis.
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from .._core import resolve_workers, run_split, as_generator, as_array, check_finite_array, check_int, check_memory, check_real, check_shape, float_dtype
from . import _inthash, _jit, _kerncache
from .kernels import KERNELS, Kernel, get_kernel

__all__ = ["LatticeNoise", "Grid", "grid_coordinates"]

_BASES = ("value", "gradient")
_ALTERNATIONS = ("table", "lattice")
_HASHES = ("table", "integer")
# without ``period``, the integer hash reduces lattice indices modulo 2**32 per axis (its words are 32-bit)
_INT_PERIOD = _inthash.PERIOD_MAX
# the 3-D scattered kernels' two-level hash table (uint16, n * n entries per
# output component; its entries reach 3n + 4 < 2**16) is used up to this
# size (n = 1024 for one component: 2 MiB)
_MAX_H2_ENTRIES = 1 << 20


class Grid(NamedTuple):
    """A regular grid: ``shape`` (one count per input axis) over ``extent``.

    ``extent`` holds one ``(start, stop)`` pair per input axis in the noise's
    input units, stop excluded as in ``numpy.arange``: sample ``j`` along axis
    ``a`` sits at ``start + j * (stop - start) / shape[a]``.
    """

    shape: tuple
    extent: tuple


def _check_grid(shape, extent, dim):
    shape = check_shape("shape", shape, ndim=dim, min_size=0)
    try:
        ext = check_finite_array("extent", extent).astype(np.float64)
    except TypeError as exc:
        raise TypeError(f"extent must be one (start, stop) pair of reals per input axis: {exc}") from None
    if dim == 1 and ext.shape == (2,):
        ext = ext[None]
    if ext.shape != (dim, 2):
        raise ValueError(f"extent must be one (start, stop) pair per input axis, shape ({dim}, 2); got shape {ext.shape}")
    if not np.isfinite(ext).all():
        raise ValueError("extent must be finite")
    return shape, ext


def grid_coordinates(shape, extent):
    """Per-axis sample coordinates of a grid: ``start + j * ((stop - start) / n)``.

    Both evaluation paths, every window and every octave use exactly this
    formula, so the same sample always gets the same coordinate bits.

    Examples
    --------
    >>> [c.tolist() for c in grid_coordinates((4,), [(0, 2)])]
    [[0.0, 0.5, 1.0, 1.5]]
    """
    shape, ext = _check_grid(shape, extent, len(check_shape("shape", shape, min_size=0)))
    return _coordinates(shape, ext)


def _coordinates(shape, ext):
    """:func:`grid_coordinates` of an already checked shape and (dim, 2) float64 extent."""
    _check_large(8 * sum(shape), f"grid coordinates for shape {shape}")
    return [ext[a, 0] + np.arange(n, dtype=np.float64) * ((ext[a, 1] - ext[a, 0]) / max(n, 1))
            for a, n in enumerate(shape)]


def _check_large(nbytes, what):
    """``check_memory`` for allocations past 64 MiB (reading /proc costs more than a small grid)."""
    if nbytes > (64 << 20):
        check_memory(nbytes, what)


# Past 2**52 lattice cells a float64 coordinate has no fractional bits: the
# separable grid pass (which works with lattice indices relative to the
# grid's first tap) is then replaced by the per-point path, which reduces
# every index exactly (fmod), so both paths give the same samples.
_SEPARABLE_LIMIT = float(2 ** 52)


def _check_reach(flat, freqs, phase, name):
    """Refuse points whose lattice coordinate ``x * frequency + phase`` (any octave) overflows float64.

    ``flat`` is ``(n, dim)``, ``freqs`` ``(octaves, dim)``. Two passes over the
    contiguous points (their max and min over every axis at once: reductions
    along axis 0 of a narrow array are several times slower); NaN propagates
    into both, so NaN and inf are caught here too, with check_finite_array's
    message. The bound mixes the axes (largest |x| times largest frequency), so
    only when it fails are the axes looked at one by one.
    """
    if flat.shape[0] == 0:
        return
    hi, lo = float(flat.max()), float(flat.min())
    if not (math.isfinite(hi) and math.isfinite(lo)):
        check_finite_array(name, flat)
    reach = max(abs(hi), abs(lo)) * float(np.max(freqs)) + float(np.max(np.abs(phase))) + 8.0
    if math.isfinite(reach):
        return
    top = np.maximum(np.abs(flat.max(axis=0)), np.abs(flat.min(axis=0)))
    with np.errstate(over="ignore", invalid="ignore"):
        reach = top * np.max(freqs, axis=0) + np.abs(phase) + 8.0
    if not np.isfinite(reach).all():
        raise ValueError(f"{name} times the frequency (and lacunarity**octave) overflows float64: |{name}| up to "
                         f"{float(top.max()):.3g} at {float(np.max(freqs)):.3g} "
                         "lattice cells per unit; keep |x * frequency| below 1.7e308")


def _jac_bound(freqs, amps):
    """Sum over octaves of |amplitude scale| x the largest frequency: the derivative's scale."""
    freqs, amps = np.abs(np.asarray(freqs, dtype=np.float64)), np.abs(np.asarray(amps, dtype=np.float64)).ravel()
    with np.errstate(over="ignore"):
        if amps.size == freqs.shape[0]:
            return float(np.sum(amps * freqs.max(axis=1)))
        return float(amps.max() * freqs.max() * freqs.shape[0])


def _check_jac_finite(out, where, bound):
    """Derivatives scale with amplitude * frequency (* (gain * lacunarity)**octave): refuse an overflowed one.

    The derivative is at most ``bound`` (:func:`_jac_bound`) times a constant of
    the kernel and tables (at most 3.6 for the stock C1 kernels, either basis,
    1-4 D, over 20,000 random points each; a polynomial kernel's derivative
    over its value stays far below 1e20), so only a bound past 1e288 pays for
    the pass over the output.
    """
    if bound < 1e288:
        return
    if not np.isfinite(out).all():
        raise ValueError(f"the derivative {where} overflows float64: amplitude times frequency (times "
                         "(gain * lacunarity)**octave) is too large; keep |amplitude * frequency| well below 1.7e308")


def _check_amplitude(amplitude, dtype, what="amplitude"):
    """The output bound ``amplitude`` (times the octaves' gains) must fit the output dtype."""
    top = float(np.finfo(dtype).max)
    if not amplitude <= top:
        raise ValueError(f"{what} {amplitude:.3g} exceeds the range of {np.dtype(dtype).name} ({top:.3g}): "
                         "the output would overflow; use dtype=float64 or a smaller amplitude")


def _per_axis(name, value, dim, *, lo=None, lo_open=False, integer=False):
    if isinstance(value, (str, bytes, set, frozenset, dict)) or value is None:
        raise TypeError(f"{name} must be a number or a sequence of dim_in={dim} numbers, got {type(value).__name__}")
    try:
        arr = np.atleast_1d(np.asarray(value, dtype=object))
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a number or a sequence of dim_in={dim} numbers, got {value!r}") from None
    if arr.ndim != 1 or arr.size not in (1, dim):
        raise ValueError(f"{name} must be a number or a sequence of dim_in={dim} numbers, got {value!r}")
    arr = np.broadcast_to(arr, (dim,))
    if integer:
        return np.array([check_int(f"{name}", v, lo=1, hi=1 << 62) for v in arr], dtype=np.int64)
    return np.array([check_real(name, v, lo=lo, lo_open=lo_open) for v in arr], dtype=np.float64)


class LatticeNoise:
    r"""Phillips' lattice noise ``a * noise(F x + phi)`` (Eq. 2) with any input and output dimension.

    Parameters
    ----------
    dim_in : int
        Input dimension d >= 1 (1: a curve of time, 2: an image, 3: solid noise, ...).
    dim_out : int, default 1
        Output components; each has its own permutation table (Phillips 2.3.1).
    seed : int or numpy.random.Generator, default 0
        Seeds the value tables, the gradients and the permutations.
    kernel : str, default "cubic"
        ``"box"``, ``"linear"``, ``"quadratic"``, ``"cubic"`` (B-splines of
        order 1-4, i.e. 1-4 box filters), ``"catmull-rom"`` (interpolating
        cubic) or ``"quintic"`` (Perlin's fade); see :mod:`noiselab.lattice.kernels`.
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
        pseudo-periodic with the table's period n.
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
        permutation; ``alternation`` must be ``"table"``. In 1-3-D with a
        stock kernel it runs SIMD kernels: float32 points give float32
        output computed in float32 (see Notes, Precision).

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

    **Precision.** Coordinates are split in float64 into an integer lattice
    index and an exact fraction (``u - floor(u)`` is exact); the index is
    reduced modulo the period before it becomes an int64 (``fmod`` past 2**52),
    so inputs up to 1e12 and beyond stay continuous, and float32 inputs are
    promoted. The output is float64 (float32 for float32 input unless ``dtype``
    says otherwise). With ``hash="integer"`` (1-3-D, stock kernels) float32
    output is computed in float32 after the exact float64 split (the split
    itself is float32 when that is exact: zero phase, power-of-two
    frequencies >= 1, kernels without a half-cell shift); its error against
    the float64 computation is a few float32 ulps (``benchmarks/bench_lattice.md``,
    integer-hash section), and the result is clamped to the proved bound,
    which absorbs only that rounding.

    Examples
    --------
    >>> import numpy as np
    >>> noise = LatticeNoise(2, seed=1)
    >>> v = noise(np.random.default_rng(0).uniform(-8, 8, (1000, 2)))
    >>> v.shape, bool(np.abs(v).max() <= 1)
    ((1000,), True)
    >>> img = noise.grid((64, 64), [(0, 4), (0, 4)])
    >>> img.shape
    (64, 64)
    >>> flow = LatticeNoise(2, 2, seed=1)(np.zeros((5, 2)))
    >>> flow.shape
    (5, 2)
    """

    def __init__(self, dim_in, dim_out=1, *, seed=0, kernel="cubic", basis="value", table_size=256,
                 period=None, frequency=1.0, phase=0.0, amplitude=1.0, alternation="table", hash="table"):
        self.dim_in = check_int("dim_in", dim_in, lo=1, hi=32)
        self.dim_out = check_int("dim_out", dim_out, lo=1)
        self.kernel: Kernel = get_kernel(kernel)
        if basis not in _BASES:
            raise ValueError(f"basis must be one of {_BASES}, got {basis!r}")
        if alternation not in _ALTERNATIONS:
            raise ValueError(f"alternation must be one of {_ALTERNATIONS}, got {alternation!r}")
        if hash not in _HASHES:
            raise ValueError(f"hash must be one of {_HASHES}, got {hash!r}")
        if hash == "integer" and alternation != "table":
            raise ValueError("alternation must be 'table' with hash='integer' (the integer hash draws signed values; "
                             f"there are no separate positive and negative tables), got {alternation!r}")
        self.basis = basis
        self.alternation = alternation
        self.hash = hash
        n = check_int("table_size", table_size, lo=2, hi=1 << 24)
        if n % 2:
            raise ValueError(f"table_size must be even (equal positive and negative tables), got {n}")
        self.table_size = n
        # permutations (int64 and the doubled uint64 copy) and the 3-D hash tables, per component
        _check_large(self.dim_out * n * (8 * 3 + 2 * min(n, 1024) + 64) + n * self.dim_in * 8,
                     f"LatticeNoise(dim_out={self.dim_out}, table_size={n})")
        d = self.dim_in
        if period is None:
            self.period = np.full(d, n if hash == "table" else _INT_PERIOD, dtype=np.int64)
            self.tileable = False
        else:
            self.period = _per_axis("period", period, d, integer=True)
            self.tileable = True
            if hash == "integer" and (self.period > _INT_PERIOD).any():
                raise ValueError(f"period must be at most 2**32 cells per axis with hash='integer' (its lattice words "
                                 f"are 32-bit), got {self.period.tolist()}")
            if alternation == "lattice" and (self.period % 2).any():
                raise ValueError(f"period must be even with alternation='lattice', got {self.period.tolist()}")
        self._pmask = np.where((self.period & (self.period - 1)) == 0, self.period - 1, -1).astype(np.int64)
        self.frequency = _per_axis("frequency", frequency, d, lo=0.0, lo_open=True)
        self.phase = _per_axis("phase", phase, d)
        self.amplitude = check_real("amplitude", amplitude, lo=0.0, lo_open=True)
        self.seed = seed

        rng = as_generator(seed)
        # Draw order is fixed (and components last) so that the first
        # components of a dim_out=k noise equal those of a smaller dim_out.
        positive = 1.0 - rng.random(n)          # (0, 1]
        negative = rng.random(n) - 1.0          # [-1, 0)
        gradients = rng.standard_normal((n, d))
        norms = np.linalg.norm(gradients, axis=1, keepdims=True)
        gradients /= np.where(norms > 0, norms, 1.0)
        # the integer hash's per-component 64-bit keys (drawn only for it, so the table hash's draws are
        # unchanged; before the permutations, so that a smaller dim_out gets the first keys)
        self._keys = _inthash.component_keys(rng.integers(0, 1 << 63, size=self.dim_out, dtype=np.int64)) \
            if hash == "integer" else np.zeros(self.dim_out, np.uint32)
        self.perms = np.stack([rng.permutation(n) for _ in range(self.dim_out)]).astype(np.int64)
        self._perms2 = np.ascontiguousarray(np.concatenate([self.perms, self.perms], axis=1), dtype=np.uint64)
        if alternation == "table":
            interleaved = np.where(np.arange(n) % 2 == 0, positive, negative)
            self.values = np.stack([interleaved, interleaved])
        else:
            self.values = np.stack([positive, negative])
        self.positive, self.negative = positive, negative
        self.gradients = np.ascontiguousarray(gradients)
        self._mult = np.ascontiguousarray(_inthash.MULT[:d])
        # the integer hash's gradient set (fixed and small in 1-3-D, see _inthash.gradient_set)
        self._int_grads = _inthash.gradient_set(d, self.gradients)
        if basis == "value":
            self.bound = self.kernel.value_bound(d)
        else:
            self.bound = self.kernel.gradient_bound(d)
        # a * basis / bound, so |output| <= a
        self.scale = self.amplitude / self.bound

    # ------------------------------------------------------------------ repr
    def __repr__(self):
        return (f"LatticeNoise(dim_in={self.dim_in}, dim_out={self.dim_out}, seed={self.seed!r}, "
                f"kernel={self.kernel.name!r}, basis={self.basis!r}, table_size={self.table_size}"
                + (", hash='integer')" if self.hash == "integer" else ")"))

    # ------------------------------------------------------------- scattered
    def _prepare_points(self, points, name="points"):
        points = as_array(name, points)
        tables = self._uses_tables() or self._int_fast() is not None  # kernels that read float32 and count non-finite
        if not (points.dtype.kind == "f" and tables):  # the table kernels check
            points = check_finite_array(name, points)
        d = self.dim_in
        if d == 1 and (points.ndim == 0 or points.shape[-1] != 1):
            lead = points.shape
            flat = points.reshape(-1, 1)
        else:
            if points.ndim == 0 or points.shape[-1] != d:
                raise ValueError(f"{name} must have shape (..., dim_in={d}), got {points.shape}")
            lead = points.shape[:-1]
            flat = points.reshape(-1, d)
        # the table and integer-hash SIMD kernels read float32 points themselves (exact widening), saving a copy
        keep = tables and points.dtype == np.float32
        return lead, np.ascontiguousarray(flat, dtype=np.float32 if keep else np.float64)

    def _out_dtype(self, points_dtype, dtype):
        if dtype is not None:
            return float_dtype(dtype)
        return np.dtype(np.float32) if points_dtype == np.float32 else np.dtype(np.float64)

    def _evaluate(self, flat, freqs, amps, absval, dtype, name="points", workers=1):
        # the computation is float64; float32 output is a rounding of the
        # float64 result (the table kernels round as they store; the others
        # write float64, one compiled specialisation each)
        use_tables = self._uses_tables()
        fast = self._int_fast()
        own = use_tables or fast is not None  # kernels that store the output dtype themselves
        out = np.empty((flat.shape[0], self.dim_out), dtype=dtype if own else np.float64)
        if not own:
            flat = np.ascontiguousarray(flat, dtype=np.float64)
        if flat.shape[0]:
            k = self.kernel
            freqs = np.ascontiguousarray(freqs, dtype=np.float64)
            amps = np.ascontiguousarray(amps, dtype=np.float64)
            basis = 0 if self.basis == "value" else 1
            tabled = self._table_kernel()
            unrolled = _kerncache.load("points").KERNELS.get((self.dim_in, k.taps))
            tables = self._hash_tables(basis) if use_tables else None
            if not own:
                _check_reach(flat, freqs, self.phase, name)  # the table and SIMD kernels count overflows themselves
            if self.hash == "integer":
                bad = self._evaluate_int(fast, flat, out, freqs, amps, absval, workers)
                if bad:
                    check_finite_array(name, flat)  # raises for NaN or inf input
                    raise ValueError(f"{name} times the frequency (and lacunarity**octave) overflows float64")
            elif tables is not None:
                bad = run_split(tabled, flat, out, (freqs, amps, self.phase, k.shift, k.left, k.coef, self.period,
                                                     self._pmask, *tables, basis, bool(absval)), workers)
                if bad:
                    check_finite_array(name, flat)  # raises for NaN or inf input
                    raise ValueError(f"{name} times the frequency (and lacunarity**octave) overflows float64")
            elif unrolled is not None and (self.period >= k.taps).all():
                run_split(unrolled, flat, out, (freqs, amps, self.phase, k.shift, k.left, k.coef, self.period,
                                                 self._pmask, self._perms2, self.values, self.gradients, basis,
                                                 bool(absval)), workers)
            else:
                run_split(_jit.eval_points, flat, out, (freqs, amps, self.phase, k.shift, k.left, k.taps, k.coef,
                                                         self.period, self._pmask, self.perms, self.values,
                                                         self.gradients, basis, bool(absval)), workers)
        return out if out.dtype == dtype else out.astype(dtype)

    def _int_fast(self):
        """The integer hash's SIMD kernels for this noise (``{variant: kernel}``), or None (4-D and up, custom kernels)."""
        if self.hash != "integer" or self.dim_in > 3:
            return None
        k = self.kernel
        stock = KERNELS.get(k.name)
        if stock is None or not np.array_equal(stock.coef, k.coef) or stock.shift != k.shift or stock.left != k.left:
            return None
        _intpoints = _kerncache.load("intpoints")  # generated and imported on first use

        return {v: _intpoints.INT_KERNELS[(self.dim_in, k.name, self.basis, v)] for v in ("s32f32", "s64f32", "s64f64")}

    def _evaluate_int(self, fast, flat, out, freqs, amps, absval, workers):
        """The integer hash at scattered points into ``out`` (``fast``: :meth:`_int_fast`); returns the non-finite count."""
        k = self.kernel
        if fast is None:  # any dimension, any kernel: the generic kernel (float64, checked by the caller)
            run_split(_inthash.int_points, flat, out,
                       (freqs, amps, self.phase, k.shift, k.left, k.taps, k.coef, self.period, self._pmask,
                        self._keys, self._mult, self._int_grads, int(self.basis == "gradient"), bool(absval)),
                       workers)
            return 0
        _intpoints = _kerncache.load("intpoints")

        if out.dtype == np.float64:
            variant = "s64f64"
        else:
            # float32 points whose split x * F + phi is exact in float32: no phase or shift, F = 2**e >= 1
            exact32 = (flat.dtype == np.float32 and k.shift == 0.0 and not self.phase.any()
                       and bool(np.all((freqs >= 1.0) & (np.frexp(freqs)[0] == 0.5))))
            variant = "s32f32" if exact32 else "s64f32"
        factor = _intpoints.FACTOR[self.basis][self.dim_in - 1]
        limit = self.bound * float(np.abs(amps).sum())
        return run_split(fast[variant], flat, out, (freqs, amps * factor, self.phase, self._keys, self._pmask,
                                                     self.period, limit, bool(absval)), workers)

    def _table_kernel(self):
        """The 3-D table kernel: with this kernel's coefficients written in if it is a stock kernel."""
        k = self.kernel
        stock = KERNELS.get(k.name)
        table_kernels = _kerncache.load("points").TABLE_KERNELS
        if stock is not None and np.array_equal(stock.coef, k.coef) and (self.dim_in, k.name) in table_kernels:
            return table_kernels[(self.dim_in, k.name)]
        return table_kernels.get((self.dim_in, k.taps))

    def _uses_tables(self):
        """Whether the scattered kernel over precombined hash tables applies (3-D input; last period n)."""
        k = self.kernel
        if self.hash != "table":
            return False
        table_kernels = _kerncache.load("points").TABLE_KERNELS
        return ((self.dim_in, k.taps) in table_kernels and (self.period >= k.taps).all()
                and self.period[-1] == self.table_size and self.table_size ** 2 * self.dim_out <= _MAX_H2_ENTRIES)

    def _hash_tables(self, basis):
        """Precombined hash tables for the 3-D scattered kernels.

        ``H2[c, q0 * n + q1] = P_c[(P_c[q0] + q1) mod n]`` (the first two
        nested levels in one load), plus, for value noise, the parity row
        offset ``S * ((q0 + q1 + h) & 1)``; ``VL[c, r * S + x] =
        values[(r + x) & 1, P_c[x mod n]]`` for ``x < S = 2n + 4``: the last
        level folded into the values, and run on past 2n so that the last
        axis's taps ``x, x + 1, ...`` are contiguous without a wrap (the last
        axis's period must be n). ``G[c, a * S + x] = gradients[P_c[x mod n], a]``
        likewise. Rebuilt whenever the permutations, values or gradients
        change (they are public attributes), so the tables never go stale.
        """
        n = self.table_size
        src = self.values if basis == 0 else self.gradients
        key = (basis, self.perms.tobytes(), src.tobytes())
        cache = getattr(self, "_tables_cache", None)
        if cache is not None and cache[0] == key:
            return cache[1]
        S = 2 * n + 4
        q = np.arange(n)
        x = np.arange(S)
        H2 = np.empty((self.dim_out, n * n), dtype=np.uint16)
        VL = np.zeros((self.dim_out, 2 * S))
        G = np.zeros((self.dim_out, self.dim_in * S))
        for c, P in enumerate(self.perms):
            h = P[(P[q][:, None] + q[None, :]) % n]
            if basis == 0:
                h = h + S * ((q[:, None] + q[None, :] + h) & 1)
                for r in range(2):
                    VL[c, r * S:(r + 1) * S] = self.values[(r + x) & 1, P[x % n]]
            else:
                G[c] = self.gradients[P[x % n]].T.ravel()
            H2[c] = h.ravel()
        tables = (H2, VL, G)
        self._tables_cache = (key, tables)
        return tables

    def __call__(self, points, *, dtype=None, workers=1):
        """Evaluate at points of shape ``(..., dim_in)``; returns ``(...)`` or ``(..., dim_out)``.

        For ``dim_in == 1`` an array whose last axis is not 1 (or a scalar) is
        taken as that many scalar inputs. ``dtype`` (float32 or float64) picks
        the output precision; the computation is float64 either way.
        ``workers`` > 1 splits the points into that many contiguous blocks
        evaluated on threads (the kernels release the GIL); every point's
        arithmetic is the same, so the result is bit-identical to one worker.
        """
        workers = resolve_workers(workers)
        raw = as_array("points", points)
        lead, flat = self._prepare_points(raw)
        dtype = self._out_dtype(raw.dtype, dtype)
        _check_amplitude(self.amplitude, dtype)
        _check_large(flat.shape[0] * (self.dim_out * dtype.itemsize + 8 * self.dim_in), "lattice noise")
        out = self._evaluate(flat, self.frequency[None], np.array([self.scale]), False, dtype, workers=workers)
        return self._shape_out(out, lead)

    def _shape_out(self, out, lead):
        if self.dim_out == 1:
            return out.reshape(lead)
        return out.reshape(tuple(lead) + (self.dim_out,))

    # ----------------------------------------------------------- derivatives
    def _check_differentiable(self):
        k = self.kernel
        if k.continuity < 1:
            smooth = ", ".join(name for name, kk in KERNELS.items() if kk.continuity >= 1)
            raise ValueError(f"kernel {k.name!r} has no continuous first derivative (its noise is "
                             f"{'discontinuous' if k.continuity < 0 else 'only C0: creased at every lattice line'}); "
                             f"derivatives need a C1 kernel: kernel must be one of {smooth}")

    def _evaluate_jac(self, flat, freqs, amps, absval, name="points", workers=1):
        """Values and Jacobians at points ``flat`` (N, d): float64 ``(N, dim_out, 1 + dim_in)``, value first."""
        self._check_differentiable()
        flat = np.ascontiguousarray(flat, dtype=np.float64)
        freqs = np.ascontiguousarray(freqs, dtype=np.float64)
        amps = np.ascontiguousarray(amps, dtype=np.float64)
        out = np.empty((flat.shape[0], self.dim_out, self.dim_in + 1))
        if flat.shape[0]:
            _check_reach(flat, freqs, self.phase, name)  # as for values: x * frequency + phase must stay finite
            k = self.kernel
            basis = 0 if self.basis == "value" else 1
            _jacobians = _kerncache.load("jacobians")  # generated and imported on the first derivative

            unrolled = _jacobians.JAC_KERNELS.get((self.dim_in, k.taps))
            tabled = _jacobians.JAC_TABLE_KERNELS.get((self.dim_in, k.taps))
            if self.hash == "integer":
                run_split(_inthash.int_points_jac, flat, out,
                           (freqs, amps, self.phase, k.shift, k.left, k.taps, k.coef, k.dcoef, self.period,
                            self._pmask, self._keys, self._mult, self._int_grads, basis, bool(absval)), workers)
            elif tabled is not None and self._uses_tables():
                run_split(tabled, flat, out, (freqs, amps, self.phase, k.shift, k.left, k.coef, k.dcoef,
                                               self.period, self._pmask, *self._hash_tables(basis), basis,
                                               bool(absval)), workers)
            elif unrolled is not None and (self.period >= k.taps).all():
                run_split(unrolled, flat, out, (freqs, amps, self.phase, k.shift, k.left, k.coef, k.dcoef,
                                                 self.period, self._pmask, self._perms2, self.values,
                                                 self.gradients, basis, bool(absval)), workers)
            else:
                run_split(_jit.eval_points_jac, flat, out,
                           (freqs, amps, self.phase, k.shift, k.left, k.taps, k.coef, k.dcoef, self.period,
                            self._pmask, self.perms, self.values, self.gradients, basis, bool(absval)), workers)
            _check_jac_finite(out, f"at the given {name}", _jac_bound(freqs, amps))
        return out

    def _jac_result(self, out, lead, return_value, scalar):
        """Views into the kernels' ``(N, dim_out, 1 + dim_in)`` output (no copies): the Jacobian and the value."""
        jac = out[:, :, 1:]
        jac = jac[:, 0].reshape(tuple(lead) + (self.dim_in,)) if scalar else \
            jac.reshape(tuple(lead) + (self.dim_out, self.dim_in))
        if not return_value:
            return jac
        return self._shape_out(out[:, :, 0], lead), jac

    def _scalar_only(self, what):
        if self.dim_out != 1:
            raise ValueError(f"{what} is for scalar noise (dim_out=1), this noise has dim_out={self.dim_out}; "
                             f"use jacobian{'_grid' if 'grid' in what else ''} for vector noise")

    def jacobian(self, points, *, return_value=False, workers=1):
        r"""The exact Jacobian ``d noise_c / d x_a`` at points ``(..., dim_in)``: shape ``(..., dim_out, dim_in)``.

        In input units: the chain rule through ``a * noise(F x + phi)`` gives
        ``a F_a`` times the lattice-space derivative, which is the kernel's
        derivative on one axis of the tensor product (and, in the gradient
        basis, the gradient component ``g_a`` weighted by the kernel). It
        needs a kernel with a continuous first derivative (``quadratic``,
        ``cubic``, ``catmull-rom``, ``quintic``); ``box`` and ``linear`` raise
        ValueError.

        Parameters
        ----------
        points : array_like, shape (..., dim_in)
            As for ``__call__`` (for ``dim_in == 1`` a plain array is that many inputs).
        return_value : bool, default False
            Also return the noise values (computed in the same pass), as ``(value, jacobian)``.
        workers : int, default 1
            Threads over blocks of points (bit-identical to one worker).

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
        >>> noise = LatticeNoise(3, 3, seed=2, frequency=2.0)
        >>> noise.jacobian(np.zeros((5, 3))).shape
        (5, 3, 3)
        """
        workers = resolve_workers(workers)
        self._check_differentiable()
        lead, flat = self._prepare_points(points)
        _check_large(flat.shape[0] * self.dim_out * (self.dim_in + 1) * 8 * 2, "lattice noise jacobian")
        out = self._evaluate_jac(flat, self.frequency[None], np.array([self.scale]), False, workers=workers)
        return self._jac_result(out, lead, return_value, scalar=False)

    def gradient(self, points, *, return_value=False, workers=1):
        """The exact gradient of scalar noise (``dim_out == 1``) at points ``(..., dim_in)``: shape ``(..., dim_in)``.

        :meth:`jacobian` of a one-component noise, without the component
        axis; see there for units, kernels and ``return_value``.

        Examples
        --------
        >>> import numpy as np
        >>> noise = LatticeNoise(2, seed=1, kernel="quintic", frequency=4.0)
        >>> value, grad = noise.gradient(np.array([[0.3, 0.7]]), return_value=True)
        >>> value.shape, grad.shape
        ((1,), (1, 2))
        """
        self._scalar_only("gradient")
        workers = resolve_workers(workers)
        self._check_differentiable()
        lead, flat = self._prepare_points(points)
        _check_large(flat.shape[0] * (self.dim_in + 1) * 8 * 2, "lattice noise gradient")
        out = self._evaluate_jac(flat, self.frequency[None], np.array([self.scale]), False, workers=workers)
        return self._jac_result(out, lead, return_value, scalar=True)

    def _grid_jac(self, shape, extent, *, window=None, octaves=1, lacunarity=2.0, gain=0.5, absval=False,
                  value=True):
        """Value (or None) and Jacobian ``shape + (dim_out, dim_in)`` on a grid, by the separable passes.

        One pass per input axis with the kernel's derivative on that axis (and
        one for the value). Turbulence (``absval``) is summed octave by octave
        as ``sign(n_o) n_o'``.
        """
        self._check_differentiable()
        shape, ext = _check_grid(shape, extent, self.dim_in)
        with np.errstate(over="ignore"):
            freqs = self.frequency[None, :] * (float(lacunarity) ** np.arange(octaves, dtype=np.float64))[:, None]
            amps = self.scale * float(gain) ** np.arange(octaves, dtype=np.float64)
        _check_reach(np.ascontiguousarray(ext.T), freqs, self.phase, "extent")  # before any allocation
        size = int(np.prod(shape, dtype=np.int64))
        _check_large(size * self.dim_out * (self.dim_in + 2) * 8, "lattice noise jacobian grid")
        kw = dict(dtype=np.float64, window=window, lacunarity=lacunarity, gain=gain)
        d = self.dim_in
        # one contiguous (dim_out, *shape) block per input axis, written in
        # place by the grid passes; returned as a (*shape, dim_out, dim_in) view
        out_shape = tuple(hi - lo for lo, hi in self._window(shape, window))
        buf = np.empty((d, self.dim_out) + out_shape)
        if not absval:
            val = self._grid(shape, ext, octaves=octaves, **kw) if value else None
            for a in range(d):
                self._grid(shape, ext, octaves=octaves, deriv_axis=a, out=buf[a], **kw)
        else:
            buf[...] = 0.0
            total = np.zeros((self.dim_out,) + out_shape)
            octave, part = np.empty_like(total), np.empty_like(total)
            for o in range(octaves):
                self._grid(shape, ext, octaves=o + 1, octave_start=o, out=octave, **kw)
                sgn = np.sign(octave)
                total += np.abs(octave)
                for a in range(d):
                    self._grid(shape, ext, octaves=o + 1, octave_start=o, deriv_axis=a, out=part, **kw)
                    buf[a] += sgn * part
            val = self._finish_grid(total) if value else None
        _check_jac_finite(buf, "on this grid (extent)", _jac_bound(freqs, amps))
        jac = np.moveaxis(buf, (0, 1), (-1, -2))
        return val, jac

    def jacobian_grid(self, shape, extent, *, window=None, return_value=False):
        """:meth:`jacobian` on a regular grid (as :meth:`grid`): shape ``shape + (dim_out, dim_in)``.

        Evaluated by the grid's separable passes with the kernel's derivative
        on one axis (one set of passes per input axis); agrees with
        :meth:`jacobian` on :meth:`grid_points` to rounding (tested).
        ``window`` as in :meth:`grid`; ``return_value`` also returns
        :meth:`grid`'s values, as ``(value, jacobian)``.

        Examples
        --------
        >>> noise = LatticeNoise(2, 2, seed=3)
        >>> noise.jacobian_grid((32, 16), [(0, 4), (0, 2)]).shape
        (32, 16, 2, 2)
        """
        val, jac = self._grid_jac(shape, extent, window=window, value=bool(return_value))
        return (val, jac) if return_value else jac

    def gradient_grid(self, shape, extent, *, window=None, return_value=False):
        """:meth:`gradient` on a regular grid (as :meth:`grid`): shape ``shape + (dim_in,)``.

        See :meth:`jacobian_grid`.

        Examples
        --------
        >>> noise = LatticeNoise(2, seed=3, kernel="quintic")
        >>> h, g = noise.gradient_grid((64, 64), [(0, 4), (0, 4)], return_value=True)
        >>> h.shape, g.shape
        ((64, 64), (64, 64, 2))
        """
        self._scalar_only("gradient_grid")
        val, jac = self._grid_jac(shape, extent, window=window, value=bool(return_value))
        jac = jac[..., 0, :]
        return (val, jac) if return_value else jac

    # ------------------------------------------------------------------ grid
    def grid_points(self, shape, extent):
        """The points ``(*shape, dim_in)`` that :meth:`grid` samples (for the scattered path)."""
        shape, extent = _check_grid(shape, extent, self.dim_in)
        _check_large(math.prod(shape) * self.dim_in * 8 * 2, f"grid_points{shape}")
        coords = grid_coordinates(shape, extent)
        return np.stack(np.meshgrid(*coords, indexing="ij"), axis=-1) if coords else np.zeros((0,))

    def grid(self, shape, extent, *, dtype=np.float64, window=None, chunks=None):
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

        Returns
        -------
        ndarray, shape ``shape`` (or ``shape + (dim_out,)``); a dask array with ``chunks``

        Notes
        -----
        The tensor-product kernel is applied one axis at a time to the block of
        lattice values the grid covers (each pass is a banded matrix product),
        so a sample costs ``taps`` multiply-adds in the last pass instead of
        ``taps**d`` hashed lookups. Grids sparser than the lattice fall back
        to the scattered path. Both paths agree to 1e-12 (tested). 2-D grids
        with the table hash run every octave in one fused kernel, tile by
        tile, with the same bits (tested); on a 512 x 512 grid of 32 cells it
        ran at 0.9-1.8x pyfastnoisesimd's value and Perlin noise with
        float64 output and 1.3-2.5x with float32 output (quintic, one and
        six octaves, three runs of ``bench_lattice.py --grid-only``; see
        ``benchmarks/bench_lattice.md``).
        """
        if chunks is not None:
            from ..scale.lattice import chunked_grid
            return chunked_grid(self, shape, extent, dtype=dtype, chunks=chunks, window=window)
        return self._grid(shape, extent, dtype=dtype, window=window, octaves=1)

    def _grid(self, shape, extent, *, dtype, window, octaves, lacunarity=2.0, gain=0.5, absval=False,
              deriv_axis=None, octave_start=0, out=None):
        dtype = float_dtype(dtype)
        shape, ext = _check_grid(shape, extent, self.dim_in)
        coords = _coordinates(shape, ext)
        sl = self._window(shape, window)
        out_shape = tuple(hi - lo for lo, hi in sl)
        size = math.prod(out_shape)
        _check_large(size * self.dim_out * dtype.itemsize * 2 + size * 8, f"lattice noise grid {shape}")
        total_gain = sum(gain ** o for o in range(octaves)) if gain <= 1 else octaves * gain ** (octaves - 1)
        _check_amplitude(self.amplitude * total_gain, dtype, "amplitude (times the sum of the octaves' gains)")
        if size == 0:
            return self._finish_grid(np.zeros((self.dim_out,) + out_shape, dtype=dtype))
        full = list(coords)
        sub = [coords[a][lo:hi] for a, (lo, hi) in enumerate(sl)]
        separable, sparse = [], []
        for o in range(octave_start, octaves):
            freq = self.frequency * lacunarity ** o
            amp = self.scale * gain ** o
            with np.errstate(over="ignore"):
                reach = max((max(abs(c[0]), abs(c[-1])) * freq[a] if c.size else 0.0) + abs(self.phase[a])
                            for a, c in enumerate(full))
            if not np.isfinite(reach):
                raise ValueError(f"extent times the frequency (and lacunarity**octave) overflows float64 "
                                 f"({freq.max():.3g} lattice cells per unit); keep |x * frequency| below 1.7e308")
            exact = reach < _SEPARABLE_LIMIT
            (separable if exact and self._separable(full, freq) else sparse).append((freq, amp))
        # the separable pass writes every sample unless it accumulates |.| (turbulence)
        writes_all = bool(separable) and not absval
        if out is None:
            out = (np.empty if writes_all else np.zeros)((self.dim_out,) + out_shape, dtype=dtype)
        else:  # the caller's contiguous (dim_out, *out_shape) float64 buffer (the derivative grids)
            assert out.shape == (self.dim_out,) + out_shape and out.flags.c_contiguous and out.dtype == dtype
            if not writes_all:
                out[...] = 0.0
        if separable:
            self._grid_separable(sub, full, separable, out, absval, deriv_axis)
        for freq, amp in sparse:
            # grids sparser than this octave's lattice: per-point path, added
            self._grid_scattered(sub, freq, amp, out, absval, deriv_axis)
        return self._finish_grid(out)

    def _window(self, shape, window):
        """The (lo, hi) sample range per axis of ``window`` (checked), or the whole grid."""
        if window is None:
            return [(0, s) for s in shape]
        win = np.asarray(window, dtype=object)
        if win.shape != (self.dim_in, 2):
            raise ValueError(f"window must be one (lo, hi) index pair per axis, got {window!r}")
        sl = []
        for a, (lo, hi) in enumerate(win):
            lo = check_int(f"window[{a}][0]", lo, lo=0, hi=shape[a])
            hi = check_int(f"window[{a}][1]", hi, lo=lo, hi=shape[a])
            sl.append((lo, hi))
        return sl

    def _finish_grid(self, out):
        if self.dim_out == 1:
            return out[0]
        return np.ascontiguousarray(np.moveaxis(out, 0, -1))

    def _separable(self, full_coords, freq):
        """Separable if the lattice block is not much larger than the grid (decided on the full grid)."""
        taps = self.kernel.taps
        block = 1.0
        samples = 1.0
        for a, c in enumerate(full_coords):
            n = c.shape[0]
            span = abs(c[-1] - c[0]) * freq[a] if n > 1 else 0.0
            block *= min(n * taps, span + taps + 1)
            samples *= n
        return block <= 4.0 * samples + 4096

    def _grid_scattered(self, sub, freq, amp, out, absval, deriv_axis=None):
        # rows along axis 0 keep the temporary small; per-point results do
        # not depend on the chunking
        rest = np.stack(np.meshgrid(*sub[1:], indexing="ij"), axis=-1).reshape(-1, self.dim_in - 1) \
            if self.dim_in > 1 else np.zeros((1, 0))
        flat_out = out.reshape(self.dim_out, sub[0].shape[0], -1)
        for j, x0 in enumerate(sub[0]):
            pts = np.empty((rest.shape[0], self.dim_in))
            pts[:, 0] = x0
            pts[:, 1:] = rest
            if deriv_axis is None:
                vals = self._evaluate(pts, freq[None], np.array([amp]), absval, np.dtype(np.float64))
            else:
                vals = self._evaluate_jac(pts, freq[None], np.array([amp]), absval)[:, :, 1 + deriv_axis]
            for c in range(self.dim_out):
                flat_out[c, j] += vals[:, c].astype(out.dtype)

    def _axis_taps(self, coords_a, freq_a, a, grad, deriv=False):
        """Weights, tap positions and the reduced lattice indices of the distinct taps along one axis.

        ``deriv``: the weights' derivatives along this axis in input units
        instead (:func:`_jit.axis_dweights`), for the derivative grids.
        """
        k = self.kernel
        fis, base, w, rw = _jit.axis_weights(coords_a, freq_a, self.phase[a], k.shift, k.left, k.taps,
                                             k.coef, int(self.period[a]), grad)
        if deriv:
            w, rw = _jit.axis_dweights(coords_a, freq_a, self.phase[a], k.shift, k.left, k.taps,
                                       k.coef, k.dcoef, grad)
        # distinct lattice taps along this axis, relative to the smallest
        span = fis.max() - fis.min() if fis.size else 0.0
        if span <= 4 * k.taps * fis.size + 64:
            lattice, pos = _jit.dense_taps(fis, base, k.taps, int(self.period[a]))
            return lattice, pos, w, rw
        j0 = int(np.argmin(fis))
        rel = (fis - fis[j0]).astype(np.int64)[:, None] + np.arange(k.taps)
        uniq, inv = np.unique(rel, return_inverse=True)
        pos = inv.reshape(rel.shape).astype(np.int64)
        lattice = (base[j0] + uniq) % self.period[a]
        return lattice, pos, w, rw

    def _block_hash(self, c, lattices):
        """Hash the block of lattice points: ``h_{a+1} = P[(h_a + j_a) mod n]``, and the index parity (flat)."""
        n = self.table_size
        perm = self.perms[c]
        h = par = np.zeros(1, np.int64)
        for a, lat in enumerate(lattices):  # no lattices: the single empty prefix
            h, par = _jit.hash_expand(h, par, np.ascontiguousarray(lat, dtype=np.int64), perm, n, a == 0)
        return h, par

    def _int_prefix(self, c, lattices):
        """The integer hash's prefix words ``key_c ^ j_0 M_0 ^ ...`` over the block of lattice points (flat)."""
        h = self._keys[c:c + 1]
        for a, lat in enumerate(lattices):
            h = _inthash.block_prefix(h, np.ascontiguousarray(lat, dtype=np.int64), self._mult[a], a == 0,
                                      self._keys[c])
        return h

    def _grid_separable(self, sub, full, octaves, out, absval, deriv_axis=None):
        """Separable grid path: per octave and term, contract axes d-1..1; then one fused pass on axis 0.

        ``deriv_axis``: the derivative along that input axis instead (the
        same passes, with the kernel's derivative on that axis).
        """
        d = self.dim_in
        grad = self.basis == "gradient"
        if d == 2 and self.hash == "table" and self._FUSED_2D:
            self._grid_fused_2d(sub, octaves, out, absval, deriv_axis)
            return
        nterm = d if grad else 1
        # Batches of octaves whose partially contracted blocks fit a memory
        # budget, decided on the full grid so that windows batch identically.
        post_full = int(np.prod([c.shape[0] for c in full[1:]], dtype=np.int64))
        budget = max(64 << 20, 2 * 8 * full[0].shape[0] * post_full)
        batches, cur, used = [], [], 0
        for freq, amp in octaves:
            span = abs(full[0][-1] - full[0][0]) * freq[0] if full[0].shape[0] > 1 else 0.0
            rows = min(full[0].shape[0] * self.kernel.taps, span + self.kernel.taps + 1)
            need = 8 * rows * post_full * nterm
            if cur and used + need > budget:
                batches.append(cur)
                cur, used = [], 0
            cur.append((freq, amp))
            used += need
        batches.append(cur)
        post = int(np.prod([c.shape[0] for c in sub[1:]], dtype=np.int64))
        nj = sub[0].shape[0]
        for bi, batch in enumerate(batches):
            axes_per_octave = [[self._axis_taps(sub[a], freq[a], a, grad, deriv=a == deriv_axis) for a in range(d)]
                               for freq, _ in batch]
            rows = sum(len(axes[0][0]) for axes in axes_per_octave) * nterm
            for c in range(self.dim_out):
                inter_all = np.empty((rows, post))
                poss, ws, scales = [], [], []
                row0 = 0
                for (freq, amp), axes in zip(batch, axes_per_octave):
                    lattices = [ax[0] for ax in axes]
                    bshape = tuple(len(lat) for lat in lattices)
                    block = np.empty(int(np.prod(bshape, dtype=np.int64)))
                    if self.hash == "integer":
                        h = self._int_prefix(c, lattices)
                        if not grad:
                            _inthash.block_values(h, block)
                    elif grad:
                        h, par = self._block_hash(c, lattices)
                    else:
                        # hash all but the last level, then hash and look up in one pass
                        h, par = self._block_hash(c, lattices[:-1])
                        _jit.hash_expand_values(h, par, np.ascontiguousarray(lattices[-1], dtype=np.int64),
                                                self.perms[c], self.table_size, d == 1, self.values, block)
                    for b in range(nterm):
                        if grad and self.hash == "integer":
                            _inthash.block_gradients(h, self._int_grads, b, block)
                        elif grad:
                            _jit.gather_gradients(h, self.gradients, b, block)
                        target = inter_all[row0:row0 + bshape[0]]
                        self._contract_rest(block.reshape(bshape), axes, b if grad else -1, target)
                        _, pos0, w0, rw0 = axes[0]
                        poss.append(pos0 + row0)
                        ws.append(rw0 if (grad and b == 0) else w0)
                        scales.append(amp)
                        row0 += bshape[0]
                group_start = (np.arange(len(batch) + 1) * nterm if absval else np.array([0, len(ws)])).astype(np.int64)
                mode = 2 if absval else (0 if bi == 0 else 1)
                poss = np.ascontiguousarray(np.stack(poss))
                ws = np.ascontiguousarray(np.stack(ws))
                scales = np.asarray(scales, dtype=np.float64)
                target = out[c].reshape(nj, post)
                if mode == 0 and target.dtype == np.float64:
                    _jit.final_pass_direct(inter_all, poss, ws, scales, target)
                else:
                    _jit.final_pass(inter_all, poss, ws, scales, group_start, target, mode)

    # 2-D grids with the table hash take the fused kernel (a test turns it off to compare with the general path)
    _FUSED_2D = True
    # columns per tile of the fused 2-D pass (None: as many as keep its ring of contracted lattice rows,
    # octaves x 2**ceil(log2 taps) rows x gradient terms x tile float64, within _RING_BYTES: measured
    # on 512^2 and 1024^2 grids, wider tiles are faster up to the L2 cache); a test sets it small
    _TILE_2D = None
    _RING_BYTES = 256 << 10

    def _grid_fused_2d(self, sub, octaves, out, absval, deriv_axis):
        """The separable pass of a 2-D grid with the table hash: every octave in one kernel (:func:`_jit.grid2d`).

        The same arithmetic, term by term, as the general path (the same
        bits), without the lattice block or octave batches in memory.
        """
        grad = self.basis == "gradient"
        k = self.kernel
        n = self.table_size
        freqs = np.array([freq for freq, _ in octaves], dtype=np.float64)
        scales = np.array([amp for _, amp in octaves], dtype=np.float64)
        nq = out.shape[2]
        tile = self._TILE_2D
        if tile is None:  # the widest tile whose ring fits the budget, the row split into equal tiles
            slots = 1 << max(0, (k.taps - 1).bit_length())
            most = max(64, self._RING_BYTES // (8 * len(octaves) * slots * (2 if grad else 1)))
            tiles = -(-nq // most)
            tile = -(-nq // tiles)
        tile = -(-tile // 8) * 8
        assert out.flags.c_contiguous
        flat = out.reshape(self.dim_out, -1)
        # one compiled kernel for both output dtypes: the other output array is empty
        if out.dtype == np.float32:
            out64, out32 = np.empty((self.dim_out, 0)), flat
        else:
            out64, out32 = flat, np.empty((self.dim_out, 0), np.float32)
        dax = -1 if deriv_axis is None else int(deriv_axis)
        if _jit.grid2d_all(sub[0], sub[1], freqs, self.phase, k.shift, k.left, k.taps, k.coef, k.dcoef, self.period,
                           n, grad, dax, scales, self.perms, self.values, self.gradients, bool(absval), out64, out32,
                           nq, tile):
            return
        # an axis whose taps spread over many cells: packed here, _axis_taps' sparse branch for that axis
        packed = []
        for a in range(2):
            ok, lat, off, pos, base, wa, wb, dense = _jit.pack_axis(
                sub[a], np.ascontiguousarray(freqs[:, a]), self.phase[a], k.shift, k.left, k.taps, k.coef, k.dcoef,
                int(self.period[a]), n, grad, a == deriv_axis, a == 1)
            if not ok:  # taps spread over many cells: _axis_taps' sparse branch, packed alike
                axis = [self._axis_taps(sub[a], freq[a], a, grad, deriv=a == deriv_axis) for freq in freqs]
                lat = np.concatenate([np.asarray(ax[0], dtype=np.int64) for ax in axis]) % n
                off = np.zeros(len(axis) + 1, np.int64)
                off[1:] = np.cumsum([len(ax[0]) for ax in axis])
                pos = np.ascontiguousarray(np.stack([ax[1] for ax in axis]), dtype=np.int64)
                base = np.ascontiguousarray(pos[:, :, 0])
                wa = np.stack([ax[2] for ax in axis])
                wb = np.stack([ax[3] for ax in axis])
                if a == 1:
                    wa, wb = wa.transpose(0, 2, 1), wb.transpose(0, 2, 1)
                wa, wb = np.ascontiguousarray(wa), np.ascontiguousarray(wb)
                dense = np.array([self.period[1] % n == 0 and bool((np.diff(ax[0]) % self.period[1] == 1).all())
                                  for ax in axis])
            packed.append((lat, off, pos, wa, wb) if a == 0 else (lat, off, base, dense, wa, wb))
        for c in range(self.dim_out):
            _jit.grid2d(*packed[0], *packed[1], scales, self.perms[c], self.values, self.gradients, 1 if grad else 0,
                        bool(absval), out64[c], out32[c], nq, tile)

    @staticmethod
    def _contract_rest(block, axes, use_r, target):
        """Contract axes d-1 .. 1 of a lattice block into ``target`` (rows of axis 0 x the other grid axes).

        Axis ``use_r`` takes the gradient ramp weights.
        """
        cur = block
        d = cur.ndim
        if d == 1:
            target[:, 0] = cur
            return
        for a in range(d - 1, 0, -1):
            _, pos, w, rw = axes[a]
            weights = rw if a == use_r else w
            pre = int(np.prod(cur.shape[:a], dtype=np.int64))
            post = int(np.prod(cur.shape[a + 1:], dtype=np.int64))
            if a == 1:
                nxt = target.reshape(pre, pos.shape[0], post)
            else:
                nxt = np.empty((pre, pos.shape[0], post))
            if post == 1:
                _jit.contract_last(cur.reshape(pre, cur.shape[a]), pos, weights, nxt.reshape(pre, pos.shape[0]))
            else:
                _jit.contract_mid(cur.reshape(pre, cur.shape[a], post), pos, weights, nxt)
            cur = nxt.reshape(cur.shape[:a] + (pos.shape[0],) + cur.shape[a + 1:])
