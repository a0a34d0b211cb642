"""The laboratory's experiments: same scene, different methods; speed against error.

Each experiment returns a list of rows (dicts with the same keys), so that the
runner (:mod:`noiselab.lab.run`) can tabulate and plot them and the tests can
check that the table is well formed. Sizes come from a :class:`Config`
(``Config.full()`` for ``benchmarks/RESULTS.md``, ``Config.quick()`` for CI).

Scenes
------
1/f texture
    A field of ``N**d`` samples whose amplitude spectrum falls as
    ``f**-(d/2)`` (equal energy per octave, the "1/f" of natural images in
    2-D) from ``f0`` cycles/frame to Nyquist. Spectral: :func:`noiselab.spectral_noise`.
    Lattice: :func:`noiselab.fractal_sum` with lacunarity 2 and gain
    ``2**(d/2 - d/2) = 1`` (equal amplitude per octave gives equal energy per
    octave), base lattice density ``f0 / lattice_peak`` cells per frame,
    octaves up to the sampling Nyquist (``fractal_sum`` skips the rest).
    Sparse Gabor (the third family): :func:`noiselab.gabor.power_law_layers`
    over the same band, one octave layer of kernels per octave.
Falling snow
    ``(T, H, W)`` frames, band ``(W/32, W/4)`` cycles/frame, ``c = 1``
    rad/frame, straight down: :func:`noiselab.snowfall.snow` (tent IFFT),
    :func:`layered_lattice_snow`, :func:`particle_snow`, and
    :func:`noiselab.gabor.gabor_snow` (moving Gabor kernels, no period).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .measure import fft_floor, fit_exponent, peak_memory, peak_rss, time_against_floor, write_floor

__all__ = ["Config", "texture_experiment", "texture_scaling", "snow_experiment", "snow_scaling", "flake_scaling",
           "pareto_sweeps", "knee", "parallax_error", "CAPABILITIES"]


@dataclass(frozen=True)
class Config:
    """Sizes and repeats of one laboratory run."""

    texture_n2: int = 512
    texture_n3: int = 96
    texture_f0: float = 4.0
    snow_shape: tuple = (64, 512, 512)
    scaling_sizes: tuple = (128, 256, 512, 1024)
    scaling_frames: int = 16
    texture_sizes: tuple = (128, 256, 512, 1024, 2048)
    flake_counts: tuple = (1_000, 10_000, 100_000, 1_000_000)
    flake_shape: tuple = (8, 256, 256)
    pareto_shape: tuple = (16, 256, 256)
    repeats: int = 5
    quick: bool = False

    @classmethod
    def full(cls):
        return cls()

    @classmethod
    def quick_config(cls):
        return cls(texture_n2=64, texture_n3=32, texture_f0=2.0, snow_shape=(8, 64, 64), scaling_sizes=(32, 64),
                   scaling_frames=4, texture_sizes=(32, 64), flake_counts=(100, 1000), flake_shape=(4, 64, 64), pareto_shape=(8, 64, 64),
                   repeats=5, quick=True)


# --------------------------------------------------------------------------- texture

def _lattice_texture(n, dim, f0, kernel, basis, seed, dtype=np.float64):
    from ..fractal import fractal_sum
    from ..lattice import Grid, LatticeNoise
    from .snowgen import lattice_peak

    cells = f0 / lattice_peak(kernel, basis)
    noise = LatticeNoise(dim, rng=seed, kernel=kernel, basis=basis)
    grid = Grid((n,) * dim, [(0.0, cells)] * dim)
    return fractal_sum(noise, grid, 60, lacunarity=2.0, gain=1.0, dtype=dtype)


def texture_methods(n, dim, f0):
    """name -> (family, callable(seed)) for the 1/f texture scene."""
    from ..lattice import kernel_names
    from ..spectral import spectral_noise

    methods = {"spectral (IFFT)": ("spectral", lambda s: spectral_noise((n,) * dim, exponent=dim / 2,
                                                                       band=(f0, n / 2), rng=s))}
    for k in kernel_names():
        methods[f"value noise, {k}"] = ("lattice", lambda s, k=k: _lattice_texture(n, dim, f0, k, "value", s))
    for k in ("quintic", "catmull-rom"):
        methods[f"gradient noise, {k}"] = ("lattice", lambda s, k=k: _lattice_texture(n, dim, f0, k, "gradient", s))
    methods["sparse Gabor, octave layers"] = ("gabor", lambda s: _gabor_texture(n, dim, f0, s))
    return methods


def _gabor_texture(n, dim, f0, seed, dtype=np.float64, density=4.0):
    from ..gabor import power_law_layers, render_layers

    layers = power_law_layers(dim=dim, exponent=dim / 2, band=(f0 / n, 0.5), density=density, rng=seed)
    return render_layers(layers, (n,) * dim, dtype=dtype)


def texture_quality(x, f0, dim):
    """Analyser figures of a 1/f texture: slope error, octave ripple, anisotropy, band leakage, range."""
    from ..analysis import anisotropy, band_energy, octave_energy, radial_spectrum, spectral_slope

    x = np.asarray(x, dtype=np.float64)
    x = (x - x.mean()) / x.std()
    n = x.shape[-1]
    target = -dim / 2.0
    slope = float(spectral_slope(x, band=(2 * f0, n / 4)))
    oe = octave_energy(x, (f0, n / 2))
    if dim == 2:
        aniso = float(anisotropy(x, band=(f0, n / 2)))
    else:
        c = n // 2
        aniso = float(np.mean([anisotropy(x[c], band=(f0, n / 2)), anisotropy(x[:, c], band=(f0, n / 2)),
                               anisotropy(x[:, :, c], band=(f0, n / 2))]))
    leak = 1.0 - band_energy(x, (f0, n / 2))
    rs = radial_spectrum(x, bins=24, log=True)
    return {"_spectrum": {"f": rs.mean_frequency.tolist(), "power": rs.power.tolist()}, "slope": slope, "slope_error": slope - target, "octave_ripple_db": oe.db_range,
            "anisotropy": aniso, "band_leakage": leak, "range_sd": float(x.max() - x.min())}


def texture_experiment(cfg: Config, *, dims=(2, 3)):
    """1/f textures, spectral against lattice, in 2-D and 3-D: quality, time, ratio to both floors, memory."""
    rows = []
    for dim in dims:
        n = cfg.texture_n2 if dim == 2 else cfg.texture_n3
        f0 = cfg.texture_f0
        methods = texture_methods(n, dim, f0)
        shape = (n,) * dim
        cases = {name: (lambda fn=fn: fn(0)) for name, (_, fn) in methods.items()}
        cases["_write_floor"] = write_floor(shape, np.float64)  # the lattice floor, timed in the same rounds
        timing = time_against_floor(cases, fft_floor(shape, np.float32), repeats=cfg.repeats)
        wf = np.array(timing["_write_floor"]["times"])
        for name, (family, fn) in methods.items():
            q = texture_quality(fn(1), f0, dim)
            rows.append({"scene": f"1/f texture {dim}-D {'x'.join(map(str, shape))}", "method": name,
                         "family": family, "dim": dim, "n": n,
                         "time_s": timing[name]["median_s"], "x_fft_floor": timing[name]["ratio"],
                         "x_write_floor": float(np.median(np.array(timing[name]["times"]) / wf)),
                         "points_per_s": n**dim / timing[name]["median_s"],
                         "peak_mib": peak_memory(lambda fn=fn: fn(2)) / 2**20, **q})
    return rows


def texture_scaling(cfg: Config):
    """Time and memory of 2-D 1/f textures against the image size: spectral vs two lattice sums."""
    from ..spectral import spectral_noise

    rows = []
    f0 = cfg.texture_f0
    for n in cfg.texture_sizes:
        cases = {"spectral (IFFT)": lambda n=n: spectral_noise((n, n), exponent=1.0, band=(f0, n / 2), rng=0),
                 "value noise, cubic": lambda n=n: _lattice_texture(n, 2, f0, "cubic", "value", 0),
                 "gradient noise, quintic": lambda n=n: _lattice_texture(n, 2, f0, "quintic", "gradient", 0)}
        timing = time_against_floor(cases, fft_floor((n, n)), repeats=cfg.repeats)
        for name, fn in cases.items():
            rows.append({"method": name, "size": n, "voxels": n * n, "time_s": timing[name]["median_s"],
                         "x_fft_floor": timing[name]["ratio"], "peak_mib": peak_memory(fn) / 2**20})
        rows.append({"method": "floor: bare irfftn", "size": n, "voxels": n * n, "time_s": timing["floor"]["median_s"],
                     "x_fft_floor": 1.0, "peak_mib": peak_memory(fft_floor((n, n))) / 2**20})
    return rows


CAPABILITIES = [
    # (capability, spectral, lattice, sparse Gabor)
    ("evaluation at arbitrary points (mesh vertices, trajectories)", "no: a whole grid at once", "yes", "yes"),
    ("unbounded domain / streaming tiles of a huge grid", "no: the output is one period",
     "yes (grid windows are bit-identical)", "yes (windows bit-identical; no period short of 2**32 cells)"),
    ("exact periodicity (seamless tiles and loops)", "yes, always", "only with period= (whole lattice cells)", "no"),
    ("exact prescribed spectrum (any envelope, sharp band edges)", "yes (round trip to float precision)",
     "no: each octave's spectrum is the kernel's, about 2 octaves wide",
     "in expectation, blurred by the kernel's lobe (closed form: expected_spectrum)"),
    ("motion envelopes (tent, motion plane) in one pass", "yes", "no: layers translated one by one",
     "yes: moving kernels, one per frequency"),
    ("bounded output without clipping", "no (Gaussian tails)", "yes: [-a, a] by construction", "no (sums of kernels)"),
    ("any number of input dimensions", "1-3 here (memory grows as N**d)", "any (tested 1-5)", "2 and 3"),
]


# --------------------------------------------------------------------------- snow

def snow_band(W):
    return (W / 32, W / 4)


def snow_methods(shape, *, layers=8, flakes=None, blur=False):
    """name -> callable(seed) for the snow scene; ``blur`` adds motion-blurred particles."""
    from ..gabor import gabor_snow
    from ..snowfall import snow
    from .snowgen import layered_lattice_snow, particle_snow

    band = snow_band(shape[2])
    methods = {
        "tent IFFT (noiselab.snow)": lambda s: snow(shape, rng=s, band=band, c=1.0),
        f"layered lattice ({layers} layers)": lambda s: layered_lattice_snow(shape, rng=s, band=band, c=1.0,
                                                                             layers=layers),
        "particles (Reeves)": lambda s: particle_snow(shape, rng=s, band=band, c=1.0, flakes=flakes),
    }
    if blur:
        methods["particles, motion-blurred (Reeves)"] = lambda s: particle_snow(shape, rng=s, band=band, c=1.0,
                                                                                flakes=flakes, motion_blur=True)
    # the third family: moving Gabor kernels, any window of an endless scene (the scene's width is the frame's)
    methods["sparse Gabor, moving kernels (noiselab.gabor)"] = lambda s: gabor_snow(shape, rng=s, band=band, c=1.0,
                                                                                    width=shape[2])
    return methods


def parallax_error(video, c, band, *, per_octave=2):
    """Speeds per band against the parallax law ``c N / (2 pi f)``.

    Returns ``(centres, measured vy, law, rms relative error)``; bands are
    ``per_octave`` per octave across ``band``, the law is taken at each band's
    power-weighted centre (:class:`noiselab.analysis.SpeedProfile`).
    """
    from ..analysis import octave_bands, speed_profile, video_spectrum

    spec = video_spectrum(video, window="hann")  # one FFT, shared by every band
    centres, speed = [], []
    for b in octave_bands(band[0], band[1], per_octave):
        try:
            prof = speed_profile(spec, [b])
        except ValueError:  # a band without power (a tiled video has gaps between its harmonics)
            continue
        centres.append(prof.centers[0])
        speed.append(prof.velocity[0, 1])
        n_ref = prof.frame_size
    if not centres:
        raise ValueError("no band of the video holds power: cannot measure the parallax curve")
    centres, speed = np.array(centres), np.array(speed)
    law = c * n_ref / (2 * np.pi * centres)
    err = float(np.sqrt(np.mean(((speed - law) / law) ** 2)))
    return centres, speed, law, err


def snow_quality(video, c, band):
    from ..analysis import loop_seam, tent_energy

    centres, speed, law, err = parallax_error(video, c, band)
    return {"tent_energy": float(tent_energy(video, c, band)), "parallax_rms_error": err,
            "loop_seam": float(loop_seam(video)), "mean_alpha": float(np.mean(video)),
            "_curve": {"f": centres.tolist(), "speed": speed.tolist(), "law": law.tolist()}}


def snow_experiment(cfg: Config):
    """Falling snow, three methods on one scene: tent energy, parallax, loop seam, time, memory."""
    shape = tuple(cfg.snow_shape)
    methods = snow_methods(shape, blur=True)
    timing = time_against_floor({k: (lambda fn=fn: fn(0)) for k, fn in methods.items()},
                                fft_floor(shape, np.float32), repeats=cfg.repeats)
    rows = []
    band = snow_band(shape[2])
    setup = "import numpy as np\nfrom noiselab.lab.experiments import snow_methods\n" \
            f"fns = list(snow_methods({shape!r}, blur=True).values())"
    for i, (name, fn) in enumerate(methods.items()):
        q = snow_quality(fn(1), 1.0, band)
        rows.append({"scene": f"falling snow {'x'.join(map(str, shape))}, band {band[0]:g}-{band[1]:g} c/frame, c=1",
                     "method": name, "time_s": timing[name]["median_s"], "x_fft_floor": timing[name]["ratio"],
                     "peak_mib": peak_memory(lambda fn=fn: fn(2)) / 2**20,
                     "rss_peak_mib": peak_rss(setup, f"fns[{i}](2)"),
                     "output_mib": int(np.prod(shape)) * 4 / 2**20, **q})
    return rows


def snow_scaling(cfg: Config):
    """Time and memory of the three snow methods as the frame size grows (fixed frame count)."""
    rows = []
    T = cfg.scaling_frames
    for W in cfg.scaling_sizes:
        shape = (T, W, W)
        methods = snow_methods(shape)
        timing = time_against_floor({k: (lambda fn=fn: fn(0)) for k, fn in methods.items()},
                                    fft_floor(shape, np.float32), repeats=cfg.repeats)
        for name, fn in methods.items():
            rows.append({"method": name, "size": W, "voxels": T * W * W, "time_s": timing[name]["median_s"],
                         "x_fft_floor": timing[name]["ratio"], "peak_mib": peak_memory(lambda fn=fn: fn(1)) / 2**20})
        rows.append({"method": "floor: bare irfftn", "size": W, "voxels": T * W * W,
                     "time_s": timing["floor"]["median_s"], "x_fft_floor": 1.0,
                     "peak_mib": peak_memory(fft_floor(shape, np.float32)) / 2**20})
    return rows


def flake_scaling(cfg: Config):
    """Particle snow time as the flake count grows (fixed frames), against the IFFT snow of the same size."""
    from ..snowfall import snow
    from .snowgen import particle_snow

    shape = tuple(cfg.flake_shape)
    band = snow_band(shape[2])
    cases = {n: (lambda n=n: particle_snow(shape, rng=0, band=band, flakes=n)) for n in cfg.flake_counts}
    cases["tent"] = lambda: snow(shape, rng=0, band=band)
    timing = time_against_floor(cases, fft_floor(shape, np.float32), repeats=cfg.repeats)
    rows = []
    for n in cfg.flake_counts:
        a = cases[n]()
        rows.append({"flakes": n, "time_s": timing[n]["median_s"], "x_fft_floor": timing[n]["ratio"],
                     "x_tent_snow": timing[n]["median_s"] / timing["tent"]["median_s"],
                     "peak_mib": peak_memory(cases[n]) / 2**20, "mean_alpha": float(a.mean())})
    return rows


def scaling_fits(rows, key="size", per="voxels"):
    """Fitted exponents of time against output size (voxels) per method.

    ``time_exponent`` over all sizes, ``time_exponent_nlogn`` of ``time / log2(size)``
    (1.0 for a clean N log N law), ``time_exponent_top`` between the two largest
    sizes only (where fixed per-call overheads no longer count), ``memory_exponent``.
    """
    from .measure import fit_nlogn

    out = []
    for m in dict.fromkeys(r["method"] for r in rows):
        rs = [r for r in rows if r["method"] == m]
        if len(rs) < 2:
            continue
        n = [r[per] for r in rs]
        t = [r["time_s"] for r in rs]
        mem = [max(r["peak_mib"], 1e-6) for r in rs]
        out.append({"method": m, "time_exponent": fit_exponent(n, t), "time_exponent_nlogn": fit_nlogn(n, t),
                    "time_exponent_top": fit_exponent(n[-2:], t[-2:]), "memory_exponent": fit_exponent(n, mem)})
    return out


# --------------------------------------------------------------------------- speed against error

def knee(points, threshold):
    """The cheapest point whose error is at most ``threshold`` (None if none is).

    ``points`` are dicts with ``time_s`` and ``error``.

    Examples
    --------
    >>> knee([{"time_s": 1, "error": 0.5}, {"time_s": 2, "error": 0.01}, {"time_s": 3, "error": 0.0}], 0.02)["time_s"]
    2
    """
    ok = [p for p in points if p["error"] is not None and p["error"] <= threshold]
    return min(ok, key=lambda p: p["time_s"]) if ok else None


def _timed(cases, floor, repeats):
    return time_against_floor(cases, floor, repeats=repeats)


def _spectral_deviation(frame, band, per_octave=4):
    """RMS deviation (dB) of a frame's radial power spectrum from the best-fitting ``f**-2`` law over ``band``."""
    from ..analysis import radial_spectrum

    edges = np.geomspace(band[0], band[1], int(round(np.log2(band[1] / band[0]) * per_octave)) + 1)
    rs = radial_spectrum(np.asarray(frame, dtype=np.float64), bins=edges, log=True)
    keep = rs.power > 0
    db = 10 * np.log10(rs.power[keep] * rs.mean_frequency[keep] ** 2)
    return float(np.sqrt(np.mean((db - db.mean()) ** 2)))


