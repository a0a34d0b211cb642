"""Monge surfaces z = f(y, x) (Phillips 2004, Eq. 8, figures 8, 14, 15) and height + colour surfaces (figure 11).

One order for grids in all of :mod:`noiselab.geometry`, the array-axis order
of :class:`noiselab.lattice.Grid`: ``shape`` is ``(rows, columns)`` =
``(ny, nx)`` (``(nz, ny, nx)`` in 3-D) and ``extent`` is
``((y0, y1), (x0, x1))`` (``((z0, z1), (y0, y1), (x0, x1))``), one
``(start, stop)`` pair per array axis, the stop excluded as in
``numpy.arange``: row ``i`` is at ``y0 + i * (y1 - y0) / ny`` and column ``j``
at ``x0 + j * (x1 - x0) / nx`` (x runs right along columns, y along rows, as
in noiselab's images). A grid point is in the same order, ``(y, x)``
(``(z, y, x)``): the field is evaluated at ``(y_i, x_j)``, as
``LatticeNoise.grid`` evaluates it, so ``height_map(noise, shape, extent)`` is
``noise.grid(shape, extent)`` and ``sampled_field(heights, extent)``
interpolates the heights back. ``phase`` has one entry per axis in that order.
A mesh on a grid puts each vertex at its grid point followed by the height,
``(y, x, z)``, so ``monge_normals(field, mesh.vertices[:, :2])`` gives its
exact normals.
"""
from __future__ import annotations

import warnings

import numpy as np

from .._core import (check_finite_array, check_int, check_memory, check_real, check_real_sequence, check_real_vector,
                     check_shape, renamed_parameters)
from .fields import evaluate_field, field_max_frequency, octave_field

__all__ = ["grid_points", "height_map", "monge_surface", "colored_surface", "height_map_image"]


def _extent(extent, dims=2):
    arr = check_finite_array("extent", extent)
    if arr.dtype.kind == "b":
        raise TypeError(f"extent must hold numbers, got booleans: {extent!r}")
    arr = arr.astype(np.float64)
    if arr.shape != (dims, 2):
        raise ValueError(f"extent must be {dims} (start, stop) pairs, one per array axis (rows first), got {extent!r}")
    if not np.all(np.isfinite(arr)) or np.any(arr[:, 1] <= arr[:, 0]):
        raise ValueError(f"extent must be finite with stop > start on every axis, got {arr.tolist()}")
    return arr


def grid_points(shape, extent):
    """Sample points of a regular grid, all in array-axis order (rows first), like :class:`noiselab.lattice.Grid`.

    Parameters
    ----------
    shape : (ny, nx) or (nz, ny, nx)
        Samples per array axis.
    extent : ((y0, y1), (x0, x1)) or ((z0, z1), (y0, y1), (x0, x1))
        One ``(start, stop)`` pair per array axis, in the order of ``shape``;
        the stop is excluded.

    Returns
    -------
    ndarray of shape ``(*shape, d)``, float64
        ``points[i, j] = (y_i, x_j)`` (3-D: ``points[k, i, j] = (z_k, y_i, x_j)``):
        the coordinate along every array axis, in axis order, computed as
        ``LatticeNoise.grid`` computes it (``start + i * ((stop - start) / n)``).

    Examples
    --------
    >>> p = grid_points((2, 4), ((0, 1), (0, 4)))
    >>> p[1, 3].tolist()
    [0.5, 3.0]
    """
    shape = check_shape("shape", shape, ndim=(2, 3), min_size=1)
    ext = _extent(extent, len(shape))
    check_memory(int(np.prod(shape)) * len(shape) * 8 * 3, "the sampling grid")
    axes = [ext[k, 0] + np.arange(n, dtype=np.float64) * ((ext[k, 1] - ext[k, 0]) / n) for k, n in enumerate(shape)]
    return np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)


def _check_grid_resolution(shape, ext, max_frequency, samples_per_period, on_alias):
    if on_alias == "ignore" or max_frequency == 0:
        return
    from ._mesh import AliasingWarning

    spacing = float(np.max((ext[:, 1] - ext[:, 0]) / np.asarray(shape, dtype=float)))
    spp = 1.0 / (max_frequency * spacing)
    if spp < samples_per_period:
        msg = (f"grid too coarse for the field: spacing {spacing:.4g} gives {spp:.2f} samples per period at the "
               f"highest frequency {max_frequency:g} cycles/unit (>= {samples_per_period:g} needed); use a shape "
               f"of at least {int(np.ceil(samples_per_period * max_frequency * spacing * max(shape)))} "
               "samples per axis, or fewer octaves")
        if on_alias == "raise":
            raise ValueError(msg)
        warnings.warn(msg, AliasingWarning, stacklevel=3)


