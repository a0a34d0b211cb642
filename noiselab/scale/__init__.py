"""Beyond one machine: chunked, lazy noise on dask, computed anywhere dask runs (layer 5, beside the core).

``LatticeNoise.grid(..., chunks=...)``, ``fractal_sum(..., chunks=...)``,
``turbulence(..., chunks=...)``, ``spectral_noise(..., chunks=...)`` and
``snow(..., chunks=...)``, ``GaborNoise.grid(..., chunks=...)`` and
``gabor_snow(..., chunks=...)`` return a lazy ``dask.array.Array``. The in-memory
core never imports this package: each of those functions asks
:func:`noiselab._core.dispatch.chunked` for the implementation registered
here under its name, and this package registers them when it is imported.
Every chunk is rendered by the in-memory path's window, so the array is
bit-identical to the in-memory result for any chunking.

Scheduling is dask's: the default threaded scheduler, or a
``dask.distributed.Client`` (worker processes, a real cluster) if one is
active or named with ``scheduler=``. dask, distributed and zarr are the
optional extra ``pip install noiselab[dask]``.

Modules: :mod:`noiselab.scale.lattice` (chunked grids and fractal sums),
:mod:`noiselab.scale.spectral` (chunked spectral noise and snow: pencil-decomposed inverse FFTs),
:mod:`noiselab.scale.gabor` (chunked Gabor noise and Gabor snow: one window per chunk),
:mod:`noiselab.scale.run` (computing on a chosen scheduler with progress).
"""
from .._core import require_dask
from . import gabor, lattice, spectral  # noqa: F401  (importing them registers the dask implementations)
from . import zarr  # noqa: F401  (registers write_zarr and read_zarr for dask arrays)
from .run import compute

__all__ = ["require_dask", "compute"]
