"""The schematics that open each paper's section of the page: the tent in (w_x, w_y, w_t), the permutation-table lookup.

A figure named ``intro`` is drawn in its group's introduction on the page,
not as a card of its own (see :mod:`noiselab.gallery.html`).
"""
from __future__ import annotations

import numpy as np

from ..registry import Result, figure


def _box(ax, x, y, text, w=2.3, h=0.9, fc="#eef3fb", fontsize=12):
    from matplotlib.patches import FancyBboxPatch

    ax.add_patch(FancyBboxPatch((x - w / 2, y - h / 2), w, h, boxstyle="round,pad=0.08", fc=fc, ec="0.25", lw=1.2))
    ax.text(x, y, text, ha="center", va="center", fontsize=fontsize)


def _arrow(ax, a, b, text=None):
    ax.annotate("", b, a, arrowprops=dict(arrowstyle="-|>", lw=1.6, color="0.2"))
    if text:
        ax.text((a[0] + b[0]) / 2, (a[1] + b[1]) / 2 + 0.25, text, ha="center", va="bottom", fontsize=11, color="0.25")


@figure("snow", "intro", source="Langer & Zhang 2003 (schematic)", title="How falling snow is made: the tent, then one inverse FFT",
        look="the tent: each spatial frequency (w_x, w_y) has one temporal frequency, so big flakes fall fast",
        params=dict(c=1.0, band=(16, 128), size=512, grid=81), quick=dict(grid=31), uses=())
def snow_intro(out, *, c, band, size, grid):
    from .._common import pyplot, save_figure

    plt = pyplot()
    fig = plt.figure(figsize=(13, 4.8))
    ax = fig.add_axes((0.0, 0.04, 0.42, 0.9), projection="3d")
    w = np.linspace(-np.pi, np.pi, grid)
    wx, wy = np.meshgrid(w, w)
    r = np.hypot(wx, wy)
    wt = np.divide(c * wy, r, out=np.zeros_like(r), where=r > 0)
    ax.plot_surface(wx, wy, wt, color="#b9cde8", alpha=0.55, linewidth=0)
    # the synthesis band: an annulus of radii 2 pi band / size rad/px, drawn on the tent
    th = np.linspace(0, 2 * np.pi, 200)
    for f, col, name in ((band[0], "#c0392b", "near, large, fast"), (band[1], "#1f618d", "far, small, slow")):
        rad = 2 * np.pi * f / size
        ax.plot(rad * np.cos(th), rad * np.sin(th), c * np.sin(th), color=col, lw=2.5, label=f"{f} cycles/frame: {name}")
    ax.set_xlabel(r"$\omega_x$ (rad/px)", fontsize=11), ax.set_ylabel(r"$\omega_y$ (rad/px)", fontsize=11)
    ax.set_zlabel(r"$\omega_t$ (rad/frame)", fontsize=11)
    ax.set_zticks([-1, 0, 1])
    ax.legend(loc="upper left", fontsize=10, frameon=False)
    ax.set_title(r"(a) the tent $\omega_t = C\,\omega_y/|\omega|$ and the band", fontsize=13)
    ax2 = fig.add_axes((0.45, 0.05, 0.54, 0.86))
    ax2.set_xlim(0, 10.6), ax2.set_ylim(0, 5), ax2.axis("off")
    ax2.set_title("(b) the method, step by step", fontsize=13)
    _box(ax2, 1.5, 3.8, "random phase,\n1/f amplitude", w=2.6, h=1.1)
    _box(ax2, 5.3, 3.8, "keep only the\ntent, in the band", w=2.7, h=1.1)
    _box(ax2, 9.1, 3.8, "inverse 3-D FFT\n(x, y, t)", w=2.6, h=1.1)
    _box(ax2, 9.1, 1.3, r"rescale to [0, 1]," + "\n" + r"opacity $\alpha^\beta$", w=2.6, h=1.1)
    _box(ax2, 4.2, 1.3, r"$I = 250\,\alpha + (1-\alpha)\,I_{bg}$", w=4.2, h=1.1, fc="#fbf3e6")
    _arrow(ax2, (2.85, 3.8), (3.9, 3.8))
    _arrow(ax2, (6.7, 3.8), (7.75, 3.8))
    _arrow(ax2, (9.1, 3.2), (9.1, 1.9))
    _arrow(ax2, (7.75, 1.3), (6.35, 1.3), "composite")
    ax2.text(5.3, 0.15, "periodic in x, y and t: the result tiles and loops", ha="center", fontsize=11, color="0.3")
    return Result([save_figure(fig, out / "snow_method.png")],
                  f"(a) The tent surface of Eq. 3.3 with C = {c:g}: a flake moving down at speed v puts its energy on "
                  "the plane w_t = v w_y; the thesis lets the speed fall as 1/|w| (near flakes are both larger and "
                  f"faster), which bends the planes into the tent. Only the band {band[0]}-{band[1]} cycles/frame of a "
                  f"{size}-pixel frame is filled (red: the nearest flakes, blue: the farthest). (b) The steps.",
                  measured={"near / far flake speed (px/frame)": [c * size / (2 * np.pi * band[0]),
                                                                  c * size / (2 * np.pi * band[1])]})


