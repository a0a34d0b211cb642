"""Base shapes: unit (ico)spheres, squashed spheres, pyvista's bundled models, mesh conversions, layouts."""
from __future__ import annotations

import math

import numpy as np

from .._core import check_int, check_real, keyword_only
from ._mesh import require_pyvista, as_trimesh, pyvista_to_trimesh, trimesh_to_pyvista  # noqa: F401  (re-exported)
from .displace import resolution_report
from .surfaces import _grid_mesh, grid_points

__all__ = [
    "sphere",
    "squashed_sphere",
    "plane",
    "sphere_for_noise",
    "load_model",
    "BUNDLED_MODELS",
    "pyvista_to_trimesh",
    "trimesh_to_pyvista",
    "normalize",
    "arrange",
]

# pyvista's ``load_*`` examples that ship inside the wheel (``download_*`` ones
# need the internet) and are surface meshes worth displacing.
BUNDLED_MODELS = ("ant", "airplane", "nut", "sphere")

# Edge length of a unit icosahedron's (level-0 icosphere) edges; each level halves it.
_ICOSAHEDRON_EDGE = 4.0 / math.sqrt(10.0 + 2.0 * math.sqrt(5.0))


def sphere(subdivisions=4, radius=1.0, center=(0.0, 0.0, 0.0)):
    """An icosphere: a subdivided icosahedron with every vertex on the sphere (watertight, near-uniform edges).

    ``subdivisions`` levels give ``10 * 4**k + 2`` vertices (level 4: 2562,
    level 6: 40962, level 8: 655362) and edges about ``1.05 * radius / 2**k``.

    Parameters
    ----------
    subdivisions : int, default 4
        Subdivision levels of the icosahedron (>= 0).
    radius : float, default 1
        Radius (> 0).
    center : (x, y, z), default (0, 0, 0)

    Returns
    -------
    trimesh.Trimesh

    Raises
    ------
    ValueError
        For a negative level, a non-positive radius or a non-finite centre.

    Examples
    --------
    >>> s = sphere(3)
    >>> len(s.vertices), s.is_watertight
    (642, True)
    """
    import trimesh

    subdivisions = check_int("subdivisions", subdivisions, lo=0, hi=10)
    radius = check_real("radius", radius, lo=1e-100, hi=1e100)
    from .._core import check_finite_array

    center = check_finite_array("center", center).astype(np.float64)
    if center.shape != (3,) or not np.all(np.isfinite(center)):
        raise ValueError(f"center must be 3 finite numbers, got {center!r}")
    mesh = trimesh.creation.icosphere(subdivisions=subdivisions, radius=radius)
    if np.any(center):
        mesh.apply_translation(center)
    return mesh


@keyword_only("axis")
def squashed_sphere(squash=0.05, subdivisions=4, radius=1.0, *, axis=2):
    """A sphere squashed by the fraction ``squash`` along ``axis`` (figure 19: 5% vertically).

    The result is an oblate spheroid with semi-axis ``radius * (1 - squash)``
    along ``axis``.

    Parameters
    ----------
    squash : float, default 0.05
        Fraction removed along ``axis``, in ``[0, 1)``.
    subdivisions : int, default 4
        Icosphere levels.
    radius : float, default 1
    axis : {0, 1, 2}, default 2

    Returns
    -------
    trimesh.Trimesh

    Examples
    --------
    >>> s = squashed_sphere(0.05)
    >>> round(float(s.vertices[:, 2].max()), 3)
    0.95
    """
    squash = check_real("squash", squash, lo=0.0, hi=1.0, hi_open=True)
    axis = check_int("axis", axis, lo=0, hi=2)
    mesh = sphere(subdivisions, radius)
    scale = np.ones(3)
    scale[axis] = 1.0 - squash
    mesh.apply_transform(np.diag(np.append(scale, 1.0)))
    return mesh


def plane(resolution=64, size=2.0):
    """A flat square sheet on z = 0, centred on the origin, ``resolution`` x ``resolution`` vertices.

    Normals point up (+z), so :func:`displace` turns it into a Monge surface
    z = s(x, y, 0) (figures 8, 14, 15) of 3-D noise.

    Parameters
    ----------
    resolution : int, default 64
        Vertices per side (>= 2).
    size : float, default 2
        Side length (> 0).

    Returns
    -------
    trimesh.Trimesh
        ``resolution**2`` vertices, ``2 (resolution - 1)**2`` faces.

    Raises
    ------
    ValueError
        For a resolution below 2 or a size that is not positive.

    Examples
    --------
    >>> p = plane(3)
    >>> len(p.vertices), len(p.faces), bool(p.face_normals[:, 2].min() > 0)
    (9, 8, True)
    """

    resolution = check_int("resolution", resolution, lo=2, hi=20_000)
    size = check_real("size", size, lo=1e-300, hi=1e300)
    half = size / 2.0
    step = size / (resolution - 1)
    # stop excluded: one step past +half so that the last sample lands on it
    pts = grid_points((resolution, resolution), ((-half, half + step), (-half, half + step)))
    return _grid_mesh(pts, np.zeros((resolution, resolution)))


