"""Phillips' permutation-table lattice noise (value and gradient bases) and its smoothing kernels.

``LatticeNoise(dim_in, dim_out=1, *, seed=0, kernel=...)`` evaluates on
scattered points (``noise(points)``, points ``(..., dim_in)``) and on regular
grids (``noise.grid(shape, extent)``, by separability); its exact derivatives
(``noise.gradient``, ``noise.jacobian``, ``noise.gradient_grid``,
``noise.jacobian_grid``) give :func:`curl_noise` (divergence-free flow) and
:func:`warp` (domain warping with its chain-rule Jacobian).
"""
from .core import Grid, LatticeNoise, grid_coordinates
from .kernels import KERNELS, Kernel, get_kernel, kernel_names
from .derivatives import Warped, curl_noise, warp

__all__ = ["LatticeNoise", "Grid", "grid_coordinates", "Kernel", "KERNELS", "get_kernel", "kernel_names",
           "curl_noise", "warp", "Warped"]
