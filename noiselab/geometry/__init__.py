"""Noise-displaced geometry (Phillips 2004, sections 2.1.2 to 4): spheres, meshes, curves, surfaces, flow fields.

Every function here is driven by a *field*: any callable on points ``(n, k)``
returning ``(n,)`` or ``(n, m)`` (a ``noiselab.LatticeNoise``, an octave sum,
a sampled spectral volume, a numpy function).

Grids take ``shape`` and ``extent`` in array-axis order, like
:class:`noiselab.lattice.Grid`: ``(ny, nx)`` and ``((y0, y1), (x0, x1))``
(3-D: ``(nz, ny, nx)``, ``((z0, z1), (y0, y1), (x0, x1))``), and their points,
vectors and phases are ``(y, x)`` in the same order, so
``height_map(noise, shape, extent)`` is ``noise.grid(shape, extent)``
(:mod:`.surfaces` says it in full).

- :mod:`.fields`: ``octave_field`` (fractal sum / turbulence of any field), ``sampled_field``
- :mod:`.displace`: ``displace`` (Eq. 11), ``displace_frames``, ``vertex_normals``,
  ``resolution_report``, ``subdivide_for_noise``
- :mod:`.shapes`: ``sphere``, ``squashed_sphere``, ``sphere_for_noise``, ``load_model``, ``arrange``
- :mod:`.curves`: ``noisy_arc``, ``noisy_circle``, ``trajectory``, ``plot_curves``, ``trajectory_frames``
- :mod:`.surfaces`: ``height_map``, ``monge_surface``, ``colored_surface``
- :mod:`.flow`: ``flow_field``, ``streamlines``, ``quiver_image``, ``flow_glyphs``
- :mod:`.render`: ``render_mesh``, ``render_stereo_pair``, ``render_turntable``, ``render_sequence``
"""
from .fields import evaluate_field, field_max_frequency, octave_field, sampled_field
from .displace import (
    AliasingWarning,
    ResolutionReport,
    as_trimesh,
    displace,
    displace_frames,
    resolution_report,
    subdivide_for_noise,
    vertex_normals,
)
from .shapes import (
    BUNDLED_MODELS,
    arrange,
    load_model,
    normalize,
    plane,
    pyvista_to_trimesh,
    sphere,
    sphere_for_noise,
    squashed_sphere,
    trimesh_to_pyvista,
)
from ._mesh import require_pyvista
from .render import figure_to_array, render_mesh, render_sequence, render_stereo_pair, render_turntable
from .curves import noisy_arc, noisy_circle, plot_curves, trajectory, trajectory_frames
from .surfaces import colored_surface, grid_points, height_map, height_map_image, monge_surface
from .flow import flow_field, flow_glyphs, quiver_image, streamline_image, streamlines

__all__ = [
    "AliasingWarning", "ResolutionReport", "BUNDLED_MODELS",
    "arrange", "as_trimesh", "colored_surface", "displace", "displace_frames", "evaluate_field",
    "field_max_frequency", "figure_to_array", "flow_field", "flow_glyphs", "grid_points", "height_map",
    "height_map_image", "load_model", "monge_surface", "noisy_arc", "noisy_circle", "normalize",
    "octave_field", "plane", "plot_curves", "pyvista_to_trimesh", "quiver_image", "render_mesh", "render_sequence", "render_stereo_pair",
    "render_turntable", "require_pyvista", "resolution_report", "sampled_field", "sphere", "sphere_for_noise",
    "squashed_sphere", "streamline_image", "streamlines", "subdivide_for_noise", "trajectory",
    "trajectory_frames", "trimesh_to_pyvista", "vertex_normals",
]
