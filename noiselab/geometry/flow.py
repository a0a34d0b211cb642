"""2-D and 3-D flow fields from vector-valued noise (Phillips 2004, figures 9 and 10).

A flow field is a field with d-D input and d-D output (``LatticeNoise(2, 2)``,
``LatticeNoise(3, 3)``): at each point a velocity. This module samples it on
grids, traces streamlines through it (a vectorised fixed-step RK4, or
scipy's adaptive ``solve_ivp``), and draws it (matplotlib quiver and
streamline plots in 2-D, pyvista arrow glyphs in 3-D).

Shapes, extents, points and vectors are in array-axis order, as everywhere in
:mod:`noiselab.geometry` (see :mod:`noiselab.geometry.surfaces`): ``shape``
``(ny, nx)``, ``extent`` ``((y0, y1), (x0, x1))``, a point ``(y, x)`` and a
velocity ``(v_y, v_x)`` (component ``k`` along array axis ``k``); in 3-D
``(z, y, x)``. The plots draw x to the right and y up.
"""
from __future__ import annotations

import numpy as np

from .._core import check_finite_array, check_int, check_real, check_real_vector, renamed_parameters
from .fields import evaluate_field
from .surfaces import _amplified, _extent, _scaled, grid_points

__all__ = ["flow_field", "streamlines", "quiver_image", "streamline_image", "flow_glyphs"]


def _velocity(field, d, amplitude, frequency, phase):
    phase = check_real_vector("phase", phase, d)
    amplitude = check_real("amplitude", amplitude, lo=-1e100, hi=1e100)  # arrow lengths are squared
    frequency = check_real("frequency", frequency, lo=0.0)

    def v(p):
        return _amplified(evaluate_field(field, _scaled("the points", p, frequency, phase), name="field",
                                         components=d), amplitude)

    return v


def flow_field(field, shape=(16, 16), extent=((0.0, 4.0), (0.0, 4.0)), amplitude=1.0, frequency=1.0, phase=0.0):
    """Sample a vector field on a grid: returns ``(points, vectors)``, both ``(*shape, d)``.

    ``shape`` ``(ny, nx)`` or ``(nz, ny, nx)`` and ``extent``
    ``((y0, y1), (x0, x1))`` or ``((z0, z1), (y0, y1), (x0, x1))`` are in
    array-axis order (stop excluded); ``points`` are :func:`grid_points`
    (``points[i, j] = (y_i, x_j)``) and
    ``vectors = amplitude * field(frequency * points + phase)[:, :d]``, in the
    same order: component ``k`` is the velocity along array axis ``k``.

    Parameters
    ----------
    field : callable or LatticeNoise
        Maps points ``(n, d)`` to vectors ``(n, >= d)``.
    shape : (ny, nx) or (nz, ny, nx), default (16, 16)
        Samples per array axis.
    extent : ((y0, y1), (x0, x1)) or ((z0, z1), (y0, y1), (x0, x1))
        The grid's span, stops excluded.
    amplitude : float
        Vector scale.
    frequency, phase : float or sequence of float
        Applied to the points before the field.

    Returns
    -------
    points, vectors : ndarray of shape ``(*shape, d)``

    Examples
    --------
    >>> import numpy as np
    >>> f = lambda p: np.stack([-p[:, 1], p[:, 0]], axis=1)   # rotation
    >>> pts, vec = flow_field(f, (3, 4), ((-1, 2), (-2, 2)))
    >>> pts[0, 0].tolist(), vec[0, 0].tolist()
    ([-1.0, -2.0], [2.0, -1.0])
    """
    pts = grid_points(shape, extent)
    d = pts.shape[-1]
    amplitude = check_real("amplitude", amplitude)
    frequency = check_real("frequency", frequency, lo=0.0)
    vec = _velocity(field, d, amplitude, frequency, phase)(pts.reshape(-1, d))
    return pts, vec.reshape(pts.shape)


