"""Argument checks shared by every public function.

Every public entry point of noiselab validates its input with these helpers so
that bad input fails early with a message that names the parameter and the
allowed range, instead of producing a silently wrong array.
"""
from __future__ import annotations

import math
import numbers
import os
import warnings

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
    "check_axes",
    "check_real_array",
    "check_real_sequence",
    "check_real_vector",
    "as_array",
    "check_band",
]

# numpy cannot index an array of more than 2**63 - 1 bytes; shapes past this many
# elements are refused by check_shape before anything is sized from them
MAX_ELEMENTS = 1 << 60


def as_generator(rng, name="rng") -> np.random.Generator:
    """Return a ``numpy.random.Generator`` for ``rng``, as SPEC 7 has it.

    ``rng`` may be a non-negative int (the same int always gives the same
    stream, across processes and platforms: PCG64 via ``default_rng``), an
    existing ``Generator`` (used as is, so a caller can thread one stream
    through several calls) or ``None`` (fresh OS entropy: not repeatable).
    ``name`` is the parameter's name in the error messages.
    """
    if isinstance(rng, np.random.Generator):
        return rng
    if rng is None:
        return np.random.default_rng()
    if isinstance(rng, (bool, np.bool_)) or not isinstance(rng, numbers.Integral):
        raise TypeError(
            f"{name} must be a non-negative int, a numpy.random.Generator or None, got {type(rng).__name__}"
        )
    if rng < 0:
        raise ValueError(f"{name} must be a non-negative int, got {rng}")
    return np.random.default_rng(int(rng))


def check_real(name, value, *, lo=None, hi=None, lo_open=False, hi_open=False) -> float:
    """Check that ``value`` is a finite real number inside ``[lo, hi]``.

    ``lo_open``/``hi_open`` make that end of the interval exclusive. Returns the
    value as a Python float. The error message names the parameter and the
    allowed range.
    """
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a real number, got {type(value).__name__}")
    try:
        value = float(value)
    except OverflowError:  # a Python int past float64's range (10**400)
        raise ValueError(f"{name} must be finite (within float64's range, |x| < 1.8e308), got an int of "
                         f"{len(str(abs(int(value))))} digits") from None
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
    """Check a shape tuple: ``ndim`` entries (an int or a set of allowed counts), each >= ``min_size``.

    Without ``ndim`` at least one entry is required. The number of elements
    must stay below ``2**60`` (numpy's arrays hold at most ``2**63 - 1``
    bytes): larger shapes are a ``ValueError`` naming ``name``, before any
    size computed from them can overflow.
    """
    if isinstance(shape, (str, bytes)):
        raise TypeError(f"{name} must be a tuple of ints, got {type(shape).__name__}")
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
    elif not shape:
        raise ValueError(f"{name} must have at least one entry, got ()")
    shape = tuple(check_int(f"{name}[{i}]", s, lo=min_size) for i, s in enumerate(shape))
    if math.prod(shape) >= MAX_ELEMENTS or any(s >= MAX_ELEMENTS for s in shape):
        raise ValueError(f"{name} {shape} has more elements than an array can hold (at most 2**60 in noiselab)")
    return shape


def check_axes(name, axes, ndim) -> tuple[int, ...]:
    """Check distinct integer axes of an ``ndim``-D array (negative ones count from the end); return them sorted, >= 0."""
    if isinstance(axes, numbers.Integral) and not isinstance(axes, (bool, np.bool_)):
        axes = (axes,)
    if isinstance(axes, (str, bytes)) or not hasattr(axes, "__iter__"):
        raise TypeError(f"{name} must be a tuple of ints, got {type(axes).__name__}")
    out = []
    for i, a in enumerate(axes):
        a = check_int(f"{name}[{i}]", a, lo=-ndim, hi=ndim - 1)
        out.append(a % ndim)
    if not out or len(set(out)) != len(out):
        raise ValueError(f"{name} must be distinct axes in [-{ndim}, {ndim - 1}], got {tuple(axes)!r}")
    return tuple(sorted(out))


