"""Falling snow with no period (sparse Gabor noise, :mod:`noiselab.gabor`): a frame, a space-time slice, the tent."""
from __future__ import annotations

import numpy as np

from ..registry import Result, figure

USES = ("noiselab.gabor", "noiselab.analysis")


@figure("lab", "gabor_snow", look="oblique streaks in the space-time slice: the coarse flakes' are steeper (faster)",
        source="The lab's own (Langer & Zhang's tent realised by moving Gabor kernels; Lagae et al. 2009)",
        title="Gabor snow with no period: a frame of frame 10**6, a y-t slice with the parallax streaks, the tent",
        params=dict(frames=64, size=256, start=10 ** 6, seed=1), quick=dict(frames=16, size=64), uses=USES)
def gabor_snow_card(out, *, frames, size, start, seed):
    from noiselab import analysis
    from noiselab.gabor import gabor_snow

    from .._common import pyplot, save_figure

    band = (size / 32, size / 4)
    alpha = gabor_snow((frames, size, size), origin=(start, 0, 0), rng=seed, width=size)
    raw = gabor_snow((frames, size, size), origin=(start, 0, 0), rng=seed, width=size, rescale=False)
    on_tent = analysis.tent_energy(raw, 1.0, band, window="hann", tol=1.5)
    plt = pyplot()
    fig, (a0, a1) = plt.subplots(1, 2, figsize=(9, 4.2))
    a0.imshow(alpha[0], cmap="gray", vmin=0, vmax=1)
    a0.set_title(f"frame {start}")
    a0.set_axis_off()
    a1.imshow(alpha[:, :, size // 2].T, cmap="gray", vmin=0, vmax=1, aspect="auto")
    a1.set_xlabel(f"frame - {start}")
    a1.set_ylabel("y (px), column x = W/2")
    a1.set_title("y-t slice: each streak's slope is a speed")
    files = [save_figure(fig, out / "gabor_snow.png")]
    return Result(files, f"Falling snow by moving Gabor kernels, {frames} frames of {size} x {size} from frame "
                         f"{start} (evaluated there directly: no block, no period), band {band[0]:g}..{band[1]:g} "
                         "cycles/frame, c = 1; right, a space-time slice down the middle column: near (coarse) "
                         "flakes cross it in steep streaks, far (fine) ones in shallow ones (motion parallax).",
                  measured={"energy on the tent (Hann taper, 1.5 bins)": float(on_tent)})
