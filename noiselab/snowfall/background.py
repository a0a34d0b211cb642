"""A built-in background for the snow command: a winter sky over hills, made with noiselab's own spectral noise."""
from __future__ import annotations

import numpy as np

from .._core import as_generator, check_int, renamed_parameters
from ..spectral import spectral_noise

__all__ = ["default_background"]


@renamed_parameters(seed="rng")
def default_background(height=512, width=512, rng=7) -> np.ndarray:
    """An RGB uint8 ``(height, width, 3)`` landscape: overcast sky, three ranges of hills, snowy ground.

    Every shape comes from :func:`noiselab.spectral.spectral_noise`: the
    ridge lines are 1-D ``1/f**2`` (Brownian) profiles, the clouds and the
    ground texture 2-D ``1/f`` fields. Far hills are pale (aerial
    perspective), near ones dark, so the white snow shows on them.

    Parameters
    ----------
    height, width : int
        Size in pixels.
    rng : int, numpy.random.Generator or None
        The random state; default 7, the one picture ``noiselab snow`` shows
        behind its snow (the same every run).

    Examples
    --------
    >>> img = default_background(64, 96)
    >>> img.shape, img.dtype
    ((64, 96, 3), dtype('uint8'))
    """
    H = check_int("height", height, lo=1)
    W = check_int("width", width, lo=1)
    rng = as_generator(rng)
    y = (np.arange(H, dtype=np.float32) / max(H - 1, 1))[:, None]
    # sky: dark blue-grey at the top to pale grey near the horizon, with soft clouds
    top = np.array([70, 84, 108], np.float32)
    horizon = np.array([176, 184, 194], np.float32)
    img = top + (horizon - top) * np.clip(y / 0.65, 0, 1)[..., None]
    img = np.broadcast_to(img, (H, W, 3)).copy()
    if H >= 4 and W >= 4:
        clouds = spectral_noise((H, W), exponent=1.5, band=(1, max(2.0, W / 8)), rng=rng)
        img += (12 * clouds * (1 - y))[..., None]
    # three ranges of hills, far to near
    layers = [
        (0.45, 0.06, np.array([132, 140, 152], np.float32)),
        (0.58, 0.08, np.array([82, 92, 96], np.float32)),
        (0.72, 0.10, np.array([40, 48, 44], np.float32)),
    ]
    for base, amp, colour in layers:
        ridge = spectral_noise((W,), exponent=2.0, band=(1, max(1.5, W / 4)), rng=rng) if W >= 4 else np.zeros(W)
        line = (base + amp * ridge / max(1e-6, np.abs(ridge).max())) * H
        inside = (np.arange(H)[:, None] >= line[None, :])
        img[inside] = colour
    # snowy ground in front
    ground = np.arange(H)[:, None] >= 0.9 * H
    if ground.any():
        tex = spectral_noise((H, W), exponent=1.0, rng=rng) if H >= 4 and W >= 4 else np.zeros((H, W))
        snowy = 215 + 10 * tex
        img[np.broadcast_to(ground, (H, W))] = np.repeat(snowy[np.broadcast_to(ground, (H, W))][:, None], 3, axis=1)
    return np.clip(np.rint(img), 0, 255).astype(np.uint8)