def check_real_sequence(name, value, *, length=None, lo=None, hi=None, lo_open=False, hi_open=False) -> tuple:
    """Check a sequence of finite reals (``length`` of them, if given), each in ``[lo, hi]``; return floats."""
    if isinstance(value, (str, bytes, set, frozenset, dict)) or not hasattr(value, "__len__"):
        what = f"{length} real numbers" if length else "real numbers"
        raise TypeError(f"{name} must be a sequence of {what}, got {type(value).__name__}")
    if isinstance(value, np.ndarray) and value.ndim != 1:
        raise ValueError(f"{name} must be a flat sequence of real numbers, got an array of shape {value.shape}")
    if length is not None and len(value) != length:
        raise ValueError(f"{name} must hold {length} real numbers, got {len(value)}: {value!r}")
    return tuple(check_real(f"{name}[{i}]", v, lo=lo, hi=hi, lo_open=lo_open, hi_open=hi_open)
                 for i, v in enumerate(value))


def check_band(name, band, fmax, *, lo_open=False, allow_none=False, width=None):
    """Check a pass band ``(lo, hi)`` in cycles/frame, ``0 <= lo < hi <= fmax``; return it as two floats.

    The one band validator of noiselab: the generators (``spectral_noise``,
    ``snow``, ``flake_speeds``) and the analysers all check their bands here,
    so a band means the same thing and fails with the same words everywhere.

    Parameters
    ----------
    name : str
        The parameter's name in the messages (``"band"``, ``"bands[2]"``).
    band : pair of real
        ``(lo, hi)`` in cycles/frame (cycles per frame width), inclusive.
    fmax : float
        The largest allowed ``hi`` in cycles/frame: the Nyquist frequency
        ``width / 2`` of a generator's band, or the Nyquist radius an
        analyser accepts (up to ``sqrt(d)`` times it, in the corners).
    lo_open : bool
        ``lo`` must be above 0 (the analysers: a band's log-spaced bins need
        ``lo > 0``); otherwise ``lo = 0`` is allowed.
    allow_none : bool
        ``band=None`` returns None instead of raising.
    width : int, optional
        Frame width in pixels: the Nyquist message then says the limit in
        cycles/pixel too.

    Examples
    --------
    >>> check_band("band", (4, 32), 32)
    (4.0, 32.0)
    >>> check_band("band", (4, 40), 32, width=64)
    Traceback (most recent call last):
    ...
    ValueError: band[1] = 40 cycles/frame is past the Nyquist frequency 32 cycles/frame (0.5 cycles/pixel for frames 64 pixels wide); allowed: 0 <= lo < hi <= 32
    """
    if band is None:
        if allow_none:
            return None
        raise ValueError(f"{name} must be a (lo, hi) pair in cycles/frame, got None")
    if isinstance(band, (str, bytes, set, frozenset, dict)):
        raise TypeError(f"{name} must be an ordered (lo, hi) pair in cycles/frame, got a {type(band).__name__}")
    if not hasattr(band, "__len__") or len(band) != 2:
        raise ValueError(f"{name} must be a (lo, hi) pair in cycles/frame, got {band!r}")
    lo = check_real(f"{name}[0] (cycles/frame)", band[0], lo=0.0, lo_open=lo_open)
    hi = check_real(f"{name}[1] (cycles/frame)", band[1], lo=0.0, lo_open=lo_open)
    if hi > fmax * (1 + 1e-12):
        px = f" (0.5 cycles/pixel for frames {width} pixels wide)" if width is not None else ""
        raise ValueError(f"{name}[1] = {hi:g} cycles/frame is past the Nyquist frequency {fmax:g} cycles/frame{px}; "
                         f"allowed: 0 {'<' if lo_open else '<='} lo < hi <= {fmax:g}")
    if not lo < hi:
        raise ValueError(f"{name} is empty: need lo < hi, got lo={lo:g}, hi={hi:g} cycles/frame")
    return lo, hi


