"""Exact normals of noise surfaces from the noise's analytic gradient.

- :func:`monge_normals`: the normal of a Monge surface / height map
  ``z = amplitude * s(frequency * (x, y) + phase)`` (Phillips Eq. 8, figures
  8, 14, 15): ``(-dz/dx, -dz/dy, 1) / |.|``.
- :func:`displaced_normals`: the normal of a displaced mesh
  ``p' = p + h(p) n(p)``, ``h = amplitude * s(frequency * p + phase)``
  (Eq. 11, figures 16-20), from the noise gradient and the base normal.
- :func:`normal_angles`: the angle between two sets of normals (degrees), to
  compare these with the normals recomputed from the displaced mesh's faces.

``s`` is a :class:`noiselab.LatticeNoise` with a C1 kernel (or anything with
``jacobian``), or its fractal sum / turbulence over ``octaves``, evaluated by
:func:`noiselab.fractal.fractal_gradient` / ``turbulence_gradient``.
"""
from __future__ import annotations

import numpy as np

from .._validate import check_finite_array, check_int, check_real

__all__ = ["monge_normals", "displaced_normals", "normal_angles", "field_gradient"]


def field_gradient(field, points, *, octaves=1, kind="fractal", lacunarity=2.0, gain=0.5):
    """Value and exact gradient of a scalar noise field (or its octave sum) at points ``(n, k)``.

    Returns ``(value (n,), gradient (n, k))`` in the field's input units.
    ``kind`` is ``"fractal"`` (Eq. 9), ``"turbulence"`` (Eq. 10; ``sign(0) = 0``
    on its creases) or ``"noise"`` (one octave), as in :func:`octave_field`.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab import LatticeNoise
    >>> v, g = field_gradient(LatticeNoise(3, seed=0), np.zeros((4, 3)), octaves=3)
    >>> v.shape, g.shape
    ((4,), (4, 3))
    """
    from ..fractal import fractal_gradient, turbulence_gradient

    if not (callable(getattr(field, "jacobian", None)) and getattr(field, "dim_out", None) == 1):
        raise TypeError("field must be a scalar noise with an exact derivative (a LatticeNoise with dim_out=1 "
                        f"and a C1 kernel, or a warp of one); got {type(field).__name__}")
    octaves = check_int("octaves", octaves, lo=1, hi=64)
    if kind not in ("fractal", "turbulence", "noise"):
        raise ValueError(f"kind must be 'noise', 'fractal' or 'turbulence', got {kind!r}")
    if kind == "noise" and octaves != 1:
        raise ValueError(f"kind='noise' means a single octave; use kind='fractal' for octaves={octaves}")
    pts = check_finite_array("points", np.asarray(points, dtype=np.float64))
    summed = turbulence_gradient if kind == "turbulence" else fractal_gradient
    value, grad = summed(field, pts, octaves, lacunarity=lacunarity, gain=gain, return_value=True)
    return np.asarray(value, dtype=np.float64), np.asarray(grad, dtype=np.float64)


def _unit(v):
    norm = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / np.where(norm > 0, norm, 1.0)


def _per_axis(name, value, size):
    arr = np.asarray(value, dtype=np.float64)
    if arr.ndim == 0:
        arr = np.full(size, float(arr))
    if arr.shape != (size,):
        raise ValueError(f"{name} must be a number or a vector of {size} numbers, got shape {arr.shape}")
    return check_finite_array(name, arr)


def monge_normals(field, points, amplitude=1.0, frequency=1.0, phase=0.0, *, octaves=1, kind="fractal",
                  lacunarity=2.0, gain=0.5, return_heights=False):
    r"""Exact unit normals of the Monge surface ``z = amplitude * s(frequency * (x, y) + phase)``.

    The parameters are those of :func:`noiselab.geometry.monge_surface` and
    :func:`~noiselab.geometry.height_map`, so ``monge_normals(field,
    mesh.vertices[:, :2], ...)`` gives the normals of the mesh those build,
    without differencing it: ``n = (-z_x, -z_y, 1) / sqrt(1 + z_x^2 + z_y^2)``
    with ``z_x = amplitude * frequency * ds/du``.

    Parameters
    ----------
    field : LatticeNoise (dim_in=2, dim_out=1, C1 kernel) or a warp of one
    points : array (..., 2)
        (x, y) positions.
    amplitude, frequency, phase, octaves, kind, lacunarity, gain
        As for :func:`noiselab.geometry.height_map`.
    return_heights : bool
        Also return the heights z (computed in the same pass), as ``(z, normals)``.

    Returns
    -------
    ndarray (..., 3), upward (``n_z > 0``) unit normals

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab import LatticeNoise
    >>> from noiselab.geometry import grid_points
    >>> pts = grid_points((64, 64), ((0, 4), (0, 4)))
    >>> n = monge_normals(LatticeNoise(2, seed=1), pts, amplitude=0.5)
    >>> n.shape, bool(np.allclose(np.linalg.norm(n, axis=-1), 1) and n[..., 2].min() > 0)
    ((64, 64, 3), True)
    """
    amplitude = check_real("amplitude", amplitude)
    frequency = check_real("frequency", frequency, lo=0.0)
    phase = _per_axis("phase", phase, 2)
    pts = check_finite_array("points", np.asarray(points, dtype=np.float64))
    if pts.ndim == 0 or pts.shape[-1] != 2:
        raise ValueError(f"points must have shape (..., 2) (x, y), got {pts.shape}")
    lead = pts.shape[:-1]
    value, grad = field_gradient(field, pts.reshape(-1, 2) * frequency + phase, octaves=octaves, kind=kind,
                                 lacunarity=lacunarity, gain=gain)
    slope = grad.reshape(lead + (2,)) * (amplitude * frequency)
    normals = _unit(np.concatenate([-slope, np.ones(lead + (1,))], axis=-1))
    return (amplitude * value.reshape(lead), normals) if return_heights else normals


