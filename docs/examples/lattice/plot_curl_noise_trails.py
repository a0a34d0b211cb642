"""
Curl-noise particle trails
==========================

:func:`noiselab.curl_noise` turns a noise potential into a divergence-free flow
(the rotated gradient in 2-D), from the noise's exact derivatives. Particles
advected through it swirl without sources or sinks; the trails are traced by
:func:`noiselab.geometry.streamlines` (4th-order Runge-Kutta).
"""
import matplotlib.pyplot as plt
import numpy as np

import noiselab
from noiselab.geometry import streamlines
from noiselab.lattice import Grid

potential = noiselab.LatticeNoise(2, rng=8, kernel="quintic")
flow = noiselab.curl_noise(potential, Grid((64, 64), ((0, 4), (0, 4))))          # (64, 64, 2)
divergence = np.gradient(flow[..., 0], axis=0) + np.gradient(flow[..., 1], axis=1)
print("max |divergence| / max |flow| on the grid:", float(abs(divergence).max() / abs(flow).max()))


def field(points):
    return noiselab.curl_noise(potential, points)


seeds = np.random.default_rng(0).uniform(0.5, 3.5, (150, 2))
trails = streamlines(field, seeds, step=0.01, n_steps=120)

fig, ax = plt.subplots(figsize=(4.5, 4.5))
speed = np.linalg.norm(flow, axis=-1)
ax.imshow(speed, extent=(0, 4, 4, 0), cmap="Blues")
for trail in trails:
    ax.plot(trail[:, 1], trail[:, 0], lw=0.7, color="k")
ax.set_title("particle trails over |flow|")
ax.set_xlabel("x")
ax.set_ylabel("y")
fig.tight_layout()
