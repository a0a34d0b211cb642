"""The hash question: Phillips' nested permutation table against an arithmetic integer hash, on the same scenes.

Phillips (2004, 2.4.1) addresses the lattice through a nested permutation,
``P[(P[i] + j) mod n]``: along any lattice row a full period visits every
table entry exactly once, so every row over a full period is a permutation of
the same ``n`` values. ``LatticeNoise(..., hash="integer")`` hashes the
coordinates arithmetically instead (32-bit words: ``mix32`` of the key xored
with each coordinate times its axis multiplier, see :mod:`noiselab.lattice._inthash`). Both are measured here on the same scenes,
with the same kernels, bases and seeds:

Full period (2-D)
    ``cells x cells`` lattice cells (the table size, 256), ``period=cells``
    for both hashes so that both fields tile exactly, ``spc`` samples per cell.
    Measures: :func:`noiselab.analysis.axis_artefacts` (spread of the row and
    column means, against an isotropic field's, and the whitened power on the
    frequency axes), the profile striping (below), and
    :func:`noiselab.analysis.anisotropy` /
    :func:`noiselab.analysis.ring_anisotropy`.
Profile striping
    The periodogram along the last axis averaged over the rows of one field,
    divided by its mean over ``SEEDS`` fields: its coefficient of variation
    over the frequencies. Independent rows average their periodograms (small
    CV); rows that are permutations of one another share a single random
    profile (CV near 1).
Period (1-D)
    A line of ``4 * 256`` cells at the default period (no ``period=``): the
    exact repeat :func:`noiselab.analysis.detect_period` finds, in cells.
Speed
    Random 3-D points and a 2-D grid, both hashes interleaved in one process
    (:func:`noiselab.lab.measure.time_against_floor`).
"""
from __future__ import annotations

import numpy as np

__all__ = ["hash_experiment", "hash_section", "profile_striping", "HASH_SCENES"]

SEEDS = (0, 1, 2, 3, 4, 5, 6, 7)
HASH_SCENES = (("cubic", "value"), ("catmull-rom", "value"), ("quintic", "value"), ("quintic", "gradient"))


