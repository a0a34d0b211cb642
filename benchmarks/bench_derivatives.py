"""Exact derivatives of lattice noise: the cost of value + gradient against the value alone and finite differences.

Run::

    python3 benchmarks/bench_derivatives.py [--repeats 7] [--quick]

Writes ``benchmarks/bench_derivatives.md`` beside this script. For each case
three candidates run interleaved in one process, one thread:

- ``value``: ``noise(x)`` (or ``noise.grid``), the fastest value kernels;
- ``value+gradient``: ``noise.gradient(x, return_value=True)`` (or
  ``noise.gradient_grid(..., return_value=True)``): the value and the exact
  gradient;
- ``finite differences``: the value and a central-difference gradient,
  ``2 d + 1`` evaluations of the value kernels (``noise(x)``,
  ``noise(x +- h e_a)``) plus the differences.

Every ratio is the median over ``--repeats`` (>= 5) of the ratios of
back-to-back runs, robust to the load drifting on a shared machine.
"""
from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from noiselab import LatticeNoise  # noqa: E402
from noiselab.lab.measure import header_lines, interleaved, run_info  # noqa: E402


def _bench(cands: dict, repeats: int):
    """Interleaved rounds (one warm-up round, order rotated each round): a :class:`~noiselab.lab.measure.Timings`."""
    return interleaved(cands, repeats=repeats, min_repeats=5)


def _fd_points(noise, x, h):
    d = x.shape[-1]
    value = noise(x)
    grad = np.empty(x.shape)
    for a in range(d):
        e = np.zeros(d)
        e[a] = h
        grad[..., a] = (noise(x + e) - noise(x - e)) / (2 * h)
    return value, grad


def _fd_grid(noise, shape, ext, h):
    d = len(shape)
    value = noise.grid(shape, ext)
    grad = np.empty(tuple(shape) + (d,))
    for a in range(d):
        e = np.zeros((d, 2))
        e[a] = h
        grad[..., a] = (noise.grid(shape, ext + e) - noise.grid(shape, ext - e)) / (2 * h)
    return value, grad


def _row(label, t, n):
    v, g, f = "value", "value+gradient", "finite differences"
    return (f"| {label} | {t.rate(v, n):.3g} | {t.rate(g, n):.3g} | {t.ratio(g, v):.2f} "
            f"| {t.ratio(f, v):.2f} | {t.ratio(f, g):.2f} |")


HEAD = ("| case | value pts/s | value+gradient pts/s | (value+gradient) / value | finite differences / value "
        "| finite differences / (value+gradient) |\n|---|---|---|---|---|---|")


def scattered(repeats, quick, lines, summary):
    npts = 50_000 if quick else 400_000
    lines += ["", f"## Scattered points ({npts} uniform points in [-50, 50)^d, one thread)", "", HEAD]
    for d in (1, 2, 3):
        for kernel in ("cubic", "quintic"):
            for basis in ("value", "gradient"):
                noise = LatticeNoise(d, rng=1, kernel=kernel, basis=basis)
                x = np.random.default_rng(d).uniform(-50, 50, (npts, d))
                t = _bench({"value": lambda: noise(x),
                            "value+gradient": lambda: noise.gradient(x, return_value=True),
                            "finite differences": lambda: _fd_points(noise, x, 1e-5)}, repeats)
                lines.append(_row(f"{d}-D {kernel} {basis}", t, npts))
                summary.append((f"{d}-D scattered, {kernel}, {basis} basis", t))


