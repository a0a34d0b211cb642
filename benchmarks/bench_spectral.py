"""Benchmark: ``noiselab.spectral_noise`` and ``synthesize`` against their floor, a bare ``scipy.fft.irfftn``.

Run from the repository root::

    python3 benchmarks/bench_spectral.py                      # writes benchmarks/bench_spectral.md
    python3 benchmarks/bench_spectral.py --before c3cdeef     # adds the version at that commit, side by side
    python3 benchmarks/bench_spectral.py --quick              # smaller, for a smoke test
    python3 benchmarks/bench_spectral.py --workers 1 2 4      # worker counts (default: 1 and every core)

The floor is ``scipy.fft.irfftn`` of a ready-made half spectrum producing the
same output (shape and dtype): the one transform any spectral synthesis must
do. Everything runs in one process, interleaved round by round (the floor and
each contender, for every case, in every round, in an order rotated from
round to round), and is reported as the median of the per-round ratios to
the floor, because the machine is shared.
Every case runs at each worker count with the same count on both sides
(``workers=`` of the floor's ``irfftn`` and of ``spectral_noise`` /
``synthesize``); the strong-scaling table gives, per case, the speed-up from
the first count to the others and the parallel fraction ``p`` it implies
(Amdahl: ``speedup = 1 / ((1 - p) + p / n)``). Peak memory is the ``tracemalloc`` peak of one call (numpy
arrays; numba's scratch and the FFT library's buffers are not traced),
given beside the output's own size.
"""
from __future__ import annotations

import argparse
import importlib.util
import os
import subprocess
import sys
import tempfile
import tracemalloc
from pathlib import Path

import numpy as np
import scipy
import scipy.fft

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


from noiselab.spectral import envelopes as E  # noqa: E402
from noiselab.lab.measure import Laps, Stopwatch, header_lines, interleaved, load_average, run_info  # noqa: E402
from noiselab.spectral import spectral_noise, synthesize  # noqa: E402


def _before_module(rev):
    """``noiselab/spectral/synthesis.py`` and its ``_kernels.py`` as they were at git revision ``rev``, imported."""
    tmp = Path(tempfile.mkdtemp())

    def load(name, relpath, subst):
        src = subprocess.run(["git", "show", f"{rev}:{relpath}"], cwd=ROOT, check=True,
                             capture_output=True, text=True).stdout
        for a, b in subst:
            src = src.replace(a, b)
        path = tmp / f"{name}.py"
        path.write_text(src)
        spec = importlib.util.spec_from_file_location(name, path)
        mod = importlib.util.module_from_spec(spec)
        sys.modules[name] = mod
        spec.loader.exec_module(mod)
        return mod

    load("spectral_kernels_before", "noiselab/spectral/_kernels.py", [])
    return load("spectral_before", "noiselab/spectral/synthesis.py", [
        ("from .._core", "from noiselab._core"),
        ("from .envelopes", "from noiselab.spectral.envelopes"),
        ("from .frequencies", "from noiselab.spectral.frequencies"),
        ("from .plan", "from noiselab.spectral.plan"),  # a revision with the shared plan: the current one's
        ("from . import _kernels", "import spectral_kernels_before as _kernels")])


