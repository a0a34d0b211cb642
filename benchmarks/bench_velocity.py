"""Calibration: how often ``noiselab.testing.assert_velocity`` passes motion clouds at, and 5 % off, their velocity.

Run from the repository root (MotionClouds comes with the ``test`` extra)::

    python3 benchmarks/bench_velocity.py              # 30 seeds per row, writes benchmarks/bench_velocity.md
    python3 benchmarks/bench_velocity.py --seeds 4    # a smoke test (writes nothing)

Videos of 64 frames of 128 x 128 px moving at (vx, vy) = (1, 0.5) px/frame,
``sf_0 = 0.125``, ``B_sf = 0.05`` cycles/px, isotropic, at speed bandwidths
``B_V`` 0.05, 0.25, 0.5 (MotionClouds' default) and 1.0 px/frame: noiselab's
``noiselab.stimuli.motion_cloud`` and MotionClouds' own ``envelope_gabor`` +
``random_cloud`` (arrays ``(x, y, t)`` turned into ``(t, y, x)``). Each video is
checked at the true velocity (default tolerance, ``false_alarm`` 1e-3 and 0.05),
and 5 % too fast and too slow (both components times 1.05 or 0.95, default
tolerance). ``z rms`` is the root mean square of ``(measured - true) / se`` over
both components and the seeds: 1 when the standard errors are honest.
"""
from __future__ import annotations

import argparse
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

SHAPE = (64, 128, 128)
VX, VY = 1.0, 0.5
B_VS = (0.05, 0.25, 0.5, 1.0)


def noiselab_cloud(B_V, seed):
    return motion_cloud(SHAPE, sf_0=0.125, B_sf=0.05, V_X=VX, V_Y=VY, B_V=B_V, rng=seed)


def mc_cloud(B_V, seed):
    t, h, w = SHAPE
    fx, fy, ft = mc.get_grids(w, h, t)
    env = mc.envelope_gabor(fx, fy, ft, V_X=VX, V_Y=VY, B_V=B_V, sf_0=0.125, B_sf=0.05, B_theta=np.inf)
    return np.transpose(mc.random_cloud(env, seed=seed), (2, 1, 0))


def passes(video, vx, vy, **kw):
    try:
        return True, T.assert_velocity(video, vx=vx, vy=vy, **kw)
    except AssertionError:
        return False, None


def row(name, make, B_V, seeds):
    true3 = true05 = fast = slow = 0
    z, tol = [], []
    for s in range(seeds):
        video = make(B_V, s)
        ok, check = passes(video, VX, VY)
        true3 += ok
        check = check or T.assert_velocity(video, vx=VX, vy=VY, tol=1e9)  # the measurement, whatever the verdict
        z += [(check.vx - VX) / check.se_vx, (check.vy - VY) / check.se_vy]
        tol.append(check.tol_vx)
        true05 += passes(video, VX, VY, false_alarm=0.05)[0]
        fast += passes(video, 1.05 * VX, 1.05 * VY)[0]
        slow += passes(video, 0.95 * VX, 0.95 * VY)[0]
    rate = lambda k: f"{k}/{seeds}"  # noqa: E731
    return [name, f"{B_V:g}", rate(true3), rate(true05), rate(fast), rate(slow),
            f"{np.sqrt(np.mean(np.square(z))):.2f}", f"{np.median(tol):.3g}"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=30)
    args = ap.parse_args()
    cmd = "python3 benchmarks/bench_velocity.py" + ("" if args.seeds == 30 else f" --seeds {args.seeds}")
    info = run_info(cmd, ["scipy", "noiselab", "MotionClouds"])
    t0 = time.process_time()
    rows = [row(name, make, b, args.seeds) for name, make in (("noiselab motion_cloud", noiselab_cloud),
                                                              ("MotionClouds", mc_cloud)) for b in B_VS]
    cpu = time.process_time() - t0
    text = "\n".join([
        "# noiselab.testing.assert_velocity: pass rates on motion clouds", "",
        *header_lines(info),
        f"- CPU time of the run: {cpu:.0f} s", "",
        (f"Videos {SHAPE[0]} frames x {SHAPE[1]} x {SHAPE[2]} px moving at (vx, vy) = ({VX:g}, {VY:g}) px/frame, "
         f"sf_0 0.125, B_sf 0.05 cycles/px, isotropic; {args.seeds} seeds per row. Pass counts at the true velocity "
         "(default tolerance: false_alarm 1e-3, and at false_alarm 0.05), and at a speed 5 % too fast (x 1.05) and "
         "too slow (x 0.95) with the default tolerance (a pass there is a miss). 'z rms': root mean square of "
         "(measured - true) / standard error over both components (1 for honest standard errors); 'tol vx': the "
         "median default tolerance on vx, px/frame (5 % of vx is 0.05)."), "",
        *markdown_table(["cloud", "B_V (px/frame)", "pass, true (1e-3)", "pass, true (0.05)", "pass, +5 %",
                         "pass, -5 %", "z rms", "tol vx"], rows, align="lrrrrrrr"),
        ""])
    print(text)
    if args.seeds == 30:
        (ROOT / "benchmarks" / "bench_velocity.md").write_text(text)


if __name__ == "__main__":
    main()