def _sample(field, shape, extent, amplitude, frequency, phase, octaves, kind, lacunarity, gain,
            components, samples_per_period, on_alias):
    shape = check_shape("shape", shape, ndim=2, min_size=2)
    ext = _extent(extent)
    amplitude = check_real("amplitude", amplitude)
    frequency = check_real("frequency", frequency, lo=0.0)
    phase = check_real_vector("phase", phase, 2)
    if on_alias not in ("warn", "raise", "ignore"):
        raise ValueError(f"on_alias must be 'warn', 'raise' or 'ignore', got {on_alias!r}")
    source = octave_field(field, octaves, kind, lacunarity=lacunarity, gain=gain)
    _check_grid_resolution(shape, ext, frequency * field_max_frequency(source), samples_per_period, on_alias)
    pts = grid_points(shape, ext)
    scaled = _scaled("extent", pts.reshape(-1, 2), frequency, phase)
    values = evaluate_field(source, scaled, components=components)
    return pts, _amplified(values.reshape(shape + values.shape[1:]), amplitude)


def _scaled(name, pts, frequency, phase):
    """``pts * frequency + phase``, refusing an overflow with a message naming the inputs."""
    with np.errstate(over="ignore", invalid="ignore"):
        out = pts * frequency + phase
    if not np.isfinite(out).all():
        raise ValueError(f"{name} times frequency plus phase overflows float64 (frequency={np.max(frequency):.3g}); "
                         "use smaller coordinates or frequency")
    return out


def _amplified(values, amplitude):
    """``amplitude * values``, refusing an overflow with a message naming amplitude."""
    with np.errstate(over="ignore", invalid="ignore"):
        out = values * amplitude
    if not np.isfinite(out).all():
        raise ValueError(f"amplitude {amplitude:.3g} times the field's values overflows float64")
    return out


@renamed_parameters(on_aliasing="on_alias")
def height_map(field, shape=(256, 256), extent=((0.0, 4.0), (0.0, 4.0)), amplitude=1.0, frequency=1.0,
               phase=0.0, *, octaves=1, kind="fractal", lacunarity=2.0, gain=0.5, samples_per_period=4.0,
               on_alias="warn") -> np.ndarray:
    """Heights ``amplitude * s(frequency * (y, x) + phase)`` on a grid: a ``(ny, nx)`` float64 array.

    ``s`` is ``field`` (2-D input, scalar output) or its fractal sum /
    turbulence over ``octaves`` (figures 14 and 15). ``shape`` is
    ``(ny, nx)`` (rows, columns) and ``extent`` ``((y0, y1), (x0, x1))``, the
    stop excluded; the field takes points ``(y, x)`` in the same array-axis
    order (``phase`` too), so for a ``LatticeNoise`` this is
    ``noise.grid(shape, extent)``. A grid too coarse for the highest octave
    warns (:class:`AliasingWarning`), or raises with ``on_alias="raise"``.

    Parameters
    ----------
    field : callable or LatticeNoise
        Maps points ``(n, 2)`` in ``(y, x)`` order to ``(n,)`` values.
    shape : (ny, nx)
        Samples per axis (rows, columns).
    extent : ((y0, y1), (x0, x1))
        The grid's span in field units, stops excluded.
    amplitude : float
        Height scale.
    frequency, phase : float or (fy, fx)
        Applied to the points before the field: ``s(frequency * p + phase)``.
    octaves : int, default 1
        Octaves of the fractal sum or turbulence (1: the field itself).
    kind : {"fractal", "turbulence"}, default "fractal"
        How the octaves combine (Phillips Eq. 9 or 10).
    lacunarity, gain : float
        Frequency and amplitude ratios between octaves.
    samples_per_period : float, default 4
        Samples per period of the highest octave below which the grid aliases.
    on_alias : {"warn", "raise", "ignore"}, default "warn"
        What a grid too coarse for the highest octave does.

    Returns
    -------
    ndarray (ny, nx) of float64

    Raises
    ------
    ValueError
        For a shape, extent, amplitude, frequency or octave count out of range,
        a field of the wrong dimension, or (``on_alias="raise"``) a grid too
        coarse for the highest octave.

    Examples
    --------
    >>> import numpy as np
    >>> h = height_map(lambda p: np.sin(p[:, 1]), (4, 8), ((0, 4), (0, 8)), on_alias="ignore")
    >>> h.shape, bool(np.allclose(h[0], np.sin(np.arange(8))))
    ((4, 8), True)
    """
    return _sample(field, shape, extent, amplitude, frequency, phase, octaves, kind, lacunarity, gain, 1,
                   samples_per_period, on_alias)[1]


