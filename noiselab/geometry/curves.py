"""Noisy arcs and circles (Phillips 2004, Eq. 3, figures 3 and 5) and trajectories (figure 4).

Eq. 3 is ``f(theta) = noise(theta) + r {sin theta, cos theta}``: a circle of
radius ``r`` (angle measured from +y towards +x, as in the paper) distorted by
noise of the angle, either along the radius (one noise output) or in x and y
(two outputs). A trajectory is a 1-D input (time) mapped to a 2-D or 3-D
position by vector-valued noise.
"""
from __future__ import annotations

import numpy as np

from .._core import check_finite_array, check_int, check_real, renamed_parameters
from .fields import evaluate_field

__all__ = ["noisy_arc", "noisy_circle", "trajectory", "plot_curves", "trajectory_frames"]


def _mode(mode):
    if mode not in ("radial", "xy"):
        raise ValueError(f"mode must be 'radial' (noise along the radius) or 'xy' (noise in x and y), got {mode!r}")
    return mode


def _unit_circle(theta):
    # the paper's {sin, cos} order: theta = 0 at the top (+y), increasing clockwise towards +x
    return np.stack([np.sin(theta), np.cos(theta)], axis=-1)


def noisy_arc(field, theta, radius=1.0, amplitude=0.1, frequency=1.0, phase=0.0, *, mode="radial",
              degrees=False):
    """Points of an arc of radius ``radius`` distorted by a 1-D-input field of the angle (Eq. 3).

    Parameters
    ----------
    field : callable
        Points ``(n, 1)`` -> ``(n,)`` for ``mode="radial"``, ``(n, 2)`` for ``mode="xy"``
        (e.g. ``LatticeNoise(1)`` or ``LatticeNoise(1, 2)``).
    theta : array (n,)
        Angles in radians, measured from +y towards +x (the paper's ``{sin, cos}``).
    radius : float
    amplitude : float
        Size of the distortion, in the units of ``radius``.
    frequency : float
        Noise cycles (lattice units) per radian of arc. The paper's figure 3
        uses 2 cycles per degree, i.e. ``frequency = 2 * 180 / pi``.
    phase : float
        Offset of the noise input.
    mode : {"radial", "xy"}
        Distort the radius (figure 3) or x and y independently (figure 5).
    degrees : bool
        ``theta`` in degrees and ``frequency`` in cycles per degree (the
        paper's units: figure 3 is a 5-degree arc at 2 cycles per degree).

    Returns
    -------
    (n, 2) float64 array of (x, y).

    Examples
    --------
    >>> import numpy as np
    >>> theta = np.linspace(0, np.pi / 2, 50)
    >>> pts = noisy_arc(lambda u: np.sin(u[:, 0]), theta, amplitude=0.1)
    >>> r = np.hypot(pts[:, 0], pts[:, 1])
    >>> bool(0.9 <= r.min() and r.max() <= 1.1)
    True
    """
    mode = _mode(mode)
    theta = check_finite_array("theta", theta).astype(np.float64)
    if theta.ndim != 1:
        raise ValueError(f"theta must be a 1-D array of angles, got shape {theta.shape}")
    radius = check_real("radius", radius, lo=0.0)
    amplitude = check_real("amplitude", amplitude)
    frequency = check_real("frequency", frequency, lo=0.0)
    phase = check_real("phase", phase)
    u = (frequency * theta + phase)[:, None]
    circle = _unit_circle(np.radians(theta) if degrees else theta)
    if mode == "radial":
        s = evaluate_field(field, u, components=1)
        return (radius + amplitude * s)[:, None] * circle
    d = evaluate_field(field, u, components=2)
    return radius * circle + amplitude * d