def sphere_for_noise(max_frequency, radius=1.0, *, samples_per_period=4.0, max_subdivisions=9):
    """The coarsest icosphere that samples a field of highest frequency ``max_frequency`` (cycles/unit) well.

    Picks the fewest subdivisions whose longest edge gives at least
    ``samples_per_period`` samples per period; rebuilding the icosphere (rather
    than subdividing a coarse one) keeps every vertex exactly on the sphere.

    Parameters
    ----------
    max_frequency : float
        Highest frequency of the field in cycles per unit.
    radius : float, default 1
        The sphere's radius (> 0).
    samples_per_period : float, default 4
        Samples wanted per period of ``max_frequency``.
    max_subdivisions : int, default 9
        The most subdivisions allowed (level 9: 2.6 million vertices).

    Returns
    -------
    trimesh.Trimesh
        A watertight icosphere.

    Raises
    ------
    ValueError
        For a non-positive radius, or when even ``max_subdivisions``
        levels are too coarse.

    Examples
    --------
    >>> len(sphere_for_noise(4.0).vertices)   # 4 cycles/unit, 4 samples per period
    10242
    """
    max_frequency = check_real("max_frequency (cycles/unit)", max_frequency, lo=0.0, hi=1e300)
    radius = check_real("radius", radius, lo=1e-100, hi=1e100)
    samples_per_period = check_real("samples_per_period", samples_per_period, lo=1.0, hi=1e6)
    max_subdivisions = check_int("max_subdivisions", max_subdivisions, lo=0, hi=10)
    if max_frequency == 0:
        return sphere(0, radius)

    for level in range(max_subdivisions + 1):
        mesh = sphere(level, radius)
        if resolution_report(mesh, max_frequency, samples_per_period=samples_per_period).ok:
            return mesh
    raise ValueError(
        f"an icosphere of radius {radius:g} needs more than max_subdivisions={max_subdivisions} levels "
        f"(> {10 * 4 ** max_subdivisions + 2:,} vertices) for {samples_per_period:g} samples per period at "
        f"{max_frequency:g} cycles/unit; lower the frequency or octaves, or raise max_subdivisions"
    )


def normalize(mesh, size=2.0):
    """Return a copy of ``mesh`` centred on its bounding-box centre and scaled so its largest extent is ``size``.

    Useful before displacing a model in unknown units (pyvista's ant is 32
    units long, the airplane 1500): a unit-frequency noise then means the
    same thing on every model.

    Parameters
    ----------
    mesh : trimesh.Trimesh
    size : float, default 2
        Largest extent of the result (> 0).

    Returns
    -------
    trimesh.Trimesh
        A copy; ``mesh`` is unchanged.

    Raises
    ------
    ValueError
        For a size that is not positive or a mesh of zero extent.

    Examples
    --------
    >>> import trimesh
    >>> box = normalize(trimesh.creation.box((4.0, 2.0, 1.0)))
    >>> box.extents.tolist()
    [2.0, 1.0, 0.5]
    """

    size = check_real("size", size, lo=1e-100, hi=1e100)
    out = as_trimesh(mesh).copy()
    lo, hi = out.bounds
    extent = float(np.max(hi - lo))
    if extent == 0:
        raise ValueError("mesh has zero extent: it cannot be normalised")
    out.apply_translation(-(lo + hi) / 2.0)
    out.apply_scale(size / extent)
    return out


def load_model(name="ant", *, size=2.0):
    """Load one of pyvista's bundled models (works offline) as a trimesh, normalised to ``size``.

    ``name`` is one of :data:`BUNDLED_MODELS` (``"ant"``, a watertight
    stand-in for the paper's cow; ``"airplane"``, open; ``"nut"``;
    ``"sphere"``). ``size=None`` keeps the file's own units.

    Parameters
    ----------
    name : str, default "ant"
        One of :data:`BUNDLED_MODELS`.
    size : float or None, default 2
        Largest extent after :func:`normalize`; None keeps the file's units.

    Returns
    -------
    trimesh.Trimesh

    Raises
    ------
    ValueError
        For a name that is not bundled (the message lists them) or a size that is not positive.

    Examples
    --------
    >>> ant = load_model("ant")
    >>> ant.is_watertight, round(float(max(ant.extents)), 6)
    (True, 2.0)
    """
    if name not in BUNDLED_MODELS:
        raise ValueError(f"model must be one of {', '.join(BUNDLED_MODELS)} (pyvista's bundled models), got {name!r}")

    require_pyvista()
    from pyvista import examples

    mesh = pyvista_to_trimesh(getattr(examples, f"load_{name}")())
    mesh.merge_vertices()
    return mesh if size is None else normalize(mesh, size)


def arrange(meshes, columns=None, spacing=0.25):
    """Lay meshes out left to right, top to bottom on the x-y plane, like a figure's panels.

    Each mesh is translated (copies; inputs untouched) so that its bounding
    box centre sits on a grid cell; cells are as wide as the largest mesh plus
    ``spacing`` (a fraction of that size). Returns the list of moved meshes,
    ready for :func:`noiselab.geometry.render_mesh`.

    Examples
    --------
    >>> row = arrange([sphere(1), sphere(1)], spacing=0.5)
    >>> [round(float(m.bounds.mean(axis=0)[0]), 6) for m in row]
    [0.0, 3.0]
    """

    if isinstance(meshes, (str, bytes)) or not hasattr(meshes, "__iter__") or hasattr(meshes, "vertices"):
        raise TypeError(f"meshes must be a sequence of meshes, got {type(meshes).__name__}")
    meshes = [as_trimesh(m, name=f"meshes[{i}]") for i, m in enumerate(meshes)]
    if not meshes:
        raise ValueError("meshes must hold at least one mesh")
    columns = len(meshes) if columns is None else check_int("columns", columns, lo=1)
    spacing = check_real("spacing", spacing, lo=0.0, hi=1e6)
    cell = max(float(np.max(m.extents)) for m in meshes) * (1.0 + spacing)
    out = []
    for i, m in enumerate(meshes):
        row, col = divmod(i, columns)
        moved = m.copy()
        lo, hi = moved.bounds
        moved.apply_translation(np.array([col * cell, -row * cell, 0.0]) - (lo + hi) / 2.0)
        out.append(moved)
    return out
