"""Download the intersphinx inventories (``objects.inv``) of the libraries the docs link to, for offline builds.

The documentation build never fetches anything: it links to numpy, scipy,
dask, trimesh, pyvista and matplotlib only through inventories found on disk
(``$NOISELAB_INTERSPHINX``, default ``~/.cache/noiselab/intersphinx``). Run
this once where the internet is reachable::

    python docs/fetch_inventories.py            # -> ~/.cache/noiselab/intersphinx/<project>.inv
    python docs/fetch_inventories.py FOLDER
"""
import importlib.util
import sys
import urllib.request
from pathlib import Path

HERE = Path(__file__).resolve().parent


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    spec = importlib.util.spec_from_file_location("noiselab_docs_conf", HERE / "conf.py")
    conf = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(conf)
    folder = Path(argv[0]) if argv else conf.inventory_folder()
    folder.mkdir(parents=True, exist_ok=True)
    status = 0
    for name, url in conf.INTERSPHINX.items():
        try:
            with urllib.request.urlopen(url + "objects.inv", timeout=30) as response:
                data = response.read()
        except OSError as exc:
            print(f"{name}: not fetched ({exc})", file=sys.stderr)
            status = 1
            continue
        (folder / f"{name}.inv").write_bytes(data)
        print(f"{name}: {folder / f'{name}.inv'} ({len(data)} bytes)")
    return status


if __name__ == "__main__":
    sys.exit(main())
