"""
A chunked volume written to zarr with a local dask cluster
==========================================================

With ``chunks=`` a fractal sum on a :class:`noiselab.lattice.Grid` is a lazy dask
array, bit-identical to the in-memory result for any chunking;
:func:`noiselab.io.write_zarr` streams it into a zarr store on whatever cluster
is active (here a ``distributed.LocalCluster`` of threads) with the seed and
parameters in its attributes. Needs the ``noiselab[dask]`` extra.
"""
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from distributed import Client, LocalCluster

import noiselab
from noiselab.io import read_zarr, write_zarr
from noiselab.lattice import Grid

noise = noiselab.LatticeNoise(3, rng=1)
grid = Grid((64, 64, 64), [(0, 4)] * 3)
volume = noiselab.fractal_sum(noise, grid, 4, dtype="float32", chunks=(32, 32, 32))   # lazy: 8 chunks
store = Path(tempfile.mkdtemp()) / "fbm.zarr"
with LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address=None) as cluster, \
        Client(cluster):
    write_zarr(store, volume, dims=("z", "y", "x"), rng=1, params={"octaves": 4}, units="amplitude")
back = read_zarr(store)
same = np.array_equal(np.asarray(back), noiselab.fractal_sum(noise, grid, 4, dtype="float32"))
print(volume.chunksize, "chunks; equal to the in-memory sum:", same)

fig, axes = plt.subplots(1, 3, figsize=(9, 3))
for ax, k in zip(axes, (0, 21, 42)):
    ax.imshow(np.asarray(back)[k], cmap="viridis")
    ax.set_title(f"slice z = {k}")
    ax.axis("off")
fig.tight_layout()