def profile_striping(fields) -> np.ndarray:
    """Coefficient of variation of each field's row-averaged periodogram (last axis) about the mean of all fields.

    ``fields``: ``(seeds, rows, cols)``. Frequencies 1 to ``cols / 4`` (where a
    lattice field with 2 or more samples per cell holds its power).

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> cv = profile_striping(rng.standard_normal((8, 256, 256)))
    >>> bool(cv.max() < 0.1)
    True
    """
    f = np.asarray(fields, dtype=np.float64)
    prof = np.mean(np.abs(np.fft.rfft(f, axis=-1)) ** 2, axis=1)[:, 1:f.shape[-1] // 4 + 1]
    ratio = prof / prof.mean(axis=0)
    return ratio.std(axis=1) / ratio.mean(axis=1)


def _noise(hash_, kernel, basis, seed, dim=2, period=None):
    from ..lattice import LatticeNoise

    return LatticeNoise(dim, rng=seed, kernel=kernel, basis=basis, hash=hash_, period=period)


def hash_experiment(cfg=None, *, cells=256, spc=2, repeats=None):
    """Measure both hashes on the same scenes; returns ``{"rows": [...], "speed": [...], "setup": {...}}``."""
    from ..analysis import anisotropy, axis_artefacts, detect_period, ring_anisotropy
    from .measure import time_against_floor, write_floor

    quick = bool(getattr(cfg, "quick", False))
    if quick:
        cells, spc = 32, 2
    repeats = repeats or getattr(cfg, "repeats", 5)
    n = cells * spc
    ext = [(0, cells), (0, cells)]
    rows = []
    for kernel, basis in HASH_SCENES:
        for hash_ in ("table", "integer"):
            imgs = np.stack([_noise(hash_, kernel, basis, s, period=cells).grid((n, n), ext) for s in SEEDS])
            arts = [axis_artefacts(im) for im in imgs]
            cv = profile_striping(imgs)
            line = _noise(hash_, kernel, basis, 0, dim=1).grid((4 * 4 * 256,), [(0, 4 * 256)])
            per = detect_period(line, min_lag=16)
            ra = ring_anisotropy(imgs)
            rows.append({
                "kernel": kernel, "basis": basis, "hash": hash_,
                # the row means' spread over an isotropic field's (1: independent rows)
                "mean_spread_excess": float(np.median([a.mean_spread_excess for a in arts])),
                "row_mean_spread_x_sqrt_rows": float(np.median([a.row_mean_spread for a in arts])) * np.sqrt(n),
                "axis_excess": float(np.median([a.axis_excess for a in arts])),
                "profile_cv": float(np.median(cv)),
                "period_cells": None if per.period is None else per.period / 4,
                "anisotropy": float(np.median([anisotropy(im) for im in imgs])),
                "ring_anisotropy_db": float(ra.mean_db),
            })
    # white noise: the reference for the profile striping and the mean spread
    rng = np.random.default_rng(0)
    white = rng.standard_normal((len(SEEDS), n, n))
    ref = {"profile_cv": float(np.median(profile_striping(white))),
           "row_mean_spread_x_sqrt_rows": float(np.median([axis_artefacts(w).row_mean_spread for w in white])) * np.sqrt(n)}
    # speed: both hashes interleaved, one thread
    npts = 20_000 if quick else 1_000_000
    pts32 = np.random.default_rng(0).uniform(0.0, 100.0, (npts, 3)).astype(np.float32)
    pts = pts32.astype(np.float64)
    speed = []
    for kernel, basis in (("quintic", "value"), ("quintic", "gradient"), ("catmull-rom", "value")):
        cases = {h: (lambda nz=_noise(h, kernel, basis, 1, dim=3): nz(pts)) for h in ("table", "integer")}
        # float32 points take the integer hash's all-float32 SIMD kernel (the table hash computes in float64)
        cases["integer32"] = lambda nz=_noise("integer", kernel, basis, 1, dim=3): nz(pts32)
        t = time_against_floor(cases, write_floor((npts,)), repeats=repeats)
        ratio = lambda k: float(np.median(np.array(t["table"]["times"]) / np.array(t[k]["times"])))  # noqa: E731
        speed.append({"scene": f"{npts:,} random 3-D points", "kernel": kernel, "basis": basis,
                      "table_pts_s": npts / t["table"]["median_s"], "integer_pts_s": npts / t["integer"]["median_s"],
                      "integer_over_table": ratio("integer"), "integer32_pts_s": npts / t["integer32"]["median_s"],
                      "integer32_over_table": ratio("integer32")})
    g = 128 if quick else 1024
    for kernel, basis in (("quintic", "value"), ("quintic", "gradient")):
        cases = {h: (lambda nz=_noise(h, kernel, basis, 1): nz.grid((g, g), [(0, 16), (0, 16)])) for h in ("table", "integer")}
        t = time_against_floor(cases, write_floor((g, g)), repeats=repeats)
        speed.append({"scene": f"2-D grid {g}^2, 16 cells", "kernel": kernel, "basis": basis,
                      "table_pts_s": g * g / t["table"]["median_s"], "integer_pts_s": g * g / t["integer"]["median_s"],
                      "integer_over_table": float(np.median(np.array(t["table"]["times"]) / np.array(t["integer"]["times"])))})
    return {"rows": rows, "white": ref, "speed": speed,
            "setup": {"cells": cells, "samples_per_cell": spc, "seeds": len(SEEDS), "repeats": repeats}}


def _f(v, digits=3):
    if v is None:
        return "none"
    if isinstance(v, float):
        if v != 0 and (abs(v) < 1e-3 or abs(v) >= 1e5):
            return f"{v:.2e}"
        return f"{v:.{digits}g}"
    return str(v)


def hash_section(res) -> str:
    """The markdown section of :func:`hash_experiment`'s result (``res`` is its dict)."""
    s = res["setup"]
    L = ["## 6. The hash question: Phillips' permutation table against an integer hash\n"]
    info = res.get("info")
    if info:
        L.append(f"This section alone was regenerated by `python3 -m noiselab.lab.hashes` "
                 f"({info.get('date', 'date not recorded')}; {info.get('cpu', '')}, {info.get('cores', '?')} cores "
                 f"shared with other jobs, load average {res.get('load', float('nan')):.1f} at start); the sections above are "
                 "from the last full `python3 -m noiselab bench`. Gallery: `lab/hashes`.\n")
    L += [
         f"Same scenes, kernels, bases and seeds for both: `LatticeNoise(2, kernel=..., basis=..., hash=...)` "
         f"with `period={s['cells']}` (the table size, so both fields tile exactly), {s['cells']}x{s['cells']} cells "
         f"at {s['samples_per_cell']} samples per cell, medians over {s['seeds']} seeds. "
         "*mean spread excess*: variance of the row and column means over an isotropic field's "
         "(`axis_artefacts`; 1 for independent rows); *row-mean spread x sqrt(rows)*: the row means' standard "
         f"deviation over the field's, times sqrt(rows) (white noise: {_f(res['white']['row_mean_spread_x_sqrt_rows'])}); "
         "*axis excess*: whitened power on the frequency axes (1: none extra); *profile CV*: coefficient of "
         "variation of one field's row-averaged periodogram along the last axis about the mean over the seeds "
         f"(white noise: {_f(res['white']['profile_cv'])}; one random periodogram: about 1); *period*: the exact "
         "repeat `detect_period` finds on a 1-D line of 1024 cells at the default period (no `period=`); "
         "*aniso*: `anisotropy`; *ring dB*: `ring_anisotropy` mean over rings (an isotropic field: "
         f"{-10 * np.log10(s['seeds']):.1f} dB for {s['seeds']} periodograms).\n"]
    L.append("| kernel | basis | hash | mean spread excess | row-mean spread x sqrt(rows) | axis excess | profile CV "
             "| period (cells) | aniso | ring dB |")
    L.append("|---|---|---|---|---|---|---|---|---|---|")
    for r in res["rows"]:
        L.append(f"| {r['kernel']} | {r['basis']} | {r['hash']} | {_f(r['mean_spread_excess'])} | "
                 f"{_f(r['row_mean_spread_x_sqrt_rows'])} | {_f(r['axis_excess'])} | {_f(r['profile_cv'])} | "
                 f"{_f(r['period_cells'])} | {_f(r['anisotropy'])} | {_f(r['ring_anisotropy_db'])} |")
    L.append("")
    L.append("Speed, one thread, both hashes interleaved in one process (median of "
             f"{s['repeats']} rounds; *integer / table*: median of the per-round speed ratios; the machine was "
             "shared with other jobs, so absolute rates are a floor while the ratios hold):\n")
    L.append("| scene | kernel | basis | table pts/s | integer pts/s | integer / table | integer, float32 points "
             "pts/s | integer float32 / table |")
    L.append("|---|---|---|---|---|---|---|---|")
    for r in res["speed"]:
        f32 = (f"{r['integer32_pts_s']:.3g} | {r['integer32_over_table']:.2f}" if "integer32_pts_s" in r
               else "n/a | n/a")
        L.append(f"| {r['scene']} | {r['kernel']} | {r['basis']} | {r['table_pts_s']:.3g} | {r['integer_pts_s']:.3g} "
                 f"| {r['integer_over_table']:.2f} | {f32} |")
    L.append("")
    return "\n".join(L) + "\n"


def update_results(path=None, *, quick=False, log=print):
    """Run :func:`hash_experiment` and put its section into ``RESULTS.md`` (only that section is rewritten).

    The section replaces a previous one (from its heading to the next ``## ``
    heading) or goes before ``## Notes``; the raw numbers go to
    ``results/hashes.json`` beside it. ``python3 -m noiselab.lab.hashes [RESULTS.md]`` (default
    ``out/bench/RESULTS.md``; the checkout's published report is ``benchmarks/RESULTS.md``).
    """
    import json
    import os
    from pathlib import Path

    from .experiments import Config
    from .measure import machine_info

    path = Path(path) if path is not None else Path("out") / "bench" / "RESULTS.md"
    load = os.getloadavg()[0]
    res = hash_experiment(Config.quick_config() if quick else Config.full())
    res["load"] = load
    res["info"] = machine_info()
    section = hash_section(res)
    text = path.read_text() if path.exists() else "## Notes\n"
    head = "## 6. The hash question"
    if head in text:
        a = text.index(head)
        b = text.find("\n## ", a + 1)
        text = text[:a] + section.rstrip("\n") + "\n" + (text[b:] if b >= 0 else "")
    elif "## Notes" in text:
        a = text.index("## Notes")
        text = text[:a] + section + text[a:]
    else:
        text += "\n" + section
    path.write_text(text)
    (path.parent / "results").mkdir(exist_ok=True)
    (path.parent / "results" / "hashes.json").write_text(json.dumps(res, indent=1, default=str))
    log(f"wrote the hash section of {path}")
    return res


if __name__ == "__main__":
    import sys

    paths = [a for a in sys.argv[1:] if not a.startswith("--")]
    update_results(paths[0] if paths else None, quick="--quick" in sys.argv)
