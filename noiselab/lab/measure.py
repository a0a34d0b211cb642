"""The one timing harness of the project, and the laboratory's other measurements (peak memory, machine, fits).

Timing rule (CONTRIBUTING.md): every candidate is timed in the same process as
its reference (a floor, a peer, the previous version), in interleaved rounds
(a, b, c, a, b, c, ...), after an untimed warm-up, and reported as the median
of at least 5 rounds together with the median of the per-round ratios; ratios
of two calls made seconds apart hold when a shared machine's speed drifts,
absolute seconds do not. :func:`interleaved` runs the rounds over a dict of
candidates and returns :class:`Timings`; :func:`time_against_floor` is the
floor-first form the laboratory's experiments use; :func:`run_info` and
:func:`header_lines` give the run header every report starts with, and
:func:`markdown_table` the table. Every ``benchmarks/bench_*.py`` script times
through this module.

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

from .._core import check_int

__all__ = ["interleaved", "Timings", "Laps", "Stopwatch", "run_info", "header_lines", "load_average",
           "markdown_table", "package_version", "time_against_floor", "peak_memory", "peak_rss", "machine_info",
           "fit_exponent", "fit_nlogn", "fft_floor", "write_floor"]

_ORDERS = ("fixed", "rotate", "alternate")


class Laps(dict):
    """Durations (seconds) of the stages of one call, returned by a candidate to have them recorded too.

    A candidate of :func:`interleaved` that returns a ``Laps`` (usually
    :attr:`Stopwatch.laps`) adds one series per stage to the
    :class:`Timings`, named ``stage`` (``prefix + stage`` with a
    ``prefix`` argument), measured in the same round as everything else,
    so a stage's per-round ratio to a floor is as robust as a whole call's.
    """


class Stopwatch:
    """Times the stages of one call: ``sw("name", fn)`` calls ``fn()``, records its duration, returns its result.

    Parameters
    ----------
    timer : callable, optional
        Clock returning seconds (default :func:`time.perf_counter`).

    Examples
    --------
    >>> sw = Stopwatch()
    >>> sw("sum", lambda: sum(range(10)))
    45
    >>> sorted(sw.laps)
    ['sum']
    """

    def __init__(self, timer=None):
        self.timer = time.perf_counter if timer is None else timer
        self.laps = Laps()

    def __call__(self, name, fn):
        t0 = self.timer()
        out = fn()
        self.laps[name] = self.laps.get(name, 0.0) + (self.timer() - t0)
        return out


class Timings(dict):
    """The result of :func:`interleaved`: median seconds per candidate (the dict), and the rounds behind it.

    Attributes
    ----------
    raw : dict name -> ndarray
        Seconds of every timed round, in round order (warm-up excluded).
    calls : list of (round, name)
        The order the candidates were called in (warm-up rounds as round -1).
    units : dict name -> float
        Work done per call (points, voxels...), where given.
    repeats, warmup : int
    """

    def __init__(self, raw, *, units=None, calls=(), repeats=None, warmup=0):
        super().__init__({k: float(np.median(v)) for k, v in raw.items()})
        self.raw = {k: np.asarray(v, dtype=float) for k, v in raw.items()}
        self.units = dict(units or {})
        self.calls = list(calls)
        self.repeats = repeats if repeats is not None else (len(next(iter(self.raw.values()))) if raw else 0)
        self.warmup = warmup

    def median(self, name):
        """Median seconds of ``name`` over the rounds."""
        return self[name]

    def min(self, name):
        """Fastest round of ``name`` (seconds)."""
        return float(np.min(self.raw[name]))

    def ratios(self, num, den):
        """Per-round ``time(num) / time(den)``, each pair measured in the same round."""
        a, b = self.raw[num], self.raw[den]
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(b > 0, a / np.where(b > 0, b, 1.0), np.nan)

    def ratio(self, num, den):
        """Median over rounds of ``time(num) / time(den)`` measured in the same round.

        On a shared machine the load drifts between rounds; a ratio of two
        neighbouring calls cancels most of that drift, a ratio of medians
        does not. ``ratio(name, "floor")`` is the time of ``name`` in floor
        times; ``ratio("floor", name)`` its speed as a fraction of the
        floor's (1 = as fast as the floor).

        Examples
        --------
        >>> t = Timings({"a": [1.0, 4.0, 2.0], "b": [2.0, 2.0, 2.0]})
        >>> t.ratio("a", "b"), t.ratio("b", "a")
        (1.0, 1.0)
        """
        return float(np.median(self.ratios(num, den)))

    def rate(self, name, units=None):
        """Work units per second of ``name``: ``units / median seconds`` (``units`` default: the ones given)."""
        u = self.units.get(name) if units is None else units
        if u is None:
            raise ValueError(f"rate: no work units given for {name!r}; pass units= to interleaved or to rate")
        return float(u) / self[name]

    def table(self, ref=None, *, labels=None, unit_name="pts/s", digits=3):
        """The standard table: candidate, median s, min s, x ``ref`` (median per-round ratio), and the rate.

        Parameters
        ----------
        ref : str, optional
            Reference candidate for the ratio column ``time / time(ref)``.
        labels : dict name -> str, optional
            Row labels (default: the names).
        unit_name : str
            Header of the rate column, shown where units were given.
        digits : int
            Significant digits.

        Returns
        -------
        list of str
            Markdown lines (see :func:`markdown_table`).

        Examples
        --------
        >>> t = Timings({"floor": [1.0, 1.0, 1.0], "f": [2.0, 3.0, 2.0]}, units={"f": 10})
        >>> print("\\n".join(t.table("floor")))
        | candidate | median s | min s | x floor | pts/s |
        | --- | ---: | ---: | ---: | ---: |
        | floor | 1 | 1 | 1 |  |
        | f | 2 | 2 | 2 | 5 |
        """
        labels = labels or {}
        head = ["candidate", "median s", "min s"] + ([f"x {ref}"] if ref else []) + ([unit_name] if self.units else [])
        rows = []
        for k in self:
            row = [labels.get(k, str(k)), f"{self[k]:.{digits}g}", f"{self.min(k):.{digits}g}"]
            if ref:
                row.append(f"{self.ratio(k, ref):.{digits}g}")
            if self.units:
                row.append(f"{self.rate(k):.{digits}g}" if k in self.units else "")
            rows.append(row)
        return markdown_table(head, rows, align="l" + "r" * (len(head) - 1))


def _order(names, r, order):
    if order == "fixed":
        return list(names)
    if order == "alternate":
        return list(names) if r % 2 == 0 else list(names)[::-1]
    k = r % len(names) if names else 0
    return list(names[k:]) + list(names[:k])


def interleaved(candidates, *, repeats=5, warmup=1, order="rotate", units=None, timer=None, collect=True,
                round_arg=False, min_repeats=1):
    """Time a dict of candidates in interleaved rounds: every candidate once per round, ``repeats`` rounds.

    Parameters
    ----------
    candidates : dict name -> callable
        Called with no argument (with the round index if ``round_arg``). A
        candidate returning :class:`Laps` also records its stages.
    repeats : int, >= ``min_repeats``
        Timed rounds (the rules ask for >= 5).
    warmup : int, >= 0
        Untimed rounds first (numba compilation, FFT plans, page faults).
    order : {"rotate", "fixed", "alternate"}
        The order within a round: ``"rotate"`` starts round ``r`` at the
        ``r``-th candidate (none always follows the same neighbour, whose
        allocations and cache state favour or hurt it); ``"fixed"`` keeps
        the dict's order; ``"alternate"`` reverses it every other round.
    units : float or dict name -> float, optional
        Work units per call (points, voxels) for :meth:`Timings.rate`; one
        number applies to every candidate.
    timer : callable, optional
        Clock returning seconds (default :func:`time.perf_counter`); tests
        inject a fake one.
    collect : bool
        ``gc.collect()`` before each timed call (outside the timing).
    round_arg : bool
        Pass the round index (``-1`` in warm-up) to every candidate, e.g. as a seed.
    min_repeats : int
        Smallest ``repeats`` accepted (scripts that publish medians pass 5).

    Returns
    -------
    Timings
        Median seconds per candidate (and per recorded stage), with the
        per-round times for :meth:`Timings.ratio`.

    Raises
    ------
    ValueError
        ``repeats`` below ``min_repeats``, ``warmup`` negative, an unknown
        ``order``, no candidate, or a lap named like a candidate.

    Examples
    --------
    >>> t = interleaved({"floor": lambda: np.ones(1000), "sum": lambda: np.ones(1000).sum()}, repeats=5,
    ...                 units=1000)
    >>> sorted(t), len(t.raw["sum"]), t.ratio("sum", "floor") > 0
    (['floor', 'sum'], 5, True)
    """
    repeats = check_int("repeats", repeats, lo=max(1, int(min_repeats)))
    warmup = check_int("warmup", warmup, lo=0)
    if order not in _ORDERS:
        raise ValueError(f"order must be one of {_ORDERS}, got {order!r}")
    if not candidates:
        raise ValueError("candidates must name at least one callable")
    names = list(candidates)
    timer = time.perf_counter if timer is None else timer
    calls = []
    for _ in range(warmup):
        for k in names:
            calls.append((-1, k))
            candidates[k](-1) if round_arg else candidates[k]()
    raw = {k: [] for k in names}
    for r in range(repeats):
        for k in _order(names, r, order):
            fn = candidates[k]
            if collect:
                gc.collect()
            calls.append((r, k))
            t0 = timer()
            out = fn(r) if round_arg else fn()
            t = timer() - t0
            raw[k].append(t)
            if isinstance(out, Laps):
                for stage, s in out.items():
                    if stage in candidates:
                        raise ValueError(f"a lap of {k!r} is named {stage!r}, like a candidate; name laps apart")
                    raw.setdefault(stage, []).append(float(s))
            del out
    if units is not None and not isinstance(units, dict):
        units = {k: units for k in names}
    return Timings(raw, units=units, calls=calls, repeats=repeats, warmup=warmup)


def load_average():
    """The 1-minute load average (``nan`` where the OS has none)."""
    try:
        return float(os.getloadavg()[0])
    except (OSError, AttributeError):
        return float("nan")


def package_version(dist):
    """Installed version of distribution ``dist``, or ``"not installed"``."""
    import importlib.metadata as md

    try:
        return md.version(dist)
    except md.PackageNotFoundError:
        return "not installed"


def run_info(command, packages=(), *, now=None, load=None, shared=True):
    """The run header's facts: UTC date, command, machine, CPU model, cores, load at start, versions.

    Parameters
    ----------
    command : str
        The command line that regenerates the report.
    packages : iterable of str
        Distributions whose versions to record beside python, numpy and numba.
    now : datetime, optional
        The time to record (default: now, UTC).
    load : float, optional
        The load average to record (default: :func:`load_average` now).
    shared : bool
        Whether the machine is shared with other jobs (said in the header).

    Returns
    -------
    dict
        ``date``, ``command``, ``machine``, ``cpu``, ``cores``, ``load``,
        ``shared``, ``versions`` (dict name -> version).

    Examples
    --------
    >>> info = run_info("python3 bench.py", ["numpy"], load=0.5)
    >>> info["load"], "numba" in info["versions"]
    (0.5, True)
    """
    now = datetime.datetime.now(datetime.timezone.utc) if now is None else now
    versions = {"python": platform.python_version(), "numpy": np.__version__}
    for d in ("numba", *packages):
        if d not in versions:
            versions[d] = package_version(d)
    return {"date": now.strftime("%Y-%m-%d %H:%M UTC"), "command": command, "machine": platform.machine(),
            "cpu": _cpu_model(), "cores": os.cpu_count() or 1, "load": load_average() if load is None else float(load),
            "shared": bool(shared), "versions": versions}


def header_lines(info, *, timing=None):
    """The run header as Markdown bullet lines, from :func:`run_info` (and a sentence on the timing).

    Examples
    --------
    >>> info = run_info("python3 bench.py", load=1.0)
    >>> [line.split(":")[0] for line in header_lines(info)]
    ['- date', '- command', '- machine', '- versions']
    """
    shared = "shared with other jobs (read the ratios)" if info["shared"] else "not shared"
    lines = [f"- date: {info['date']}",
             f"- command: `{info['command']}`",
             (f"- machine: {info['machine']}, {info['cpu']}, {info['cores']} cores, {shared}; "
              f"load average (1 min) at start {info['load']:.1f}"),
             "- versions: " + ", ".join(f"{k} {v}" for k, v in info["versions"].items())]
    if timing:
        lines.append(f"- timing: {timing}")
    return lines


def markdown_table(header, rows, align=None):
    """A Markdown table as a list of lines.

    Parameters
    ----------
    header : sequence of str
    rows : iterable of sequences (cells are formatted with ``str``)
    align : str, optional
        One letter per column, ``l`` or ``r`` (default all ``---``).

    Examples
    --------
    >>> print("\\n".join(markdown_table(["a", "b"], [[1, 2]], align="lr")))
    | a | b |
    | --- | ---: |
    | 1 | 2 |
    """
    header = [str(h) for h in header]
    if align is not None and len(align) != len(header):
        raise ValueError(f"align must give one letter per column ({len(header)}), got {align!r}")
    sep = ["---:" if a == "r" else "---" for a in (align or "l" * len(header))]
    out = ["| " + " | ".join(header) + " |", "| " + " | ".join(sep) + " |"]
    for row in rows:
        row = [str(c) for c in row]
        if len(row) != len(header):
            raise ValueError(f"a row has {len(row)} cells, the header {len(header)}")
        out.append("| " + " | ".join(row) + " |")
    return out


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


def time_against_floor(cases, floor, repeats=5, warmup=1, *, timer=None, collect=True):
    """Time each case and the floor in interleaved rounds, the floor first in every round.

    The floor-first form of :func:`interleaved` the laboratory's experiments use.

    Parameters
    ----------
    cases : dict name -> callable
    floor : callable
    repeats : int, >= 1 (the rules ask for >= 5)
    warmup : int
        Untimed calls first (numba compilation, FFT plans, page faults).
    timer : callable, optional
        Clock (default :func:`time.perf_counter`).
    collect : bool
        ``gc.collect()`` before each timed call (outside the timing).

    Returns
    -------
    dict name -> {"median_s", "ratio" (median of per-round time/floor), "times"}; the floor under ``"floor"``.

    Examples
    --------
    >>> r = time_against_floor({"sum": lambda: np.ones(1000).sum()}, lambda: np.ones(1000), repeats=5)
    >>> sorted(r), len(r["sum"]["times"])
    (['floor', 'sum'], 5)
    """
    key = object()  # never collides with a case's name
    t = interleaved({key: floor, **cases}, repeats=repeats, warmup=warmup, order="fixed", timer=timer,
                    collect=collect)
    out = {name: {"median_s": t[name], "ratio": t.ratio(name, key), "times": [float(x) for x in t.raw[name]]} for name in cases}
    out["floor"] = {"median_s": t[key], "ratio": 1.0, "times": [float(x) for x in t.raw[key]]}
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
    """Date (UTC), CPU model, cores, load average at the call, memory, OS and the versions that matter, as a dict of strings."""
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
        "load (1 min) at start": f"{load_average():.1f}",
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
