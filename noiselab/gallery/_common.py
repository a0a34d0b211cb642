"""Small helpers shared by the figure modules: matplotlib set-up, saving figures and videos."""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np

os.environ.setdefault("MPLBACKEND", "Agg")
os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")


def pyplot():
    """matplotlib.pyplot on the Agg backend (no display needed)."""
    import matplotlib

    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt

    return plt


def smallest_text(fig) -> float | None:
    """The font size, in points, of the smallest visible, non-empty text of a matplotlib figure."""
    from matplotlib.text import Text

    sizes = [t.get_fontsize() for t in fig.findobj(Text) if t.get_visible() and t.get_text().strip()
             and t.get_figure() is not None]
    return min(sizes) if sizes else None


def save_figure(fig, path, dpi=100) -> Path:
    """Save a matplotlib figure to ``path`` and close it.

    A PNG records the size of its smallest text in its own pixels (``noiselab.gallery.checks.TEXT_PX_KEY``),
    which ``noiselab gallery --check`` compares with the width the page shows it at.
    """
    from .checks import TEXT_PX_KEY

    plt = pyplot()
    path = Path(path)
    points = smallest_text(fig)
    meta = {TEXT_PX_KEY: f"{points * dpi / 72:.2f}"} if points and path.suffix.lower() == ".png" else None
    fig.savefig(path, dpi=dpi, bbox_inches="tight", metadata=meta)
    plt.close(fig)
    return path


def save_image(path, image, vmin=None, vmax=None) -> Path:
    from noiselab.io import write_image

    return write_image(path, image, vmin=vmin, vmax=vmax)


def save_video(out, stem, frames, *, fps=25.0, vmin=None, vmax=None, poster_frame=0):
    """Write ``stem.mp4`` and ``stem_poster.png``, a full-resolution still of frame ``poster_frame``.

    Returns the two paths, MP4 first. The page shows the MP4 itself (never a
    subsampled GIF, which aliases fine detail such as the smallest flakes) with
    the poster as the still shown before it plays.
    """
    from noiselab.io import to_uint8, write_video

    out = Path(out)
    frames = np.asarray(frames)
    mp4 = write_video(out / f"{stem}.mp4", frames, fps=fps, vmin=vmin, vmax=vmax, progress=False)
    poster = save_image(out / f"{stem}_poster.png", to_uint8(frames[poster_frame], vmin, vmax))
    return [mp4, poster]


def label_band(image, labels, *, centres=None, height=30, size=18):
    """``image`` (uint8, grey or RGB) under a white band holding ``labels``, centred at the columns ``centres``.

    ``centres`` defaults to the middles of equal column spans, one per label.
    The image's own pixels are kept as they are (a stimulus keeps its displayed values); the labels are drawn in
    matplotlib's DejaVu Sans, ``size`` pixels high, so the band is the same on every machine.
    """
    from matplotlib import font_manager
    from PIL import Image, ImageDraw, ImageFont

    image = np.asarray(image)
    if image.dtype != np.uint8:
        raise TypeError(f"image must be uint8, got {image.dtype}")
    band = Image.new("L", (image.shape[1], height), 255)
    draw = ImageDraw.Draw(band)
    font = ImageFont.truetype(font_manager.findfont("DejaVu Sans"), size)
    if centres is None:
        centres = [(k + 0.5) * image.shape[1] / len(labels) for k in range(len(labels))]
    for x, text in zip(centres, labels):
        draw.text((x, height / 2), text, fill=0, font=font, anchor="mm")
    top = np.asarray(band)
    if image.ndim == 3:
        top = np.repeat(top[..., None], image.shape[2], axis=-1)
    return np.concatenate([top, image], axis=0)


def grey_to_rgb(image):
    image = np.asarray(image)
    return np.repeat(image[..., None], 3, axis=-1) if image.ndim == 2 else image


def checkerboard(n, squares=4):
    """A black/white checkerboard of ``n`` x ``n`` pixels (1 = white)."""
    idx = (np.arange(n) * squares) // n
    return ((idx[:, None] + idx[None, :]) % 2).astype(np.float32)


def disc(n, radius=0.3, centre=(0.5, 0.5)):
    """A white disc on black (1 inside), radius and centre in units of the frame."""
    y, x = (np.mgrid[0:n, 0:n] + 0.5) / n
    return (((x - centre[0]) ** 2 + (y - centre[1]) ** 2) <= radius ** 2).astype(np.float32)


def moon(n):
    """A white crescent on black: a disc minus a shifted disc."""
    return np.clip(disc(n, 0.32) - disc(n, 0.28, centre=(0.62, 0.42)), 0, 1).astype(np.float32)


def alpha_to_rgb_composite(alpha, background, intensity=250):
    """Eq. 3.6 over an RGB background, as uint8."""
    from noiselab.snowfall import composite

    out = composite(alpha, background, intensity=intensity)
    out = np.asarray(out)
    return out if out.dtype == np.uint8 else np.clip(np.rint(out), 0, 255).astype(np.uint8)


