"""Deprecated: the falling-snow subpackage is :mod:`noiselab.snowfall`; ``noiselab.snow`` is its function.

``noiselab.snow(shape, ...)`` renders snow (the function
:func:`noiselab.snowfall.snow`, exported at the top level like
``noiselab.spectral_noise``). Until 0.2.0 the subpackage had the same name,
which made ``noiselab.snow`` a module or a function depending on what had
been imported before. For one release the old import paths
(``from noiselab.snow import composite``, ``import noiselab.snow.background``)
still work through this module, with a DeprecationWarning; importing them
binds the name ``noiselab.snow`` to this module for the rest of the process,
so import from :mod:`noiselab.snowfall` instead.
"""
import sys as _sys
import warnings as _warnings

from . import snowfall as _snowfall
from .snowfall import background, render, tent, tiling  # noqa: F401
from .snowfall import *  # noqa: F401,F403
from .snowfall import __all__  # noqa: F401

_warnings.warn("the subpackage noiselab.snow is now noiselab.snowfall (noiselab.snow is the function snow): "
               "import from noiselab.snowfall; the old path goes in the release after 0.2.0",
               DeprecationWarning, stacklevel=2)

# ``import noiselab.snow.tent`` finds the modules of noiselab.snowfall themselves (one module object each)
for _name in ("background", "composite", "render", "tent", "tiling"):
    _sys.modules.setdefault(f"{__name__}.{_name}", _sys.modules[f"{_snowfall.__name__}.{_name}"])
