"""Argument and overflow checks of lattice noise: each error names the parameter and the allowed range.

The checks of the constructor (:func:`per_axis`, :func:`check_choices`), of
an evaluation (:func:`check_octaves`, :func:`check_amplitude`,
:func:`check_reach`, :func:`check_large`), of a window of a grid
(:func:`check_window`) and of the derivatives (:func:`check_differentiable`,
:func:`check_scalar`, :func:`check_jac_finite` with :func:`jac_bound`).
Pure functions of their arguments; :class:`~noiselab.lattice.LatticeNoise`
and its paths call them as ``checks.name(...)``.
"""
from __future__ import annotations

import math

import numpy as np

from .._core import check_finite_array, check_int, check_memory, check_real, float_dtype
from ._jit import PERIOD_MAX
from .kernels import KERNELS

__all__ = ["BASES", "ALTERNATIONS", "HASHES", "DEFAULT_KERNELS", "default_kernel", "check_choices", "check_table_size", "per_axis", "check_period", "check_large",
           "check_octaves", "octave_periods", "total_gain", "check_amplitude", "check_reach", "check_window", "check_differentiable",
           "check_scalar", "jac_bound", "check_jac_finite", "ARITHMETICS", "check_arithmetic"]

BASES = ("value", "gradient")
ALTERNATIONS = ("table", "lattice")
HASHES = ("table", "integer")
ARITHMETICS = ("float64", "float32")


# the kernel a basis gets when none is named (see LatticeNoise's ``kernel``): Phillips' cubic B-spline for
# value noise, Perlin's quintic fade for gradient noise
DEFAULT_KERNELS = {"value": "cubic", "gradient": "quintic"}


def default_kernel(basis):
    """The kernel ``basis`` gets when none is named (a checked basis)."""
    return DEFAULT_KERNELS[basis]


def check_choices(basis, alternation, hash):
    """The constructor's three choices, each one of its names, and their one forbidden combination."""
    if basis not in BASES:
        raise ValueError(f"basis must be one of {BASES}, got {basis!r}")
    if alternation not in ALTERNATIONS:
        raise ValueError(f"alternation must be one of {ALTERNATIONS}, got {alternation!r}")
    if hash not in HASHES:
        raise ValueError(f"hash must be one of {HASHES}, got {hash!r}")
    if hash == "integer" and alternation != "table":
        raise ValueError("alternation must be 'table' with hash='integer' (the integer hash draws signed values; "
                         f"there are no separate positive and negative tables), got {alternation!r}")


def check_table_size(table_size) -> int:
    """Entries of the permutation and value tables: an even int in [2, 2**24]."""
    n = check_int("table_size", table_size, lo=2, hi=1 << 24)
    if n % 2:
        raise ValueError(f"table_size must be even (equal positive and negative tables), got {n}")
    return n


def per_axis(name, value, dim, *, lo=None, lo_open=False, integer=False):
    """One number, or one per input axis, as a ``(dim,)`` float64 (int64 with ``integer``) array."""
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


def check_period(period, dim, table_size, hash, alternation):
    """The lattice period per axis, ``(dim,)`` int64: ``period`` checked, or the default (not tileable).

    The default is the table's size n (table hash) or 2**32 (integer hash:
    its lattice words are 32-bit, so it allows no more).
    """
    if period is None:
        return np.full(dim, table_size if hash == "table" else PERIOD_MAX, dtype=np.int64)
    period = per_axis("period", period, dim, integer=True)
    if hash == "integer" and (period > PERIOD_MAX).any():
        raise ValueError(f"period must be at most 2**32 cells per axis with hash='integer' (its lattice words "
                         f"are 32-bit), got {period.tolist()}")
    if alternation == "lattice" and (period % 2).any():
        raise ValueError(f"period must be even with alternation='lattice', got {period.tolist()}")
    return period


def check_large(nbytes, what):
    """``check_memory`` for allocations past 64 MiB (reading /proc costs more than a small grid)."""
    if nbytes > (64 << 20):
        check_memory(nbytes, what)


def check_octaves(octaves, lacunarity, gain):
    """``octaves`` an int in [1, 10000], ``lacunarity`` > 1, ``gain`` > 0 (as fractal sums take them)."""
    return (check_int("octaves", octaves, lo=1, hi=10_000), check_real("lacunarity", lacunarity, lo=1.0, lo_open=True),
            check_real("gain", gain, lo=0.0, lo_open=True))


