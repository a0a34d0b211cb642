"""The lab's own comparisons: spectral against lattice noise, measured with the same instruments."""
from __future__ import annotations

import numpy as np

from ..registry import Result, figure

USES = ("noiselab.spectral", "noiselab.lattice", "noiselab.fractal", "noiselab.analysis", "noiselab.io")


@figure("lab", "one_over_f", look="the spectral texture and the gain-1 fractal sum share a -1 slope; gain 1/2 falls as -2",
        source="The lab's own comparison (no seed figure)",
        title="1/f texture: spectral synthesis beside lattice fractal sums, with radial spectra and anisotropy",
        params=dict(size=512, octaves=8, cells=4.0, gains=(1.0, 0.5), seed=21), quick=dict(size=64, octaves=4), uses=USES)
def one_over_f(out, *, size, octaves, cells, gains, seed):
    from noiselab import analysis
    from noiselab.fractal import fractal_sum
    from noiselab.lattice import LatticeNoise, Grid
    from noiselab.spectral import spectral_noise

    from .._common import pyplot, save_figure

    plt = pyplot()
    fields = {"spectral: spectral_noise, 1/f": spectral_noise((size, size), exponent=1.0, rng=seed, dtype=np.float64)}
    for g in gains:
        f, used = fractal_sum(LatticeNoise(2, rng=seed), Grid((size, size), [(0, cells), (0, cells)]), octaves,
                              gain=g, normalize=True, return_octaves=True)
        fields[f"lattice: fractal_sum, gain {g:g}, {used} octaves"] = f
    fit_band = (2 * cells, min(size / 4, cells * 2 ** (used - 1)))
    n = len(fields)
    fig, axes = plt.subplots(1, n + 2, figsize=(2.8 * (n + 2), 3.6), layout="constrained")
    measured = {}
    for ax, (name, f) in zip(axes[:n], fields.items()):
        ax.imshow(f, cmap="gray"), ax.set_title(name.replace(", ", "\n", 1), fontsize=10), ax.axis("off")
    for k, (name, f) in enumerate(fields.items()):
        short = name.split(",")[0] + ("" if k == 0 else f" g={gains[k - 1]:g}")
        # the lattice sums do not tile the frame: every field is measured through a Hann window, so no
        # wrap-around edge puts a false cross on the axes of the spectrum
        rad = analysis.radial_spectrum(f, log=True, window="hann")
        keep = rad.counts > 0
        axes[n].loglog(rad.centers[keep], np.sqrt(rad.power[keep]), label=short, color=f"C{k}")
        slope = analysis.spectral_slope(f, fit_band, window="hann")
        ori = analysis.orientation_energy(f, fit_band, window="hann")
        theta = np.concatenate([ori.angles, ori.angles + 180.0])   # degrees, wave-vector orientation
        axes[n + 1].plot(theta, np.concatenate([ori.energy, ori.energy]) / ori.energy.mean(), label=short, color=f"C{k}")
        measured[f"{short}: range"] = [float(f.min()), float(f.max())]
        measured[f"{short}: amplitude slope over {fit_band[0]:g}-{fit_band[1]:g} cycles/frame"] = float(slope)
        measured[f"{short}: anisotropy (0 = isotropic)"] = analysis.anisotropy(f, fit_band, window="hann")
    axes[n].axvspan(*fit_band, color="0.92", zorder=0)
    f0 = np.geomspace(*fit_band, 10)
    axes[n].loglog(f0, 0.3 * np.sqrt(rad.power[keep]).max() * f0[0] / f0, "k--", lw=1, label="1/f")
    axes[n].set_xlabel("cycles/frame"), axes[n].set_ylabel("radial amplitude"), axes[n].legend(fontsize=10)
    axes[n].set_title("radially averaged amplitude\nspectra (Hann window)", fontsize=10)
    axes[n + 1].set_xlabel("wave-vector orientation (degrees)"), axes[n + 1].set_ylabel("energy / mean")
    # no legend of its own (it covered the curves): the colours are the spectra's, whose legend names them
    axes[n + 1].set_xticks(range(0, 361, 90))
    axes[n + 1].set_title("energy against orientation\n(whitened; colours as in the spectra)", fontsize=10)
    return Result([save_figure(fig, out / "one_over_f.png")],
                  f"{size} x {size} textures: one with a 1/f amplitude spectrum shaped in the Fourier domain and inverted "
                  f"(noiselab.spectral_noise), and fractal sums of cubic value noise over {cells:g} lattice cells "
                  f"(lacunarity 2) with gains {', '.join(f'{g:g}' for g in gains)}. A gain g per octave gives an amplitude "
                  "spectral density slope of log2(g) - d/2 in d dimensions: in 2-D, gain 1 is the 1/f texture and "
                  "Phillips' gain 1/2 (Eq. 9) is 1/f^2 (Brownian). Right: radial amplitude spectra and energy against "
                  "orientation, all measured through a Hann window.", measured)


