"""Bias of ``assert_velocity`` on motion clouds whose speed band reaches the temporal Nyquist frequency.

Run from the repository root (MotionClouds comes with the ``test`` extra)::

    python3 benchmarks/bench_velocity_bias.py              # writes benchmarks/bench_velocity_bias.md
    python3 benchmarks/bench_velocity_bias.py --seeds 5    # a smoke test (writes nothing)

Clouds moving at (vx, vy) = (1, 0.5) px/frame, isotropic, with a narrow band
(``sf_0`` 0.125, ``B_sf`` 0.05 cycles/px) and a broad one (``sf_0`` 0.15,
``B_sf`` 0.1: power up to about 0.4 cycles/px), at ``B_V`` 0.1, 0.5 and 1.0
px/frame; noiselab's ``motion_cloud`` and MotionClouds' ``envelope_gabor`` +
``random_cloud``. Both synthesise the speed band ``exp(-(ft + v.f)**2 / (2
(B_V |f|)**2))`` on the temporal frequencies of the grid, ``[-1/2, 1/2)``
cycles/frame: where ``|v.f| + 2 B_V |f|`` passes 1/2 the band is cut there
(not wrapped), and the circular mean of that cell's temporal spectrum, which
the velocity fit reads, moves towards 0. ``band cut`` measures within
``band=(1, N / 2 / (|v| + 2 B_V))`` cycles/frame, where the band fits.
'bias': mean of (measured - true) / true over the seeds, with its standard
error; 'z mean': mean of (measured - true) / se (0 for an unbiased fit); 'pass':
the default tolerance (false_alarm 1e-3) at the true velocity.
"""
from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import MotionClouds as mc  # noqa: E402

from noiselab import testing as T  # noqa: E402
from noiselab.lab.measure import header_lines, markdown_table, run_info  # noqa: E402
from noiselab.stimuli import motion_cloud  # noqa: E402

VX, VY = 1.0, 0.5
BANDS = {"narrow": (0.125, 0.05), "broad": (0.15, 0.1)}


def nl(shape, seed, sf_0, B_sf, B_V):
    return motion_cloud(shape, sf_0=sf_0, B_sf=B_sf, V_X=VX, V_Y=VY, B_V=B_V, rng=seed)


def mcloud(shape, seed, sf_0, B_sf, B_V):
    t, h, w = shape
    fx, fy, ft = mc.get_grids(w, h, t)
    env = mc.envelope_gabor(fx, fy, ft, V_X=VX, V_Y=VY, B_V=B_V, sf_0=sf_0, B_sf=B_sf, B_theta=np.inf)
    return np.transpose(mc.random_cloud(env, seed=seed), (2, 1, 0))


def row(name, make, shape, band_name, B_V, cut, seeds):
    sf_0, B_sf = BANDS[band_name]
    band = (1.0, shape[-1] / 2 / (math.hypot(VX, VY) + 2 * B_V)) if cut else None
    rel, z, ok = [], [], 0
    for s in range(seeds):
        video = make(shape, s, sf_0, B_sf, B_V)
        c = T.assert_velocity(video, vx=VX, vy=VY, tol=1e9, band=band)
        rel.append([(c.vx - VX) / VX, (c.vy - VY) / VY])
        z.append([(c.vx - VX) / c.se_vx, (c.vy - VY) / c.se_vy])
        try:
            T.assert_velocity(video, vx=VX, vy=VY, band=band)
            ok += 1
        except AssertionError:
            pass
    rel, z = np.array(rel), np.array(z)
    sem = rel.std(axis=0) / math.sqrt(seeds)
    return [name, "x".join(map(str, shape)), band_name, f"{B_V:g}", "all" if band is None else f"1 .. {band[1]:.3g}",
            f"{100 * rel[:, 0].mean():+.2f} ± {100 * sem[0]:.2f} %",
            f"{100 * rel[:, 1].mean():+.2f} ± {100 * sem[1]:.2f} %",
            f"{z[:, 0].mean():+.2f}, {z[:, 1].mean():+.2f}", f"{ok}/{seeds}"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=100)
    args = ap.parse_args()
    small, large = (32, 64, 64), (64, 128, 128)
    big_seeds = max(1, args.seeds * 3 // 10)
    cmd = "python3 benchmarks/bench_velocity_bias.py" + ("" if args.seeds == 100 else f" --seeds {args.seeds}")
    info = run_info(cmd, ["scipy", "noiselab", "MotionClouds"])
    t0 = time.process_time()
    rows = []
    for name, make in (("noiselab motion_cloud", nl), ("MotionClouds", mcloud)):
        for band_name in BANDS:
            for B_V in (0.1, 0.5, 1.0):
                rows.append(row(name, make, small, band_name, B_V, False, args.seeds))
        for B_V in (0.5, 1.0):
            rows.append(row(name, make, small, "broad", B_V, True, args.seeds))
    for B_V in (0.5, 1.0):
        for cut in (False, True):
            rows.append(row("noiselab motion_cloud", nl, large, "broad", B_V, cut, big_seeds))
    cpu = time.process_time() - t0
    text = "\n".join([
        "# noiselab.testing.assert_velocity: bias where a cloud's speed band meets the temporal Nyquist frequency", "",
        *header_lines(info),
        f"- CPU time of the run: {cpu:.0f} s", "",
        (f"Clouds moving at (vx, vy) = ({VX:g}, {VY:g}) px/frame; narrow band sf_0 0.125, B_sf 0.05 cycles/px, broad "
         f"band sf_0 0.15, B_sf 0.1; {args.seeds} seeds per row at 32x64x64, {big_seeds} at 64x128x128. 'bias': mean "
         "relative error of vx and vy with its standard error; 'z mean': mean of (measured - true) / se per "
         "component; 'pass': the default tolerance (false_alarm 1e-3) at the true velocity. 'band': all spatial "
         "frequencies, or 1 .. N / 2 / (|v| + 2 B_V) cycles/frame, where the speed band stays below the temporal "
         "Nyquist frequency."), "",
        *markdown_table(["cloud", "frames x px", "band", "B_V", "band (cycles/frame)", "bias vx", "bias vy", "z mean",
                         "pass"], rows, align="lllrlrrrr"),
        "",
        ("Reading (the figures of the run recorded here): the narrow band stays below the temporal Nyquist "
         "frequency and reads within 0.5 % (z mean within 0.22); the broad band reads 0.8 to 1.3 % slow at B_V 0.5 "
         "and 4.4 to 5.2 % slow at B_V 1, for noiselab's clouds and MotionClouds' alike, at 32x64x64 as at "
         "64x128x128, where the larger video's smaller standard errors make it fail at the true velocity (7 and "
         "0 of 30 pass). Within the band where the speed band fits, the bias is within its standard error "
         "(|z mean| <= 0.26) and the truth passes. At 32x64x64 the rows without bias failed at the truth 7 times "
         "in 1200 checks (false_alarm 1e-3 would give about 1): the small video's standard errors are a little "
         "optimistic."),
        ""])
    print(text)
    if args.seeds == 100:
        (ROOT / "benchmarks" / "bench_velocity_bias.md").write_text(text)


if __name__ == "__main__":
    main()
