"""Beyond one machine: chunked, lazy noise on dask, computed anywhere dask runs.

``LatticeNoise.grid(..., chunks=...)``, ``fractal_sum(..., chunks=...)`` and
``turbulence(..., chunks=...)`` on a :class:`noiselab.lattice.Grid` return a
lazy ``dask.array.Array``; every chunk is rendered by the ``window=`` path, so
the array is bit-identical to the in-memory grid for any chunking, and no
chunk needs more than its own samples (plus the lattice block under it) in
memory. :func:`noiselab.io.write_zarr` streams such an array into a zarr store
atomically, with its provenance in the attributes.

Scheduling is dask's: the default threaded scheduler, or a
``dask.distributed.Client`` (worker processes, a real cluster) if one is
active or named with ``scheduler=``. dask, distributed and zarr are the
optional extra ``pip install noiselab[dask]``.

Modules: :mod:`noiselab.scale.lattice` (chunked grids and fractal sums),
:mod:`noiselab.scale.spectral` (chunked spectral noise and snow: pencil-decomposed inverse FFTs),
:mod:`noiselab.scale.run` (computing on a chosen scheduler with progress).
"""
from .._core import require_dask
from .run import compute

__all__ = ["require_dask", "compute"]
