"""``noiselab gallery``: build the gallery of the seed papers' figures (same as ``python3 gallery/build.py``).

The builder lives in the repository's ``gallery/`` folder (beside this
package); this command loads that folder as the package ``noiselab_gallery``
by path and runs its ``build.py``, so both entry points share one code path.
"""
from __future__ import annotations

import importlib
import importlib.util
import sys
from pathlib import Path

NAME = "gallery"
HELP = "build the gallery (the seed papers' figures, reproduced and measured) and print where index.html is"

PACKAGE = "noiselab_gallery"
# NOISELAB_EXAMPLE_SIZE=small (the README test): every figure at its quick size
SMALL = {"quick": True}
GALLERY_DIR = Path(__file__).resolve().parents[2] / "gallery"


def load_builder():
    """Import ``gallery/`` as the package ``noiselab_gallery`` and return its ``build`` module."""
    if PACKAGE not in sys.modules:
        init = GALLERY_DIR / "__init__.py"
        if not init.is_file():
            raise FileNotFoundError(f"the gallery builder is not at {str(GALLERY_DIR)!r} "
                                    "(noiselab must be installed editable from its repository: ./install.sh)")
        spec = importlib.util.spec_from_file_location(PACKAGE, init, submodule_search_locations=[str(GALLERY_DIR)])
        module = importlib.util.module_from_spec(spec)
        sys.modules[PACKAGE] = module
        try:
            spec.loader.exec_module(module)
        except BaseException:
            del sys.modules[PACKAGE]
            raise
    return importlib.import_module(f"{PACKAGE}.build")


def add_arguments(parser):
    try:
        load_builder().add_arguments(parser)
    except FileNotFoundError:
        pass


def run(args) -> int:
    builder = load_builder()
    if not getattr(args, "list", False) and getattr(args, "out", None):
        from ..io import prepare_output

        out = Path(args.out)
        if out.exists() and not out.is_dir():
            from ..io import OutputError

            raise OutputError(out, "it is an existing file, not a folder for the gallery")
        prepare_output(out / "index.html")   # fail now, not after building the figures
    import scipy.fft

    with scipy.fft.set_workers(-1):  # every core for the FFTs of snow, spectral_noise and the analysers
        return builder.run(args)
