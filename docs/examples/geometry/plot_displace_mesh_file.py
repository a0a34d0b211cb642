"""
Noise-displacing a mesh from a file
===================================

:func:`noiselab.displace` moves every vertex of a mesh along its normal by a
3-D noise of its position (Phillips Eq. 11). Any mesh file trimesh reads will
do (:func:`noiselab.io.read_mesh`); here one is written first so the example is
self-contained. :func:`noiselab.geometry.sphere_for_noise` gives a sphere fine
enough for the octaves asked.
"""
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt

import noiselab
from noiselab.geometry import sphere_for_noise
from noiselab.io import read_mesh, write_mesh

folder = Path(tempfile.mkdtemp())
write_mesh(folder / "ball.obj", sphere_for_noise(2.0 * 2 ** 2))     # "your" mesh file
mesh = read_mesh(folder / "ball.obj")
bumpy = noiselab.displace(mesh, noiselab.LatticeNoise(3, rng=7), amplitude=0.15, frequency=2.0, octaves=3)
write_mesh(folder / "bumpy.ply", bumpy)
print(len(mesh.vertices), "vertices; radius", round(float(abs(bumpy.vertices).max()), 3))

fig = plt.figure(figsize=(8, 3.6))
for i, (m, title) in enumerate(((mesh, "read from ball.obj"), (bumpy, "displaced, 3 octaves"))):
    ax = fig.add_subplot(1, 2, i + 1, projection="3d")
    v = m.vertices
    ax.plot_trisurf(v[:, 0], v[:, 1], v[:, 2], triangles=m.faces, cmap="bone", linewidth=0)
    ax.set_title(title)
    ax.set_box_aspect((1, 1, 1))
    ax.set_axis_off()
fig.tight_layout()