def sweep_tiles(cfg):
    """Tiled snow: render a (T, s, s) tile and tile it to the frame; error = parallax RMS error (and repeats)."""
    from ..snowfall import snow, tile

    T, H, W = cfg.pareto_shape
    band = snow_band(W)
    sizes = [s for s in (W // 8, W // 4, W // 2, W) if s >= 16]
    cases = {}
    for s in sizes:
        b = (band[0] * s / W, band[1] * s / W)
        cases[s] = (lambda s=s, b=b: tile(snow((T, s, s), rng=0, band=b), (1, W // s, W // s)))
    timing = _timed(cases, fft_floor((T, H, W)), cfg.repeats)
    pts = []
    base = None
    for s in sizes:
        v = cases[s]()
        dev = _spectral_deviation(v[0], band)
        pts.append({"setting": f"tile {s}x{s} ({(W // s) ** 2} repeats)", "time_s": timing[s]["median_s"],
                    "x_floor": timing[s]["ratio"], "error": dev, "parallax_error": parallax_error(v, 1.0, band)[3]})
        if s == W:
            base = dev
    return {"name": "tiled snow: tile size",
            "error": "spectral deviation: RMS dB of frame 0's radial spectrum from the 1/f**2 power law over the band "
                     "(4 bins per octave); visible periodicity: the repeat count",
            "threshold": base + 0.5, "points": pts,
            "note": "threshold: the untiled frame's own deviation (its sampling noise) + 0.5 dB. Tiles smaller than "
                    "the frame also repeat, which a viewer sees whatever the spectrum says: the knee is a floor on "
                    "the tile size, not a licence"}


def sweep_precision(cfg):
    """float32 against float64: snow and 2-D spectral noise (max |difference| of the output)."""
    from ..snowfall import snow
    from ..spectral import spectral_noise

    shape = tuple(cfg.pareto_shape)
    n = cfg.texture_n2
    cases = {("snow", "float32"): lambda: snow(shape, rng=0, dtype=np.float32),
             ("snow", "float64"): lambda: snow(shape, rng=0, dtype=np.float64),
             ("noise", "float32"): lambda: spectral_noise((n, n), rng=0, dtype=np.float32),
             ("noise", "float64"): lambda: spectral_noise((n, n), rng=0, dtype=np.float64)}
    timing = _timed(cases, fft_floor(shape), cfg.repeats)
    sweeps = []
    for what, label in (("snow", f"snow {'x'.join(map(str, shape))}"), ("noise", f"spectral_noise {n}x{n}")):
        ref = cases[(what, "float64")]()
        pts = []
        for prec in ("float32", "float64"):
            out = cases[(what, prec)]()
            scale = 1.0 if what == "snow" else float(ref.max() - ref.min())
            err = float(np.max(np.abs(out.astype(np.float64) - ref))) / scale
            pts.append({"setting": prec, "time_s": timing[(what, prec)]["median_s"],
                        "x_floor": timing[(what, prec)]["ratio"], "error": max(err, 1e-17),
                        "peak_mib": peak_memory(cases[(what, prec)]) / 2**20})
        sweeps.append({"name": f"precision: {label}, float32 vs float64",
                       "error": "max |difference| to float64, fraction of full range", "threshold": 1 / 510,
                       "points": pts, "note": "threshold: half a step of 8-bit output (1/510 of full range); "
                                              "floor: bare irfftn of the snow size"})
    return sweeps


def sweep_kernels(cfg):
    """Lattice 1/f texture per kernel and basis: time against a visibility score of slope error and anisotropy.

    Score ``max(|slope error| / 0.05, anisotropy / 0.1)``: at most 1 when the
    slope is within the analysers' resolution (0.05 at 512 x 512) and the
    lattice axes are not visible (anisotropy 0.1; the spectral field measures
    0.006 in ``benchmarks/RESULTS.md`` of 2026-11-23).
    """
    n, f0 = cfg.texture_n2, cfg.texture_f0
    methods = {k: fn for k, (fam, fn) in texture_methods(n, 2, f0).items() if fam == "lattice"}
    pts = _texture_visibility(methods, cfg, "octave_ripple_db")
    return {"name": "lattice kernel (2-D 1/f texture)", "error": "max(|slope error| / 0.05, anisotropy / 0.1)",
            "threshold": 1.0, "points": pts,
            "note": "0.05: the analysers' slope resolution at 512 x 512; 0.1: anisotropy where the lattice axes show"}


def _texture_visibility(methods, cfg, extra):
    """Time (rendering ``fn(0)``, against the write floor) and the visibility score of ``fn(1)`` per method.

    The score is ``max(|slope error| / 0.05, anisotropy / 0.1)`` of the 2-D 1/f
    texture; ``extra`` names one more figure of :func:`texture_quality` to keep.
    """
    n, f0 = cfg.texture_n2, cfg.texture_f0
    timing = _timed({k: (lambda fn=fn: fn(0)) for k, fn in methods.items()}, write_floor((n, n)), cfg.repeats)
    pts = []
    for k, fn in methods.items():
        q = texture_quality(fn(1), f0, 2)
        pts.append({"setting": k, "time_s": timing[k]["median_s"], "x_floor": timing[k]["ratio"],
                    "error": max(abs(q["slope_error"]) / 0.05, q["anisotropy"] / 0.1),
                    "slope_error": q["slope_error"], "anisotropy": q["anisotropy"], extra: q[extra]})
    return pts


def sweep_families(cfg):
    """The three families on the 2-D 1/f texture: time against :func:`sweep_kernels`' visibility score.

    Spectral (IFFT), every lattice sum of :func:`texture_methods`, and sparse
    Gabor octave layers at 1, 2, 4 and 8 impulses per cell (its knob: more
    kernels, a more Gaussian field, more time).
    """
    n, f0 = cfg.texture_n2, cfg.texture_f0
    methods = {k: fn for k, (fam, fn) in texture_methods(n, 2, f0).items() if fam in ("spectral", "lattice")}
    for d in (1.0, 2.0, 4.0, 8.0):
        methods[f"sparse Gabor, {d:g} impulses/cell"] = lambda s, d=d: _gabor_texture(n, 2, f0, s, density=d)
    pts = _texture_visibility(methods, cfg, "band_leakage")
    return {"name": "three families (2-D 1/f texture)", "error": "max(|slope error| / 0.05, anisotropy / 0.1)",
            "threshold": 1.0, "points": pts,
            "note": "the same score as the lattice kernel sweep; floor: writing the output array"}


def sweep_octaves(cfg):
    """Fractal sum with o octaves against the full (Nyquist-limited) sum: RMS difference / RMS of the full sum."""
    from ..fractal import fractal_sum
    from ..lattice import Grid, LatticeNoise

    n = cfg.texture_n2
    noise = LatticeNoise(2, rng=0, kernel="cubic")
    grid = Grid((n, n), [(0.0, 4.0)] * 2)
    full, used = fractal_sum(noise, grid, 60, return_octaves=True)
    octs = list(range(1, used + 1))
    cases = {o: (lambda o=o: fractal_sum(noise, grid, o)) for o in octs}
    timing = _timed(cases, write_floor((n, n)), cfg.repeats)
    rms = float(np.sqrt(np.mean(full**2)))
    pts = []
    for o in octs:
        err = float(np.sqrt(np.mean((cases[o]() - full) ** 2))) / rms
        pts.append({"setting": f"{o} octaves", "time_s": timing[o]["median_s"], "x_floor": timing[o]["ratio"],
                    "error": max(err, 1e-17)})
    return {"name": f"fractal sum: octaves (gain 1/2, {used} visible of 60)",
            "error": "RMS difference to the full sum / its RMS", "threshold": 2 / 255,
            "points": pts, "note": "threshold: half an 8-bit level when +-2 sd spans 0..255 (RMS 2/255 of the sd)"}


def sweep_layers(cfg):
    """Layered lattice snow: depth layers against tent energy and parallax."""
    from .snowgen import layered_lattice_snow

    shape = tuple(cfg.pareto_shape)
    band = snow_band(shape[2])
    counts = (2, 4, 8, 16) if not cfg.quick else (2, 4)
    cases = {k: (lambda k=k: layered_lattice_snow(shape, rng=0, band=band, layers=k)) for k in counts}
    timing = _timed(cases, fft_floor(shape), cfg.repeats)
    pts = []
    for k in counts:
        q = snow_quality(cases[k](), 1.0, band)
        pts.append({"setting": f"{k} layers", "time_s": timing[k]["median_s"], "x_floor": timing[k]["ratio"],
                    "error": q["parallax_rms_error"], "tent_energy": q["tent_energy"]})
    return {"name": "layered lattice snow: depth layers", "error": "parallax RMS relative error",
            "threshold": 0.10, "points": pts, "note": "tent energy in the extra column"}


def sweep_fft(cfg):
    """FFT backends for the snow-sized inverse FFT: numpy, scipy (1 and all workers), pyfftw if installed."""
    import os

    import scipy.fft

    shape = tuple(cfg.pareto_shape)
    half = shape[:-1] + (shape[-1] // 2 + 1,)
    rng = np.random.default_rng(0)
    spec64 = rng.standard_normal(half) + 1j * rng.standard_normal(half)
    spec32 = spec64.astype(np.complex64)
    ref = np.fft.irfftn(spec64, s=shape)
    workers = os.cpu_count() or 1
    cases = {"numpy.fft complex128": lambda: np.fft.irfftn(spec64, s=shape),
             "numpy.fft complex64": lambda: np.fft.irfftn(spec32, s=shape),
             "scipy.fft complex64, 1 worker": lambda: scipy.fft.irfftn(spec32, s=shape, workers=1),
             f"scipy.fft complex64, {workers} workers": lambda: scipy.fft.irfftn(spec32, s=shape, workers=workers),
             "scipy.fft complex128, 1 worker": lambda: scipy.fft.irfftn(spec64, s=shape, workers=1)}
    missing = []
    try:
        import pyfftw.interfaces.scipy_fft as pf  # noqa: F401

        cases[f"pyfftw complex64, {workers} threads"] = lambda: pf.irfftn(spec32, s=shape, workers=workers)
    except ImportError as exc:
        missing.append(f"pyfftw not installed ({exc})")
    timing = _timed(cases, fft_floor(shape), cfg.repeats)
    scale = float(ref.max() - ref.min())
    pts = []
    for k, fn in cases.items():
        err = float(np.max(np.abs(fn().astype(np.float64) - ref))) / scale
        pts.append({"setting": k, "time_s": timing[k]["median_s"], "x_floor": timing[k]["ratio"],
                    "error": max(err, 1e-17)})
    note = "floor = scipy.fft.irfftn complex64, scipy's default of 1 worker" + ("; " + "; ".join(missing) if missing else "")
    return {"name": f"FFT backend (irfftn {'x'.join(map(str, shape))})",
            "error": "max |difference| to numpy complex128, fraction of range", "threshold": 1 / 510,
            "points": pts, "note": note}


def pareto_sweeps(cfg: Config):
    """All the speed-against-error sweeps; each with its points, threshold and knee."""
    sweeps = [sweep_tiles(cfg), *sweep_precision(cfg), sweep_kernels(cfg), sweep_families(cfg), sweep_octaves(cfg),
              sweep_layers(cfg), sweep_fft(cfg)]
    for s in sweeps:
        k = knee(s["points"], s["threshold"])
        s["knee"] = k["setting"] if k else None
    return sweeps
