"""
The permutation-table lookup of lattice noise
=============================================

Phillips' lattice noise gives every integer lattice point ``i`` a random value
read through a permutation table ``P`` of ``n`` entries: ``V[P[i mod n]]`` in 1-D,
``V[P[(P[i mod n] + j) mod n]]`` in 2-D (nested, one lookup per axis), and
interpolates between the points with a kernel (a B-spline, Catmull-Rom or
Perlin's quintic). The top panel draws the lookup for a table of ``n = 8``
(made here with numpy for the picture); the bottom panel evaluates
:class:`noiselab.LatticeNoise` with ``table_size=8``: the noise repeats every
8 cells, and the linear kernel passes through the lattice values.
"""
import matplotlib.pyplot as plt
import numpy as np

import noiselab

n = 8
rng = np.random.default_rng(0)
P = rng.permutation(n)
V = np.where(np.arange(n) % 2 == 0, rng.uniform(0, 1, n), -rng.uniform(0, 1, n))   # interleaved signs

fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 5.5), gridspec_kw={"height_ratios": [1, 1.3]})
for row, (label, cells) in enumerate((("i mod n", np.arange(n)), ("P[i mod n]", P), ("V[P[i mod n]]", V[P]))):
    y = 2 - row
    top.text(-0.7, y, label, ha="right", va="center", fontsize=9)
    for k, value in enumerate(cells):
        top.add_patch(plt.Rectangle((k - 0.45, y - 0.3), 0.9, 0.6, fc="w", ec="k"))
        top.text(k, y, f"{value:.2f}" if row == 2 else str(value), ha="center", va="center", fontsize=8)
    if row < 2:
        for k in range(n):
            top.annotate("", xy=(k, y - 1 + 0.32), xytext=(k, y - 0.32), arrowprops=dict(arrowstyle="->", lw=0.8))
top.set_xlim(-3.2, n)
top.set_ylim(-0.5, 2.5)
top.axis("off")
top.set_title("one lookup per lattice point, n = 8")

x = np.linspace(0, 24, 1200)
for kernel in ("linear", "cubic", "quintic"):
    noise = noiselab.LatticeNoise(1, rng=0, table_size=n, kernel=kernel)
    bottom.plot(x, noise(x), lw=1, label=kernel)
lattice = noiselab.LatticeNoise(1, rng=0, table_size=n, kernel="linear")(np.arange(25.0))
bottom.plot(np.arange(25), lattice, "ko", ms=3, label="lattice values")
for edge in (8, 16):
    bottom.axvline(edge, color="0.7", ls="--", lw=0.8)
bottom.set_xlabel("x (lattice cells); the table repeats every 8")
bottom.legend(fontsize=7, ncol=4, loc="lower right")
fig.tight_layout()