@figure("lab", "kernels", look="the steeper the spectrum falls past one cycle per cell, the smoother the texture looks",
        source="The lab's own comparison (Phillips 2004, Sec. 2.1.1 smoothing filters)",
        title="Value and gradient noise for every smoothing kernel: images and radial spectra",
        params=dict(size=256, cells=8.0, seed=22), quick=dict(size=64), uses=USES)
def kernels(out, *, size, cells, seed):
    from noiselab import analysis
    from noiselab.lattice import LatticeNoise, kernel_names

    from .._common import pyplot, save_figure

    plt = pyplot()
    names = kernel_names()
    fig, axes = plt.subplots(2, len(names) + 1, figsize=(1.9 * (len(names) + 1) + 1.5, 5.0), layout="constrained",
                             gridspec_kw=dict(width_ratios=[1] * len(names) + [1.7]))
    measured, rolloff = {}, {}
    for r, basis in enumerate(("value", "gradient")):
        for c, k in enumerate(names):
            img = LatticeNoise(2, rng=seed, kernel=k, basis=basis).grid((size, size), [(0, cells), (0, cells)])
            axes[r, c].imshow(img, cmap="gray", vmin=-1, vmax=1)
            axes[r, c].set_title(f"{basis} / {k}", fontsize=11), axes[r, c].axis("off")
            rad = analysis.radial_spectrum(img, log=True, window="hann")
            keep = rad.counts > 0
            axes[r, -1].loglog(rad.centers[keep] / cells, rad.power[keep], label=k, lw=1)
            measured[f"{basis}/{k}: range"] = [float(img.min()), float(img.max())]
            measured[f"{basis}/{k}: anisotropy"] = analysis.anisotropy(img, (cells / 2, min(2 * cells, size / 2 - 1)))
            band = (cells, min(4 * cells, size / 2 - 1))     # 1 to 4 cycles per lattice cell
            rolloff[f"{basis}/{k}"] = float(2 * analysis.spectral_slope(img, band, window="hann"))
        measured[f"{basis}: power slope 1-4 cycles/cell"] = ", ".join(
            f"{k}: {rolloff[f'{basis}/{k}']:.1f}" for k in names)
        axes[r, -1].set_title(f"{basis} noise: radial power\n(Hann window)", fontsize=11)
        axes[r, -1].set_ylabel("power", fontsize=11)
        axes[r, -1].set_xlabel("cycles per lattice cell", fontsize=11)
        axes[r, -1].tick_params(labelsize=11)
    # one legend for both spectra, under them, outside the plots: it covers no curve
    handles, labels = axes[0, -1].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower right", ncol=3, fontsize=11, frameon=False)
    return Result([save_figure(fig, out / "kernels.png")],
                  f"LatticeNoise over {cells:g} x {cells:g} lattice cells, {size} x {size} pixels, for each kernel, with value "
                  "(Phillips) and gradient (Perlin) bases; right: radial power spectra against frequency in cycles per "
                  "lattice cell. Power slopes from 1 to 4 cycles per cell, Hann window (the lattice band limit and above; steeper = "
                  "smoother): " + "; ".join(f"{k} {v:.1f}" for k, v in rolloff.items()) + ".", measured)


@figure("lab", "measures", look="shorter bars are better in the first three panels; in the last, the nearer the dotted line, the more isotropic",
        source="Lagae et al. 2010 (band-limitedness, anisotropy); Cook & DeRose 2005; Ulichney 1987",
        title="One octave asked of every generator: leakage, aliasing, anisotropy and Ulichney's dB",
        params=dict(size=256), quick=dict(size=64), uses=USES + ("noiselab.lab",))