def grids(repeats, quick, lines, summary):
    lines += ["", "## Grids (separable passes; 16 lattice cells per side)", "",
              "`write floor` = time of writing the d + 1 float64 output arrays of value + gradient (`np.full`) / "
              "time of writing the value's one: what the larger output alone costs. `vs d+1 value grids` = "
              "(value+gradient) / the time of d + 1 value grids kept alive (the same amount of output): a value "
              "grid timed alone reuses the cache-hot memory its predecessor freed, d + 1 arrays do not.", "",
              HEAD.split("\n")[0] + " write floor | vs d+1 value grids |", HEAD.split("\n")[1] + "---|---|"]
    sizes = [(2, (256, 256)), (3, (32,) * 3)] if quick else [(2, (256, 256)), (2, (1024, 1024)), (3, (48,) * 3),
                                                             (3, (128,) * 3)]
    for d, shape in sizes:
        ext = np.array([(0.0, 16.0)] * d)
        floor = _bench({"value": lambda: np.full(shape, 0.5),
                        "value+gradient": lambda: [np.full(shape, 0.5) for _ in range(d + 1)],
                        "finite differences": lambda: None}, repeats)
        floor_ratio = floor.ratio("value+gradient", "value")
        for kernel in ("cubic", "quintic"):
            for basis in ("value", "gradient"):
                noise = LatticeNoise(d, rng=1, kernel=kernel, basis=basis)
                t = _bench({"value": lambda: noise.grid(shape, ext),
                            "value+gradient": lambda: noise.gradient_grid(shape, ext, return_value=True),
                            "finite differences": lambda: _fd_grid(noise, shape, ext, 1e-5),
                            "d+1 values": lambda: [noise.grid(shape, ext) for _ in range(d + 1)]}, repeats)
                size = int(np.prod(shape))
                lines.append(_row(f"{d}-D {'x'.join(map(str, shape))} {kernel} {basis}", t, size)
                             + f" {floor_ratio:.2f} | {t.ratio('value+gradient', 'd+1 values'):.2f} |")
                summary.append((f"{d}-D grid {'x'.join(map(str, shape))}, {kernel}, {basis} basis", t))


def accuracy(lines):
    """Gradient error of finite differences against the exact gradient, at two steps."""
    noise = LatticeNoise(3, rng=1, kernel="quintic")
    lines += ["", "## Accuracy of the finite-difference gradient (3-D quintic, 20000 points)", "",
              "| coordinates | step h | max error / max abs gradient |", "|---|---|---|"]
    for base in (0.0, 1e9):
        x = base + np.random.default_rng(0).uniform(0, 50, (20_000, 3))
        exact = noise.gradient(x)
        for h in (1e-3, 1e-5, 1e-7):
            _, fd = _fd_points(noise, x, h)
            lines.append(f"| {base:g} + [0, 50) | {h:g} | {np.abs(fd - exact).max() / np.abs(exact).max():.1e} |")


def build_parser():
    """The command line (``--repeats``, ``--quick``)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--quick", action="store_true", help="small sizes (a smoke run)")
    return ap


def main(argv=None):
    ap = build_parser()
    args = ap.parse_args(argv)
    if args.repeats < 5:
        ap.error("--repeats must be >= 5")
    cmd = "python3 benchmarks/bench_derivatives.py" + (" --quick" if args.quick else "") + f" --repeats {args.repeats}"
    lines = ["# Derivatives of lattice noise: benchmark", "",
             *header_lines(run_info(cmd), timing="one thread"),
             f"- ratios: median of the {args.repeats} per-round ratios of interleaved rounds (one warm-up round, order "
             "rotated each round, `noiselab.lab.measure.interleaved`); pts/s: median time",
             "- `value+gradient` = `noise.gradient(x, return_value=True)` / `noise.gradient_grid(..., "
             "return_value=True)`; `finite differences` = the value plus central differences, 2d+1 value "
             "evaluations (h = 1e-5)"]
    summary = []
    body = []
    scattered(args.repeats, args.quick, body, summary)
    grids(args.repeats, args.quick, body, summary)
    accuracy(body)
    lines += ["", "## Summary", ""]
    for label, t in summary:
        lines.append(f"- {label}: value + gradient costs {t.ratio('value+gradient', 'value'):.2f}x the "
                     f"value alone; finite differences cost {t.ratio('finite differences', 'value'):.2f}x "
                     f"({t.ratio('finite differences', 'value+gradient'):.2f}x value + gradient)")
    lines += body
    out = Path(__file__).with_suffix(".md")
    out.write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