@renamed_parameters(normalize="unit_speed")
def streamlines(field, seeds, *, step=0.01, n_steps=200, amplitude=1.0, frequency=1.0, phase=0.0,
                method="rk4", unit_speed=False):
    """Trace streamlines from ``seeds`` (m, d) through the flow ``amplitude * field(frequency * p + phase)``.

    ``method="rk4"`` takes ``n_steps`` classical Runge-Kutta steps of size
    ``step`` for all seeds at once (one field call per stage for every seed:
    fast, and exact for the sampled positions up to O(step^4)).
    ``method="solve_ivp"`` integrates each seed with scipy's adaptive RK45 to
    rtol 1e-6 and reports it at the same times (slower; a reference).
    ``unit_speed=True`` follows the direction only, so that
    streamlines have equal length whatever the local speed. Seeds and
    positions are in the field's input order: ``(y, x)`` (``(z, y, x)``) for
    the array-axis order of :func:`flow_field`.

    Returns ``(m, n_steps + 1, d)`` positions, the seeds first.

    Parameters
    ----------
    field : callable or LatticeNoise
        Maps points ``(n, d)`` to velocities ``(n, d)`` (extra components are ignored).
    seeds : array_like (m, d)
        Start positions.
    step : float, default 0.01
        Step size in the field's input units (per unit of speed).
    n_steps : int, default 200
        Steps per streamline.
    amplitude : float
        Velocity scale.
    frequency, phase : float or sequence of float
        Applied to the positions before the field.
    method : {"rk4", "solve_ivp"}, default "rk4"
        Fixed-step Runge-Kutta for all seeds at once, or scipy's adaptive RK45 per seed.
    unit_speed : bool, default False
        Follow the direction only (unit speed). (``normalize=`` is the old
        spelling, refused since 0.4: ``normalize`` elsewhere scales a field's values.)

    Returns
    -------
    ndarray (m, n_steps + 1, d)
        Positions, the seeds first.

    Raises
    ------
    ValueError
        For non-finite seeds, a step or step count out of range, an unknown
        method, or a field that returns fewer components than the seeds have.

    Examples
    --------
    >>> import numpy as np
    >>> rot = lambda p: np.stack([-p[:, 1], p[:, 0]], axis=1)
    >>> path = streamlines(rot, [[1.0, 0.0]], step=np.pi / 100, n_steps=100)
    >>> bool(np.allclose(path[0, -1], [-1.0, 0.0], atol=1e-6))
    True
    """
    seeds = np.atleast_2d(check_finite_array("seeds", seeds).astype(np.float64))
    if seeds.ndim != 2 or seeds.shape[1] not in (2, 3):
        raise ValueError(f"seeds must have shape (m, 2) or (m, 3), got {seeds.shape}")
    step = check_real("step", step, lo=0.0, lo_open=True)
    n_steps = check_int("n_steps", n_steps, lo=1, hi=10_000_000)
    amplitude = check_real("amplitude", amplitude)
    frequency = check_real("frequency", frequency, lo=0.0)
    if method not in ("rk4", "solve_ivp"):
        raise ValueError(f"method must be 'rk4' or 'solve_ivp', got {method!r}")
    d = seeds.shape[1]
    vel = _velocity(field, d, amplitude, frequency, phase)
    if unit_speed:
        raw = vel

        def vel(p):
            v = raw(p)
            norm = np.linalg.norm(v, axis=1, keepdims=True)
            return np.divide(v, norm, out=np.zeros_like(v), where=norm > 0)

    out = np.empty((len(seeds), n_steps + 1, d))
    out[:, 0] = seeds
    if method == "rk4":
        p = seeds.copy()
        h = step
        for i in range(1, n_steps + 1):
            k1 = vel(p)
            k2 = vel(p + 0.5 * h * k1)
            k3 = vel(p + 0.5 * h * k2)
            k4 = vel(p + h * k3)
            p = p + (h / 6.0) * (k1 + 2 * k2 + 2 * k3 + k4)
            out[:, i] = p
        return out
    from scipy.integrate import solve_ivp

    times = np.arange(n_steps + 1) * step
    for m, seed in enumerate(seeds):
        sol = solve_ivp(lambda t, y: vel(y[None, :])[0], (0.0, times[-1]), seed, t_eval=times,
                        rtol=1e-6, atol=1e-9)
        if not sol.success:
            raise RuntimeError(f"solve_ivp failed on seed {m}: {sol.message}")
        out[m] = sol.y.T
    return out


@renamed_parameters(seed="rng")
def quiver_image(field, path=None, *, shape=(20, 20), extent=((0.0, 4.0), (0.0, 4.0)), amplitude=1.0,
                 frequency=1.0, phase=0.0, size=512, color="black", streamline_seeds=0, rng=0,
                 n_steps=100, step=0.02) -> np.ndarray:
    """A 2-D flow field as arrows (figure 9), matplotlib; optional streamlines from random seeds.

    ``shape`` ``(ny, nx)`` and ``extent`` ``((y0, y1), (x0, x1))`` are in
    array-axis order, as for :func:`flow_field`; the plot draws x (axis 1) to
    the right and y (axis 0) up (mathematical axes), each arrow ``(v_x, v_y)``.
    ``streamline_seeds`` > 0 traces that many streamlines (RK4, ``n_steps`` of
    ``step``) from seeded uniform positions in the extent, drawn in grey
    under the arrows. Returns the RGB image; writes it when ``path`` is given.

    Examples
    --------
    >>> import numpy as np
    >>> swirl = lambda p: np.stack([np.sin(p[:, 1]), np.cos(p[:, 0])], axis=1)
    >>> quiver_image(swirl, shape=(6, 6), size=64).shape
    (64, 64, 3)
    """
    from .._core import as_generator
    from .render import _new_figure, _save_array, figure_to_array

    pts, vec = flow_field(field, shape, extent, amplitude, frequency, phase)
    if pts.shape[-1] != 2:
        raise ValueError(f"quiver_image draws 2-D fields: shape must have 2 entries, got {shape!r}")
    ext = _extent(extent)
    fig = _new_figure(size)
    ax = fig.add_axes((0.02, 0.02, 0.96, 0.96))
    n_seeds = check_int("streamline_seeds", streamline_seeds, lo=0, hi=100_000)
    if n_seeds:
        rng = as_generator(rng)
        seeds = ext[:, 0] + rng.random((n_seeds, 2)) * (ext[:, 1] - ext[:, 0])
        lines = streamlines(field, seeds, step=step, n_steps=n_steps, amplitude=amplitude, frequency=frequency,
                            phase=phase)
        for line in lines:
            ax.plot(line[:, 1], line[:, 0], color="0.6", lw=0.8)
    ax.quiver(pts[..., 1], pts[..., 0], vec[..., 1], vec[..., 0], color=color, angles="xy", pivot="mid")
    cell = (ext[:, 1] - ext[:, 0]) / np.asarray(pts.shape[:2])
    ax.set_xlim(ext[1, 0] - cell[1], ext[1, 1])
    ax.set_ylim(ext[0, 0] - cell[0], ext[0, 1])
    ax.set_aspect("equal")
    ax.axis("off")
    return _save_array(figure_to_array(fig, close=False), path)


