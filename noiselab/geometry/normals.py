"""Exact normals of noise surfaces from the noise's analytic gradient.

- :func:`monge_normals`: the normal of a Monge surface / height map
  ``z = amplitude * s(frequency * (y, x) + phase)`` (Phillips Eq. 8, figures
  8, 14, 15): ``(-dz/dy, -dz/dx, 1) / |.|``, its points and normals in the
  array-axis order of the geometry grids (``(y, x)``, see
  :mod:`noiselab.geometry.surfaces`).
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

import numbers

import numpy as np

from .._core import check_finite_array, check_int, check_real, check_real_array, check_real_vector
from .surfaces import _scaled

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
    >>> v, g = field_gradient(LatticeNoise(3, rng=0), np.zeros((4, 3)), octaves=3)
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
    pts = check_finite_array("points", points).astype(np.float64, copy=False)
    if pts.ndim != 2:
        raise ValueError(f"points must be an (n, k) array of k-D points, got shape {pts.shape}")
    if getattr(field, "dim_in", None) != pts.shape[1]:
        raise ValueError(f"field must take {pts.shape[1]}-D points here (dim_in={pts.shape[1]}), got "
                         f"dim_in={getattr(field, 'dim_in', None)}")
    summed = turbulence_gradient if kind == "turbulence" else fractal_gradient
    value, grad = summed(field, pts, octaves, lacunarity=lacunarity, gain=gain, return_value=True)
    return np.asarray(value, dtype=np.float64), np.asarray(grad, dtype=np.float64)


def _unit(v):
    """Rows of ``v`` scaled to unit length (0 rows stay 0); scaled by their largest entry first, so that
    neither huge (1e300) nor tiny (1e-300) rows overflow or underflow in the squares."""
    big = np.max(np.abs(v), axis=-1, keepdims=True)
    v = v / np.where(big > 0, big, 1.0)
    norm = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / np.where(norm > 0, norm, 1.0)


def _gain(amplitude, frequency):
    """``(c0, ca, fs)`` with ``c0 n - ca grad(s) * (frequency / fs)`` proportional to the normal's terms:
    ``(1, amplitude, 1)`` when ``|amplitude| * max(frequency) <= 1``, else everything divided by that
    product (computed without forming it, which may overflow)."""
    top = float(np.max(frequency))
    if abs(amplitude) * top <= 1.0:
        return 1.0, amplitude, 1.0
    return (1.0 / top) / abs(amplitude), float(np.sign(amplitude)), top


def monge_normals(field, points, amplitude=1.0, frequency=1.0, phase=0.0, *, octaves=1, kind="fractal",
                  lacunarity=2.0, gain=0.5, return_heights=False):
    r"""Exact unit normals of the Monge surface ``z = amplitude * s(frequency * (y, x) + phase)``.

    The parameters are those of :func:`noiselab.geometry.monge_surface` and
    :func:`~noiselab.geometry.height_map`, so ``monge_normals(field,
    mesh.vertices[:, :2], ...)`` gives the normals of the mesh those build,
    and ``monge_normals(field, grid_points(shape, extent))`` those of the
    height map, without differencing it:
    ``n = (-z_y, -z_x, 1) / sqrt(1 + z_y^2 + z_x^2)`` with
    ``z_y = amplitude * frequency * ds/du_0`` (the derivative along the field's
    first input, array axis 0 of a grid).

    Parameters
    ----------
    field : LatticeNoise (dim_in=2, dim_out=1, C1 kernel) or a warp of one
    points : array (..., 2)
        ``(y, x)`` positions, the field's inputs: array-axis order, as
        :func:`~noiselab.geometry.grid_points` gives them. The normals'
        first two components follow the same order.
    amplitude, frequency, phase, octaves, kind, lacunarity, gain
        As for :func:`noiselab.geometry.height_map`.
    return_heights : bool
        Also return the heights z (computed in the same pass), as ``(z, normals)``.

    Returns
    -------
    ndarray (..., 3), upward (``n_z >= 0``) unit normals

    Notes
    -----
    With ``|amplitude| * frequency > 1`` the normal is computed divided
    through by that product, so a huge one (1e300) gives the limit, a
    horizontal normal against the gradient, instead of overflowing.

    Raises
    ------
    ValueError
        For a field that does not take 2-D points, or a kernel without a
        continuous first derivative.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab import LatticeNoise
    >>> from noiselab.geometry import grid_points
    >>> pts = grid_points((64, 64), ((0, 4), (0, 4)))
    >>> n = monge_normals(LatticeNoise(2, rng=1), pts, amplitude=0.5)
    >>> n.shape, bool(np.allclose(np.linalg.norm(n, axis=-1), 1) and n[..., 2].min() > 0)
    ((64, 64, 3), True)
    """
    amplitude = check_real("amplitude", amplitude)
    frequency = check_real("frequency", frequency, lo=0.0)
    phase = check_real_vector("phase", phase, 2)
    pts = check_finite_array("points", points).astype(np.float64, copy=False)
    if pts.ndim == 0 or pts.shape[-1] != 2:
        raise ValueError(f"points must have shape (..., 2) (y, x), got {pts.shape}")
    lead = pts.shape[:-1]
    value, grad = field_gradient(field, _scaled("points", pts.reshape(-1, 2), frequency, phase), octaves=octaves,
                                 kind=kind, lacunarity=lacunarity, gain=gain)
    # n ~ (-amplitude * frequency * grad, 1), scaled by 1 / (|amplitude| * frequency) when that product is large
    c0, ca, fs = _gain(amplitude, frequency)
    slope = grad.reshape(lead + (2,)) * (ca * (frequency / fs))
    normals = _unit(np.concatenate([-slope, np.full(lead + (1,), c0)], axis=-1))
    if not return_heights:
        return normals
    with np.errstate(over="ignore"):
        heights = amplitude * value.reshape(lead)
    if not np.isfinite(heights).all():
        raise ValueError(f"amplitude {amplitude:.3g} times the field's values overflows float64 (the heights)")
    return heights, normals


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
    ndarray (n_vertices, 3): unit normals of the displaced surface at its vertices (0 where the normal
    is undefined: ``(1 + h kappa) n = grad_S h = 0``). Computed divided through by
    ``max(1, |amplitude| * F)``, ``F`` the largest frequency or ``|curvature|``, so that no term overflows.

    Raises
    ------
    ValueError
        For a mesh without faces, a field that does not take 3-D points, or a
        kernel without a continuous first derivative.

    Examples
    --------
    >>> import numpy as np, trimesh
    >>> from noiselab import LatticeNoise
    >>> sphere = trimesh.creation.icosphere(3)
    >>> n = displaced_normals(sphere, LatticeNoise(3, rng=0), amplitude=0.1, frequency=2.0, curvature=1.0)
    >>> bool(np.allclose(np.linalg.norm(n, axis=1), 1))
    True
    """
    from .displace import as_trimesh, vertex_normals

    mesh = as_trimesh(mesh)
    vertices = np.asarray(mesh.vertices, dtype=np.float64)
    amplitude = check_real("amplitude", amplitude)
    freq = check_real_vector("frequency", frequency, 3, lo=0.0)
    phase_v = check_real_vector("phase", phase, 3)
    if normals is None:
        base = vertex_normals(mesh, weld=True)
        if len(mesh.faces) and mesh.is_watertight and mesh.is_winding_consistent and _inside_out(vertices, mesh.faces):
            base = -base
    else:
        base = check_finite_array("normals", normals).astype(np.float64, copy=False)
        if base.shape != vertices.shape:
            raise ValueError(f"normals must have shape {vertices.shape}, got {base.shape}")
        base = _unit(base)
    if isinstance(curvature, (numbers.Real, np.generic)) and not isinstance(curvature, (bool, np.bool_)):
        kappa = np.float64(check_real("curvature", curvature))
    else:
        kappa = check_real_array("curvature", curvature).astype(np.float64, copy=False)
        if kappa.ndim and kappa.shape != (len(vertices),):
            raise ValueError(f"curvature must be a number or one per vertex ({len(vertices)}), got shape "
                             f"{kappa.shape}")
    value, grad = field_gradient(field, _scaled("points", vertices, freq, phase_v), octaves=octaves, kind=kind,
                                 lacunarity=lacunarity, gain=gain)
    # N ~ (1 + h kappa) n - grad_S h, h = amplitude * s: divided through by max(1, |amplitude| * F) (see
    # _gain), F the largest of the frequencies and |kappa|, so no product can overflow
    c0, ca, fs = _gain(amplitude, np.concatenate([freq, np.abs(np.atleast_1d(kappa)), [0.0]]))
    grad_h = ca * grad * (freq / fs)
    surface_grad = grad_h - np.einsum("ij,ij->i", grad_h, base)[:, None] * base
    return _unit((c0 + ca * value * (kappa / fs))[..., None] * base - surface_grad)