def _half_spectrum(shape, dtype):
    rng = np.random.default_rng(0)
    h = shape[:-1] + (shape[-1] // 2 + 1,)
    S = np.empty(h, np.complex64 if dtype == np.float32 else np.complex128)
    S.real = rng.standard_normal(h, dtype=np.float32)
    S.imag = rng.standard_normal(h, dtype=np.float32)
    return S


def _cases(quick):
    n2, n3 = (256, 32) if quick else (1024, 128)
    out = []
    for dt in (np.float32, np.float64):
        out += [
            ((n2, n2), None, dt),
            ((n2, n2), (4, n2 // 16), dt),
            ((n3, n3, n3), None, dt),
            ((n3, n3, n3), (4, n3 // 2), dt),
            ((n3, n3, n3), (2, n3 // 8), dt),
        ]
    return out


def _label(shape, band, dt):
    b = "full band" if band is None else f"band ({band[0]:g}, {band[1]:g})"
    return f"{' x '.join(map(str, shape))} {b} {np.dtype(dt).name}"


def _synth_env(shape, band):
    n = shape[-1]
    lo, hi = (0.0, 0.5 * np.sqrt(len(shape)) + 1.0) if band is None else (band[0] / n, band[1] / n)
    return lambda *w: E.annulus(*w, band_cycles_per_sample=(lo, hi)) * E.power_law(*w, exponent=1.0)


def _peak(f):
    tracemalloc.start()
    tracemalloc.reset_peak()
    out = f()
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    del out
    return peak


def run(rounds, quick, before_rev, workers):
    before = _before_module(before_rev) if before_rev else None
    cases = _cases(quick)
    spectral_noise((8, 8), rng=0)  # numba warm-up (cached kernels load)
    synthesize((8, 8), lambda wy, wx: 1.0 + 0 * wy * wx, rng=0)
    contenders = {
        "spectral_noise": lambda shape, band, dt, r, w: spectral_noise(shape, band=band, rng=r, dtype=dt,
                                                                       workers=w),
        "synthesize": lambda shape, band, dt, r, w: synthesize(shape, _synth_env(shape, band), rng=r,
                                                               amplitude_distribution="rayleigh", dtype=dt, workers=w),
    }
    if before is not None:
        # the earlier version has no workers: it runs single-threaded (compare it at 1 worker)
        contenders["spectral_noise before"] = lambda shape, band, dt, r, w: before.spectral_noise(
            shape, band=band, rng=r, dtype=dt)
    floors = {c: _half_spectrum(c[0], c[2]) for c in cases}
    names = ["floor", *contenders]

    def call(c, w, k, r):
        shape, band, dt = c
        y = (scipy.fft.irfftn(floors[c], s=shape, workers=w) if k == "floor"
             else contenders[k](shape, band, dt, max(r, 0), w))
        assert y.dtype == dt and y.shape == shape
        return y

    # one interleaved run per case, over every (worker count, contender): one warm-up round, then each round
    # in an order rotated from the last, so that none always follows the same (memory-hungry) neighbour: the
    # allocator's and the caches' state favour whoever comes first
    timings = {c: interleaved({(w, k): (lambda r, c=c, w=w, k=k: call(c, w, k, r)) for w in workers for k in names},
                              repeats=rounds, round_arg=True) for c in cases}
    rows = []
    for c in cases:
        shape, band, dt = c
        peak = _peak(lambda: spectral_noise(shape, band=band, rng=0, dtype=dt)) / 2**20
        serial = serial_share(shape, band, dt, rounds)
        peak_floor = _peak(lambda: scipy.fft.irfftn(floors[c], s=shape)) / 2**20
        peak_before = (_peak(lambda: before.spectral_noise(shape, band=band, rng=0, dtype=dt)) / 2**20
                       if before is not None else None)
        t = timings[c]
        for w in workers:
            row = {"case": _label(*c), "workers": w, "floor_ms": 1e3 * t[(w, "floor")],
                   "out_mib": np.prod(shape) * np.dtype(dt).itemsize / 2**20}
            for k in contenders:
                row[k] = (t.ratio((w, k), (w, "floor")), 1e3 * t[(w, k)])
            # strong scaling against the first worker count, per round (the same round's load on both)
            base = workers[0]
            for k in ("floor", "spectral_noise"):
                row[f"speedup {k}"] = t.ratio((base, k), (w, k))
            row["serial"] = serial
            row["peak_mib"] = peak
            row["peak_floor_mib"] = peak_floor
            if peak_before is not None:
                row["peak_before_mib"] = peak_before
            rows.append(row)
    return rows, list(contenders)


def serial_share(shape, band, dt, rounds):
    """Shares of one single-worker ``spectral_noise`` call: (outside the threaded stages, spectrum fill + scaling, FFT).

    The stages are timed by wrapping ``map_blocks`` (fill, then scaling) and the inverse FFT
    (``_inverse_in_place``, whose last pass scales) of the module; medians of ``rounds`` calls. Robust to the
    load (one call's own parts)."""
    import noiselab.spectral.synthesis as SY

    orig = (SY.map_blocks, SY._inverse_in_place)

    def wrap(f, key, sw):
        return lambda *a, **k: sw(key, lambda: f(*a, **k))

    def one(r):
        sw = Stopwatch()
        SY.map_blocks, SY._inverse_in_place = wrap(orig[0], "fill", sw), wrap(orig[1], "fft", sw)
        try:
            SY.spectral_noise(shape, band=band, rng=max(r, 0), dtype=dt, workers=1)
        finally:
            SY.map_blocks, SY._inverse_in_place = orig
        return Laps(fill=sw.laps.get("fill", 0.0), fft=sw.laps.get("fft", 0.0))

    t = interleaved({"call": one}, repeats=rounds, round_arg=True)
    fill, fft = t.ratio("fill", "call"), t.ratio("fft", "call")
    return float(1 - float(np.median((t.raw["fill"] + t.raw["fft"]) / t.raw["call"]))), fill, fft


def exponent_sweep(rounds, before_rev, path, argv):
    """``spectral_noise`` 1024^2 float32, one worker, at several exponents against the floor (and ``--before``)."""
    before = _before_module(before_rev) if before_rev else None
    info = run_info(f"python3 benchmarks/bench_spectral.py {' '.join(argv)}".rstrip(), ["scipy", "noiselab"])
    shape = (1024, 1024)
    S = _half_spectrum(shape, np.float32)
    exps = (1.0, 1.5, 2.0, 0.5, 1.3, 2.7)
    runs = {"spectral_noise": lambda e, r: spectral_noise(shape, exponent=e, rng=r, workers=1)}
    if before is not None:
        runs["before"] = lambda e, r: before.spectral_noise(shape, exponent=e, rng=r)
    cands = {(e, k): (lambda r, e=e, k=k: scipy.fft.irfftn(S, s=shape, workers=1) if k == "floor"
                      else runs[k](e, max(r, 0))) for e in exps for k in ["floor", *runs]}
    t = interleaved(cands, repeats=rounds, round_arg=True)
    lines = ["# spectral_noise: cost of the power law's exponent", "", *header_lines(info), "",
             "1024 x 1024 "
             f"float32, full band, one worker; ratio = median over {rounds} interleaved rounds of time / bare "
             "`irfftn` time in the same round. Exponents that are multiples of 1/2 are computed with square roots "
             "and products (vectorised), the others with `pow` per cell." +
             (f" `before` = `{before_rev}` (`pow` for every exponent but 1)." if before is not None else ""), "",
             "| exponent | spectral_noise (x floor) |" + (" before (x floor) |" if before is not None else ""),
             "|---|---|" + ("---|" if before is not None else "")]
    for e in exps:
        cells = [f"{t.ratio((e, k), (e, 'floor')):.2f}" for k in runs]
        lines.append(f"| {e:g} | " + " | ".join(cells) + " |")
    lines.append("")
    path.write_text("\n".join(lines))
    print("\n".join(lines))


BITS_CASES = [((1024, 1024), {}), ((2048, 2048), {}), ((512, 512), {"band": (4, 64)}),
              ((256, 256), {"exponent": 2.0, "normalize": "sample"}),
              ((300, 301), {"amplitude_distribution": "uniform", "exponent": 0.5}), ((64, 64, 64), {}),
              ((128, 96, 80), {"band": (2, 16)}), ((4096,), {"dc": True}), ((1000, 1000), {}),
              ((48, 40), {"band": (4, 20), "normalize": "sample"}), ((17, 19, 15), {"exponent": 1.5}),
              ((100, 96, 110), {"band": (2, 20)})]


def bits_against(rev, seeds=3):
    """The largest absolute difference between ``spectral_noise`` now and at ``rev``, per dtype, over :data:`BITS_CASES`.

    Prints, per case, whether every seed gave the same bits, and per dtype the largest difference.
    """
    before = _before_module(rev)
    worst = {}
    for shape, kw in BITS_CASES:
        same = True
        for dt in (np.float32, np.float64):
            for seed in range(seeds):
                a = spectral_noise(shape, rng=seed, dtype=dt, **kw)
                b = before.spectral_noise(shape, rng=seed, dtype=dt, **kw)
                same &= a.tobytes() == b.tobytes()
                d = float(np.max(np.abs(a.astype(np.float64) - b)))
                name = np.dtype(dt).name
                if d >= worst.get(name, (-1.0,))[0]:
                    worst[name] = (d, shape, kw, seed)
        print(f"{shape} {kw}: {'the same bits' if same else 'changed'}")
    for name, (d, shape, kw, seed) in worst.items():
        print(f"{name}: largest difference {d:.2g} ({shape}, {kw}, rng={seed})")


def _parallel_fraction(speedup, n_from, n_to):
    """Amdahl's parallel fraction implied by ``speedup`` going from ``n_from`` to ``n_to`` workers."""
    r = n_to / n_from
    if r == 1:
        return float("nan")
    return (1 - 1 / speedup) / (1 - 1 / r)


def write_md(rows, names, rounds, argv, path, before_rev=None):
    load = next((x for x in argv if x.startswith("#load")), None)
    cmd = f"python3 benchmarks/bench_spectral.py {' '.join(a for a in argv if not a.startswith('#load'))}".rstrip()
    info = run_info(cmd, ["scipy", "noiselab"], load=float(load.split()[1]) if load else None)
    lines = [
        "# spectral_noise / synthesize against a bare irfftn",
        "",
        *header_lines(info, timing="load average (1 min) before and after the timing: "
                      f"{' and '.join(load.split()[1:]) if load else '?'}; ratios are what hold, the milliseconds "
                      "move with the load"),
        "",
        f"Ratio = median over {rounds} interleaved rounds after one warm-up round (`noiselab.lab.measure.interleaved`, "
        "one run per case over its worker counts and contenders, the order rotated each round) of (time / floor time "
        "in the same round); floor = "
        "`scipy.fft.irfftn` of a ready half spectrum to the same output shape and dtype, with the row's worker "
        "count (`workers=`) on both sides. "
        "`synthesize` gets the float64 envelope `annulus * power_law` as a callable (the general path). "
        "Peak = `tracemalloc` peak of one `spectral_noise` call (numpy arrays only), floor's for comparison.",
        "",
    ]
    if before_rev:
        lines[-1:-1] = ["", f"`spectral_noise before` = `noiselab/spectral/synthesis.py` and `_kernels.py` at "
                        f"`{before_rev}` (with the current plan module), timed in the same rounds."]
    head = "| case | workers | floor ms | " + " | ".join(f"{n} (x floor, ms)" for n in names) + \
        " | peak MiB (floor; output) |" + (" before peak MiB |" if "spectral_noise before" in names else "")
    lines.append(head)
    lines.append("|" + "---|" * (head.count("|") - 1))
    for r in rows:
        cells = [r["case"], str(r["workers"]), f"{r['floor_ms']:.1f}"]
        cells += [f"**{r[n][0]:.2f}** ({r[n][1]:.1f})" if n == "spectral_noise" else f"{r[n][0]:.2f} ({r[n][1]:.1f})"
                  for n in names]
        cells.append(f"{r['peak_mib']:.1f} ({r['peak_floor_mib']:.1f}; {r['out_mib']:.1f})")
        if "peak_before_mib" in r:
            cells.append(f"{r['peak_before_mib']:.1f}")
        lines.append("| " + " | ".join(cells) + " |")
    lines.append("")
    base = rows[0]["workers"]
    scaled = [r for r in rows if r["workers"] != base]
    if scaled:
        lines += ["## Strong scaling", "",
                  f"Speed-up = median over the rounds of (time at {base} worker(s) / time at n workers) in the same "
                  "round; p = Amdahl's parallel fraction it implies. On a machine shared with other jobs the "
                  "second core is often busy, so both sides scale less than they would alone.", "",
                  "The last column is measured on one worker instead (robust to the load): the shares of one call "
                  "spent outside the threaded stages (serial: 1 - p at most), in the spectrum fill and scaling, and "
                  "in the FFT passes.", "",
                  "| case | workers | floor speed-up (p) | spectral_noise speed-up (p) | 1-worker call: serial / fill / FFT |",
                  "|---|---|---|---|---|"]
        for r in scaled:
            fs, ns = r["speedup floor"], r["speedup spectral_noise"]
            lines.append(f"| {r['case']} | {base} -> {r['workers']} | {fs:.2f} "
                         f"({_parallel_fraction(fs, base, r['workers']):.2f}) | {ns:.2f} "
                         f"({_parallel_fraction(ns, base, r['workers']):.2f}) | "
                         + " / ".join(f"{100 * x:.0f} %" for x in r["serial"]) + " |")
        lines.append("")
    path.write_text("\n".join(lines))
    print("\n".join(lines))


def build_parser():
    """The command line (``--rounds``, ``--quick``, ``--before``, ``--workers``, ``--output``, ``--exponents``)."""
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--rounds", type=int, default=7)
    p.add_argument("--quick", action="store_true")
    p.add_argument("--before", default=None, help="git revision whose spectral_noise to time beside (e.g. c3cdeef)")
    p.add_argument("--workers", type=int, nargs="+", default=[1, os.cpu_count() or 1],
                   help="worker counts, the same on both sides (default: 1 and every core)")
    p.add_argument("--output", default=None, help="default benchmarks/bench_spectral.md "
                   "(bench_spectral_exponents.md with --exponents)")
    p.add_argument("--exponents", action="store_true", help="only the exponent sweep (1024^2 float32, 1 worker)")
    p.add_argument("--bits-against", default=None, metavar="REV",
                   help="only print the largest difference of spectral_noise's fields from those at REV")
    return p


def main(argv=None):
    p = build_parser()
    argv = sys.argv[1:] if argv is None else argv
    a = p.parse_args(argv)
    if a.rounds < 5:
        p.error("--rounds must be at least 5 (medians of fewer are not reported)")
    if a.bits_against:
        bits_against(a.bits_against)
        return
    if a.exponents:
        exponent_sweep(a.rounds, a.before, Path(a.output or ROOT / "benchmarks" / "bench_spectral_exponents.md"),
                       argv)
        return
    a.output = a.output or str(ROOT / "benchmarks" / "bench_spectral.md")
    load0 = load_average()
    rows, names = run(a.rounds, a.quick, a.before, a.workers)
    argv = list(argv) + [f"#load {load0:.1f} {load_average():.1f}"]
    write_md(rows, names, a.rounds, argv, Path(a.output), a.before)


if __name__ == "__main__":
    main()