def measures(out, *, size):
    from noiselab.lab.quality import generator_measures, octave_generators

    from .._common import pyplot, save_figure

    plt = pyplot()
    rows = [generator_measures(name, fam, make, info, size)
            for name, (fam, make, info) in octave_generators(size, 2).items()]
    names = [r["method"].replace(" noise, ", " ").replace("spectral_noise (flat octave)", "spectral") for r in rows]
    panels = [("outside", "power outside the octave\n(aliasing included)", True, "fraction of the power"),
              ("aliased", "power past the output's Nyquist\n(2x render)", True, "fraction of the power"),
              ("anisotropy", "anisotropy\n(0 = isotropic)", False, "anisotropy index"),
              ("ulichney_db", "Ulichney anisotropy\n(dotted: an isotropic field)", False, "dB")]
    fig, axes = plt.subplots(1, len(panels), figsize=(2.9 * len(panels) + 2.2, 0.42 * len(rows) + 2.2),
                             layout="constrained")
    measured = {}
    for ax, (key, title, log, unit) in zip(axes, panels):
        vals = np.array([r[key] for r in rows], dtype=float)
        shown = np.maximum(vals, 1e-12) if log else vals
        ax.barh(range(len(rows)), shown, color=["C3" if r["family"] == "spectral" else "C0" for r in rows])
        if log:
            ax.set_xscale("log")
        if key == "ulichney_db":  # what an isotropic Gaussian field reads with this many periodograms
            ax.axvline(rows[0]["ulichney_floor_db"], color="k", ls=":", lw=1)
        ax.set_yticks(range(len(rows)))
        ax.set_yticklabels(names if ax is axes[0] else [], fontsize=11)
        ax.set_title(title, fontsize=12)
        ax.set_xlabel(unit, fontsize=11)
        ax.tick_params(axis="x", labelsize=11)
        ax.invert_yaxis()
        for r, v in zip(rows, vals):
            measured[f"{r['method']}: {key}"] = float(v)
    return Result([save_figure(fig, out / "measures.png")],
                  f"Every generator asked for one octave around {size / 16:g} cycles/frame of a {size} x {size} frame "
                  "(noiselab.lab.quality: a flat spectral octave; lattice noise of each kernel and basis at the density "
                  "that puts its mean frequency there). Left to right: power outside the octave, power past the output's "
                  "Nyquist when the noise is rendered twice as densely (what sampling folds back; the spectral field "
                  "has none, drawn at 1e-12), the anisotropy index and Ulichney's anisotropy over 8 seeds. The "
                  "numbers for 512 x 512 are in benchmarks/RESULTS.md, section 5.", measured)


@figure("lab", "hashes", look="with the permutation every row averages the same; a 1-D line repeats after the table size, not with the integer hash",
        source="The lab's own comparison (Phillips 2004, Sec. 2.4.1 nested permutation)",
        title="The hash question: Phillips' nested permutation table against an arithmetic integer hash",
        params=dict(cells=256, spc=2, seeds=8, kernel="catmull-rom", seed=23), quick=dict(cells=32, seeds=3),
        uses=USES + ("noiselab.lab",))
