"""
A panning camera
================

A camera panning at ``pan = (ux, uy)`` px/frame shears the tent (thesis Eq. 4.2):
every flake gets the pan's velocity on top of its fall. The space-time slice
(y against t along one column) shows the streaks of flakes; the pan tilts them.
:func:`noiselab.analysis.best_velocity` measures the video's dominant motion.
"""
import matplotlib.pyplot as plt

import noiselab
from noiselab import analysis

still_camera = noiselab.snow((32, 128, 128), rng=4, c=1.0)
panning = noiselab.snow((32, 128, 128), rng=4, c=1.0, pan_yx=(0.0, 1.5))
for name, video in (("still", still_camera), ("panning", panning)):
    vx, vy = analysis.best_velocity(video)
    print(f"{name}: best velocity ({vx:.2f}, {vy:.2f}) px/frame")

fig, axes = plt.subplots(1, 2, figsize=(8, 3))
for ax, video, title in zip(axes, (still_camera, panning), ("still camera: x-t slice", "pan 1.5 px/frame: x-t slice")):
    ax.imshow(video[:, 64, :], cmap="gray", aspect="auto")
    ax.set_xlabel("x (px)")
    ax.set_ylabel("t (frame)")
    ax.set_title(title)
fig.tight_layout()
