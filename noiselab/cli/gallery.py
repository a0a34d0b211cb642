"""``noiselab gallery``: build the gallery of the seed papers' figures (same as ``python3 -m noiselab.gallery``).

The builder is the package :mod:`noiselab.gallery`; this command adds the
command line's error handling and checks the output folder before the
figures are built. It runs from any folder, from an installed noiselab, and
writes where ``--out`` says (default ``out/gallery`` under the current folder).
"""
from __future__ import annotations

from pathlib import Path

NAME = "gallery"
HELP = "build the gallery (the seed papers' figures, reproduced and measured) and print where index.html is"


def add_arguments(parser):
    from ..gallery.build import add_arguments as gallery_arguments

    gallery_arguments(parser)


def run(args) -> int:
    from ..gallery.build import run as build_gallery

    if not args.list:
        from ..io import OutputError, prepare_output

        out = Path(args.out)
        if out.exists() and not out.is_dir():
            raise OutputError(out, "it is an existing file, not a folder for the gallery")
        prepare_output(out / "index.html")   # fail now, not after building the figures
    import scipy.fft

    with scipy.fft.set_workers(-1):  # every core for the FFTs of snow, spectral_noise and the analysers
        return build_gallery(args)
