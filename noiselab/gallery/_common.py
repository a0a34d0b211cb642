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


def save_figure(fig, path, dpi=100) -> Path:
    """Save a matplotlib figure to ``path`` and close it."""
    plt = pyplot()
    path = Path(path)
    fig.savefig(path, dpi=dpi, bbox_inches="tight")
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
    mp4 = write_video(out / f"{stem}.mp4", frames, fps=fps, vmin=vmin, vmax=vmax, show_progress=False)
    poster = save_image(out / f"{stem}_poster.png", to_uint8(frames[poster_frame], vmin, vmax))
    return [mp4, poster]


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
    from noiselab.snow import composite

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


def cow(resolution=96, size=2.0):
    """A closed, single-part stylised cow, built in code (no file): a smooth union of ellipsoids, contoured.

    Body, neck, head, muzzle, four legs and two ears blended with a smooth
    minimum and turned into a triangle mesh by VTK's contour filter (marching
    cubes) on a ``resolution``-cell grid along the body. Returns a watertight
    ``trimesh.Trimesh`` normalised so its longest extent is ``size``.
    """
    import trimesh

    from noiselab.geometry import normalize, require_pyvista, pyvista_to_trimesh

    pv = require_pyvista()
    parts = [((0.0, 0.0, 0.0), (0.95, 0.42, 0.42)),            # body
             ((0.85, 0.0, 0.25), (0.35, 0.2, 0.25)),            # neck
             ((1.2, 0.0, 0.35), (0.3, 0.2, 0.22)),             # head
             ((1.45, 0.0, 0.22), (0.17, 0.17, 0.15)),          # muzzle
             ((1.1, 0.24, 0.5), (0.1, 0.15, 0.09)),            # ears
             ((1.1, -0.24, 0.5), (0.1, 0.15, 0.09))]
    parts += [((x, y, -0.55), (0.14, 0.14, 0.45)) for x in (-0.6, 0.6) for y in (-0.22, 0.22)]   # legs
    lo, hi = np.array([-1.15, -0.6, -1.1]), np.array([1.75, 0.6, 0.75])
    step = float((hi - lo)[0] / resolution)
    dims = np.ceil((hi - lo) / step).astype(int) + 1
    grid = pv.ImageData(dimensions=tuple(int(d) for d in dims), spacing=(step,) * 3, origin=tuple(lo))
    pts = np.asarray(grid.points)
    d = _ellipsoid_distance(pts, *parts[0])
    for c, r in parts[1:]:
        d = _smooth_min(d, _ellipsoid_distance(pts, c, r), 0.12)
    # keep the surface at least a fifth of a cell from every grid point: marching cubes then cuts no edge
    # near its end, which is what leaves sliver triangles (they are the first faces to flip when displaced)
    eps = 0.1 * step
    d = np.where(np.abs(d) < eps, np.where(d < 0, -eps, eps), d)
    grid.point_data["d"] = d
    surf = grid.contour([0.0], scalars="d").triangulate().clean().smooth_taubin(n_iter=40, pass_band=0.05)
    mesh = pyvista_to_trimesh(surf)
    mesh.merge_vertices()
    parts_found = len(mesh.split(only_watertight=False))
    if not mesh.is_watertight or parts_found != 1:
        raise ValueError(f"the cow mesh should be closed and in one part: watertight={mesh.is_watertight}, parts={parts_found}")
    trimesh.repair.fix_normals(mesh)
    return normalize(mesh, size)
