"""The literature's measures for every generator: band-limitedness, aliasing, slices, envelope, variance and
range, periods, lattice-axis artefacts, anisotropy and motion per band.

One scene per question, the same for every method:

One octave (2-D, ``N x N``)
    Every generator is asked for one octave centred on ``c = N / 16``
    cycles/frame: :func:`noiselab.spectral_noise` with a flat spectrum in
    ``[c / sqrt 2, c sqrt 2]``; :class:`noiselab.LatticeNoise` of every kernel
    and basis with ``F`` lattice cells across the frame, ``F = round(c /
    lattice_peak)`` so that its power-weighted mean frequency falls on ``c``
    (then ``c`` is moved to ``F x lattice_peak``), with ``period=F`` so that
    the field tiles and its expected spectrum is exact (:func:`lattice_spectrum`).
One octave (3-D, ``n**3``)
    The same in a volume (``c = n / 8``), for the slices (Cook & DeRose).
Falling snow
    :func:`noiselab.snowfall.snow` and the lab's two alternatives over three seeds.
"""
from __future__ import annotations

import numpy as np

__all__ = ["lattice_spectrum", "lattice_variance", "octave_generators", "generator_measures", "quality_experiment",
           "motion_experiment", "quality_section", "QUALITY_SEEDS"]

QUALITY_SEEDS = (0, 1, 2)
ULICHNEY_K = 8  # periodograms averaged for Ulichney's anisotropy (an isotropic field: -9.0 dB)


# --------------------------------------------------------------------------- lattice theory

def _kernel_power(kernel, n, cells):
    """``A(k) = sum_j |DFT K(x - j)|**2`` and ``B(k)``, the same for ``(x - j) K(x - j)``, over the lattice points ``j``.

    ``x`` runs over the ``n`` samples of a period of ``cells`` cells; the kernel is periodised over the period. When
    ``n / cells`` is not an integer every lattice point sits at another sampling phase, hence the sum over ``j``.
    """
    from ..lattice.kernels import get_kernel

    k = get_kernel(kernel)
    x = np.arange(n) * (cells / n)
    d = (x[None, :] - np.arange(cells)[:, None] + cells / 2) % cells - cells / 2  # signed distance, wrapped
    g = np.zeros_like(d)
    h = np.zeros_like(d)
    for m in range(-3, 4):  # the kernel's images one period away (support <= 2 cells each side)
        km = k(d + m * cells)
        g += km
        h += (d + m * cells) * km
    return (np.sum(np.abs(np.fft.fft(g, axis=1)) ** 2, axis=0),
            np.sum(np.abs(np.fft.fft(h, axis=1)) ** 2, axis=0))