def hashes(out, *, cells, spc, seeds, kernel, seed):
    from noiselab import analysis
    from noiselab.lattice import LatticeNoise
    from noiselab.lab.hashes import profile_striping

    from .._common import pyplot, save_figure

    plt = pyplot()
    n = cells * spc
    ext = [(0, cells), (0, cells)]
    make = {"table": lambda s, **kw: LatticeNoise(2, rng=s, kernel=kernel, table_size=cells, period=cells, **kw),
            "integer": lambda s, **kw: LatticeNoise(2, rng=s, kernel=kernel, hash="integer", period=cells, **kw)}
    fig, axes = plt.subplots(2, 3, figsize=(13.5, 8.4), layout="constrained")
    measured = {}
    for r, (h, mk) in enumerate(make.items()):
        imgs = np.stack([mk(seed + s).grid((n, n), ext) for s in range(seeds)])
        art = analysis.axis_artefacts(imgs[0])
        cv = profile_striping(imgs)
        axes[r, 0].imshow(imgs[0], cmap="gray", vmin=-1, vmax=1)
        axes[r, 0].set_title(f"hash={h!r}: one full period, {cells} x {cells} cells", fontsize=12)
        axes[r, 0].axis("off")
        axes[0, 1].plot(imgs[0].mean(axis=1), lw=0.8, label=f"hash={h!r}", color=f"C{r}")
        prof = np.mean(np.abs(np.fft.rfft(imgs, axis=-1)) ** 2, axis=1)[:, 1:n // 4 + 1]
        axes[1, 1].semilogy(np.arange(1, n // 4 + 1), prof[0] / prof.mean(axis=0), lw=0.8, color=f"C{r}",
                            label=f"hash={h!r}: CV {np.median(cv):.2f}")
        line = LatticeNoise(1, rng=seed, kernel=kernel, table_size=cells, hash=h).grid((16 * cells,), [(0, 4 * cells)])
        per = analysis.detect_period(line, min_lag=16)
        lags = np.arange(16, line.size // 2)
        diff = [np.mean((line[L:] - line[:-L]) ** 2) / (2 * line.var()) for L in lags]
        axes[0, 2].plot(lags / 4, diff, lw=0.8, color=f"C{r}", label=f"hash={h!r}: period "
                        + ("none" if per.period is None else f"{per.period / 4:g} cells"))
        measured[f"{h}: mean spread excess (1 = independent rows)"] = art.mean_spread_excess
        measured[f"{h}: row-mean spread x sqrt(rows)"] = art.row_mean_spread * np.sqrt(n)
        measured[f"{h}: profile CV (median over {seeds} seeds)"] = float(np.median(cv))
        measured[f"{h}: period of a 1-D line at the default period (cells)"] = None if per.period is None else per.period / 4
        measured[f"{h}: range"] = [float(imgs.min()), float(imgs.max())]
    axes[0, 1].set_title("row means of one field", fontsize=12)
    axes[0, 1].set_xlabel("row (pixels)"), axes[0, 1].set_ylabel("mean value"), axes[0, 1].legend(fontsize=10)
    axes[1, 1].set_title("row-averaged periodogram along x\n/ its mean over seeds", fontsize=12)
    # headroom above the traces (a third more decades) for the legend, which covered the first one
    lo, hi = axes[1, 1].get_ylim()
    axes[1, 1].set_ylim(lo, hi * (hi / lo) ** 0.35)
    axes[1, 1].set_xlabel("cycles/frame"), axes[1, 1].set_ylabel("ratio")
    axes[1, 1].legend(fontsize=10, loc="upper right")
    axes[0, 2].set_title("1-D line: mean squared difference\nat a lag / 2 var (0 = it repeats)", fontsize=12)
    axes[0, 2].set_xlabel("lag (cells)"), axes[0, 2].set_ylabel("ratio"), axes[0, 2].legend(fontsize=10)
    # the striping measure as bars (the numbers themselves are in the caption's details)
    keys = list(make)
    cvs = [measured[f"{h}: profile CV (median over {seeds} seeds)"] for h in keys]
    axes[1, 2].bar(keys, cvs, color=["C0", "C1"])
    axes[1, 2].axhline(1 / np.sqrt(n), color="k", ls=":", lw=1, label="1/sqrt(rows): independent rows")
    axes[1, 2].set_title("spread of the row-averaged spectrum\nover seeds (coefficient of variation)", fontsize=12)
    axes[1, 2].set_xlabel("hash"), axes[1, 2].set_ylabel("coefficient of variation"), axes[1, 2].legend(fontsize=10)
    return Result([save_figure(fig, out / "hashes.png")],
                  f"{kernel} value noise over one full period of {cells} x {cells} lattice cells ({spc} samples per cell), "
                  "addressed by Phillips' nested permutation P[(P[i] + j) mod n] (top, n = period) and by the "
                  "integer hash fmix64(key + i M0 + j M1) (bottom). With the permutation every lattice row is a "
                  "permutation of the same n values: the row means are all equal (middle top: a flat line) and a "
                  "field's row-averaged spectrum along x is one random periodogram (middle bottom: the coefficient "
                  "of variation about the mean over seeds is near 1, against about 1/sqrt(rows) for independent "
                  "rows; bottom right, as bars). Top right: a 1-D line repeats after the table size with the permutation "
                  "and not with the integer hash. Figures: benchmarks/RESULTS.md section 6.", measured)
