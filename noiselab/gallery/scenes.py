"""Backgrounds for the snow figures, drawn in code: a house on a sunny winter day, a sunny harbour city.

The thesis composites its snow over a painting (*Jimmy's place*, Fig. 3.1) and
a photograph of Sydney (Fig. 3.3); neither ships with anything we may use, so
the gallery draws stand-ins with matplotlib: flat, crisp shapes in saturated
colours under a bright sky, so that the white flakes have dark, sharp edges to
fall in front of (a soft, low-contrast background makes the snow read as film
grain). Both scenes can be made periodic in x (every shape drawn again one
period to the left and right), so a background panning at a whole number of
pixels per frame loops without a jump (Fig. 4.1).
"""
from __future__ import annotations

import numpy as np

from noiselab._core import as_generator, renamed_parameters

from ._common import pyplot


def _size(height, width):
    from noiselab._core import check_int

    return check_int("height", height, lo=16, hi=8192), check_int("width", width, lo=16, hi=8192)


def _canvas(height, width):
    """A figure and axes whose data units are pixels, (0, 0) at the top left, y down."""
    plt = pyplot()
    fig = plt.figure(figsize=(width / 100, height / 100), dpi=100)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, width), ax.set_ylim(height, 0), ax.axis("off")
    return plt, fig, ax


def _finish(plt, fig):
    fig.canvas.draw()
    img = np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()
    plt.close(fig)
    return img


def _sky(ax, height, width, horizon, top=(38, 104, 196), bottom=(168, 208, 244)):
    t = np.linspace(0, 1, 64)[:, None, None]
    grad = (np.array(top) * (1 - t) + np.array(bottom) * t) / 255.0
    ax.imshow(np.repeat(grad, 2, axis=1), extent=(0, width, horizon, 0), aspect="auto", interpolation="bicubic", zorder=0)


def _sun(ax, x, y, r, period=None):
    from matplotlib.patches import Circle

    for dx in _copies(period):
        ax.add_patch(Circle((x + dx, y), 2.2 * r, color=(1.0, 0.97, 0.8), alpha=0.35, lw=0, zorder=1))
        ax.add_patch(Circle((x + dx, y), r, color=(1.0, 0.96, 0.72), lw=0, zorder=1))


def _copies(period):
    return (0.0,) if period is None else (-period, 0.0, period)


def _poly(ax, points, color, z, period=None, **kw):
    from matplotlib.patches import Polygon

    pts = np.asarray(points, dtype=float)
    for dx in _copies(period):
        ax.add_patch(Polygon(pts + [dx, 0.0], closed=True, color=np.asarray(color) / 255.0, lw=0, zorder=z, **kw))


def _rect(ax, x0, y0, x1, y1, color, z, period=None):
    _poly(ax, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)], color, z, period)


def _pine(ax, x, base, h, z, period=None, dark=(22, 66, 42)):
    """A pine: three stacked dark triangles with snow on the top edge of each, and a trunk."""
    w = 0.42 * h
    _rect(ax, x - 0.05 * w, base - 0.16 * h, x + 0.05 * w, base, (88, 56, 36), z, period)
    for k, (b, t, s) in enumerate(((0.16, 0.62, 1.0), (0.42, 0.84, 0.78), (0.64, 1.0, 0.56))):
        yb, yt, half = base - b * h, base - t * h, 0.5 * w * s
        _poly(ax, [(x - half, yb), (x + half, yb), (x, yt)], dark, z + 0.01 * k, period)
        # snow on the upper part of each layer: a lighter triangle hugging the apex
        _poly(ax, [(x - 0.45 * half, yt + 0.55 * (yb - yt)), (x + 0.3 * half, yt + 0.5 * (yb - yt)), (x, yt)],
              (236, 242, 250), z + 0.01 * k + 0.005, period)


