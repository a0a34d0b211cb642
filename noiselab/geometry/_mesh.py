"""Mesh conversions and the pyvista loader: the leaf module of :mod:`noiselab.geometry`.

It imports nothing else from the package, so ``displace``, ``shapes``,
``surfaces`` and ``render`` all build on it and none of them imports another
one back (the package's import graph has no cycle; ``tests/test_geometry_imports.py``
checks it).
"""
from __future__ import annotations

import os

import numpy as np

from .._core import check_finite_array

__all__ = ["AliasingWarning", "as_trimesh", "pyvista_to_trimesh", "require_pyvista", "trimesh_to_pyvista"]


class AliasingWarning(UserWarning):
    """The mesh is too coarse for the field's highest frequency."""


def require_pyvista():
    """Import pyvista for off-screen rendering (EGL window selected before the first import)."""
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista as pv

    pv.OFF_SCREEN = True
    return pv


def as_trimesh(mesh, *, name="mesh"):
    """Return ``mesh`` as a ``trimesh.Trimesh`` (accepts a Trimesh, a pyvista PolyData, or a one-mesh Scene).

    A point cloud, a mesh without faces or with non-triangle faces that cannot
    be triangulated is a clear error: displacement needs faces to define normals.
    """
    import trimesh

    if isinstance(mesh, trimesh.Trimesh):
        out = mesh
    elif isinstance(mesh, trimesh.Scene):
        geoms = [g for g in mesh.geometry.values() if isinstance(g, trimesh.Trimesh)]
        if not geoms:
            raise ValueError(f"{name} is a scene without any triangle mesh (a point cloud or paths only)")
        out = mesh.to_mesh() if len(geoms) > 1 else geoms[0]
    elif isinstance(mesh, trimesh.PointCloud):
        raise ValueError(f"{name} is a point cloud without faces: displacement needs faces to define normals")
    elif hasattr(mesh, "points") and hasattr(mesh, "faces") and hasattr(mesh, "triangulate"):
        out = pyvista_to_trimesh(mesh)
    else:
        raise TypeError(f"{name} must be a trimesh.Trimesh or pyvista.PolyData, got {type(mesh).__name__}")
    if len(out.faces) == 0:
        raise ValueError(
            f"{name} has no faces ({len(out.vertices)} vertices): a point cloud has no surface normals to "
            "displace along; reconstruct a surface first"
        )
    check_finite_array(f"{name} vertices", np.asarray(out.vertices))
    return out


def pyvista_to_trimesh(poly):
    """Convert a pyvista ``PolyData`` (any polygons; triangulated here) to a ``trimesh.Trimesh``.

    Examples
    --------
    >>> from noiselab.geometry._mesh import require_pyvista
    >>> pv = require_pyvista()
    >>> len(pyvista_to_trimesh(pv.Cube()).faces)      # 6 quads -> 12 triangles
    12
    """
    import trimesh

    if not hasattr(poly, "extract_surface"):
        raise TypeError(f"expected a pyvista dataset, got {type(poly).__name__}")
    surf = poly if poly.__class__.__name__ == "PolyData" else poly.extract_surface()
    surf = surf.triangulate()
    if surf.n_cells == 0 or surf.faces.size == 0:
        raise ValueError(f"the pyvista mesh has no polygon faces ({surf.n_points} points): nothing to displace")
    faces = np.asarray(surf.faces).reshape(-1, 4)[:, 1:]
    return trimesh.Trimesh(np.asarray(surf.points, dtype=np.float64), faces.astype(np.int64), process=False)


def trimesh_to_pyvista(mesh):
    """Convert a ``trimesh.Trimesh`` to a pyvista ``PolyData`` (vertex colours as ``"rgb"`` point data).

    Examples
    --------
    >>> from noiselab.geometry import sphere
    >>> poly = trimesh_to_pyvista(sphere(1))
    >>> poly.n_points, poly.n_cells
    (42, 80)
    """
    pv = require_pyvista()
    faces = np.asarray(mesh.faces, dtype=np.int64)
    cells = np.empty((len(faces), 4), dtype=np.int64)
    cells[:, 0] = 3
    cells[:, 1:] = faces
    poly = pv.PolyData(np.asarray(mesh.vertices, dtype=np.float64), cells.ravel())
    if mesh.visual.kind == "vertex":
        poly.point_data["rgb"] = np.asarray(mesh.visual.vertex_colors)[:, :3]
    for key, value in getattr(mesh, "vertex_attributes", {}).items():
        value = np.asarray(value)
        if value.shape[:1] == (len(mesh.vertices),) and value.dtype.kind in "fiu":
            poly.point_data[key] = value
    return poly