def _ellipsoid_distance(points, centre, radii):
    """An approximate signed distance to an axis-aligned ellipsoid (exact on the axes), negative inside."""
    q = (points - np.asarray(centre, dtype=float)) / np.asarray(radii, dtype=float)
    return (np.linalg.norm(q, axis=-1) - 1.0) * float(min(radii))


def _smooth_min(a, b, k):
    """Polynomial smooth minimum (a smooth union of two solids), blending over a width ``k``."""
    h = np.clip(0.5 + 0.5 * (b - a) / k, 0.0, 1.0)
    return b * (1 - h) + a * h - k * h * (1 - h)


def _capsule_distance(points, a, b, radius):
    """Signed distance to a capsule (the segment a-b thickened by ``radius``), negative inside."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    ab = b - a
    t = np.clip((points - a) @ ab / float(ab @ ab), 0.0, 1.0)
    return np.linalg.norm(points - (a + t[:, None] * ab), axis=-1) - radius


# the cow's parts, x forward (head at +x), y to its left, z up: (kind, geometry, blend width of the smooth union)
_COW = ([("e", ((0.0, 0.0, 0.0), (1.0, 0.42, 0.45)), 0.0),          # barrel
         ("e", ((-0.62, 0.0, 0.06), (0.46, 0.42, 0.42)), 0.15),     # hindquarters
         ("e", ((0.55, 0.0, -0.02), (0.45, 0.37, 0.45)), 0.15),     # chest
         ("c", ((0.8, 0.0, 0.12), (1.18, 0.0, 0.3), 0.2), 0.12),    # neck
         ("e", ((1.32, 0.0, 0.24), (0.3, 0.18, 0.2)), 0.08),         # head
         ("e", ((1.56, 0.0, 0.06), (0.2, 0.16, 0.15)), 0.06),       # muzzle
         ("e", ((-0.35, 0.0, -0.43), (0.2, 0.16, 0.12)), 0.06)]     # udder
        + [("c", ((1.26, y, 0.4), (1.22, 1.9 * y, 0.56), 0.05), 0.04) for y in (-0.12, 0.12)]       # horns
        + [("e", ((1.2, 2.1 * y, 0.33), (0.06, 0.12, 0.045)), 0.04) for y in (-0.12, 0.12)]       # ears
        + [("c", ((x, y, -0.15), (x, y, -1.05), 0.1), 0.1) for x in (-0.66, 0.62) for y in (-0.22, 0.22)]   # legs
        + [("c", ((-1.02, 0.0, 0.3), (-1.12, 0.0, -0.42), 0.05), 0.05),                         # tail
           ("e", ((-1.12, 0.0, -0.5), (0.07, 0.07, 0.1)), 0.04)])                                # its tuft


def cow(resolution=110, size=2.0):
    """A closed, single-part cow built in code (no file): ellipsoids and capsules in a smooth union, contoured.

    Barrel body, hindquarters, chest, neck, head, muzzle, horns, ears, udder,
    four legs and a tail with a tuft, blended with a polynomial smooth
    minimum and turned into a triangle mesh by VTK's contour filter (marching
    cubes) on a ``resolution``-cell grid along the body. Returns a watertight
    ``trimesh.Trimesh`` normalised so its longest extent is ``size``.
    """
    import trimesh

    from noiselab.geometry import normalize, require_pyvista, pyvista_to_trimesh

    pv = require_pyvista()
    lo, hi = np.array([-1.3, -0.6, -1.15]), np.array([1.8, 0.6, 0.7])
    step = float((hi - lo)[0] / resolution)
    dims = np.ceil((hi - lo) / step).astype(int) + 1
    grid = pv.ImageData(dimensions=tuple(int(d) for d in dims), spacing=(step,) * 3, origin=tuple(lo))
    pts = np.asarray(grid.points)
    d = None
    for kind, geo, k in _COW:
        part = _ellipsoid_distance(pts, *geo) if kind == "e" else _capsule_distance(pts, *geo)
        d = part if d is None else _smooth_min(d, part, k)
    # keep the surface at least a tenth of a cell from every grid point: marching cubes then cuts no edge
    # near its end, which is what leaves sliver triangles (they are the first faces to flip when displaced)
    eps = 0.1 * step
    d = np.where(np.abs(d) < eps, np.where(d < 0, -eps, eps), d)
    grid.point_data["d"] = d
    surf = grid.contour([0.0], scalars="d").triangulate().clean().smooth_taubin(n_iter=30, pass_band=0.08)
    mesh = pyvista_to_trimesh(surf)
    mesh.merge_vertices()
    parts_found = len(mesh.split(only_watertight=False))
    if not mesh.is_watertight or parts_found != 1:
        raise ValueError(f"the cow mesh should be closed and in one part: watertight={mesh.is_watertight}, parts={parts_found}")
    trimesh.repair.fix_normals(mesh)
    return normalize(mesh, size)