@renamed_parameters(seed="rng")
def house_scene(height, width, *, periodic=False, rng=0):
    """A red house on a sunny winter day, snow on the ground and none falling: RGB uint8 ``(height, width, 3)``.

    Parameters
    ----------
    height, width : int
        Size in pixels.
    periodic : bool
        Draw the scene periodic in x with period ``width`` (for a panning loop).
    rng : int, numpy.random.Generator or None
        Places the far forest and the small trees.

    Returns
    -------
    numpy.ndarray
        ``(height, width, 3)`` uint8.

    Raises
    ------
    ValueError
        If ``height`` or ``width`` is not an int in [16, 8192].

    Examples
    --------
    >>> img = house_scene(64, 96)
    >>> img.shape, img.dtype.name
    ((64, 96, 3), 'uint8')
    >>> bool((house_scene(32, 32, periodic=True)[:, :1] != 0).any())
    True
    """
    height, width = _size(height, width)
    rng = as_generator(rng)
    H, W = float(height), float(width)
    P = W if periodic else None
    plt, fig, ax = _canvas(height, width)
    horizon = 0.56 * H
    _sky(ax, height, width, horizon + 2)
    _sun(ax, 0.84 * W, 0.13 * H, 0.045 * H, P)
    # snowy hills far away, pale blue-white, then the dark forest edge
    xs = np.linspace(-W, 2 * W, 400)
    hill = horizon - 0.09 * H * (0.6 + 0.4 * np.sin(2 * np.pi * xs / W * 2 + 1.0)) * (0.7 + 0.3 * np.cos(2 * np.pi * xs / W * 3))
    _poly(ax, np.c_[np.r_[xs, xs[::-1]], np.r_[hill, np.full_like(xs, horizon + 4)]], (214, 226, 242), 2)
    for x in rng.uniform(0, W, 70):
        h = rng.uniform(0.05, 0.1) * H
        _poly(ax, [(x - 0.2 * h, horizon + 3), (x + 0.2 * h, horizon + 3), (x, horizon + 3 - h)], (30, 62, 48), 3, P)
    # the snowy ground with a blue shadow band near the forest
    _rect(ax, -W, horizon + 2, 2 * W, H, (246, 249, 253), 4)
    _rect(ax, -W, horizon + 2, 2 * W, horizon + 0.03 * H, (196, 212, 236), 4.1)
    # the house: red walls, a snow-covered gable roof, lit windows, a door, a chimney
    x0, x1, yb, yw = 0.2 * W, 0.56 * W, 0.78 * H, 0.5 * H
    _poly(ax, [(x0 - 0.02 * W, yb + 0.035 * H), (x1 + 0.1 * W, yb + 0.035 * H), (x1 + 0.02 * W, yb), (x0, yb)],
          (176, 196, 228), 5, P)                                            # its shadow on the snow
    _rect(ax, x0, yw, x1, yb, (168, 36, 32), 6, P)
    # the side wall, in shade; it starts under the roof (at the far slope's lower edge, yw - 0.005 H, less a
    # pixel), not at yw: the band between them showed the sky as a dashed white line under the right eave
    _rect(ax, x1, yw - 0.005 * H - 1, x1 + 0.1 * W, yb, (120, 26, 24), 6, P)
    _rect(ax, 0.46 * W, 0.24 * H, 0.5 * W, 0.38 * H, (96, 40, 32), 6.5, P)   # chimney
    _rect(ax, 0.455 * W, 0.225 * H, 0.505 * W, 0.245 * H, (250, 252, 255), 6.6, P)
    _poly(ax, [(x0 - 0.03 * W, yw + 0.01 * H), (x1 + 0.03 * W, yw + 0.01 * H), (0.5 * (x0 + x1), 0.27 * H)],
          (60, 36, 30), 7, P)                                               # roof edge
    _poly(ax, [(x0 - 0.02 * W, yw - 0.005 * H), (x1 + 0.02 * W, yw - 0.005 * H), (0.5 * (x0 + x1), 0.29 * H)],
          (250, 252, 255), 7.1, P)                                          # snow on the roof
    _poly(ax, [(x1 + 0.02 * W, yw - 0.005 * H), (x1 + 0.12 * W, yw - 0.005 * H), (x1 + 0.1 * W, 0.29 * H),
               (0.5 * (x0 + x1), 0.29 * H)], (205, 218, 238), 7.05, P)      # the far roof slope, in shade
    for wx in (0.25, 0.43):
        _rect(ax, wx * W, 0.56 * H, (wx + 0.07) * W, 0.65 * H, (40, 28, 24), 8, P)
        _rect(ax, (wx + 0.008) * W, 0.568 * H, (wx + 0.062) * W, 0.642 * H, (252, 214, 110), 8.1, P)
        _rect(ax, (wx + 0.032) * W, 0.56 * H, (wx + 0.038) * W, 0.65 * H, (40, 28, 24), 8.2, P)
    _rect(ax, 0.345 * W, 0.6 * H, 0.405 * W, yb, (64, 40, 28), 8, P)
    # a fence and pines in front
    for fx in np.arange(0.0, W, 0.04 * W):
        _rect(ax, fx, 0.82 * H, fx + 0.012 * W, 0.9 * H, (82, 54, 36), 9, P)
    _rect(ax, 0.0 if P else -W, 0.835 * H, W if P else 2 * W, 0.845 * H, (82, 54, 36), 9, P)
    _rect(ax, 0.0 if P else -W, 0.865 * H, W if P else 2 * W, 0.875 * H, (82, 54, 36), 9, P)
    for x, h in ((0.08, 0.42), (0.7, 0.5), (0.8, 0.36), (0.92, 0.46)):
        _pine(ax, x * W, 0.8 * H + 0.04 * H * (h > 0.4), h * H, 10, P)
    return _finish(plt, fig)


