"""Fields built from lattice noise's exact derivatives (layer 3): curl noise and domain warping.

- :func:`curl_noise` (:mod:`.curl`): a divergence-free velocity field, the
  rotated gradient (2-D) or the curl (3-D) of a noise potential;
- :func:`warp` (:mod:`.warp`): domain warping with its chain-rule Jacobian;
  a :class:`Warped` noise is a noise itself (warps compose).

Both take any object with ``dim_in``, ``dim_out`` and ``jacobian(points,
return_value=...)``: a :class:`~noiselab.lattice.LatticeNoise` with a C1
kernel, or a :class:`Warped`. Fractal sums of either come from
:func:`noiselab.fractal.fractal_gradient`.
"""
from .curl import curl_noise
from .warp import Warped, warp

__all__ = ["curl_noise", "warp", "Warped"]
