"""noiselab: spectral and lattice procedural noise side by side, measured with the same instruments.

The public names are imported lazily (on first use), so ``import noiselab``
and the command line start fast and a missing optional renderer never blocks
the rest.

Subpackages, one idea each:

- ``noiselab.spectral``: spectral synthesis on the real-FFT half spectrum and its envelopes
- ``noiselab.snowfall``: Langer & Zhang's falling snow (tent model), compositing, tiling; its function
  ``snow`` is ``noiselab.snow``
- ``noiselab.lattice``: Phillips' permutation-table lattice noise and its kernels
- ``noiselab.fractal``: fractal sums and turbulence over any noise
- ``noiselab.fields``: curl noise (divergence-free flow) and domain warping, with exact derivatives
- ``noiselab.geometry``: noise-displaced meshes, curves, surfaces, flow fields, rendering
- ``noiselab.stimuli``: stimuli in physical units (degrees, seconds, cd/m², contrast) on a described display
- ``noiselab.analysis``: spectra, slopes, isotropy, motion and seam measurements
- ``noiselab.io``: atomic image, video, mesh and zarr I/O
- ``noiselab.lab``: the laboratory (experiments, the timing harness)
- ``noiselab.scale``: chunked evaluation on dask (the ``noiselab[dask]`` extra)
- ``noiselab.gallery``: the gallery builder
- ``noiselab.cli``: the ``noiselab`` command
"""
from __future__ import annotations

import importlib

__version__ = "0.6.2"

# public name -> module that defines it
_API = {
    # spectral synthesis
    "spectral_noise": "noiselab.spectral",
    "synthesize": "noiselab.spectral",
    # falling snow
    "snow": "noiselab.snowfall",
    "composite": "noiselab.snowfall",
    "parallax_composite": "noiselab.snowfall",
    "tile": "noiselab.snowfall",
    "iter_tiled_frames": "noiselab.snowfall",
    # lattice noise
    "LatticeNoise": "noiselab.lattice",
    "fractal_sum": "noiselab.fractal",
    "turbulence": "noiselab.fractal",
    # exact derivatives of lattice noise
    "fractal_gradient": "noiselab.fractal",
    "turbulence_gradient": "noiselab.fractal",
    "curl_noise": "noiselab.fields",
    "warp": "noiselab.fields",
    "monge_normals": "noiselab.geometry.normals",
    "displaced_normals": "noiselab.geometry.normals",
    "normal_angles": "noiselab.geometry.normals",
    # geometry
    "displace": "noiselab.geometry",
    # stimuli in physical units
    "Display": "noiselab.stimuli",
    # the laboratory's alternative snow generators
    "layered_lattice_snow": "noiselab.lab",
    "particle_snow": "noiselab.lab",
}

# the modules whose import registers the dask implementations that ``chunks=`` calls reach through
# ``noiselab._core.dispatch`` (the core names no layer above it; the root, which knows them all, does)
_DISPATCH_PROVIDERS = ("noiselab.scale",)

_SUBPACKAGES = ("spectral", "snowfall", "lattice", "gabor", "fractal", "fields", "geometry", "stimuli", "analysis", "io",
                "lab", "scale", "gallery", "cli")

__all__ = sorted(_API) + list(_SUBPACKAGES)


def __getattr__(name):
    if name in _API:   # (no public name is also a subpackage's: ``noiselab.snow`` is a function)
        value = getattr(importlib.import_module(_API[name]), name)
        globals()[name] = value
        return value
    if name in _SUBPACKAGES:
        return importlib.import_module(f"noiselab.{name}")
    raise AttributeError(f"module 'noiselab' has no attribute {name!r}")


def __dir__():
    return __all__