def _grid_faces(h, w):
    idx = np.arange(h * w, dtype=np.int64).reshape(h, w)
    a, b = idx[:-1, :-1].ravel(), idx[:-1, 1:].ravel()
    c, d = idx[1:, :-1].ravel(), idx[1:, 1:].ravel()
    # vertex (i, j) sits at (y_i, x_j): counter-clockwise seen from +z with the first coordinate right and the
    # second up, so that the normals point up
    return np.concatenate([np.stack([a, d, b], 1), np.stack([a, c, d], 1)])


def _grid_mesh(pts, heights):
    import trimesh

    h, w = heights.shape
    vertices = np.concatenate([pts.reshape(-1, 2), heights.reshape(-1, 1)], axis=1)
    mesh = trimesh.Trimesh(vertices, _grid_faces(h, w), process=False, validate=False)
    mesh.vertex_attributes["height"] = heights.ravel().copy()
    return mesh


@renamed_parameters(on_aliasing="on_alias")
def monge_surface(field, shape=(128, 128), extent=((0.0, 4.0), (0.0, 4.0)), amplitude=0.5, frequency=1.0,
                  phase=0.0, *, octaves=1, kind="fractal", lacunarity=2.0, gain=0.5, samples_per_period=4.0,
                  on_alias="warn"):
    """A Monge-form surface z = amplitude * s(y, x) (Eq. 8) as a triangle mesh (figures 8, 14, 15).

    ``shape`` ``(ny, nx)`` and ``extent`` ``((y0, y1), (x0, x1))`` in
    array-axis order, as for :func:`height_map`. Vertex ``i * nx + j`` is the
    grid point followed by its height, ``(y_i, x_j, z_ij)``, so the vertices'
    first two coordinates are the points the field was evaluated at (and
    ``monge_normals(field, mesh.vertices[:, :2])`` its exact normals); two
    triangles per cell, wound so that normals point up (+z).
    ``vertex_attributes["height"]`` holds z. The mesh is open (a sheet), not
    watertight.

    Parameters
    ----------
    field : callable or LatticeNoise
        Maps points ``(n, 2)`` in ``(y, x)`` order to ``(n,)`` values.
    shape : (ny, nx)
        Samples per axis (rows, columns).
    extent : ((y0, y1), (x0, x1))
        The grid's span in field units, stops excluded.
    amplitude : float
        Height scale.
    frequency, phase : float or (fy, fx)
        Applied to the points before the field: ``s(frequency * p + phase)``.
    octaves : int, default 1
        Octaves of the fractal sum or turbulence (1: the field itself).
    kind : {"fractal", "turbulence"}, default "fractal"
        How the octaves combine (Phillips Eq. 9 or 10).
    lacunarity, gain : float
        Frequency and amplitude ratios between octaves.
    samples_per_period : float, default 4
        Samples per period of the highest octave below which the grid aliases.
    on_alias : {"warn", "raise", "ignore"}, default "warn"
        What a grid too coarse for the highest octave does.

    Returns
    -------
    trimesh.Trimesh
        ``ny * nx`` vertices ``(y, x, z)``, ``2 (ny - 1)(nx - 1)`` faces.

    Raises
    ------
    ValueError
        For a shape, extent, amplitude, frequency or octave count out of range,
        a field of the wrong dimension, or (``on_alias="raise"``) a grid too
        coarse for the highest octave.

    Examples
    --------
    >>> import numpy as np
    >>> m = monge_surface(lambda p: np.sin(p[:, 0]), (8, 8), on_alias="ignore")
    >>> len(m.vertices), len(m.faces), bool(m.face_normals[:, 2].min() > 0)
    (64, 98, True)
    """
    pts, heights = _sample(field, shape, extent, amplitude, frequency, phase, octaves, kind, lacunarity, gain, 1,
                           samples_per_period, on_alias)
    return _grid_mesh(pts, heights)


def _unit(values, value_range):
    lo, hi = value_range
    return np.clip((values - lo) / (hi - lo), 0.0, 1.0)