def _inside_out(vertices, faces):
    """Whether a closed mesh's signed volume is negative, from its vertices scaled to at most 1 (the sign does
    not depend on the scale, and trimesh's volume overflows for coordinates past about 1e100)."""
    big = float(np.max(np.abs(vertices), initial=0.0))
    v = vertices / big if big > 0 else vertices
    tri = v[np.asarray(faces, dtype=np.int64)]
    return float(np.einsum("ij,ij->", tri[:, 0], np.cross(tri[:, 1], tri[:, 2]))) < 0


def normal_angles(a, b):
    """Angles in degrees between corresponding unit normals ``a`` and ``b`` (``(..., 3)`` each).

    Computed as ``atan2(|a x b|, a . b)`` of the vectors scaled to unit
    length (any length works, 1e-300 to 1e300), accurate for small angles
    too; a zero vector (an undefined normal) gives 0.

    Parameters
    ----------
    a, b : array_like (..., 3)
        Normals (any length), broadcastable against each other.

    Returns
    -------
    ndarray (...)
        Angles in degrees, in ``[0, 180]``.

    Raises
    ------
    ValueError
        For non-finite vectors, or shapes that do not broadcast.

    Examples
    --------
    >>> float(normal_angles([0, 0, 1], [0, 1, 1] / np.sqrt(2)).round(6))
    45.0
    """
    a = check_real_array("a", a).astype(np.float64, copy=False)
    b = check_real_array("b", b).astype(np.float64, copy=False)
    for name, v in (("a", a), ("b", b)):
        if v.ndim == 0 or v.shape[-1] != 3:
            raise ValueError(f"{name} must hold 3-D vectors, shape (..., 3); got shape {v.shape}")
    try:
        np.broadcast_shapes(a.shape, b.shape)
    except ValueError:
        raise ValueError(f"a and b must have the same (or broadcastable) shapes, got {a.shape} and {b.shape}") \
            from None
    # the angle does not depend on the lengths: scaled to unit length, the products neither overflow nor underflow
    a, b = _unit(a), _unit(b)
    cross = np.linalg.norm(np.cross(a, b), axis=-1)
    return np.degrees(np.arctan2(cross, np.sum(a * b, axis=-1)))