@figure("phillips", "intro", source="Phillips 2004 (schematic)", title="How lattice noise is made: two table look-ups, then smoothing",
        look="an integer lattice point picks a random value through the permutation table; the kernel smooths between them",
        params=dict(entries=8, seed=1), quick=dict(), uses=("noiselab.lattice",))
def phillips_intro(out, *, entries, seed):
    from noiselab.lattice import LatticeNoise

    from .._common import pyplot, save_figure

    plt = pyplot()
    noise = LatticeNoise(1, rng=seed, kernel="catmull-rom")
    perm = noise.perms[0][:entries]
    vals = noise(np.arange(entries, dtype=float)[:, None]) * noise.bound
    fig = plt.figure(figsize=(13, 4.6))
    ax = fig.add_axes((0.0, 0.0, 0.56, 0.92))
    ax.set_xlim(0, 11), ax.set_ylim(0, 5), ax.axis("off")
    ax.set_title("(a) the look-up for a point x, in 1-D (2-D nests it: P[P[i] + j])", fontsize=13)
    _box(ax, 1.2, 4.0, "x = 3.4", w=1.8)
    _box(ax, 1.2, 2.3, "lattice points\ni = 2, 3, 4, 5", w=2.1, h=1.1)
    _arrow(ax, (1.2, 3.5), (1.2, 2.9), None)
    ax.text(3.1, 4.25, "permutation table P", fontsize=11)
    for k in range(entries):
        fc = "#fde2c8" if k in (2, 3, 4, 5) else "white"
        ax.add_patch(plt.Rectangle((3.0 + 0.6 * k, 3.3), 0.6, 0.7, fc=fc, ec="0.3"))
        ax.text(3.3 + 0.6 * k, 3.65, str(int(perm[k])), ha="center", va="center", fontsize=10)
        ax.text(3.3 + 0.6 * k, 3.15, str(k), ha="center", va="top", fontsize=10, color="0.4")
    _arrow(ax, (2.3, 2.5), (3.6, 3.25), None)
    ax.text(3.1, 1.75, "random value table, read at P[i]: value[P[i]]", fontsize=11)
    for k in range(entries):
        fc = "#d5e8d4" if k in (2, 3, 4, 5) else "white"
        ax.add_patch(plt.Rectangle((3.0 + 0.6 * k, 0.8), 0.6, 0.7, fc=fc, ec="0.3"))
        ax.text(3.3 + 0.6 * k, 1.15, f"{vals[k]:+.1f}", ha="center", va="center", fontsize=10)
    _arrow(ax, (5.4, 3.1), (5.4, 2.2), None)
    _box(ax, 9.6, 2.3, "kernel-weighted\nsum of the 4\nvalues: noise(x)", w=2.3, h=1.5, fc="#fbf3e6")
    _arrow(ax, (7.9, 1.15), (8.4, 2.0), None)
    ax2 = fig.add_axes((0.62, 0.15, 0.36, 0.68))
    xs = np.linspace(0, entries - 1, 400)
    ax2.plot(xs, noise(xs[:, None]) * noise.bound, color="C2", lw=2, label="noise(x) (Catmull-Rom)")
    ax2.vlines(np.arange(entries), 0, vals, color="k", lw=1.5)
    ax2.plot(np.arange(entries), vals, "ko", ms=5, label="value[P[i]] at the lattice points")
    ax2.axvline(3.4, color="C3", ls="--", lw=1)
    ax2.axhline(0, color="0.6", lw=0.5)
    ax2.set_xlabel("x (lattice cells)", fontsize=11), ax2.set_ylabel("noise value", fontsize=11)
    ax2.legend(fontsize=10, loc="lower left", bbox_to_anchor=(0, 1.0), frameon=False)
    ax2.set_title("(b) the result", fontsize=13, pad=46)
    return Result([save_figure(fig, out / "lattice_method.png")],
                  "(a) Phillips' lattice noise: the integer lattice points around x index a permutation table, whose "
                  "entries index a table of random values; (b) a kernel (here Catmull-Rom, which passes through the "
                  "values) blends the values of the nearest lattice points into a smooth function. A frequency F "
                  "scales x (F lattice cells per unit); octaves at F, 2F, 4F... summed with weights 1, 1/2, 1/4... "
                  "make the fractal sum (Eq. 9), their magnitudes turbulence (Eq. 10).",
                  measured={"values at the lattice points": [float(v) for v in vals]})