def streamline_image(lines, path=None, *, size=512, color="black", linewidth=1.0, limits=None) -> np.ndarray:
    """Draw 2-D streamlines ``(m, n, 2)`` (from :func:`streamlines`) with matplotlib; return the image.

    The lines' points are ``(y, x)``, in array-axis order like every point of
    :mod:`noiselab.geometry`; they are drawn as :func:`quiver_image` draws its
    field, x to the right and y up. ``limits`` is ``((y0, y1), (x0, x1))``, in
    the same order (default: fitted to the lines).

    Examples
    --------
    >>> import numpy as np
    >>> rot = lambda p: np.stack([-p[:, 1], p[:, 0]], axis=1)
    >>> streamline_image(streamlines(rot, [[1.0, 0.0]], step=0.1, n_steps=60), size=48).shape
    (48, 48, 3)
    """
    from .curves import plot_curves

    lines = np.asarray(lines, dtype=np.float64)
    if lines.ndim != 3 or lines.shape[2] < 2:
        raise ValueError(f"lines must have shape (m, n, 2), got {lines.shape}")
    # plot_curves draws geometric (x, y) curves: hand it the lines and the limits with their two axes swapped
    xy = list(lines[..., 1::-1])
    if limits is not None:
        limits = tuple(limits)[::-1]
    return plot_curves(xy, path, size=size, colors=color, linewidth=linewidth, limits=limits)


def flow_glyphs(field, shape=(6, 6, 6), extent=((0.0, 4.0), (0.0, 4.0), (0.0, 4.0)), amplitude=1.0,
                frequency=1.0, phase=0.0, *, scale=None):
    """A 3-D flow field as a pyvista mesh of arrows (figure 10), ready for :func:`render_mesh`.

    ``shape`` ``(nz, ny, nx)`` and ``extent`` ``((z0, z1), (y0, y1), (x0, x1))``
    in array-axis order, as for :func:`flow_field`: each arrow starts at its
    grid point ``(z, y, x)`` (the mesh's coordinates) and points along
    ``(v_z, v_y, v_x)``; its length is ``scale`` times the vector's (default:
    the longest arrow is 0.9 grid cells). Render a cross-fusible stereo pair
    with :func:`render_stereo_pair`.

    Examples
    --------
    >>> import numpy as np
    >>> arrows = flow_glyphs(lambda p: p[:, ::-1] - 1.0, (2, 2, 2), ((0, 2), (0, 2), (0, 2)))
    >>> arrows.n_points > 8
    True
    """
    from .render import require_pyvista

    pts, vec = flow_field(field, shape, extent, amplitude, frequency, phase)
    if pts.shape[-1] != 3:
        raise ValueError(f"flow_glyphs draws 3-D fields: shape must have 3 entries, got {shape!r}")
    ext = _extent(extent, 3)
    cell = float(np.min((ext[:, 1] - ext[:, 0]) / np.asarray(pts.shape[:3])))
    vec = vec.reshape(-1, 3)
    longest = float(np.max(np.linalg.norm(vec, axis=1)))
    if scale is None:
        scale = 0.9 * cell / longest if longest > 0 else 1.0
    scale = check_real("scale", scale, lo=0.0, lo_open=True)
    pv = require_pyvista()
    cloud = pv.PolyData(pts.reshape(-1, 3))
    cloud["vectors"] = vec
    cloud["speed"] = np.linalg.norm(vec, axis=1)
    return cloud.glyph(orient="vectors", scale="speed", factor=scale, geom=pv.Arrow())