def lattice_spectrum(kernel, basis, n, cells, dim=2) -> np.ndarray:
    """Expected power spectrum (up to a constant) of periodic lattice noise, in ``rfftn`` layout of ``(n,) * dim``.

    With ``period=cells`` lattice cells over ``n`` samples per axis, the noise
    is ``sum_j v_j K(x - j)`` (value) or ``sum_j g_j . (x - j) K(x - j)``
    (gradient, ``K`` the tensor product). For uncorrelated lattice values its
    expected periodogram is ``prod_a A(k_a)`` (value) and, for unit gradients
    with uncorrelated components, ``sum_a B(k_a) prod_{b != a} A(k_b)``
    (gradient), with ``A(k) = sum_j |DFT_x K(x - j)|**2`` and ``B`` the same
    for ``(x - j) K(x - j)``, ``x`` the sample positions: exact on the
    sampling grid, aliasing included, for any number of samples per cell. (The
    permutation hash makes the values only nearly uncorrelated.)

    Examples
    --------
    >>> p = lattice_spectrum("linear", "value", 64, 8, dim=1)
    >>> p.shape, int(np.argmax(p))   # a low-pass: the peak at DC
    ((33,), 0)
    """
    A, B = _kernel_power(kernel, n, cells)

    def outer(parts):
        out = parts[0]
        for p in parts[1:]:
            out = np.multiply.outer(out, p)
        return out

    if basis == "value":
        full = outer([A] * dim)
    elif basis == "gradient":
        full = sum(outer([B if a == b else A for b in range(dim)]) for a in range(dim))
    else:
        raise ValueError(f"basis must be 'value' or 'gradient', got {basis!r}")
    return np.ascontiguousarray(full[..., : n // 2 + 1])


def lattice_variance(noise, *, table=True) -> float:
    """Analytic variance of a :class:`noiselab.LatticeNoise`, averaged over the position in the cell.

    Value noise: ``E[v**2] A**d / bound**2`` with ``A = int_0^1 sum_m K(t - m)**2 dt``
    and ``E[v**2]`` the noise's own value table (``table=True``) or 1/3, its
    expectation over seeds (values uniform in [-1, 1]);
    gradient noise (unit gradients, ``E[(g . r)**2] = |r|**2 / d``):
    ``M A**(d-1) / bound**2`` with ``M = int_0^1 sum_m (t - m)**2 K(t - m)**2 dt``.
    ``bound`` is the range normalisation (:meth:`noiselab.lattice.kernels.Kernel.value_bound`).

    Examples
    --------
    >>> from noiselab import LatticeNoise
    >>> round(lattice_variance(LatticeNoise(1, kernel="linear", rng=0), table=False), 4)   # 1/3 x 2/3
    0.2222
    """
    t = (np.arange(4096) + 0.5) / 4096
    m = np.arange(-4, 5)[:, None]
    kt = noise.kernel(t[None, :] - m)
    a = float(np.mean(np.sum(kt**2, axis=0)))
    d = noise.dim_in
    if noise.basis == "value":
        v2 = float(np.mean(noise.values[0] ** 2)) if table else 1.0 / 3.0
        var = v2 * a**d
    else:
        mm = float(np.mean(np.sum((t[None, :] - m) ** 2 * kt**2, axis=0)))
        var = mm * a ** (d - 1)
    return var * noise.scale**2


# --------------------------------------------------------------------------- generators

def octave_generators(n, dim=2):
    """name -> (family, make(seed, size) -> field, info) for the one-octave scene (see the module docstring).

    ``make(seed, m)`` renders the generator's field over the same domain at
    ``m`` samples per axis (``m = 2 n`` for the aliasing measurement).
    ``info`` holds the band, the lattice cells and kernel, and the analytic variance and bounds.
    """
    from ..lattice import LatticeNoise, kernel_names
    from ..spectral import spectral_noise
    from .snowgen import lattice_peak

    c0 = n / (16 if dim == 2 else 8)
    gens = {}

    def spectral(seed, m, lo=c0 / np.sqrt(2), hi=c0 * np.sqrt(2)):
        x = spectral_noise((n,) * dim, exponent=0.0, band=(lo, hi), rng=seed, dtype=np.float64)
        if m == n:
            return x
        from scipy.signal import resample

        for ax in range(dim):  # the same trigonometric field at m samples per axis
            x = resample(x, m, axis=ax)
        return x

    gens["spectral_noise (flat octave)"] = ("spectral", spectral,
                                            {"band": (c0 / np.sqrt(2), c0 * np.sqrt(2)), "variance": 1.0,
                                             "bounds": None, "cells": None})
    for basis in ("value", "gradient"):
        for k in kernel_names():
            peak = lattice_peak(k, basis)
            cells = max(int(round(c0 / peak)), 2)
            c = cells * peak
            noise = LatticeNoise(dim, rng=0, kernel=k, basis=basis, period=cells)  # the variance over seeds

            def make(seed, m, k=k, basis=basis, cells=cells):
                nz = LatticeNoise(dim, rng=seed, kernel=k, basis=basis, period=cells)
                return nz.grid((m,) * dim, [(0.0, float(cells))] * dim)

            gens[f"{basis} noise, {k}"] = ("lattice", make,
                                          {"band": (c / np.sqrt(2), c * np.sqrt(2)), "variance": lattice_variance(noise, table=False),
                                           "bounds": (-1.0, 1.0), "cells": cells, "kernel": k, "basis": basis})
    return gens


def _period_of(family, info, n, seed=0):
    """Detected repeat along x: a lattice line over twice its table, an FFT field tiled twice (the domain)."""
    from ..analysis import detect_period
    from ..lattice import LatticeNoise
    from ..spectral import spectral_noise

    if family == "lattice":
        table = 64  # a small table keeps the line short; the default 256 repeats after 256 cells the same way
        spc = 4
        nz = LatticeNoise(1, rng=seed, kernel=info["kernel"], basis=info["basis"], table_size=table)
        line = nz.grid((2 * table * spc + spc,), [(0.0, 2 * table + 1.0)])
        p = detect_period(line, tol=1e-9)
        return {"period": None if p.period is None else p.period / spc, "period_unit": "cells",
                "period_expected": float(table)}
    x = spectral_noise((n,), exponent=0.0, band=(1, n / 2), rng=seed, dtype=np.float64)
    p = detect_period(np.tile(x, 2), tol=1e-9)  # wider than its domain, an FFT field can only repeat
    return {"period": p.period, "period_unit": "samples", "period_expected": float(n)}


def generator_measures(name, family, make, info, n, dim=2, *, seeds=ULICHNEY_K):
    """Every measure of one generator in the one-octave scene (a dict of numbers; per-octave lists under ``_``)."""
    from ..analysis import (anisotropy, axis_artefacts, band_leakage, envelope_error, orientation_energy,
                            ring_anisotropy, value_statistics, variance_striping)

    lo, hi = info["band"]
    x = make(1, n)
    row = {"method": name, "family": family, "n": n, "band": [lo, hi], "cells": info["cells"]}
    fine = make(1, 2 * n)
    leak = band_leakage(fine, (lo, hi), oversample=2)
    row.update({"below": leak.below, "above": leak.above, "aliased": leak.aliased, "outside": leak.outside,
                "_octaves": {"edges": leak.edges.tolist(), "fraction": leak.octaves.tolist(),
                             "aliased": leak.octaves_aliased.tolist()}})
    if family == "spectral":
        target = lambda f: np.where((f >= lo) & (f <= hi), 1.0, 0.0)  # noqa: E731
    else:
        target = lattice_spectrum(info["kernel"], info["basis"], n, info["cells"], dim)
    env = envelope_error(x, target)
    row.update({"envelope_rms_db": env.rms_db, "envelope_noise_db": env.noise_db, "envelope_max_db": env.max_db,
                "envelope_outside": env.outside})
    vs = value_statistics(x, variance=info["variance"], bounds=info["bounds"])
    stack = np.stack([make(s, n) for s in range(10, 10 + seeds)]) if dim == 2 else None
    # the variance over seeds (one lattice realisation holds few independent values)
    ratio = float(np.mean([np.var(f) for f in stack]) / info["variance"]) if stack is not None else vs.variance_ratio
    row.update({"variance_ratio": ratio, "range_used": vs.range_used, "within_bounds": vs.within_bounds,
                "range_sd": vs.range_sd})
    if dim == 2:
        o = orientation_energy(x)
        ra = ring_anisotropy(stack, (lo, hi))
        art = axis_artefacts(x, (lo, hi))
        period_px = n / info["cells"] if info["cells"] else 8.0  # spectral: the cell of a lattice peaking at 0.5 cycle/cell
        row.update({"anisotropy": anisotropy(x), "m4": o.m4, "anisotropy_ring": orientation_energy(x, whiten="ring").index,
                    "ulichney_db": ra.mean_db, "ulichney_floor_db": ra.floor_db,
                    "axis_excess": art.axis_excess, "mean_spread": max(art.row_mean_spread, art.column_mean_spread),
                    "striping": max(variance_striping(x, period_px, axis=0), variance_striping(x, period_px, axis=1))})
        row.update(_period_of(family, info, n))
    return row


def _slice_row(name, family, make, info, n):
    from ..analysis import shell_slice_below, slice_leakage

    lo, hi = info["band"]
    vol = make(1, n)
    s = slice_leakage(vol, (lo, hi))
    row = {"method": name, "family": family, "n": n, "band": [lo, hi], "volume_below": s.volume.below,
           "volume_outside": s.volume.outside, "slice_below": s.slices.below, "slice_outside": s.slices.outside,
           "added_below": s.added_below}
    if family == "spectral":
        row["shell_law_below"] = shell_slice_below(lo, hi)
    return row


def quality_experiment(cfg):
    """The one-octave scene in 2-D (every measure) and 3-D (slices), for spectral noise and every lattice kernel and basis."""
    n2, n3 = cfg.texture_n2, cfg.texture_n3
    rows2 = [generator_measures(name, fam, make, info, n2)
             for name, (fam, make, info) in octave_generators(n2, 2).items()]
    rows3 = [_slice_row(name, fam, make, info, n3) for name, (fam, make, info) in octave_generators(n3, 3).items()]
    return {"image": rows2, "volume": rows3, "motion": motion_experiment(cfg)}


# --------------------------------------------------------------------------- motion

def motion_experiment(cfg, seeds=QUALITY_SEEDS):
    """Falling snow: each octave band's share of power on the tent, mean and spread over seeds; envelope error."""
    from ..analysis import envelope_error, tent_energy_per_band
    from ..snowfall import snow
    from ..snowfall.render import snow_spectrum
    from .experiments import snow_band, snow_methods

    shape = tuple(cfg.pareto_shape)
    band = snow_band(shape[2])
    methods = dict(snow_methods(shape))
    methods = {"tent IFFT, linear field (rescale=False)":
               lambda s: snow(shape, rng=s, band=band, c=1.0, rescale=False, dtype=np.float64), **methods}
    target = np.abs(snow_spectrum(shape, rng=0, band=band, c=1.0, amplitude_distribution="fixed", dtype=np.float64)) ** 2
    rows = []
    for name, fn in methods.items():
        fr, env, off = [], [], []
        bands = None
        for s in seeds:
            v = np.asarray(fn(s), dtype=np.float64)
            m = tent_energy_per_band(v, 1.0, band)
            bands = m.bands
            fr.append(m.fraction)
            e = envelope_error(v, target)
            env.append(e.rms_db)
            off.append(e.outside)
        fr = np.array(fr)
        rows.append({"method": name, "bands": bands.tolist(), "tent_mean": fr.mean(axis=0).tolist(),
                     "tent_sd": fr.std(axis=0, ddof=1).tolist(), "envelope_rms_db": float(np.mean(env)),
                     "envelope_rms_db_sd": float(np.std(env, ddof=1)), "off_envelope": float(np.mean(off)),
                     "off_envelope_sd": float(np.std(off, ddof=1)), "seeds": len(seeds)})
    return rows


# --------------------------------------------------------------------------- report

def _f(v, digits=3):
    if v is None:
        return "-"
    if isinstance(v, bool):
        return "yes" if v else "no"
    v = float(v)
    if not np.isfinite(v):
        return "-" if np.isnan(v) else "inf"
    if v == 0:
        return "0"
    if abs(v) < 1e-3 or abs(v) >= 1e5:
        return f"{v:.1e}"
    return f"{v:.{digits}f}"


def quality_section(res) -> str:
    """The Markdown section of ``RESULTS.md`` for :func:`quality_experiment` (and the peers' new figures)."""
    q = res.get("quality")
    if not q:
        return ""
    L = ["## 5. The literature's measures, for every generator\n"]
    img = q["image"]
    n = img[0]["n"]
    L.append(f"Scene: one octave asked of every generator on a {n} x {n} frame, centred on {n / 16:g} cycles/frame "
             "(a lattice noise at the lattice density that puts its power-weighted mean frequency there, with "
             "`period=` so that it tiles and its expected spectrum is exact; the band is the octave around that "
             "centre). Functions from `noiselab.analysis` (`band_leakage`, `envelope_error`, `value_statistics`, "
             "`anisotropy`, `ring_anisotropy`, `axis_artefacts`, `variance_striping`, `detect_period`):\n")
    L.append("- **below / above**: power under / over the requested octave, inside the output's Nyquist; **aliased**: "
             "power past the output's Nyquist when the same noise is evaluated twice as densely over the same domain "
             "(what sampling folds back; the spectral field is a trigonometric polynomial: 0 by construction, measured "
             "on its Fourier-interpolated double);")
    L.append("- **envelope dB**: RMS error of the measured spectrum against the target envelope (spectral: the flat "
             "octave; lattice: the kernel's exact expected spectrum, `noiselab.lab.quality.lattice_spectrum`), cells "
             "pooled by target level, gain removed, beside the RMS a field drawn exactly from the target gives "
             "(**noise dB**);")
    L.append(f"- **var ratio**: empirical variance, mean over {ULICHNEY_K} seeds, over the analytic one (spectral: 1; lattice: "
             "`lattice_variance`, from the kernel, values uniform in [-1, 1] or unit gradients, and the range "
             "normalisation); **range used**: (max - min) / 2 of the guaranteed "
             "[-1, 1]; **range/sd**;")
    L.append("- **aniso**: `anisotropy` (whitened by a smooth fit of the radial spectrum; 0 isotropic, 1 one "
             "orientation or an axis cross), **aniso (ring)**: the old ring-by-ring whitening; **Ulichney dB**: "
             f"`ring_anisotropy` over the band, {ULICHNEY_K} seeds' periodograms averaged (an isotropic field reads "
             f"{-10 * np.log10(ULICHNEY_K):.1f} dB);")
    L.append("- **axis excess**: the band's frequency-axis cells over their rings' mean (1 isotropic); **mean spread**: "
             "sd of the row or column means over the field's sd (the larger); **striping**: (max - min) / mean of the "
             "variance folded over one lattice cell (0 stationary; spectral: folded over 8 px, the cell of a lattice peaking at 0.5 cycle/cell);")
    L.append("- **period**: the shortest exact repeat along x: a lattice line over two tables of 64 entries "
             "(`table_size=64`, in cells; the default 256 repeats after 256 cells the same way), the spectral field "
             "tiled twice (in samples: its domain).\n")
    cols = [("method", "method"), ("cells", "cells"), ("below", "below"), ("above", "above"), ("aliased", "aliased"),
            ("envelope_rms_db", "envelope dB"), ("envelope_noise_db", "noise dB"), ("variance_ratio", "var ratio"),
            ("range_used", "range used"), ("range_sd", "range/sd"), ("anisotropy", "aniso"),
            ("anisotropy_ring", "aniso (ring)"), ("ulichney_db", "Ulichney dB"), ("axis_excess", "axis excess"),
            ("mean_spread", "mean spread"), ("striping", "striping"), ("period", "period")]
    L.append("| " + " | ".join(h for _, h in cols) + " |")
    L.append("| " + " | ".join("---" for _ in cols) + " |")
    for r in img:
        cells = []
        for k, _ in cols:
            v = r.get(k)
            if k == "method":
                cells.append(str(v))
            elif k == "cells":
                cells.append("-" if v is None else str(v))
            elif k == "period":
                cells.append("none" if v is None else f"{v:g} {r['period_unit']}")
            else:
                cells.append(_f(v))
        L.append("| " + " | ".join(cells) + " |")
    L.append("")
    sp = next(r for r in img if r["family"] == "spectral")
    lat = [r for r in img if r["family"] == "lattice"]
    if lat:
        worst = max(lat, key=lambda r: r["below"] + r["above"] + r["aliased"])
        best = min(lat, key=lambda r: r["below"] + r["above"] + r["aliased"])
        L.append(f"Outside the octave: spectral {sp['outside']:.1e}; lattice from {best['outside']:.3f} ({best['method']}) "
                 f"to {worst['outside']:.3f} ({worst['method']}). Aliasing: lattice "
                 f"{min(r['aliased'] for r in lat):.1e} to {max(r['aliased'] for r in lat):.1e}. Anisotropy: spectral "
                 f"{sp['anisotropy']:.3f}, lattice {min(r['anisotropy'] for r in lat):.3f} to "
                 f"{max(r['anisotropy'] for r in lat):.3f}; Ulichney spectral {sp['ulichney_db']:.1f} dB, lattice "
                 f"{min(r['ulichney_db'] for r in lat):.1f} to {max(r['ulichney_db'] for r in lat):.1f} dB. "
                 f"Envelope error: spectral {sp['envelope_rms_db']:.2f} dB (sampling noise {sp['envelope_noise_db']:.2f} "
                 f"dB); lattice {min(r['envelope_rms_db'] for r in lat):.2f} to {max(r['envelope_rms_db'] for r in lat):.2f} "
                 "dB against the kernel's exact expectation. The noise column assumes independent cells; a lattice of "
                 "F x F cells has only F**2 independent values (fewer distinct ones when F**2 exceeds the 256-entry "
                 "table), so its own sampling error is larger: the envelope column says the kernel's spectrum is "
                 "reproduced to about that many dB, and the leakage columns how wide that spectrum is.\n")
    vol = q["volume"]
    L.append(f"### Slices of volumes (Cook & DeRose)\n")
    L.append(f"The same octave asked of a {vol[0]['n']}^3 volume (centre {vol[0]['n'] / 8:g} cycles/frame); `slice_leakage`: "
             "power under the octave in the volume (3-D radius) and in its 2-D slices (spectra of the slices "
             "perpendicular to axis 0, averaged). A slice of a band-limited volume is not band-limited: every 3-D "
             "frequency projects to a radius between 0 and itself. For the flat spectral shell the continuous law "
             "(`shell_slice_below`) is given beside it.\n")
    vcols = [("method", "method"), ("volume_below", "volume below"), ("slice_below", "slice below"),
             ("added_below", "added by slicing"), ("volume_outside", "volume outside"),
             ("slice_outside", "slice outside"), ("shell_law_below", "shell law")]
    L.append("| " + " | ".join(h for _, h in vcols) + " |")
    L.append("| " + " | ".join("---" for _ in vcols) + " |")
    for r in vol:
        L.append("| " + " | ".join(str(r[k]) if k == "method" else _f(r.get(k)) for k, _ in vcols) + " |")
    L.append("")
    mot = q["motion"]
    if mot:
        L.append("### Motion: the share of each band's power on the tent\n")
        L.append(f"`tent_energy_per_band` (octave bands across the snow band), mean +- sd over {mot[0]['seeds']} seeds; "
                 "envelope dB: `envelope_error` of the video's 3-D spectrum against the tent's own (|`snow_spectrum`| "
                 "squared with fixed amplitudes: the thickened tent with its 1/f envelope) over the cells the tent fills, "
                 "and the share of the power outside those cells, mean +- sd over the seeds. "
                 "The linear tent field is what `snow` inverts; `snow` then rescales it to [0, 1] and raises it to "
                 "beta = 1.5 (a pointwise non-linearity that spreads power off the tent).\n")
        bands = mot[0]["bands"]
        hdr = ["method"] + [f"{b[0]:g}-{b[1]:g} c/frame" for b in bands] + ["envelope dB", "power off the tent's cells"]
        L.append("| " + " | ".join(hdr) + " |")
        L.append("| " + " | ".join("---" for _ in hdr) + " |")
        for r in mot:
            cells = [r["method"]] + [f"{m:.3f} +- {s:.3f}" for m, s in zip(r["tent_mean"], r["tent_sd"])]
            cells.append(f"{r['envelope_rms_db']:.1f} +- {r['envelope_rms_db_sd']:.1f}")
            cells.append(f"{r['off_envelope']:.3f} +- {r['off_envelope_sd']:.3f}")
            L.append("| " + " | ".join(cells) + " |")
        L.append("")
    return "\n".join(L) + "\n"
