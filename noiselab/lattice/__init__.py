"""Phillips' permutation-table lattice noise (value and gradient bases) and its smoothing kernels.

``LatticeNoise(dim_in, dim_out=1, *, seed=0, kernel=...)`` evaluates on
scattered points (``noise(points)``, points ``(..., dim_in)``) and on regular
grids (``noise.grid(shape, extent)``, by separability).
"""
from .core import Grid, LatticeNoise, grid_coordinates
from .kernels import KERNELS, Kernel, get_kernel, kernel_names

__all__ = ["LatticeNoise", "Grid", "grid_coordinates", "Kernel", "KERNELS", "get_kernel", "kernel_names"]
