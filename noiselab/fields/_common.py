"""What the fields share: the duck type of a differentiable noise, and points as float64 ``(..., dim)``."""
from __future__ import annotations

import numpy as np

from .._core import check_finite_array

__all__ = ["check_noise", "as_points"]


def check_noise(name, noise):
    """``noise`` must have ``dim_in``, ``dim_out`` and ``jacobian(points, return_value=...)``."""
    if not (callable(getattr(noise, "jacobian", None)) and hasattr(noise, "dim_in") and hasattr(noise, "dim_out")):
        raise TypeError(f"{name} must be a LatticeNoise (or a warp of one): an object with dim_in, dim_out and "
                        f"jacobian(points); got {type(noise).__name__}")


def as_points(points, dim, name="points"):
    """``points`` as float64 ``(..., dim)`` (for ``dim == 1`` a plain array is that many inputs)."""
    pts = check_finite_array(name, points).astype(np.float64, copy=False)
    if dim == 1 and (pts.ndim == 0 or pts.shape[-1] != 1):
        pts = pts[..., None]
    if pts.ndim == 0 or pts.shape[-1] != dim:
        raise ValueError(f"{name} must have shape (..., dim_in={dim}), got {np.shape(points)}")
    return pts