def displaced_normals(mesh, field, amplitude=1.0, frequency=1.0, phase=0.0, *, octaves=1, kind="fractal",
                      lacunarity=2.0, gain=0.5, normals=None, curvature=0.0):
    r"""Exact normals of :func:`noiselab.geometry.displace`'s surface from the noise gradient and the base normal.

    The displaced surface is ``P = p + h(p) n`` with ``h = amplitude *
    s(frequency * p + phase)``. Along a tangent ``e`` of the base,
    ``dP(e) = (I + h S) e + (grad_S h . e) n`` (``S`` the base's shape
    operator, ``grad_S h = grad h - (grad h . n) n`` the surface gradient), so
    for an umbilic base (``S = curvature * I``: a plane, 0; a sphere of radius
    R, 1/R) the normal is exactly

    .. math:: N \propto (1 + h\,\kappa)\, n - \nabla_S h .

    On any other base ``curvature=0`` gives the normal to first order in
    ``h`` times the base's curvature.

    Parameters
    ----------
    mesh : trimesh.Trimesh or pyvista.PolyData
        The base (undisplaced) mesh, as given to ``displace``.
    field, amplitude, frequency, phase, octaves, kind, lacunarity, gain
        As for ``displace`` (``frequency`` and ``phase`` scalars or 3-vectors;
        ``field`` a 3-D scalar :class:`~noiselab.LatticeNoise` with a C1 kernel).
    normals : (n, 3) array, optional
        Base unit normals; default the welded area-weighted vertex normals
        ``displace`` uses (flipped outwards for an inside-out closed mesh).
    curvature : float or (n,) array
        The base's normal curvature ``kappa`` (1/R for a sphere of radius R).

    Returns
    -------
    ndarray (n_vertices, 3): unit normals of the displaced surface at its vertices

    Examples
    --------
    >>> import numpy as np, trimesh
    >>> from noiselab import LatticeNoise
    >>> sphere = trimesh.creation.icosphere(3)
    >>> n = displaced_normals(sphere, LatticeNoise(3, seed=0), amplitude=0.1, frequency=2.0, curvature=1.0)
    >>> bool(np.allclose(np.linalg.norm(n, axis=1), 1))
    True
    """
    from .displace import as_trimesh, vertex_normals

    mesh = as_trimesh(mesh)
    vertices = np.asarray(mesh.vertices, dtype=np.float64)
    amplitude = check_real("amplitude", amplitude)
    freq = _per_axis("frequency", frequency, 3)
    if np.any(freq < 0):
        raise ValueError(f"frequency must be >= 0 (on every axis), got {freq.tolist()}")
    phase_v = _per_axis("phase", phase, 3)
    if normals is None:
        base = vertex_normals(mesh, weld=True)
        if len(mesh.faces) and mesh.is_watertight and mesh.is_winding_consistent and mesh.volume < 0:
            base = -base
    else:
        base = check_finite_array("normals", np.asarray(normals, dtype=np.float64))
        if base.shape != vertices.shape:
            raise ValueError(f"normals must have shape {vertices.shape}, got {base.shape}")
        base = _unit(base)
    kappa = np.asarray(curvature, dtype=np.float64)
    if kappa.ndim and kappa.shape != (len(vertices),):
        raise ValueError(f"curvature must be a number or one per vertex ({len(vertices)}), got shape {kappa.shape}")
    kappa = check_finite_array("curvature", kappa)
    value, grad = field_gradient(field, vertices * freq + phase_v, octaves=octaves, kind=kind,
                                 lacunarity=lacunarity, gain=gain)
    h = amplitude * value
    grad_h = amplitude * grad * freq
    surface_grad = grad_h - np.einsum("ij,ij->i", grad_h, base)[:, None] * base
    return _unit((1.0 + h * kappa)[..., None] * base - surface_grad)


def normal_angles(a, b):
    """Angles in degrees between corresponding unit normals ``a`` and ``b`` (``(..., 3)`` each).

    Computed as ``atan2(|a x b|, a . b)``, accurate for small angles too.

    Examples
    --------
    >>> float(normal_angles([0, 0, 1], [0, 1, 1] / np.sqrt(2)).round(6))
    45.0
    """
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    cross = np.linalg.norm(np.cross(a, b), axis=-1)
    return np.degrees(np.arctan2(cross, np.sum(a * b, axis=-1)))