def noisy_circle(field, n=720, radius=1.0, amplitude=0.1, frequency=1.0, phase=0.0, *, mode="radial",
                 closed=True):
    """A whole noisy circle of ``n`` points (figure 5): radial or x-y distortion.

    ``closed=True`` evaluates the field on a circle in its 2-D input space,
    ``frequency * (cos theta, sin theta) + phase``: the distortion is then
    exactly periodic in theta and the curve closes without a seam, with the
    same ``frequency`` noise units per radian as the arc (the field must take
    2-D points). ``closed=False`` is Eq. 3 literally (1-D input theta): the
    end does not meet the start.

    Returns ``(n, 2)`` points at ``theta = 2 pi k / n`` (the first point is not repeated).

    Parameters
    ----------
    field : callable or LatticeNoise
        Takes 2-D points with ``closed=True`` (1-D with ``closed=False``);
        scalar output for ``mode="radial"``, 2 components for ``mode="xy"``.
    n : int, default 720
        Points on the circle.
    radius : float, default 1
        Radius of the undistorted circle.
    amplitude : float, default 0.1
        Size of the distortion.
    frequency, phase : float
        Noise units per radian, and offset.
    mode : {"radial", "xy"}, default "radial"
        Push each point along its radius, or displace it in x and y.
    closed : bool, default True
        Sample the field on a circle of its input space, so the curve closes.

    Returns
    -------
    ndarray (n, 2)

    Examples
    --------
    >>> import numpy as np
    >>> f = lambda p: np.sin(3 * p[:, 0]) * np.cos(2 * p[:, 1])
    >>> c = noisy_circle(f, 64, amplitude=0.2)
    >>> c.shape
    (64, 2)
    """
    mode = _mode(mode)
    n = check_int("n", n, lo=3, hi=100_000_000)
    radius = check_real("radius", radius, lo=0.0)
    amplitude = check_real("amplitude", amplitude)
    frequency = check_real("frequency", frequency, lo=0.0)
    phase = check_real("phase", phase)
    theta = np.arange(n) * (2.0 * np.pi / n)
    if not closed:
        return noisy_arc(field, theta, radius, amplitude, frequency, phase, mode=mode)
    u = frequency * np.stack([np.cos(theta), np.sin(theta)], axis=-1) + phase
    circle = _unit_circle(theta)
    if mode == "radial":
        s = evaluate_field(field, u, components=1)
        return (radius + amplitude * s)[:, None] * circle
    return radius * circle + amplitude * evaluate_field(field, u, components=2)


def trajectory(field, t, amplitude=1.0, frequency=1.0, phase=0.0, *, dims=None):
    """A path from 1-D input to 2-D or 3-D output (figure 4): ``amplitude * field(frequency * t + phase)``.

    ``field`` maps ``(n, 1)`` to ``(n, d)`` (e.g. ``LatticeNoise(1, 2)``);
    ``dims`` keeps the first ``dims`` components (default all, at least 2).

    Parameters
    ----------
    field : callable or LatticeNoise
        Maps ``(n, 1)`` points to ``(n, d)`` values (e.g. ``LatticeNoise(1, 2)``).
    t : array_like (n,)
        The path parameter.
    amplitude : float
        Scale of the output.
    frequency, phase : float
        Applied to ``t`` before the field.
    dims : int, optional
        Output components kept (2 or 3; default all).

    Returns
    -------
    ndarray (n, dims)

    Raises
    ------
    ValueError
        For a non-finite ``t`` or ``dims`` larger than the field's components.

    Examples
    --------
    >>> import numpy as np
    >>> f = lambda u: np.stack([np.sin(u[:, 0]), np.cos(u[:, 0])], axis=1)
    >>> trajectory(f, np.linspace(0, 1, 5)).shape
    (5, 2)
    """
    t = check_finite_array("t", t).astype(np.float64)
    if t.ndim != 1:
        raise ValueError(f"t must be a 1-D array, got shape {t.shape}")
    amplitude = check_real("amplitude", amplitude)
    frequency = check_real("frequency", frequency, lo=0.0)
    phase = check_real("phase", phase)
    if dims is not None:
        dims = check_int("dims", dims, lo=1, hi=64)
    out = evaluate_field(field, (frequency * t + phase)[:, None], components=dims)
    if out.ndim == 1:
        raise ValueError("field must return a vector (n, d) per time for a trajectory, got a scalar per point")
    return amplitude * out


