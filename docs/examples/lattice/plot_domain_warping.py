"""
Domain warping
==============

:func:`noiselab.warp` evaluates ``noise(x + amount * warp_noise(x))``; the result
is itself a noise (call it on points, take its ``gradient``, warp it again), with
exact derivatives by the chain rule.
"""
import matplotlib.pyplot as plt

import noiselab
from noiselab.geometry import grid_points

base = noiselab.LatticeNoise(2, rng=1)
once = noiselab.warp(base, noiselab.LatticeNoise(2, 2, rng=2), amount=0.8)
twice = noiselab.warp(once, noiselab.LatticeNoise(2, 2, rng=3, frequency=2.0), amount=0.4)

points = grid_points((160, 160), ((0, 4), (0, 4)))   # (160, 160, 2), (y, x) order
fig, axes = plt.subplots(1, 3, figsize=(9, 3.2))
for ax, noise, title in zip(axes, (base, once, twice), ("noise", "warped once", "warped twice")):
    ax.imshow(noise(points), cmap="magma")
    ax.set_title(title)
    ax.axis("off")
fig.tight_layout()
