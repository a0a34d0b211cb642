"""Measurement helpers of the laboratory: interleaved timing against a floor, peak memory, machine, fits.

Timing rule (DEVELOPERS.md): every case is timed in the same process as its
floor, round by round (floor, case, floor, case, ...), and reported as the
median of at least 5 repeats together with the median of the per-round ratios
to the floor; ratios hold when a shared machine's speed drifts, absolute
seconds do not.

Memory: the peak of :mod:`tracemalloc` during one call, which sees every numpy
allocation (numpy reports to tracemalloc) but not scratch that C/C++
libraries allocate themselves (pocketfft's work buffers, numba's stack).
"""
from __future__ import annotations

import datetime
import gc
import os
import platform
import time
import tracemalloc

import numpy as np

from .._validate import check_int

__all__ = ["time_against_floor", "peak_memory", "peak_rss", "machine_info", "fit_exponent", "fit_nlogn",
           "fft_floor", "write_floor"]


def fft_floor(shape, dtype=np.float32):
    """The spectral floor: a bare ``scipy.fft.irfftn`` producing a real array of ``shape`` and ``dtype``."""
    import scipy.fft

    shape = tuple(int(s) for s in shape)
    cdt = np.complex64 if np.dtype(dtype) == np.float32 else np.complex128
    half = shape[:-1] + (shape[-1] // 2 + 1,)
    rng = np.random.default_rng(0)
    spec = (rng.standard_normal(half) + 1j * rng.standard_normal(half)).astype(cdt)

    def floor():
        return scipy.fft.irfftn(spec, s=shape)

    return floor


def write_floor(shape, dtype=np.float64):
    """The lattice floor: allocating and writing an output array of ``shape`` and ``dtype``."""
    shape = tuple(int(s) for s in shape)

    def floor():
        out = np.empty(shape, dtype=dtype)
        out.fill(1.0)
        return out

    return floor


def time_against_floor(cases, floor, repeats=5, warmup=1):
    """Time each case and the floor in interleaved rounds.

    Parameters
    ----------
    cases : dict name -> callable
    floor : callable
    repeats : int, >= 1 (the rules ask for >= 5)
    warmup : int
        Untimed calls first (numba compilation, FFT plans, page faults).

    Returns
    -------
    dict name -> {"median_s", "ratio" (median of per-round time/floor), "times"}; the floor under ``"floor"``.

    Examples
    --------
    >>> r = time_against_floor({"sum": lambda: np.ones(1000).sum()}, lambda: np.ones(1000), repeats=5)
    >>> sorted(r), len(r["sum"]["times"])
    (['floor', 'sum'], 5)
    """
    repeats = check_int("repeats", repeats, lo=1)
    for _ in range(warmup):
        floor()
        for fn in cases.values():
            fn()
    times = {name: [] for name in cases}
    ftimes = []
    ratios = {name: [] for name in cases}
    for _ in range(repeats):
        gc.collect()
        t0 = time.perf_counter()
        r = floor()
        tf = time.perf_counter() - t0
        del r
        ftimes.append(tf)
        for name, fn in cases.items():
            gc.collect()
            t0 = time.perf_counter()
            r = fn()
            t = time.perf_counter() - t0
            del r
            times[name].append(t)
            ratios[name].append(t / tf if tf > 0 else float("nan"))
    out = {name: {"median_s": float(np.median(times[name])), "ratio": float(np.median(ratios[name])),
                  "times": times[name]} for name in cases}
    out["floor"] = {"median_s": float(np.median(ftimes)), "ratio": 1.0, "times": ftimes}
    return out


def peak_memory(fn):
    """Peak traced allocation (bytes) during one call of ``fn`` (see the module docstring)."""
    gc.collect()
    tracemalloc.start()
    try:
        r = fn()
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    del r
    return int(peak)


_RSS_SNIPPET = """
import json, sys
{setup}
def _kb(key):
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith(key + ":"):
                return int(line.split()[1])
    return 0
_warm = ({call})  # compile and import everything first
del _warm
try:
    with open("/proc/self/clear_refs", "w") as fh:
        fh.write("5")  # reset the high-water mark to the current RSS
    _reset = True
except OSError:
    _reset = False
_base = _kb("VmRSS")
_out = ({call})
print(json.dumps({{"rss_peak_mib": (_kb("VmHWM") - _base) / 1024, "hwm_reset": _reset}}))
"""


def peak_rss(setup, call, *, timeout=600):
    """Peak resident memory (MiB) of one ``call`` above the process's baseline, in a fresh subprocess.

    Unlike :func:`peak_memory` it sees every allocation (the FFT library's and
    numba's scratch included). ``setup`` is Python source run first (imports),
    ``call`` an expression; it is evaluated once untraced (warm-up), then the
    high-water mark is reset (``/proc/self/clear_refs``, Linux) and it is
    evaluated again. Returns ``None`` where the reset is not allowed.
    """
    import json
    import subprocess
    import sys

    code = _RSS_SNIPPET.format(setup=setup, call=call)
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=timeout)
    if proc.returncode != 0:
        raise RuntimeError(f"peak_rss failed: {proc.stderr.strip().splitlines()[-1:]}")
    r = json.loads(proc.stdout.strip().splitlines()[-1])
    return r["rss_peak_mib"] if r["hwm_reset"] else None


def _cpu_model():
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def machine_info():
    """Date (UTC), CPU model, cores, memory, OS and the versions that matter, as a dict of strings."""
    import numba
    import scipy

    from .. import __version__

    mem = "unknown"
    try:
        with open("/proc/meminfo") as fh:
            for line in fh:
                if line.startswith("MemTotal:"):
                    mem = f"{int(line.split()[1]) / 2**20:.1f} GiB"
                    break
    except OSError:
        pass
    return {
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "cpu": _cpu_model(),
        "cores": str(os.cpu_count()),
        "memory": mem,
        "os": platform.platform(),
        "python": platform.python_version(),
        "noiselab": __version__,
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "numba": numba.__version__,
    }


def fit_exponent(sizes, values):
    """Least-squares slope of ``log(values)`` against ``log(sizes)``: ``values ~ sizes**k``; returns ``k``.

    Examples
    --------
    >>> round(fit_exponent([1e3, 1e4, 1e5], [2e-3, 2e-2, 2e-1]), 6)
    1.0
    """
    x = np.log(np.asarray(sizes, dtype=float))
    y = np.log(np.asarray(values, dtype=float))
    if x.size < 2:
        raise ValueError("fit_exponent needs at least two sizes")
    return float(np.polyfit(x, y, 1)[0])


def fit_nlogn(sizes, values):
    """Exponent of ``values / log2(sizes)`` against ``sizes``: 1.0 for a clean ``N log N`` law."""
    n = np.asarray(sizes, dtype=float)
    return fit_exponent(n, np.asarray(values, dtype=float) / np.log2(n))
