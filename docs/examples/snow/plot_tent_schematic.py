"""
The tent: where falling snow's energy lies
==========================================

A flake at spatial frequency ``|w|`` falls at ``c / |w|`` px/frame (near flakes
are big and fast, far ones small and slow), so its energy lies at temporal
frequency ``w_t = -c (d·w) / |w|``: a *tent* over the (w_x, w_y) plane with its
ridge across the fall direction ``d`` (Langer & Zhang). noiselab fills only the
band's part of it (between the annulus radii) and inverts. This figure draws
the surface with :func:`noiselab.spectral.envelopes.tent_surface` and checks it
against the power of an actual snow field (the inverse FFT before the opacity
curve, ``rescale=False``: the curve's nonlinearity spreads some power off the tent).
"""
import matplotlib.pyplot as plt
import numpy as np

import noiselab
from noiselab import analysis
from noiselab.spectral.envelopes import tent_surface

c, direction = 1.0, (0.0, 1.0)
w = np.linspace(-np.pi / 2, np.pi / 2, 61)
wy, wx = np.meshgrid(w, w, indexing="ij")
radius = np.hypot(wx, wy)
wt = np.where(radius > 0, tent_surface(wy, wx, c, direction_yx=direction[::-1]), np.nan)
inside = (radius >= 2 * np.pi * 4 / 64) & (radius <= 2 * np.pi * 16 / 64)   # the band, 4..16 cycles per 64 px

fig = plt.figure(figsize=(9, 4))
ax = fig.add_subplot(1, 2, 1, projection="3d")
ax.plot_surface(wx, wy, np.where(inside, wt, np.nan), color="tab:blue", alpha=0.9, linewidth=0)
ax.plot_wireframe(wx, wy, wt, rstride=6, cstride=6, color="0.6", linewidth=0.4)
ax.set_xticks([-1.5, 0, 1.5])
ax.set_yticks([-1.5, 0, 1.5])
ax.set_xlabel("w_x (rad/px)")
ax.set_ylabel("w_y (rad/px)")
ax.set_zlabel("w_t (rad/frame)")
ax.set_title("tent surface (grey), band (blue)")

video = noiselab.snow((32, 64, 64), rng=0, c=c, band=(4, 16), direction_yx=direction[::-1], rescale=False)
print("share of the field's power on the tent:",
      round(analysis.tent_energy(video, c, (4, 16), direction_yx=direction[::-1]), 3))
ax2 = fig.add_subplot(1, 2, 2)
ky = np.fft.fftfreq(64) * 2 * np.pi
section = np.fft.fftshift(np.abs(np.fft.fftn(video - video.mean()))[:, :, 0] ** 2)   # the w_x = 0 plane
ax2.imshow(np.log10(section + 1e-12), extent=(ky.min(), -ky.min(), np.pi, -np.pi), aspect="auto", cmap="magma")
ax2.plot(w, -c * np.sign(w), "c--", lw=1, label="tent: w_t = -c sign(w_y)")
ax2.set_xlabel("w_y (rad/px)")
ax2.set_ylabel("w_t (rad/frame)")
ax2.set_title("a snow field's power, w_x = 0")
ax2.legend(fontsize=7, loc="lower left")
fig.tight_layout()
