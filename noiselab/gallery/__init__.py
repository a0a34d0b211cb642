"""The noiselab gallery: the seed papers' figures, reproduced with noiselab and measured.

Layer 6 of the package (above ``scale``, below ``cli``): the figures use
noiselab only through public names, as a user's script would. Two entry
points run the same code, from any folder, installed or not::

    noiselab gallery [--out out/gallery] [--only GROUP] [--quick] [--force]
    python3 -m noiselab.gallery [same options]

The output goes where ``--out`` says (default ``out/gallery`` under the current
folder), never into the package. Figures live in :mod:`noiselab.gallery.figures`,
one module per group, registered with :func:`figure`; build from Python with
:func:`noiselab.gallery.build.build`.

Examples
--------
>>> from noiselab.gallery import specs
>>> "snow/opacity" in [s.key for s in specs("snow")]
True
"""
from .build import DEFAULT_OUT, main
from .registry import Result, figure, specs

__all__ = ["DEFAULT_OUT", "Result", "figure", "main", "specs"]
