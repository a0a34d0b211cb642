"""Argument checks shared by every public function.

Every public entry point of noiselab validates its input with these helpers so
that bad input fails early with a message that names the parameter and the
allowed range, instead of producing a silently wrong array.
"""
from __future__ import annotations

import math
import numbers
import os

import numpy as np

__all__ = [
    "as_generator",
    "check_finite_array",
    "check_int",
    "check_real",
    "check_shape",
    "check_memory",
    "available_memory",
    "float_dtype",
]


def as_generator(seed) -> np.random.Generator:
    """Return a ``numpy.random.Generator`` for ``seed``.

    ``seed`` may be a non-negative int (the same int always gives the same
    stream, across processes and platforms: PCG64 via ``default_rng``) or an
    existing ``Generator`` (used as is, so a caller can thread one stream
    through several calls). ``None`` draws fresh OS entropy and is therefore
    not repeatable; it is accepted only because numpy accepts it.
    """
    if isinstance(seed, np.random.Generator):
        return seed
    if seed is None:
        return np.random.default_rng()
    if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, numbers.Integral):
        raise TypeError(
            f"seed must be a non-negative int or a numpy.random.Generator, got {type(seed).__name__}"
        )
    if seed < 0:
        raise ValueError(f"seed must be a non-negative int, got {seed}")
    return np.random.default_rng(int(seed))


def check_real(name, value, *, lo=None, hi=None, lo_open=False, hi_open=False) -> float:
    """Check that ``value`` is a finite real number inside ``[lo, hi]``.

    ``lo_open``/``hi_open`` make that end of the interval exclusive. Returns the
    value as a Python float. The error message names the parameter and the
    allowed range.
    """
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a real number, got {type(value).__name__}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value}")
    bad_lo = lo is not None and (value <= lo if lo_open else value < lo)
    bad_hi = hi is not None and (value >= hi if hi_open else value > hi)
    if bad_lo or bad_hi:
        left = "-inf" if lo is None else f"{lo:g}"
        right = "inf" if hi is None else f"{hi:g}"
        lb = "(" if (lo_open or lo is None) else "["
        rb = ")" if (hi_open or hi is None) else "]"
        raise ValueError(f"{name} must be in {lb}{left}, {right}{rb}, got {value:g}")
    return value


def check_int(name, value, *, lo=None, hi=None) -> int:
    """Check that ``value`` is an integer inside ``[lo, hi]`` and return it."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name} must be an int, got {type(value).__name__}")
    value = int(value)
    if (lo is not None and value < lo) or (hi is not None and value > hi):
        left = "-inf" if lo is None else str(lo)
        right = "inf" if hi is None else str(hi)
        raise ValueError(f"{name} must be an int in [{left}, {right}], got {value}")
    return value


def check_shape(name, shape, *, ndim=None, min_size=1) -> tuple[int, ...]:
    """Check a shape tuple: ``ndim`` entries (an int or a set of allowed counts), each >= ``min_size``."""
    if isinstance(shape, numbers.Integral):
        shape = (shape,)
    try:
        shape = tuple(shape)
    except TypeError:
        raise TypeError(f"{name} must be a tuple of ints, got {type(shape).__name__}") from None
    if ndim is not None:
        allowed = (ndim,) if isinstance(ndim, int) else tuple(ndim)
        if len(shape) not in allowed:
            raise ValueError(f"{name} must have {' or '.join(map(str, allowed))} entries, got {len(shape)}: {shape}")
    return tuple(check_int(f"{name}[{i}]", s, lo=min_size) for i, s in enumerate(shape))


def check_finite_array(name, array) -> np.ndarray:
    """Return ``array`` as an ndarray; raise if it holds NaN or inf (naming how many)."""
    array = np.asarray(array)
    if array.dtype.kind not in "biuf":
        raise TypeError(f"{name} must be a real numeric array, got dtype {array.dtype}")
    if array.dtype.kind == "f":
        bad = ~np.isfinite(array)
        if bad.any():
            raise ValueError(f"{name} must be finite; it holds {int(bad.sum())} NaN or inf value(s)")
    return array


def float_dtype(dtype) -> np.dtype:
    """Check that ``dtype`` is float32 or float64 and return it as an ``np.dtype``."""
    try:
        dt = np.dtype(dtype)
    except TypeError:
        raise TypeError(f"dtype must be float32 or float64, got {dtype!r}") from None
    if dt not in (np.dtype(np.float32), np.dtype(np.float64)):
        raise ValueError(f"dtype must be float32 or float64, got {dt}")
    return dt


def available_memory() -> int:
    """Bytes of memory this process can still allocate (MemAvailable, or a cgroup limit if lower)."""
    avail = None
    try:
        with open("/proc/meminfo") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    avail = int(line.split()[1]) * 1024
                    break
    except OSError:
        pass
    for path in ("/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"):
        try:
            with open(path) as fh:
                raw = fh.read().strip()
            if raw != "max":
                limit = int(raw)
                used = 0
                for upath in ("/sys/fs/cgroup/memory.current", "/sys/fs/cgroup/memory/memory.usage_in_bytes"):
                    if os.path.exists(upath):
                        with open(upath) as fh:
                            used = int(fh.read().strip())
                        break
                room = max(limit - used, 0)
                avail = room if avail is None else min(avail, room)
        except (OSError, ValueError):
            continue
    return avail if avail is not None else 1 << 62


def check_memory(nbytes: int, what: str) -> None:
    """Refuse an allocation of ``nbytes`` (with a clear message) when it cannot fit.

    Called before large allocations with an estimate of the *peak* the
    operation needs, so that an impossible request fails at once instead of
    swapping or being killed half-way through.
    """
    avail = available_memory()
    if nbytes > avail:
        raise MemoryError(
            f"{what} needs about {nbytes / 2**30:.2f} GiB but only {avail / 2**30:.2f} GiB is available; "
            "use a smaller size, float32, or a tiled/chunked path"
        )
