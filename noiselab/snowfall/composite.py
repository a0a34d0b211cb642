"""Compositing snow over a background (thesis Eq. 3.6) and the two-contrast stimuli of Eq. 6.1."""
from __future__ import annotations

import numpy as np

from .._core import as_array, check_finite_array, check_memory, check_real
from .._core.contrast import michelson_contrast  # one definition (noiselab.analysis's too), for the Eq. 6.1 reports

__all__ = ["composite", "parallax_composite", "michelson_contrast"]


def _check_alpha(alpha, name="alpha"):
    alpha = check_finite_array(name, alpha)
    if alpha.ndim not in (2, 3):
        raise ValueError(f"{name} must have shape (T, H, W) or (H, W), got {alpha.shape}")
    if alpha.size and (alpha.min() < 0 or alpha.max() > 1):
        raise ValueError(f"{name} must lie in [0, 1], got values in [{alpha.min():g}, {alpha.max():g}]")
    return alpha


def _background_layout(bg_shape, T, H, W):
    """(is_video, is_rgb) of a background for alpha frames (H, W), or raise naming both shapes."""
    nd = len(bg_shape)
    if nd == 2 and bg_shape == (H, W):
        return False, False
    if nd == 3 and bg_shape == (H, W, 3):
        return False, True
    if T is not None and nd == 3 and bg_shape == (T, H, W):
        return True, False
    if T is not None and nd == 4 and bg_shape == (T, H, W, 3):
        return True, True
    want = f"(H, W), (H, W, 3), (T, H, W) or (T, H, W, 3) with T, H, W = {T}, {H}, {W}" if T is not None \
        else f"(H, W) or (H, W, 3) with H, W = {H}, {W}"
    raise ValueError(f"background shape {tuple(bg_shape)} does not match the snow: expected {want}")


def composite(alpha, background, intensity=250):
    """Snow of constant intensity over a background: ``I = intensity*alpha + (1 - alpha)*I_bg`` (Eq. 3.6).

    Parameters
    ----------
    alpha : ndarray, (T, H, W) or (H, W)
        Opacity in [0, 1] (from :func:`noiselab.snow.snow`).
    background : ndarray
        A still ``(H, W)`` / ``(H, W, 3)`` or a video ``(T, H, W)`` /
        ``(T, H, W, 3)``; grey or RGB (alpha is broadcast over colour); uint8
        (0..255) or float (0..1). A still alpha over a video background is
        applied to every frame.
    intensity : float
        Snow intensity on the 0..255 scale (thesis: 250, below saturation);
        used as ``intensity/255`` for float backgrounds.

    Returns
    -------
    ndarray
        uint8 for a uint8 background (rounded and clipped in float, so it
        never wraps around), float32 in [0, 1] for a float background.
        Shape: alpha's frames times the background's frame shape.

    Raises
    ------
    ValueError
        For alpha outside ``[0, 1]`` or non-finite, or a background whose shape
        does not match the snow (the message lists the accepted shapes).

    Examples
    --------
    >>> import numpy as np
    >>> a = np.array([[[0.0, 0.5, 1.0]]], dtype=np.float32)      # 1 frame, 1 x 3
    >>> composite(a, np.full((1, 3, 3), 100, np.uint8))[0, 0]     # RGB background
    array([[100, 100, 100],
           [175, 175, 175],
           [250, 250, 250]], dtype=uint8)
    """
    alpha = _check_alpha(alpha)
    intensity = check_real("intensity", intensity, lo=0, hi=255)
    bg = check_finite_array("background", background)
    still_alpha = alpha.ndim == 2
    H, W = alpha.shape[-2:]
    T = None if still_alpha else alpha.shape[0]
    if still_alpha and bg.ndim in (3, 4) and not (bg.ndim == 3 and bg.shape == (H, W, 3)):
        T = bg.shape[0]
    is_video, is_rgb = _background_layout(bg.shape, T, H, W)
    if bg.dtype == np.uint8:
        out_dtype, level = np.uint8, intensity
    elif bg.dtype.kind == "f":
        if bg.size and (bg.min() < 0 or bg.max() > 1):
            raise ValueError(f"a float background must lie in [0, 1] (pass uint8 for 0..255), "
                             f"got values in [{bg.min():g}, {bg.max():g}]")
        out_dtype, level = np.float32, intensity / 255.0
    else:
        raise TypeError(f"background must be uint8 (0..255) or float (0..1), got dtype {bg.dtype}")
    n_frames = (T if T is not None else 1)
    frame_shape = (H, W, 3) if is_rgb else (H, W)
    out_shape = frame_shape if (still_alpha and not is_video) else (n_frames,) + frame_shape
    check_memory(int(np.prod(out_shape)) * np.dtype(out_dtype).itemsize + 4 * H * W * 3 * 4, "composite")
    out = np.empty(out_shape, dtype=out_dtype)
    level = np.float32(level)
    for i in range(1 if out.ndim == len(frame_shape) else n_frames):
        a = alpha if still_alpha else alpha[i]
        b = bg[i] if is_video else bg
        a = a.astype(np.float32, copy=False)
        if is_rgb:
            a = a[..., None]
        frame = level * a + (np.float32(1) - a) * b.astype(np.float32)
        target = out if out.ndim == len(frame_shape) else out[i]
        if out_dtype == np.uint8:
            np.clip(np.rint(frame), 0, 255, out=frame)
            target[...] = frame.astype(np.uint8)
        else:
            np.clip(frame, 0, 1, out=frame)
            target[...] = frame
    return out


