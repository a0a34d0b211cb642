"""
A tileable fBm height map exported as a mesh
============================================

With ``period=`` a :class:`noiselab.LatticeNoise` repeats exactly after
``period / frequency`` input units, and so does a fractal sum whose octaves
keep whole periods (lacunarity 2). :func:`noiselab.geometry.monge_surface`
turns the heights into a triangle mesh, :func:`noiselab.io.write_mesh` writes it
(PLY, OBJ, STL, GLB or OFF; atomically). The figure shows the height map twice
side by side: no seam at the join.
"""
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import noiselab
from noiselab.geometry import monge_surface
from noiselab.io import read_mesh, write_mesh
from noiselab.lattice import Grid

noise = noiselab.LatticeNoise(2, rng=6, period=4)                  # repeats every 4 units along y and x
heights = noiselab.fractal_sum(noise, Grid((128, 128), ((0, 4), (0, 4))), 5, normalize=True)
print("left-right jump:", float(np.abs(heights[:, 0] - heights[:, -1]).max()),
      "neighbour step:", float(np.abs(np.diff(heights, axis=1)).max()))

mesh = monge_surface(noise, shape=(64, 64), extent=((0, 4), (0, 4)), amplitude=0.3, octaves=3)
path = write_mesh(Path(tempfile.mkdtemp()) / "terrain.ply", mesh)
print(path.name, len(read_mesh(path).faces), "faces")

fig, axes = plt.subplots(1, 2, figsize=(9, 3), gridspec_kw={"width_ratios": [2, 1.2]})
axes[0].imshow(np.hstack([heights, heights]), cmap="terrain")
axes[0].set_title("the height map, twice side by side")
axes[0].axis("off")
ax3 = fig.add_subplot(1, 2, 2, projection="3d")
axes[1].remove()
v = mesh.vertices
ax3.plot_trisurf(v[:, 1], v[:, 0], v[:, 2], triangles=mesh.faces, cmap="terrain", linewidth=0)
ax3.set_title("the mesh (64 x 64 vertices)")
ax3.set_axis_off()
fig.tight_layout()