def check_real_vector(name, value, size, *, lo=None, hi=None, lo_open=False) -> np.ndarray:
    """A number (broadcast) or a sequence of ``size`` finite reals in ``[lo, hi]``, as float64 ``(size,)``."""
    if isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_)) or (
            isinstance(value, np.ndarray) and value.ndim == 0):
        v = check_real(name, value.item() if isinstance(value, np.ndarray) else value, lo=lo, hi=hi, lo_open=lo_open)
        return np.full(size, v)
    if isinstance(value, np.ndarray) and value.ndim != 1:
        raise ValueError(f"{name} must be a number or a vector of {size} numbers, got an array of shape {value.shape}")
    if isinstance(value, (str, bytes, set, frozenset, dict)) or not hasattr(value, "__len__"):
        raise TypeError(f"{name} must be a number or a vector of {size} numbers, got {type(value).__name__}")
    if len(value) != size:
        raise ValueError(f"{name} must be a number or a vector of {size} numbers, got {len(value)}: {value!r}")
    return np.array([check_real(name, v, lo=lo, hi=hi, lo_open=lo_open) for v in value], dtype=np.float64)


def check_real_array(name, array, *, ndim=None, allow_empty=True) -> np.ndarray:
    """Return ``array`` as a finite real ndarray (bool/int/float), ``ndim``-D if given (an int or allowed counts)."""
    arr = check_finite_array(name, array)
    if ndim is not None:
        allowed = (ndim,) if isinstance(ndim, int) else tuple(ndim)
        if arr.ndim not in allowed:
            raise ValueError(f"{name} must be {' or '.join(f'{d}-D' for d in allowed)}, got shape {arr.shape}")
    if not allow_empty and arr.size == 0:
        raise ValueError(f"{name} is empty (shape {arr.shape})")
    return arr


def as_array(name, value) -> np.ndarray:
    """``np.asarray(value)``, with numpy's conversion errors (ragged lists, huge ints) turned into ones naming ``name``."""
    if isinstance(value, np.ndarray):
        return value
    if isinstance(value, (str, bytes, dict, set, frozenset)) or value is None:
        raise TypeError(f"{name} must be a real numeric array, got {type(value).__name__}")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error", np.exceptions.VisibleDeprecationWarning)
            return np.asarray(value)
    except (ValueError, TypeError, OverflowError, np.exceptions.VisibleDeprecationWarning) as exc:
        raise TypeError(f"{name} must be a real numeric array (a regular nest of numbers): {exc}") from None


def check_finite_array(name, array) -> np.ndarray:
    """Return ``array`` as an ndarray; raise if it holds NaN or inf (naming how many)."""
    array = as_array(name, array)
    if array.dtype.kind not in "biuf":
        kind = "complex" if array.dtype.kind == "c" else "real numeric"
        raise TypeError(f"{name} must be a real numeric array, got dtype {array.dtype}"
                        + (" (pass its real part or magnitude)" if kind == "complex" else ""))
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


def _meminfo_available() -> int | None:
    try:
        with open("/proc/meminfo") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return None


def _read_int(path):
    try:
        with open(path) as fh:
            raw = fh.read().strip()
    except OSError:
        return None
    if raw == "max":
        return None
    try:
        return int(raw)
    except ValueError:
        return None


