"""The octave loop over a plain callable: what the in-memory and the dask fractal sums share.

:func:`noiselab.fractal.fractal_sum` and :func:`~noiselab.fractal.turbulence`
run it on the whole point set (or grid), and the dask path
(:mod:`noiselab.scale.lattice`) on the points of each chunk, with the octave
count decided once on the full grid, so both give the same bits. A
``LatticeNoise`` does not come here: its own octave sum
(:meth:`~noiselab.lattice.LatticeNoise.evaluate`,
:meth:`~noiselab.lattice.LatticeNoise.evaluate_grid`) runs every octave in
its kernels.
"""
from __future__ import annotations

import numpy as np

__all__ = ["callable_sum"]


def callable_sum(noise, pts, used, lacunarity, gain, absval, norm, out_dtype):
    """``sum_o gain**o b(noise(lacunarity**o pts)) / norm`` for ``o < used``, as ``out_dtype``; finite or refused.

    Parameters
    ----------
    noise : callable
        Called on points ``(..., dim)`` scaled by ``lacunarity**o``; returns one value per point
        (or one row of components).
    pts : ndarray (..., dim)
        The points.
    used : int
        Octaves summed (as :func:`noiselab.fractal.octaves_used` decided).
    lacunarity, gain : float
        Frequency and amplitude ratio between octaves.
    absval : bool
        ``b = abs`` (turbulence) instead of the identity.
    norm : float
        Divides the sum (1 for none).
    out_dtype : numpy.dtype
        The result's dtype (the sum is float64).

    Raises
    ------
    ValueError
        If ``noise`` returned NaN or inf, or the sum overflowed ``out_dtype``.

    Examples
    --------
    >>> import numpy as np
    >>> pts = np.linspace(0, 1, 5)[:, None]
    >>> callable_sum(lambda p: p[:, 0], pts, 3, 2.0, 0.5, False, 1.0, np.dtype(np.float64)).tolist()
    [0.0, 0.75, 1.5, 2.25, 3.0]
    """
    result = None
    with np.errstate(over="ignore", invalid="ignore"):
        for o in range(used):
            v = np.asarray(noise(pts * lacunarity ** o), dtype=np.float64)
            term = gain ** o * (np.abs(v) if absval else v)
            result = term if result is None else result + term
        result = (result / norm).astype(out_dtype)
    if not np.isfinite(result).all():
        raise ValueError(f"noise returned NaN or inf (or the octave sum overflowed {out_dtype.name}) at "
                         f"{int((~np.isfinite(result)).sum())} point(s); noise must return finite values")
    return result