@renamed_parameters(axes="show_axes")
def plot_curves(curves, path=None, *, size=512, closed=False, colors="black", linewidth=1.5, limits=None,
                background="white", show_axes=False) -> np.ndarray:
    """Draw 2-D curves (each ``(n, 2)``) with matplotlib, equal aspect; return the RGB image, write it if ``path``.

    ``closed`` joins each curve's end to its start. ``limits`` is
    ``((xmin, xmax), (ymin, ymax))``; default fits all curves with a margin.
    ``show_axes`` draws matplotlib's axes (``axes=`` is its old spelling, until
    0.3: ``axes`` elsewhere means array axes).

    Examples
    --------
    >>> import numpy as np
    >>> img = plot_curves(np.stack([np.linspace(0, 1, 9), np.linspace(0, 1, 9) ** 2], 1), size=64)
    >>> img.shape, bool((img < 128).any())
    ((64, 64, 3), True)
    """
    from .render import _new_figure, _save_array, figure_to_array

    if isinstance(curves, np.ndarray) and curves.ndim == 2:
        curves = [curves]
    curves = [check_finite_array(f"curves[{i}]", np.asarray(c, dtype=np.float64)) for i, c in enumerate(curves)]
    for i, c in enumerate(curves):
        if c.ndim != 2 or c.shape[1] < 2 or len(c) < 2:
            raise ValueError(f"curves[{i}] must have shape (n >= 2, 2), got {c.shape}")
    if not curves:
        raise ValueError("curves must hold at least one curve")
    colors = [colors] * len(curves) if isinstance(colors, str) else list(colors)
    fig = _new_figure(size)
    ax = fig.add_axes((0.02, 0.02, 0.96, 0.96))
    ax.set_facecolor(background)
    fig.set_facecolor(background)
    for c, color in zip(curves, colors):
        c = c[:, :2]
        if closed:
            c = np.vstack([c, c[:1]])
        ax.plot(c[:, 0], c[:, 1], color=color, lw=linewidth)
    ax.set_aspect("equal")
    if limits is None:
        allp = np.vstack([c[:, :2] for c in curves])
        lo, hi = allp.min(axis=0), allp.max(axis=0)
        pad = 0.05 * max(float(np.max(hi - lo)), 1e-12)
        limits = ((lo[0] - pad, hi[0] + pad), (lo[1] - pad, hi[1] + pad))
    ax.set_xlim(*limits[0])
    ax.set_ylim(*limits[1])
    if not show_axes:
        ax.axis("off")
    return _save_array(figure_to_array(fig, close=False), path)


def trajectory_frames(points, *, tail=25, size=256, marker_size=60.0, limits=None, path=None, fps=25.0):
    """Animate a 2-D trajectory (figure 4): one frame per sample, the point plus a ``tail`` of earlier samples.

    Returns ``(frames, height, width, 3)`` uint8; writes a GIF/MP4 when ``path`` is given.

    Parameters
    ----------
    points : array_like (n, 2)
        The trajectory, one sample per frame.
    tail : int, default 25
        Earlier samples drawn behind the point.
    size : int, default 256
        Frame size in pixels.
    marker_size : float, default 60
        Marker area (matplotlib points squared).
    limits : ((xmin, xmax), (ymin, ymax)), optional
        Default: fitted to the trajectory.
    path : str or Path, optional
        Also write the animation there (GIF, MP4, ...).
    fps : float, default 25

    Returns
    -------
    ndarray (n, size, size, 3) of uint8

    Examples
    --------
    >>> import numpy as np
    >>> trajectory_frames(np.random.default_rng(0).random((4, 2)), size=32).shape
    (4, 32, 32, 3)
    """
    from .render import _new_figure, figure_to_array

    points = check_finite_array("points", points).astype(np.float64)
    if points.ndim != 2 or points.shape[1] < 2 or len(points) < 1:
        raise ValueError(f"points must have shape (n, 2), got {points.shape}")
    tail = check_int("tail", tail, lo=0)
    if limits is None:
        lo, hi = points[:, :2].min(axis=0), points[:, :2].max(axis=0)
        pad = 0.1 * max(float(np.max(hi - lo)), 1e-12)
        limits = ((lo[0] - pad, hi[0] + pad), (lo[1] - pad, hi[1] + pad))
    fig = _new_figure(size)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(*limits[0])
    ax.set_ylim(*limits[1])
    ax.set_aspect("equal")
    ax.axis("off")
    (line,) = ax.plot([], [], color="0.5", lw=1.5)
    dot = ax.scatter([points[0, 0]], [points[0, 1]], s=marker_size, color="black", zorder=3)
    frames = []
    for i in range(len(points)):
        seg = points[max(0, i - tail):i + 1, :2]
        line.set_data(seg[:, 0], seg[:, 1])
        dot.set_offsets(points[i:i + 1, :2])
        frames.append(figure_to_array(fig, close=False))
    video = np.stack(frames)
    if path is not None:
        from pathlib import Path

        from ..io import write_video

        Path(path).parent.mkdir(parents=True, exist_ok=True)
        write_video(path, video, fps=fps)
    return video
