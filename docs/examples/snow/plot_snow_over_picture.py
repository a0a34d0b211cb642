"""
Snow over your own picture
==========================

:func:`noiselab.snow` renders the opacity of falling snow; :func:`noiselab.composite`
lays it over any background, grey or RGB, still or video (thesis Eq. 3.6:
``I = 250 alpha + (1 - alpha) I_bg``). Here the "picture" is made in code; with
a file use ``noiselab.io.read_image("my.png")`` (the command line:
``noiselab snow --background my.png``).
"""
import matplotlib.pyplot as plt
import numpy as np

import noiselab

height, width = 128, 192
y, x = np.mgrid[:height, :width] / np.array([height, width])[:, None, None]
picture = np.stack([0.35 + 0.4 * y, 0.45 + 0.3 * y, 0.75 - 0.2 * y], axis=-1)   # a sky, RGB floats in [0, 1]
picture[y > 0.7 + 0.08 * np.sin(12 * x)] = (0.25, 0.3, 0.2)                    # and a hill

alpha = noiselab.snow((16, height, width), rng=1, direction_yx=(2, 1))   # falls down and to the right
video = noiselab.composite(alpha, picture)                           # uint8 (16, 128, 192, 3)

fig, axes = plt.subplots(1, 3, figsize=(9, 2.4))
axes[0].imshow(picture)
axes[0].set_title("background")
axes[1].imshow(alpha[0], cmap="gray")
axes[1].set_title("opacity, frame 0")
axes[2].imshow(video[0])
axes[2].set_title("composite, frame 0")
for ax in axes:
    ax.axis("off")
fig.tight_layout()
