"""The noiselab gallery builder (see ``build.py``).

This folder is loaded as a package by ``noiselab.cli.gallery.load_builder``
(under the name ``noiselab_gallery``), so ``python3 gallery/build.py`` and
``python3 -m noiselab gallery`` run the same code. Figures live in
``figures/``, one module per group, registered with
:func:`gallery.registry.figure`.
"""
