"""``noiselab cache``: list the folders of numba's compile cache that hold noiselab's kernels, or clear them.

numba keeps the machine code of noiselab's kernels on disk (``cache=True``)
so that only a first call compiles. A cache damaged on disk (a file truncated
by a full disk, copied half) makes numba fail on a kernel's first call;
``noiselab cache --clear`` removes noiselab's cache files (Python's ``*.pyc``
stay), and the next run compiles the kernels again and fills the cache anew.
Setting ``NUMBA_CACHE_DIR`` to an empty folder does the same for one shell.
"""
from __future__ import annotations

NAME = "cache"
HELP = "list the folders of numba's compile cache holding noiselab's kernels; --clear removes them"


def add_arguments(parser):
    parser.add_argument("--clear", action="store_true",
                        help="remove noiselab's compiled-kernel cache files (the next run compiles anew, seconds)")


def run(args) -> int:
    from .._core.jitcache import cache_folders, clear_cache

    if args.clear:
        removed = clear_cache()
        print(f"noiselab cache: removed {len(removed)} cache entr{'y' if len(removed) == 1 else 'ies'}")
        return 0
    folders = cache_folders()
    for folder in folders:
        print(folder)
    if not folders:
        print("noiselab cache: no cache folder yet (the first call of a kernel makes one)")
    return 0
