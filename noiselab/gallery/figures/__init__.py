"""Figure groups: one module each, registered here (the one place).

The order below is the order of the gallery page. Adding a group is adding a
module and its name here; adding a figure is adding a decorated function to
a module (see :mod:`noiselab.gallery.registry`).
"""
import importlib

GROUP_MODULES = ("intro", "snow", "phillips", "lab", "derivatives", "gabor")

for _name in GROUP_MODULES:
    importlib.import_module(f"{__name__}.{_name}")
