"""Off-screen rendering: pyvista for meshes (images, turntables, time-varying shapes), matplotlib for plots.

pyvista/VTK renders headless through VTK's EGL window on Mesa's software
renderer (``install.sh`` installs ``libegl1 libgl1-mesa-dri``); the
environment variable that selects it is set before pyvista is first
imported. Images are ``(height, width, 3)`` uint8 arrays, videos
``(frames, height, width, 3)``, written through :mod:`noiselab.io` (atomic).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .._core import check_int, check_real, renamed_parameters
from ._mesh import require_pyvista, as_trimesh, pyvista_to_trimesh, trimesh_to_pyvista
from .displace import vertex_normals

__all__ = ["render_mesh", "render_stereo_pair", "render_turntable", "render_sequence", "figure_to_array"]

_VIEWS = ("iso", "xy", "xz", "yz", "yx", "zx", "zy")
DEFAULT_COLOR = "#c8d2e6"


def _size(size):
    if isinstance(size, (int, np.integer)):
        size = (size, size)
    size = tuple(size)
    if len(size) != 2:
        raise ValueError(f"size must be an int or (height, width), got {size!r}")
    h = check_int("size height", size[0], lo=16, hi=8192)
    w = check_int("size width", size[1], lo=16, hi=8192)
    return h, w


def _as_list(meshes):
    import trimesh

    if isinstance(meshes, (trimesh.Trimesh,)) or hasattr(meshes, "n_points"):
        return [meshes]
    meshes = list(meshes)
    if not meshes:
        raise ValueError("meshes must hold at least one mesh")
    return meshes


def _to_poly(mesh, name):

    if hasattr(mesh, "n_points") and hasattr(mesh, "faces"):
        surf = mesh if mesh.__class__.__name__ == "PolyData" else mesh.extract_surface()
        return surf if surf.is_all_triangles else surf.triangulate()
    return trimesh_to_pyvista(as_trimesh(mesh, name=name))


_STYLES = ("surface", "wireframe", "points")


def _plotter(meshes, *, size, colors, scalars, cmap, clim, background, smooth_shading, show_edges, style="surface"):
    pv = require_pyvista()
    h, w = _size(size)
    meshes = _as_list(meshes)
    if colors is None or isinstance(colors, str) or (np.ndim(colors) == 1 and len(colors) in (3, 4)
                                                     and not isinstance(colors[0], str)):
        colors = [DEFAULT_COLOR if colors is None else colors] * len(meshes)
    if len(colors) != len(meshes):
        raise ValueError(f"colors must be one colour or one per mesh ({len(meshes)}), got {len(colors)}")
    plotter = pv.Plotter(off_screen=True, window_size=(w, h))
    plotter.set_background(background)
    polys = []
    for i, (mesh, color) in enumerate(zip(meshes, colors)):
        poly = _to_poly(mesh, f"meshes[{i}]")
        polys.append(poly)
        if smooth_shading and "Normals" not in poly.point_data:
            _set_normals(poly)
        if style not in _STYLES:
            raise ValueError(f"style must be one of {', '.join(_STYLES)}, got {style!r}")
        kw = dict(smooth_shading=False, show_edges=show_edges, lighting=style == "surface", style=style)
        if scalars is not None:
            if scalars not in poly.point_data:
                raise ValueError(f"scalars {scalars!r} is not a vertex attribute of meshes[{i}] "
                                 f"(it has: {', '.join(poly.point_data.keys()) or 'none'})")
            actor = plotter.add_mesh(poly, scalars=scalars, cmap=cmap, clim=clim, show_scalar_bar=False, **kw)
        elif "rgb" in poly.point_data:
            actor = plotter.add_mesh(poly, scalars="rgb", rgb=True, **kw)
        else:
            actor = plotter.add_mesh(poly, color=color, **kw)
        if smooth_shading:
            # Gouraud shading with our own area-weighted normals (pyvista's
            # smooth_shading would shade a private copy that a sequence cannot update)
            actor.prop.interpolation = "gouraud"
    return plotter, polys


def _set_normals(poly):

    if poly.is_all_triangles:
        faces = np.asarray(poly.faces).reshape(-1, 4)[:, 1:]
        import trimesh

        tm = trimesh.Trimesh(np.asarray(poly.points), faces, process=False, validate=False)
    else:
        tm = pyvista_to_trimesh(poly)
    poly.point_data["Normals"] = vertex_normals(tm)
    poly.point_data.active_normals_name = "Normals"


def _set_camera(plotter, view, azimuth, elevation, zoom, fit=None):
    if isinstance(view, str):
        if view not in _VIEWS:
            raise ValueError(f"view must be one of {', '.join(_VIEWS)} or a pyvista camera position, got {view!r}")
        plotter.camera_position = view
    else:
        plotter.camera_position = view
    plotter.reset_camera()
    if azimuth:
        plotter.camera.Azimuth(check_real("azimuth", azimuth))
    if elevation:
        plotter.camera.Elevation(check_real("elevation", elevation))
        plotter.camera.OrthogonalizeViewUp()
    if fit:
        _fit(plotter, fit)
    zoom = check_real("zoom", zoom, lo=0.0, lo_open=True, hi=100.0)
    if zoom != 1.0:
        plotter.camera.Zoom(zoom)
    plotter.reset_camera_clipping_range()


def _fit(plotter, polys, margin=0.04, passes=2, max_points=20000):
    """Zoom so that the scene fills the frame up to ``margin``.

    pyvista's reset_camera fits a bounding *sphere* into the image height,
    which leaves wide images, and any object seen along a diagonal, mostly
    empty. Here an even subsample of the vertices is projected with the
    camera's composite projection matrix and the zoom set so that the
    farthest one lands ``margin`` inside the border.
    """
    pts = []
    total = sum(p.n_points for p in polys)
    stride = max(1, total // max_points)
    for p in polys:
        pts.append(np.asarray(p.points, dtype=np.float64)[::stride])
    pts = np.concatenate(pts)
    if len(pts) == 0:
        return
    homog = np.concatenate([pts, np.ones((len(pts), 1))], axis=1)
    w, h = plotter.window_size
    for _ in range(passes):
        m = plotter.camera.GetCompositeProjectionTransformMatrix(w / h, -1, 1)
        mat = np.array([[m.GetElement(i, j) for j in range(4)] for i in range(4)])
        clip = homog @ mat.T
        ndc = clip[:, :2] / clip[:, 3:4]
        reach = float(np.max(np.abs(ndc)))
        if not np.isfinite(reach) or reach <= 0:
            return
        factor = (1.0 - margin) / reach
        if abs(factor - 1.0) < 0.005:
            return
        plotter.camera.Zoom(factor)
        plotter.reset_camera_clipping_range()


def _snap(plotter):
    plotter.render()
    return np.asarray(plotter.screenshot(return_img=True))[..., :3].copy()


def render_mesh(meshes, path=None, *, size=512, view="iso", azimuth=0.0, elevation=0.0, zoom=1.0,
                colors=None, scalars=None, cmap="viridis", clim=None, background="white",
                smooth_shading=True, show_edges=False, style="surface", fit=True) -> np.ndarray:
    """Render one mesh or a scene of meshes off screen; return the image and optionally write it.

    Parameters
    ----------
    meshes : trimesh.Trimesh, pyvista.PolyData, or a list of them
        Several meshes are drawn in one scene (see :func:`arrange` for figure layouts).
    path : str or Path, optional
        Write the image there (PNG/JPEG/TIFF, atomically).
    size : int or (height, width)
        Image size in pixels.
    view : str or camera position
        ``"iso"`` (default), or ``"xy"`` (looking down -z: x right, y up),
        ``"xz"``, ``"yz"``... or a pyvista ``camera_position`` triple. The
        camera is then fitted to the scene.
    azimuth, elevation, zoom : float
        Camera turns (degrees) about the view-up and the horizontal axis, and
        zoom (applied after the fit).
    fit : bool
        Zoom so that the scene fills the image (4% margin; from a subsample
        of up to 20,000 vertices); otherwise pyvista's fit of the bounding
        sphere to the height.
    colors : colour or list of colours
        One per mesh (matplotlib names or RGB); default a pale blue-grey.
        Meshes with vertex colours are drawn in them.
    scalars : str, optional
        Colour by a vertex attribute instead (e.g. ``"displacement"``) through ``cmap``/``clim``.
    style : {"surface", "wireframe", "points"}
        Shaded surface (default), or the paper's wire-frame look (unlit lines).

    Returns
    -------
    (height, width, 3) uint8 array

    Examples
    --------
    >>> from noiselab.geometry import sphere
    >>> img = render_mesh(sphere(2), size=64)
    >>> img.shape, bool((img != 255).any())
    ((64, 64, 3), True)
    """
    plotter, polys = _plotter(meshes, size=size, colors=colors, scalars=scalars, cmap=cmap, clim=clim,
                              background=background, smooth_shading=smooth_shading, show_edges=show_edges,
                              style=style)
    try:
        _set_camera(plotter, view, azimuth, elevation, zoom, fit=polys if fit else None)
        image = _snap(plotter)
    finally:
        plotter.close()
    if path is not None:
        from ..io import write_image

        Path(path).parent.mkdir(parents=True, exist_ok=True)
        write_image(path, image)
    return image


def render_stereo_pair(meshes, path=None, *, separation=5.0, cross=True, size=384, view="iso", elevation=0.0,
                       gap=8, **kwargs) -> np.ndarray:
    """A stereo pair side by side (figure 10): two renders ``separation`` degrees of azimuth apart.

    ``cross=True`` puts the right eye's view on the left (cross-fused, as in
    the paper); ``cross=False`` is for parallel (wall-eyed) viewing. ``gap``
    background pixels separate the halves. Other keywords go to
    :func:`render_mesh`. Returns ``(height, 2 * width + gap, 3)`` uint8.

    Examples
    --------
    >>> from noiselab.geometry import sphere
    >>> render_stereo_pair(sphere(2), size=32, gap=4).shape
    (32, 68, 3)
    """
    separation = check_real("separation", separation, lo=0.0, hi=30.0)
    gap = check_int("gap", gap, lo=0, hi=4096)
    left = render_mesh(meshes, size=size, view=view, azimuth=-separation / 2, elevation=elevation, **kwargs)
    right = render_mesh(meshes, size=size, view=view, azimuth=separation / 2, elevation=elevation, **kwargs)
    spacer = np.full((left.shape[0], gap, 3), left[0, 0], dtype=np.uint8)
    image = np.concatenate([right, spacer, left] if cross else [left, spacer, right], axis=1)
    return _save_array(image, path)


@renamed_parameters(show_progress="progress")
def render_turntable(meshes, path=None, *, frames=36, fps=25.0, degrees=360.0, size=512, view="iso",
                     elevation=0.0, zoom=1.0, colors=None, scalars=None, cmap="viridis", clim=None,
                     background="white", smooth_shading=True, show_edges=False, style="surface",
                     progress=None) -> np.ndarray:
    """Render a turntable: the camera turns ``degrees`` about the view-up axis over ``frames`` frames.

    Returns the frames ``(frames, height, width, 3)`` uint8 and writes them to
    ``path`` (MP4, GIF, NPY or a folder of PNGs) when given. The last frame
    stops one step short of a full turn so that the loop is seamless.

    Examples
    --------
    >>> from noiselab.geometry import load_model
    >>> render_turntable(load_model("ant"), frames=3, size=32).shape
    (3, 32, 32, 3)
    """
    from .._core import progress as progress_bar

    frames = check_int("frames", frames, lo=1, hi=100_000)
    degrees = check_real("degrees", degrees, lo=-3600.0, hi=3600.0)
    plotter, _ = _plotter(meshes, size=size, colors=colors, scalars=scalars, cmap=cmap, clim=clim,
                          background=background, smooth_shading=smooth_shading, show_edges=show_edges, style=style)
    out = []
    try:
        _set_camera(plotter, view, 0.0, elevation, zoom)
        step = degrees / frames
        for i in progress_bar(range(frames), desc="turntable", enabled=progress, unit="frame"):
            if i:
                plotter.camera.Azimuth(step)
                plotter.reset_camera_clipping_range()
            out.append(_snap(plotter))
    finally:
        plotter.close()
    video = np.stack(out)
    if path is not None:
        from ..io import write_video

        Path(path).parent.mkdir(parents=True, exist_ok=True)
        write_video(path, video, fps=fps)
    return video


@renamed_parameters(show_progress="progress")
def render_sequence(meshes, path=None, *, fps=25.0, size=512, view="iso", azimuth=0.0, elevation=0.0,
                    zoom=1.0, color=None, scalars=None, cmap="viridis", clim=None, background="white",
                    smooth_shading=True, spin=0.0, progress=None) -> np.ndarray:
    """Render a time-varying shape: an iterable of meshes with the same faces (e.g. :func:`displace_frames`).

    The camera is fitted to the first mesh and then held fixed (``spin``
    degrees of azimuth per frame turn it), so that the motion seen is the
    shape's own. Frames are rendered by updating the vertex positions of one
    actor. Returns ``(frames, height, width, 3)`` uint8 and writes to ``path``
    (MP4/GIF/NPY/folder) when given.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab.geometry import displace_frames, sphere
    >>> boil = displace_frames(sphere(3), lambda p: np.sin(3 * p[:, 0] + p[:, 3]), [0.0, 0.5], amplitude=0.1)
    >>> render_sequence(boil, size=32).shape
    (2, 32, 32, 3)
    """
    from .._core import progress as progress_bar

    spin = check_real("spin", spin)
    out = []
    plotter = polys = None
    first_faces = None
    try:
        for i, mesh in enumerate(progress_bar(meshes, desc="frames", enabled=progress, unit="frame")):
            mesh = as_trimesh(mesh, name=f"meshes[{i}]")
            if plotter is None:
                plotter, polys = _plotter([mesh], size=size, colors=color, scalars=scalars, cmap=cmap, clim=clim,
                                          background=background, smooth_shading=smooth_shading, show_edges=False)
                _set_camera(plotter, view, azimuth, elevation, zoom)
                first_faces = np.asarray(mesh.faces)
            else:
                if mesh.faces.shape != first_faces.shape or len(mesh.vertices) != polys[0].n_points:
                    raise ValueError(f"meshes[{i}] has a different topology from meshes[0]; "
                                     "a sequence must keep its faces and vertex count")
                polys[0].points = np.asarray(mesh.vertices, dtype=np.float64)
                if scalars is not None:
                    polys[0].point_data[scalars] = np.asarray(mesh.vertex_attributes[scalars])
                if smooth_shading:
                    _set_normals(polys[0])
                polys[0].Modified()
                if spin:
                    plotter.camera.Azimuth(spin)
                plotter.reset_camera_clipping_range()
            out.append(_snap(plotter))
    finally:
        if plotter is not None:
            plotter.close()
    if not out:
        raise ValueError("meshes is empty: nothing to render")
    video = np.stack(out)
    if path is not None:
        from ..io import write_video

        Path(path).parent.mkdir(parents=True, exist_ok=True)
        write_video(path, video, fps=fps)
    return video


def figure_to_array(fig, *, close=True) -> np.ndarray:
    """Draw a matplotlib figure (Agg) and return it as a ``(height, width, 3)`` uint8 array.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    close : bool, default True
        Close the figure afterwards (pyplot figures only).

    Returns
    -------
    ndarray (height, width, 3) of uint8

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> fig = Figure(figsize=(2, 1), dpi=50)
    >>> figure_to_array(fig, close=False).shape
    (50, 100, 3)
    """
    if not hasattr(fig.canvas, "buffer_rgba"):
        # a bare Figure (not made by pyplot) has no raster canvas yet: give it Agg's
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        FigureCanvasAgg(fig)
    fig.canvas.draw()
    image = np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()
    if close:
        import sys

        if "matplotlib.pyplot" in sys.modules:      # only pyplot keeps figures alive
            sys.modules["matplotlib.pyplot"].close(fig)
    return image


def _new_figure(size, dpi=100):
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    h, w = _size(size)
    fig = Figure(figsize=(w / dpi, h / dpi), dpi=dpi)
    FigureCanvasAgg(fig)
    return fig


def _save_array(image, path):
    if path is not None:
        from ..io import write_image

        Path(path).parent.mkdir(parents=True, exist_ok=True)
        write_image(path, image)
    return image