def _cgroup_room(cgroup_text: str, mount: str = "/sys/fs/cgroup") -> int | None:
    """Bytes left under this process's cgroup memory limits (v2 ``memory.max``, v1 ``memory.limit_in_bytes``).

    ``cgroup_text`` is the content of ``/proc/self/cgroup``. Every level from
    the process's own cgroup up to the root is checked (a parent's limit binds
    its children), both at the path the kernel names and at the mount's root
    (inside a container's cgroup namespace the own cgroup is the root);
    returns the least ``limit - usage``, or None when no limit is set.
    """
    v2, v1 = None, None
    for line in cgroup_text.splitlines():
        parts = line.split(":", 2)
        if len(parts) != 3:
            continue
        hid, controllers, path = parts
        if hid == "0" and controllers == "":
            v2 = path
        elif "memory" in controllers.split(","):
            v1 = path
    candidates = []
    for base, path, limit_name, usage_name in (
            (mount, v2, "memory.max", "memory.current"),
            (os.path.join(mount, "unified"), v2, "memory.max", "memory.current"),
            (os.path.join(mount, "memory"), v1, "memory.limit_in_bytes", "memory.usage_in_bytes")):
        if path is None:
            continue
        rel = path.strip("/")
        levels = [rel]
        while rel:
            rel = os.path.dirname(rel)
            levels.append(rel)
        for level in levels:
            candidates.append((os.path.join(base, level, limit_name), os.path.join(base, level, usage_name)))
    room = None
    for limit_path, usage_path in dict.fromkeys(candidates):
        limit = _read_int(limit_path)
        if limit is None or limit >= (1 << 62):  # v1 writes "no limit" as a huge number
            continue
        used = _read_int(usage_path) or 0
        left = max(limit - used, 0)
        room = left if room is None else min(room, left)
    return room


def _address_space_room() -> int | None:
    """Bytes of address space left under ``RLIMIT_AS`` (``ulimit -v``), or None when unlimited."""
    try:
        import resource
    except ImportError:  # not on POSIX
        return None
    soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    if soft == resource.RLIM_INFINITY or soft < 0:
        return None
    used = 0
    try:
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith("VmSize:"):
                    used = int(line.split()[1]) * 1024
                    break
    except (OSError, ValueError, IndexError):
        pass
    return max(soft - used, 0)


def memory_limits() -> dict:
    """What bounds an allocation now, in bytes: ``{"free RAM": ..., "cgroup limit": ..., "address-space limit": ...}``.

    Only the limits that apply are present: ``MemAvailable`` from
    ``/proc/meminfo``, the room under the cgroup (v2 or v1) memory limit of
    this process and its parents, and the room under ``RLIMIT_AS``.
    """
    limits = {}
    ram = _meminfo_available()
    if ram is not None:
        limits["free RAM"] = ram
    try:
        with open("/proc/self/cgroup") as fh:
            cg = _cgroup_room(fh.read())
    except OSError:
        cg = None
    if cg is not None:
        limits["cgroup limit"] = cg
    aspace = _address_space_room()
    if aspace is not None:
        limits["address-space limit"] = aspace
    return limits


def available_memory() -> int:
    """Bytes of memory this process can still allocate: the least of free RAM, the cgroup room and the RLIMIT_AS room."""
    limits = memory_limits()
    return min(limits.values()) if limits else 1 << 62


def check_memory(nbytes: int, what: str) -> None:
    """Refuse an allocation of ``nbytes`` (with a clear message) when it cannot fit.

    Called before large allocations with an estimate of the *peak* the
    operation needs, so that an impossible request fails at once instead of
    swapping or being killed half-way through. The bound is the least of the
    free RAM, the room under this process's cgroup memory limit and the room
    under its address-space limit (``ulimit -v``); the message says which.
    """
    nbytes = float(nbytes)
    if nbytes <= (1 << 20):  # a MiB always fits; skip reading /proc
        return
    limits = memory_limits()
    if not limits:
        return
    which = min(limits, key=limits.get)
    avail = limits[which]
    if nbytes > avail:
        raise MemoryError(
            f"{what} needs about {nbytes / 2**30:.3g} GiB but only {avail / 2**30:.2f} GiB is available "
            f"({which}); use a smaller size, float32, or a tiled/chunked path"
        )
