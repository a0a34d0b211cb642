"""
Parallax stimuli at given Michelson contrasts
=============================================

:func:`noiselab.parallax_composite` builds the two-contrast motion-parallax
stimuli of thesis Eq. 6.1: a veil of luminance ``veil`` over the masked region
lets ``transmittance`` ``T`` of the snow through: ``I = 255 (1 - T) + T 255 f``. With
the foreground ``f`` between ``lo`` and ``hi`` the veiled region's Michelson
contrast is ``T (hi - lo) / (2 (1 - T) + T (hi + lo))``, so a target contrast
``c`` needs ``T = 2c / ((hi - lo) + 2c - c (hi + lo))``. The function reports
the contrast it made, measured on the composite.
"""
import matplotlib.pyplot as plt
import numpy as np

import noiselab

foreground = noiselab.snow((8, 128, 128), rng=5, beta=1.0)   # the thesis rescales without the exponent
yy, xx = np.mgrid[:128, :128]
disc = (yy - 64) ** 2 + (xx - 64) ** 2 < 40 ** 2                 # the veiled region

fig, axes = plt.subplots(1, 3, figsize=(9, 3))
lo, hi = float(foreground[:, disc].min()), float(foreground[:, disc].max())
for ax, target in zip(axes, (0.5, 0.176, 0.05)):
    transmittance = 2 * target / ((hi - lo) + 2 * target - target * (hi + lo))
    video, contrast = noiselab.parallax_composite(foreground, disc, transmittance=transmittance)
    print(f"target {target}: veiled {contrast['veiled']:.3f}, clear {contrast['clear']:.3f}")
    ax.imshow(video[0], cmap="gray", vmin=0, vmax=255)
    ax.set_title(f"veiled contrast {contrast['veiled']:.3f}")
    ax.axis("off")
fig.tight_layout()
