"""Phillips' permutation-table lattice noise (value and gradient bases) and its smoothing kernels.

``LatticeNoise(dim_in, dim_out=1, *, rng=0, kernel=...)`` evaluates on
scattered points (``noise(points)``, points ``(..., dim_in)``) and on regular
grids (``noise.grid(shape, extent)``, by separability), with exact
derivatives (``noise.gradient``, ``noise.jacobian``, ``noise.gradient_grid``,
``noise.jacobian_grid``). Its evaluation interface (``noise.evaluate``,
``noise.evaluate_grid`` and their Jacobian twins) sums octaves and is what
:mod:`noiselab.fractal`, :mod:`noiselab.fields` (curl noise, domain
warping) and the dask path call.

Where to look: :mod:`.core` (the ``LatticeNoise`` class: state, and the
calls), :mod:`.tables` (random tables and hashes), :mod:`.points_path`
(scattered points), :mod:`.grid_path` (grids), :mod:`.derivatives`
(Jacobians), :mod:`.checks` (argument checks), :mod:`.grid` (``Grid``,
``check_grid``, ``grid_coordinates``), :mod:`.kernels` (the smoothing
kernels), :mod:`._jit` (every compiled kernel: the lattice engine).
"""
from .core import LatticeNoise
from .grid import Grid, grid_coordinates
from .kernels import KERNELS, Kernel, get_kernel, kernel_names

__all__ = ["LatticeNoise", "Grid", "grid_coordinates", "Kernel", "KERNELS", "get_kernel", "kernel_names"]