def octave_periods(period, octaves, lacunarity, table_size, hash):
    """The lattice period of each octave of a tileable octave sum: ``(octaves, dim)`` int64, ``period * L**o``.

    Octave ``o`` runs at ``lacunarity**o`` times the base frequency; with the
    base period it would repeat ``lacunarity**o`` times inside the tile.
    Scaling its lattice period by the same factor keeps the tile (``period /
    frequency`` input units) its only period, which needs a whole-number
    lacunarity. The table hash repeats every ``table_size`` cells whatever
    the period, and the integer hash's words are 32-bit, so the finest
    octave's period is bounded by those.
    """
    if lacunarity != math.floor(lacunarity):
        raise ValueError(f"lacunarity must be a whole number (2, 3, ...) for an octave sum of a tileable noise "
                         f"(period={period.tolist()}): octave o has lattice period period * lacunarity**o, "
                         f"got lacunarity={lacunarity:g}")
    factor = int(lacunarity) ** (octaves - 1)
    finest = [int(p) * factor for p in period]
    top, why = ((table_size, f"table_size={table_size} (the table hash repeats every table_size cells); "
                             "use a larger table_size or hash='integer'")
                if hash == "table" else (int(PERIOD_MAX), "2**32 (the integer hash's lattice words are 32-bit)"))
    if max(finest) > top:
        raise ValueError(f"period * lacunarity**(octaves-1) = {finest} cells for the finest of octaves={octaves} "
                         f"(period={period.tolist()}, lacunarity={lacunarity:g}) exceeds {why}, or use fewer octaves")
    return np.array([[int(p) * int(lacunarity) ** o for p in period] for o in range(octaves)], dtype=np.int64)


def total_gain(octaves, gain):
    """The bound on ``sum_o gain**o`` over the octaves: the output's range in units of the amplitude."""
    return sum(gain ** o for o in range(octaves)) if gain <= 1 else octaves * gain ** (octaves - 1)


def check_amplitude(amplitude, dtype, what="amplitude"):
    """The output bound ``amplitude`` (times the octaves' gains) must fit the output dtype."""
    top = float(np.finfo(dtype).max)
    if not amplitude <= top:
        raise ValueError(f"{what} {amplitude:.3g} exceeds the range of {np.dtype(dtype).name} ({top:.3g}): "
                         "the output would overflow; use dtype=float64 or a smaller amplitude")


def check_arithmetic(arithmetic, noise, dtype):
    """Whether ``arithmetic`` asks for the float32 kernels, refusing what they do not do (never a fallback)."""
    if not isinstance(arithmetic, str) or arithmetic not in ARITHMETICS:
        raise ValueError(f"arithmetic must be one of {ARITHMETICS}, got {arithmetic!r}")
    if arithmetic == "float64":
        return False
    asked = [what for what, bad in ((f"hash={noise.hash!r}", noise.hash != "integer"),
                                    (f"dim_in={noise.dim_in}", noise.dim_in > 3),
                                    ("a period", bool((noise.period != PERIOD_MAX).any())),
                                    (f"dtype={dtype!r}", dtype is not None and float_dtype(dtype) != np.float32))
             if bad]
    if asked:
        raise ValueError(f"arithmetic='float32' supports integer-hash values in 1-3-D without a period, output "
                         f"float32 (dtype None or float32); got {', '.join(asked)}: use arithmetic='float64'")
    return True


def check_reach(flat, freqs, phase, name):
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


def check_window(window, shape, dim):
    """The (lo, hi) sample range per axis of ``window`` (checked against ``shape``), or the whole grid."""
    if window is None:
        return [(0, s) for s in shape]
    win = np.asarray(window, dtype=object)
    if win.shape != (dim, 2):
        raise ValueError(f"window must be one (lo, hi) index pair per axis, got {window!r}")
    sl = []
    for a, (lo, hi) in enumerate(win):
        lo = check_int(f"window[{a}][0]", lo, lo=0, hi=shape[a])
        hi = check_int(f"window[{a}][1]", hi, lo=lo, hi=shape[a])
        sl.append((lo, hi))
    return sl


def check_differentiable(kernel):
    """Derivatives need a kernel with a continuous first derivative."""
    if kernel.continuity < 1:
        smooth = ", ".join(name for name, kk in KERNELS.items() if kk.continuity >= 1)
        raise ValueError(f"kernel {kernel.name!r} has no continuous first derivative (its noise is "
                         f"{'discontinuous' if kernel.continuity < 0 else 'only C0: creased at every lattice line'}); "
                         f"derivatives need a C1 kernel: kernel must be one of {smooth}")


def check_scalar(dim_out, what):
    """``gradient`` and ``gradient_grid`` are for one-component noise."""
    if dim_out != 1:
        raise ValueError(f"{what} is for scalar noise (dim_out=1), this noise has dim_out={dim_out}; "
                         f"use jacobian{'_grid' if 'grid' in what else ''} for vector noise")


def jac_bound(freqs, amps):
    """Sum over octaves of |amplitude scale| x the largest frequency: the derivative's scale."""
    freqs, amps = np.abs(np.asarray(freqs, dtype=np.float64)), np.abs(np.asarray(amps, dtype=np.float64)).ravel()
    with np.errstate(over="ignore"):
        if amps.size == freqs.shape[0]:
            return float(np.sum(amps * freqs.max(axis=1)))
        return float(amps.max() * freqs.max() * freqs.shape[0])


def check_jac_finite(out, where, bound):
    """Derivatives scale with amplitude * frequency (* (gain * lacunarity)**octave): refuse an overflowed one.

    The derivative is at most ``bound`` (:func:`jac_bound`) times a constant of
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
