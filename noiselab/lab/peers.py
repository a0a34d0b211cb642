"""The peers, side by side in one process: time, peak memory, points/s and the same analyser figures.

Run inside the peer environment (``benchmarks/.venv-peers``, built by
``bash benchmarks/setup_peers.sh``; it sees noiselab through the system
site-packages)::

    PYTHONPATH=. benchmarks/.venv-peers/bin/python -m noiselab.lab.peers --n 512 --json /tmp/peers.json

:func:`noiselab.lab.run.run_all` does this for ``noiselab bench``. A peer that
fails to import or to run is reported with its error, never dropped.

Cases (every one an ``n x n`` image unless said):

- spectral 1/f fields (target: amplitude ``1/f`` in 2-D, slope -1): noiselab
  ``spectral_noise``, powerbox (``P(k) = k**-2``), colorednoise
  (``powerlaw_psd_gaussian(2, (n, n))``: 1-D along rows only), stimupy
  ``one_over_f``;
- spectral video ``(T, n/2, n/2)``: MotionClouds (speed-plane envelope
  ``V_Y = 1``, the comparable envelope) against noiselab ``snow``;
- lattice, one octave (Perlin/gradient noise, 32 cells across) and six
  octaves (gain 1/2, 8 cells across at the base; target slope -2): noiselab
  ``LatticeNoise.grid``/``fractal_sum`` (gradient, quintic), noise
  (``pnoise2``, a Python loop per point), pyfastnoiselite, opensimplex,
  vnoise, perlin-numpy, VTK's ``vtkPerlinNoise`` via pyvista (one octave only),
  pyfastnoisesimd (needs ``numpy.product``, removed in NumPy 2: shimmed here);
  pyfastnoiselite and pyfastnoisesimd also with their value noise, beside
  noiselab's value noise (float32 output).
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import traceback

import numpy as np

CELLS_1 = 32  # lattice cells across the frame, one octave
CELLS_6 = 8  # base cells across the frame, six octaves


def _coords(n, cells):
    return np.arange(n, dtype=np.float64) * (cells / n)


# ----------------------------------------------------------------------- spectral 1/f fields

def spectral_cases(n):
    def noiselab_spectral():
        from noiselab.spectral import spectral_noise

        return spectral_noise((n, n), exponent=1.0, band=(1, n / 2), rng=0)

    def powerbox():
        import powerbox as pb

        return pb.PowerBox(N=n, dim=2, pk=lambda k: k**-2.0, boxlength=float(n), seed=0).delta_x()

    def colorednoise():
        import colorednoise as cn

        return cn.powerlaw_psd_gaussian(2, (n, n), random_state=0)

    def stimupy():
        from stimupy.noises.naturals import one_over_f

        return one_over_f(shape=(n, n), ppd=1, exponent=1.0, rng=np.random.default_rng(0))["img"]

    return {"noiselab spectral_noise": noiselab_spectral, "powerbox": powerbox,
            "colorednoise (1-D per row)": colorednoise, "stimupy one_over_f": stimupy}


def video_cases(n, frames):
    m = n // 2

    def motionclouds():
        import MotionClouds as mc

        fx, fy, ft = mc.get_grids(m, m, frames)
        env = mc.envelope_gabor(fx, fy, ft, V_X=0.0, V_Y=1.0, B_V=0.5, sf_0=0.125, B_sf=0.1)
        z = mc.rectif(mc.random_cloud(env, seed=0))
        return np.ascontiguousarray(np.transpose(z, (2, 1, 0)))  # (x, y, t) -> (t, y, x)

    def noiselab_snow():
        from noiselab.snowfall import snow

        return snow((frames, m, m), rng=0)

    return {"MotionClouds": motionclouds, "noiselab snow": noiselab_snow}


# ----------------------------------------------------------------------- lattice

def lattice_cases(n, octaves):
    cells = CELLS_1 if octaves == 1 else CELLS_6
    x = _coords(n, cells)

    def noiselab_lattice():
        from noiselab.fractal import fractal_sum
        from noiselab.lattice import Grid, LatticeNoise

        noise = LatticeNoise(2, rng=0, kernel="quintic", basis="gradient")
        if octaves == 1:
            return noise.grid((n, n), [(0, cells), (0, cells)])
        return fractal_sum(noise, Grid((n, n), [(0, cells), (0, cells)]), octaves)

    def noiselab_value32():
        from noiselab.fractal import fractal_sum
        from noiselab.lattice import Grid, LatticeNoise

        noise = LatticeNoise(2, rng=0, kernel="cubic")
        if octaves == 1:
            return noise.grid((n, n), [(0, cells), (0, cells)], dtype=np.float32)
        return fractal_sum(noise, Grid((n, n), [(0, cells), (0, cells)]), octaves, dtype=np.float32)

    def noise_pkg():
        import noise

        xs = x.tolist()
        out = np.empty((n, n))
        p = noise.pnoise2
        for i, yv in enumerate(xs):
            out[i] = [p(xv, yv, octaves) for xv in xs]
        return out

    def fastnoiselite(kind="NoiseType_Perlin"):
        from pyfastnoiselite.pyfastnoiselite import FastNoiseLite, FractalType, NoiseType

        f = FastNoiseLite(0)
        f.noise_type = getattr(NoiseType, kind)
        f.frequency = 1.0
        if octaves > 1:
            f.fractal_type = FractalType.FractalType_FBm
            f.fractal_octaves = octaves
        yy, xx = np.meshgrid(x, x, indexing="ij")
        return f.gen_from_coords(np.stack([xx.ravel(), yy.ravel()]).astype(np.float32)).reshape(n, n)

    def opensimplex():
        import opensimplex

        opensimplex.seed(0)
        out = np.zeros((n, n))
        for o in range(octaves):
            out += 0.5**o * opensimplex.noise2array(x * 2**o, x * 2**o)
        return out

    def vnoise():
        import vnoise

        return vnoise.Noise(0).noise2(x, x, octaves=octaves, grid_mode=True)

    def perlin_numpy():
        from perlin_numpy import generate_fractal_noise_2d, generate_perlin_noise_2d

        np.random.seed(0)  # perlin-numpy draws from numpy's global state
        if octaves == 1:
            return generate_perlin_noise_2d((n, n), (cells, cells))
        return generate_fractal_noise_2d((n, n), (cells, cells), octaves)

    def vtk_perlin():
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
        import pyvista as pv

        if octaves != 1:
            raise NotImplementedError("vtkPerlinNoise has no octaves (one frequency per function)")
        f = pv.perlin_noise(1.0, (cells / n, cells / n, 1.0), (0.0, 0.0, 0.0))
        g = pv.sample_function(f, bounds=(0, n - 1, 0, n - 1, 0, 0), dim=(n, n, 1))
        return np.asarray(g.active_scalars).reshape(n, n)

    def fastnoisesimd(kind="Perlin"):
        if not hasattr(np, "product"):
            np.product = np.prod  # shim: removed in NumPy 2, still used by pyfastnoisesimd 0.4.2
        import pyfastnoisesimd as fns

        f = fns.Noise(seed=0, numWorkers=1)
        f.noiseType = getattr(fns.NoiseType, kind)
        f.frequency = cells / n
        if octaves > 1:
            f.noiseType = getattr(fns.NoiseType, kind + "Fractal")
            f.fractal.octaves = octaves
            f.fractal.fractalType = fns.FractalType.FBM
        return f.genAsGrid([1, n, n])[0]

    return {"noiselab (gradient, quintic, float64)": noiselab_lattice,
            "noiselab (value, cubic, float32)": noiselab_value32,
            "noise (pnoise2, per point)": noise_pkg, "pyfastnoiselite (Perlin)": fastnoiselite,
            "pyfastnoiselite (value)": lambda: fastnoiselite("NoiseType_Value"),
            "opensimplex": opensimplex, "vnoise": vnoise, "perlin-numpy": perlin_numpy,
            "VTK vtkPerlinNoise (pyvista)": vtk_perlin, "pyfastnoisesimd (Perlin, np.product shim)": fastnoisesimd,
            "pyfastnoisesimd (value, np.product shim)": lambda: fastnoisesimd("Value")}


# ----------------------------------------------------------------------- measurement

def _version(mod):
    try:
        from importlib.metadata import version

        return version(mod)
    except Exception:  # noqa: BLE001 - any failure means "unknown"
        return "not installed"


PACKAGES = ["powerbox", "colorednoise", "stimupy", "MotionClouds", "noise", "pyfastnoiselite", "opensimplex",
            "vnoise", "perlin-numpy", "pyvista", "vtk", "pyfastnoisesimd", "pyfftw", "numpy", "scipy"]


def image_quality(img, target_slope, band):
    from noiselab.analysis import anisotropy, octave_energy, spectral_slope

    x = np.asarray(img, dtype=np.float64)
    if not np.all(np.isfinite(x)):
        return {"error": "non-finite output"}
    q = {"min": float(x.min()), "max": float(x.max())}
    x = x - x.mean()
    sd = x.std()
    if sd == 0:
        return {**q, "error": "constant output"}
    x = x / sd
    s = float(spectral_slope(x, band=band))
    q.update({"slope": s, "slope_error": s - target_slope, "anisotropy": float(anisotropy(x, band=band)),
              "octave_ripple_db": octave_energy(x, band).db_range})
    from noiselab.analysis import axis_artefacts, band_leakage

    art = axis_artefacts(x, band, window="hann")  # peers' fields do not tile: the window keeps the edge off the axes
    q.update({"outside_band": band_leakage(x, band, window="hann").outside, "axis_excess": art.axis_excess,
              "mean_spread": max(art.row_mean_spread, art.column_mean_spread)})
    return q


def video_quality(v):
    from noiselab.analysis import best_velocity, loop_seam, motion_energy

    v = np.asarray(v, dtype=np.float64)
    vel = best_velocity(v)
    return {"best_velocity": [float(vel[0]), float(vel[1])], "motion_energy_v(0,1)": float(motion_energy(v, velocity_yx=(1, 0))),
            "loop_seam": float(loop_seam(v))}


def run_group(name, cases, shape, floor_kind, repeats, quality):
    from noiselab.lab.measure import fft_floor, peak_memory, time_against_floor, write_floor

    ok, rows = {}, []
    for label, fn in cases.items():
        try:
            out = fn()
            arr = np.asarray(out)
            if arr.shape != tuple(shape):
                raise ValueError(f"returned shape {arr.shape}, expected {tuple(shape)}")
            ok[label] = (fn, arr)
        except Exception as exc:  # noqa: BLE001 - a failing peer is reported, not dropped
            rows.append({"group": name, "case": label, "status": "failed",
                         "error": f"{type(exc).__name__}: {exc}".splitlines()[0][:200]})
    floor = fft_floor(shape, np.float32) if floor_kind == "fft" else write_floor(shape, np.float64)
    timing = time_against_floor({k: v[0] for k, v in ok.items()}, floor, repeats=repeats)
    size = int(np.prod(shape))
    for label, (fn, arr) in ok.items():
        try:
            q = quality(arr)
        except Exception as exc:  # noqa: BLE001
            q = {"quality_error": f"{type(exc).__name__}: {exc}"[:200]}
        rows.append({"group": name, "case": label, "status": "ok", "dtype": str(arr.dtype),
                     "time_s": timing[label]["median_s"], "x_floor": timing[label]["ratio"],
                     "floor": "bare irfftn (float32)" if floor_kind == "fft" else "write float64 array",
                     "points_per_s": size / timing[label]["median_s"], "peak_mib": peak_memory(fn) / 2**20, **q})
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=512, help="image size n x n (default 512)")
    ap.add_argument("--frames", type=int, default=32, help="video frames (video size frames x n/2 x n/2)")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--json", required=True, help="write the rows here")
    args = ap.parse_args(argv)
    n = args.n
    band = (2.0, n / 4)
    rows = []
    rows += run_group(f"1/f image {n}x{n}", spectral_cases(n), (n, n), "fft", args.repeats,
                      lambda a: image_quality(a, -1.0, band))
    rows += run_group(f"spectral video {args.frames}x{n // 2}x{n // 2}", video_cases(n, args.frames),
                      (args.frames, n // 2, n // 2), "fft", args.repeats, video_quality)
    rows += run_group(f"lattice 1 octave {n}x{n} ({CELLS_1} cells)", lattice_cases(n, 1), (n, n), "write",
                      args.repeats, lambda a: image_quality(a, float("nan"), (CELLS_1 / 2, 2.0 * CELLS_1)))
    rows += run_group(f"lattice 6 octaves {n}x{n} ({CELLS_6} base cells, gain 1/2)", lattice_cases(n, 6), (n, n),
                      "write", args.repeats, lambda a: image_quality(a, -2.0, (2 * CELLS_6, n / 4)))
    info = {"python": sys.version.split()[0], "versions": {p: _version(p) for p in PACKAGES}}
    with open(args.json, "w") as fh:
        json.dump({"info": info, "rows": rows}, fh, indent=1, default=float)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except Exception:  # noqa: BLE001
        traceback.print_exc()
        sys.exit(1)