@renamed_parameters(on_aliasing="on_alias")
def colored_surface(field, shape=(128, 128), extent=((0.0, 4.0), (0.0, 4.0)), amplitude=0.5, frequency=1.0,
                    phase=0.0, *, color="hue", value_range=(-1.0, 1.0), saturation=0.85, value=0.95,
                    samples_per_period=4.0, on_alias="warn"):
    """A surface whose height and colour both come from one vector-valued field (figure 11).

    ``color="hue"``: the field returns 2 components, the first is the height,
    the second picks a hue (``value_range`` mapped onto the hue circle
    [0, 1), at the given HSV ``saturation`` and ``value``).
    ``color="rgb"``: the field returns 4 components, the first is the height
    and the other three, mapped from ``value_range`` to [0, 1], are R, G, B.
    Values outside ``value_range`` are clipped. ``shape`` ``(ny, nx)`` and
    ``extent`` ``((y0, y1), (x0, x1))`` in array-axis order; returns a Monge
    mesh as :func:`monge_surface` builds it, with vertex colours (kept by
    PLY/GLB/OBJ export and used by the renderer).

    Examples
    --------
    >>> import numpy as np
    >>> f = lambda p: np.stack([np.sin(p[:, 0]), np.cos(p[:, 1])], axis=1)
    >>> m = colored_surface(f, (8, 8), on_alias="ignore")
    >>> m.visual.vertex_colors.shape
    (64, 4)
    """
    from matplotlib.colors import hsv_to_rgb

    if color not in ("hue", "rgb"):
        raise ValueError(f"color must be 'hue' (2-component field) or 'rgb' (4-component field), got {color!r}")
    lo, hi = check_real_sequence("value_range", value_range, length=2)
    if not hi > lo:
        raise ValueError(f"value_range must be (low, high) with high > low, got {value_range!r}")
    saturation = check_real("saturation", saturation, lo=0.0, hi=1.0)
    value = check_real("value", value, lo=0.0, hi=1.0)
    comps = 2 if color == "hue" else 4
    pts, out = _sample(field, shape, extent, 1.0, frequency, phase, 1, "fractal", 2.0, 0.5, comps,
                       samples_per_period, on_alias)
    amplitude = check_real("amplitude", amplitude)
    mesh = _grid_mesh(pts, amplitude * out[..., 0])
    if color == "hue":
        hue = _unit(out[..., 1].ravel(), (lo, hi)) % 1.0
        hsv = np.stack([hue, np.full_like(hue, saturation), np.full_like(hue, value)], axis=1)
        rgb = hsv_to_rgb(hsv)
    else:
        rgb = _unit(out[..., 1:4].reshape(-1, 3), (lo, hi))
    rgba = np.concatenate([np.rint(rgb * 255), np.full((len(rgb), 1), 255)], axis=1).astype(np.uint8)
    mesh.visual.vertex_colors = rgba
    return mesh


def height_map_image(heights, path=None, *, vmin=None, vmax=None) -> np.ndarray:
    """A depth-map image of heights, lighter = higher (figure 8, right): ``(H, W)`` uint8, written if ``path``.

    ``heights`` is drawn as it is stored: row 0 (``y0`` of :func:`height_map`)
    at the top, x to the right. ``vmin``/``vmax`` default to the array's range.

    Parameters
    ----------
    heights : array_like (H, W)
        Finite heights.
    path : str or Path, optional
        Also write the image there (PNG, ...).
    vmin, vmax : float, optional
        Heights mapped to black and white (default: the array's range).

    Returns
    -------
    ndarray (H, W) of uint8

    Raises
    ------
    ValueError
        For non-finite heights or an array that is not 2-D.

    Examples
    --------
    >>> import numpy as np
    >>> height_map_image(np.array([[0.0, 0.5, 1.0]])).tolist()
    [[0, 128, 255]]
    """
    from ..io import to_uint8
    from .render import _save_array

    heights = check_finite_array("heights", heights).astype(np.float64)
    if heights.ndim != 2 or heights.size == 0:
        raise ValueError(f"heights must be a non-empty (height, width) array, got shape {heights.shape}")
    lo = float(heights.min()) if vmin is None else check_real("vmin", vmin)
    hi = float(heights.max()) if vmax is None else check_real("vmax", vmax)
    if hi <= lo:
        hi = lo + 1.0
    return _save_array(to_uint8(heights, lo, hi), path)
