"""
A looping snow tile
===================

Snow is periodic in x, y and t, so a small tile repeats without seams in space
and loops without a jump in time (thesis 3.4). :func:`noiselab.tile` repeats it
eagerly, :func:`noiselab.iter_tiled_frames` lazily for as many frames as asked.
:func:`noiselab.analysis.loop_seam` measures the jump from the last frame to the
first against the jump between neighbouring frames (1 means no visible seam).
"""
import matplotlib.pyplot as plt

import noiselab
from noiselab import analysis

tile = noiselab.snow((16, 64, 64), rng=3)                          # one 64 px tile, 16-frame loop
frames = list(noiselab.iter_tiled_frames(tile, (2, 3), n_frames=40))   # 40 frames of 128 x 192: 2.5 loops
print(len(frames), frames[0].shape)
print("loop seam:", round(float(analysis.loop_seam(tile)), 3))

fig, axes = plt.subplots(1, 2, figsize=(8, 2.8))
axes[0].imshow(frames[0], cmap="gray")
axes[0].set_title("2 x 3 tiles, frame 0")
axes[1].imshow(frames[16], cmap="gray")
axes[1].set_title("frame 16 = frame 0 (the loop)")
for ax in axes:
    ax.axis("off")
fig.tight_layout()
