"""Draw docs/_static/noiselab.png, the README's picture (run from the repository root; about 40 KB).

Three panels: a frame of falling snow composited over noiselab's landscape, a
lattice fractal sum, and the snow video's x-t slice (the flakes' streaks).
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402

import noiselab  # noqa: E402
from noiselab.lattice import Grid  # noqa: E402
from noiselab.snowfall.background import default_background  # noqa: E402

alpha = noiselab.snow((32, 160, 160), rng=1)
frame = noiselab.composite(alpha, default_background(160, 160))[0]
terrain = noiselab.fractal_sum(noiselab.LatticeNoise(2, rng=2, kernel="quintic", basis="gradient"),
                               Grid((160, 160), ((0, 4), (0, 4))), 6)
fig, axes = plt.subplots(1, 3, figsize=(6, 2.1), dpi=100)
axes[0].imshow(frame, cmap="gray" if frame.ndim == 2 else None)
axes[0].set_title("falling snow (spectral)", fontsize=8)
axes[1].imshow(terrain, cmap="terrain")
axes[1].set_title("fractal sum (lattice)", fontsize=8)
axes[2].imshow(alpha[:, :, 80], cmap="gray", aspect="auto")
axes[2].set_title("snow: frames (down) by y", fontsize=8)
for ax in axes:
    ax.set_xticks([])
    ax.set_yticks([])
fig.tight_layout(pad=0.3)
fig.canvas.draw()
# 64 colours keep the file small enough to commit (about 60 KB instead of 160)
image = Image.fromarray(np.asarray(fig.canvas.buffer_rgba())[..., :3]).quantize(64, dither=Image.Dither.NONE)
image.save("docs/_static/noiselab.png", optimize=True)
