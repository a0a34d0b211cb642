"""Falling snow by inverse FFT (Langer & Zhang 2003; Zhang's thesis), compositing and tiling.

- :func:`snow`: opacity video ``alpha(t, y, x)`` in [0, 1] from the (thickened,
  sheared) tent spectrum, built sparsely and inverted by a pruned inverse FFT.
- :func:`composite`: snow of constant intensity over a still or video background (Eq. 3.6).
- :func:`parallax_composite`: the two-contrast compositing of Eq. 6.1 with the
  Michelson contrast of each region.
- :func:`tile`, :func:`iter_tiled_frames`: seamless tiling in x, y and t (thesis 3.4).
- :func:`flake_speeds`: how ``c`` maps to the speeds of the nearest and farthest flakes.
"""
from .composite import composite, michelson_contrast, parallax_composite
from .render import rescale_opacity, snow, snow_spectrum
from .tent import flake_speeds
from .tiling import iter_tiled_frames, tile

__all__ = [
    "snow",
    "snow_spectrum",
    "rescale_opacity",
    "composite",
    "parallax_composite",
    "michelson_contrast",
    "tile",
    "iter_tiled_frames",
    "flake_speeds",
]