def _region_contrast(out, region):
    """Michelson contrast of ``out`` over a non-empty ``region``: 0 for an all-black one."""
    if not np.any(out, where=region):
        return 0.0
    return michelson_contrast(out, region)


def parallax_composite(foreground, mask, *, transmittance=0.3, veil=255.0, veiled_foreground=None):
    """Two-contrast motion-parallax stimulus (thesis Eq. 6.1) and the Michelson contrast of each region.

    ``I = veil*(1 - transmittance) + transmittance*I_fg`` where the mask is
    set (the light, low-contrast "veiled" region) and ``I = I_fg`` elsewhere,
    with ``I_fg = 255*foreground``. The thesis uses ``transmittance = 0.3``
    and ``veil = 255``: contrast 1 in the clear region and 0.176 in the veiled
    one.

    Parameters
    ----------
    foreground : ndarray (T, H, W) or (H, W)
        The motion parallax in [0, 1] (e.g. ``snow(..., beta=1)``: the
        thesis rescales the inverse FFT to [0, 255] without the exponent).
    mask : ndarray (H, W) or (T, H, W)
        The geometric pattern: bool, or a background image whose bright half
        (above the middle of its range) is the veiled region. Both regions
        must be non-empty (else ``ValueError``: a contrast of no pixels is undefined).
    transmittance : float in [0, 1]
        Fraction of the foreground seen through the veil.
    veil : float in [0, 255]
        Luminance of the veil.
    veiled_foreground : ndarray, optional
        A different foreground for the veiled region (the thesis's
        ``motion_inconsistent`` experiment: another fall direction there).

    Returns
    -------
    video : ndarray of uint8, same shape as ``foreground``
    contrast : dict
        ``{"veiled": c1, "clear": c2}``: Michelson contrast of each region,
        measured on the exact (unrounded) composite over all frames.

    Raises
    ------
    ValueError
        For a mask that leaves one region empty, ``transmittance`` outside
        ``[0, 1]``, ``veil`` outside ``[0, 255]``, or shapes that do not match.

    Examples
    --------
    >>> import numpy as np
    >>> fg = np.linspace(0, 1, 16, dtype=np.float32).reshape(1, 4, 4)
    >>> m = np.zeros((4, 4), bool); m[:, 2:] = True
    >>> video, contrast = parallax_composite(fg, m)
    >>> {k: round(v, 3) for k, v in contrast.items()}
    {'veiled': 0.149, 'clear': 1.0}
    """
    fg = _check_alpha(foreground, "foreground")
    transmittance = check_real("transmittance", transmittance, lo=0, hi=1)
    veil = check_real("veil", veil, lo=0, hi=255)
    fg2 = fg if veiled_foreground is None else _check_alpha(veiled_foreground, "veiled_foreground")
    if fg2.shape != fg.shape:
        raise ValueError(f"veiled_foreground shape {fg2.shape} does not match foreground shape {fg.shape}")
    m = as_array("mask", mask)
    if m.dtype != bool:
        m = check_finite_array("mask", m)
        lo, hi = (float(m.min()), float(m.max())) if m.size else (0.0, 0.0)
        m = m > (lo + hi) / 2 if hi > lo else np.full(m.shape, hi > 0)
    H, W = fg.shape[-2:]
    if m.shape not in ((H, W), fg.shape):
        raise ValueError(f"mask shape {m.shape} does not match the foreground: expected {(H, W)} or {fg.shape}")
    m = np.broadcast_to(m, fg.shape)
    if fg.size and (m.all() or not m.any()):
        which = "veiled" if m.all() else "clear"
        raise ValueError(f"mask must mark some pixels veiled and leave some clear; it makes every pixel {which}, "
                         "so the other region's contrast is undefined")
    lum = 255.0 * fg.astype(np.float32)
    veiled = np.float32(veil * (1 - transmittance)) + np.float32(transmittance) * (255.0 * fg2.astype(np.float32))
    out = np.where(m, veiled, lum)
    contrast = {
        "veiled": _region_contrast(out, m),
        "clear": _region_contrast(out, ~m),
    }
    video = np.clip(np.rint(out), 0, 255).astype(np.uint8)
    return video, contrast
