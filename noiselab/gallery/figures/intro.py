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


@figure("readme", "picture", source="The gallery's own (the README's picture)",
        title="What noiselab makes: falling snow, a displaced mesh, a motion cloud, a tileable texture, a surface",
        params=dict(panel=384, frames=16, octaves=4, seed=2), quick=dict(panel=96, frames=4, octaves=2),
        uses=("noiselab.snowfall", "noiselab.geometry", "noiselab.lattice", "noiselab.stimuli", "noiselab.spectral",
              "noiselab.analysis"),
        look="the flakes in the 2x crop, big near ones and small far ones; the seams of the 2 x 2 tiling cannot be found")
def readme_picture(out, *, panel, frames, octaves, seed):
    """The first picture a visitor sees: six panels of what noiselab does, each made here with its public API.

    Written as ``noiselab.png``; a full-size build also copies it to the checkout's ``docs/_static/`` (see
    :func:`noiselab.gallery.build.publish_readme_picture`).
    """
    from noiselab import analysis
    from noiselab.geometry import displace, monge_surface, render_mesh, sphere_for_noise
    from noiselab.lattice import LatticeNoise
    from noiselab.snowfall import snow
    from noiselab.spectral import spectral_noise
    from noiselab.stimuli import motion_cloud

    from .._common import alpha_to_rgb_composite, pyplot
    from ..checks import TEXT_PX_KEY
    from ..scenes import frame_with_crop, house_scene

    n = panel
    # (a, b) falling snow over a scene: a frame and its 2x crop (the thesis's Fig. 3.1 method, Eq. 3.6)
    alpha = snow((frames, n, n), rng=seed, c=1.0, beta=3.0, direction_yx=(1.0, 0.4))
    frame = alpha_to_rgb_composite(alpha[0], house_scene(n, n), 250)
    snow_pair = frame_with_crop(frame, (int(0.36 * n), int(0.3 * n)), gap=0)
    # (c) a sphere displaced along its normals by turbulence (Phillips' Eq. 11)
    field = LatticeNoise(3, rng=seed)
    mesh = displace(sphere_for_noise(2.0 ** (octaves - 1), 1.0, max_subdivisions=6), field, amplitude=0.35,
                    frequency=1.0, octaves=octaves, kind="turbulence", on_alias="ignore")
    render = render_mesh(mesh, size=n, view="iso", elevation=10)
    # (d) a motion cloud: band-pass, oriented noise (one frame)
    cloud = motion_cloud((4, n, n), sf_0=0.06, B_sf=0.02, theta=np.pi / 4, B_theta=np.pi / 16,
                         V_X=1.0, rng=seed, dtype=np.float64)[0]
    cloud = cloud / (3 * cloud.std())
    # (e) a periodic 1/f texture, one quarter of the panel, tiled 2 x 2: the seams do not show
    tile = spectral_noise((n // 2, n // 2), exponent=1.5, rng=seed, dtype=np.float64)
    tiled = np.tile(tile, (2, 2))
    # (f) a lattice fractal sum as a Monge surface z = f(x, y) (Phillips' Figs. 8 and 14), coloured by height
    terrain = monge_surface(LatticeNoise(2, rng=seed + 1), (n // 2, n // 2), ((0.0, 3.0), (0.0, 3.0)), amplitude=0.9,
                            octaves=5, on_alias="ignore")
    z = np.asarray(terrain.vertices)[:, 2]
    land = render_mesh(terrain, size=n, view="iso", elevation=20, zoom=1.1, scalars="height", cmap="gist_earth",
                       clim=(1.3 * float(z.min()), 1.3 * float(z.max())))

    plt = pyplot()
    gap, top = 12, 34   # px: between panels, above each (its label)
    width = 3 * n + 2 * gap
    height = 2 * (n + top) + gap
    dpi = 100
    fig = plt.figure(figsize=(width / dpi, height / dpi), dpi=dpi, facecolor="white")
    fontsize = max(8.0, 13.0 * n / 384)

    def put(img, col, row, title="", **kw):
        x0 = col * (n + gap)
        y0 = row * (n + top + gap) + top
        ax = fig.add_axes([x0 / width, 1 - (y0 + n) / height, n / width, n / height])
        ax.imshow(img, interpolation="nearest", aspect="auto", **kw)
        ax.set_axis_off()
        fig.text((x0 + 2) / width, 1 - (y0 - 6) / height, title, fontsize=fontsize, va="bottom", ha="left")
        return ax

    put(snow_pair[:, :n], 0, 0, title="falling snow: one frame, no particles")
    put(snow_pair[:, n:], 1, 0, title="the square, 2x: near and far flakes")
    put(render, 2, 0, title="a sphere displaced by turbulence")
    put(cloud, 0, 1, title="a motion cloud (band-pass, drifting)", cmap="gray", vmin=-1, vmax=1)
    ax = put(tiled, 1, 1, title="a periodic texture, tiled 2 x 2", cmap="gist_earth")
    for t in (n // 2 - 0.5,):   # ticks outside the image mark where the tiles meet
        ax.annotate("", (t, -4), (t, -14), arrowprops=dict(arrowstyle="-", color="0.4"), annotation_clip=False)
    put(land, 2, 1, title="a lattice fractal sum as a surface")
    spec = analysis.video_spectrum(alpha)
    on_tent = analysis.tent_energy(spec, 1.0, (n / 32, n / 4), direction_yx=(1.0, 0.4))
    path = out / "noiselab.png"
    fig.canvas.draw()
    rgb = np.asarray(fig.canvas.buffer_rgba())[..., :3]
    plt.close(fig)
    # 256 colours: about a quarter of the bytes of full colour, small enough to commit as the README's picture
    from PIL import Image, PngImagePlugin

    info = PngImagePlugin.PngInfo()
    info.add_text(TEXT_PX_KEY, f"{fontsize * dpi / 72:.2f}")
    image = Image.fromarray(rgb)
    palette = image.quantize(256, method=Image.Quantize.MEDIANCUT)       # (Pillow dithers only onto a given palette)
    image.quantize(palette=palette, dither=Image.Dither.FLOYDSTEINBERG).save(path, optimize=True, pnginfo=info)
    return Result([path], "The README's picture, rebuilt with every gallery build: a frame of falling snow over a "
                          "winter scene and its outlined square enlarged 2x (the flakes read there: large near ones, "
                          f"small far ones); a sphere displaced along its normals by {octaves} octaves of turbulence; one "
                          "frame of a drifting motion cloud; a periodic 1/f texture shown as 2 x 2 copies of itself "
                          "(the tiles meet at the grey tick); five octaves of lattice noise as a height field.",
                  measured={"energy on the tent": on_tent, "mean opacity": float(alpha.mean()),
                            "texture: largest jump across a seam / largest jump inside (<= 1: no seam)":
                                float(max(np.abs(tile[:, 0] - tile[:, -1]).max(), np.abs(tile[0] - tile[-1]).max())
                                      / max(np.abs(np.diff(tile, axis=1)).max(), np.abs(np.diff(tile, axis=0)).max()))})