@renamed_parameters(seed="rng")
def city_scene(height, width, *, periodic=False, rng=1):
    """A harbour city on a sunny day (towers, a tower with a turret, shell roofs, a steel arch bridge): RGB uint8.

    Parameters
    ----------
    height, width : int
        Size in pixels.
    periodic : bool
        Periodic in x with period ``width``.
    rng : int, numpy.random.Generator or None
        Places and colours the towers.

    Returns
    -------
    numpy.ndarray
        ``(height, width, 3)`` uint8.

    Raises
    ------
    ValueError
        If ``height`` or ``width`` is not an int in [16, 8192].

    Examples
    --------
    >>> city_scene(48, 64).shape
    (48, 64, 3)
    """
    from matplotlib.patches import Arc

    height, width = _size(height, width)
    rng = as_generator(rng)
    H, W = float(height), float(width)
    P = W if periodic else None
    plt, fig, ax = _canvas(height, width)
    water = 0.7 * H
    _sky(ax, height, width, water + 2, top=(30, 96, 200), bottom=(150, 200, 246))
    _sun(ax, 0.14 * W, 0.12 * H, 0.04 * H, P)
    palette = [(222, 200, 160), (92, 120, 150), (200, 206, 214), (60, 74, 96), (178, 120, 86), (236, 236, 230)]
    # the skyline: towers of random height with window grids
    x = 0.0
    while x < W:
        w = rng.uniform(0.045, 0.1) * W
        h = rng.uniform(0.18, 0.55) * H
        col = np.asarray(palette[rng.integers(len(palette))], dtype=float)
        _rect(ax, x, water - h, x + w, water, col, 3, P)
        _rect(ax, x + 0.75 * w, water - h, x + w, water, 0.72 * col, 3.1, P)      # the shaded side
        win = (30, 40, 60) if col.mean() > 150 else (210, 226, 240)
        for wy in np.arange(water - h + 0.02 * H, water - 0.02 * H, 0.035 * H):
            for wx in np.arange(x + 0.12 * w, x + 0.7 * w, 0.22 * w):
                _rect(ax, wx, wy, wx + 0.1 * w, wy + 0.015 * H, win, 3.2, P)
        x += w + rng.uniform(0.0, 0.02) * W
    # a tower with a golden turret
    tx = 0.62 * W
    _rect(ax, tx - 0.006 * W, 0.12 * H, tx + 0.006 * W, water, (70, 70, 76), 4, P)
    _poly(ax, [(tx - 0.03 * W, 0.2 * H), (tx + 0.03 * W, 0.2 * H), (tx + 0.022 * W, 0.26 * H), (tx - 0.022 * W, 0.26 * H)],
          (214, 170, 60), 4.1, P)
    # the water, with bright ripples
    _rect(ax, -W, water, 2 * W, H, (18, 70, 140), 5)
    for k in range(140):
        rx, ry = rng.uniform(0, W), rng.uniform(water + 4, H)
        _rect(ax, rx, ry, rx + rng.uniform(0.01, 0.05) * W, ry + 1.5, (120, 176, 230), 5.1, P)
    # the shell roofs on a sandstone podium
    sx = 0.3 * W
    _rect(ax, sx - 0.14 * W, water - 0.03 * H, sx + 0.16 * W, water + 0.02 * H, (206, 170, 120), 6, P)
    for k, (dx, hgt) in enumerate(((-0.1, 0.1), (-0.02, 0.15), (0.06, 0.12))):
        base = sx + dx * W
        _poly(ax, [(base - 0.02 * W, water - 0.03 * H), (base + 0.09 * W, water - 0.03 * H), (base + 0.005 * W, water - (0.03 + hgt) * H)],
              (250, 250, 246), 6.2 + 0.01 * k, P)
        _poly(ax, [(base + 0.005 * W, water - (0.03 + hgt) * H), (base + 0.09 * W, water - 0.03 * H), (base + 0.05 * W, water - 0.03 * H)],
              (206, 212, 222), 6.25 + 0.01 * k, P)
    # the arch bridge: a dark steel arch, its deck and pylons
    bx, span = 0.8 * W, 0.46 * W
    for dx in _copies(P):
        for lw, col in ((5.0, (0.16, 0.18, 0.22)), (2.0, (0.3, 0.32, 0.36))):
            ax.add_patch(Arc((bx + dx, water - 0.08 * H), span, 0.44 * H, theta1=180, theta2=360, lw=lw * H / 512, color=col,
                             zorder=7))
    _rect(ax, bx - 0.3 * W, water - 0.09 * H, bx + 0.3 * W, water - 0.075 * H, (40, 44, 52), 7.1, P)
    for px in (bx - 0.27 * W, bx + 0.25 * W):
        _rect(ax, px, water - 0.16 * H, px + 0.03 * W, water + 0.01 * H, (196, 170, 130), 7.2, P)
    return _finish(plt, fig)


def frame_with_crop(frame, box=None, gap=6, outline=(255, 200, 0)):
    """A frame beside a 2x nearest-neighbour enlargement of a quarter of it, the quarter outlined on the frame.

    Parameters
    ----------
    frame : (h, w) or (h, w, 3) uint8
        One frame.
    box : (y0, x0) or None
        Top-left corner of the ``h/2 x w/2`` crop (default: the centre).
    gap : int
        White pixels between the two.
    outline : RGB
        Colour of the crop's outline on the frame.

    Returns
    -------
    numpy.ndarray
        ``(h, 2 w + gap, 3)`` uint8.

    Raises
    ------
    ValueError
        If ``frame`` is not ``(h, w)`` or ``(h, w, 3)`` with h, w >= 2, or the crop does not fit in it.

    Examples
    --------
    >>> frame_with_crop(np.zeros((8, 8), np.uint8)).shape
    (8, 22, 3)
    """
    from ._common import grey_to_rgb

    frame = np.asarray(frame)
    if not (frame.ndim == 2 or (frame.ndim == 3 and frame.shape[2] == 3)) or min(frame.shape[:2]) < 2:
        raise ValueError(f"frame must be (h, w) or (h, w, 3) with h, w >= 2, got shape {frame.shape}")
    f = grey_to_rgb(frame)
    h, w = f.shape[:2]
    ch, cw = h // 2, w // 2
    y0, x0 = box if box is not None else (h // 4, w // 4)
    if not (0 <= y0 <= h - ch and 0 <= x0 <= w - cw):
        raise ValueError(f"box (y0, x0) = {box} puts the {ch} x {cw} crop outside the {h} x {w} frame")
    crop = f[y0:y0 + ch, x0:x0 + cw].repeat(2, axis=0).repeat(2, axis=1)
    marked = f.copy()
    t = max(1, h // 256)
    for ys, xs in ((slice(y0, y0 + t), slice(x0, x0 + cw)), (slice(y0 + ch - t, y0 + ch), slice(x0, x0 + cw)),
                   (slice(y0, y0 + ch), slice(x0, x0 + t)), (slice(y0, y0 + ch), slice(x0 + cw - t, x0 + cw))):
        marked[ys, xs] = outline
    out = np.full((h, 2 * w + gap, 3), 255, np.uint8)
    out[:, :w] = marked
    out[:crop.shape[0], w + gap:w + gap + crop.shape[1]] = crop
    return out
