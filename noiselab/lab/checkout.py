"""Where the laboratory finds the noiselab git checkout: the published results and the peers' environment.

An ordinary ``noiselab bench`` needs no checkout: it writes where
``--output`` says. Two things live only in a checkout: the published
``benchmarks/RESULTS.md`` (``bench --publish``) and the peers' virtualenv
``benchmarks/.venv-peers`` (made by ``bash benchmarks/setup_peers.sh``).
The checkout is the folder this package was installed from in editable mode
(``./install.sh`` does that), else the current folder or one above it.
"""
from __future__ import annotations

from pathlib import Path

__all__ = ["CheckoutNotFound", "find_checkout", "is_checkout", "package_parent", "peer_python", "published_dir"]


class CheckoutNotFound(ValueError):
    """``bench --publish`` (or the peers) needs the noiselab git checkout, and none was found."""


def package_parent() -> Path:
    """The folder that holds the running ``noiselab`` package (a checkout, or site-packages)."""
    return Path(__file__).resolve().parents[2]


def is_checkout(folder) -> bool:
    """Whether ``folder`` looks like the noiselab repository (``pyproject.toml``, ``noiselab/``, ``benchmarks/``)."""
    folder = Path(folder)
    return ((folder / "pyproject.toml").is_file() and (folder / "noiselab" / "__init__.py").is_file()
            and (folder / "benchmarks").is_dir())


def find_checkout(cwd=None):
    """The noiselab checkout: the editable install's source folder, else ``cwd`` or a folder above it; or None.

    Examples
    --------
    >>> import tempfile
    >>> find_checkout(tempfile.gettempdir()) in (None, package_parent())   # an editable install finds itself
    True
    """
    here = Path.cwd() if cwd is None else Path(cwd)
    here = here.resolve()
    for folder in (package_parent(), here, *here.parents):
        if is_checkout(folder):
            return folder
    return None


def published_dir() -> Path:
    """``benchmarks/`` of the checkout, where the published ``RESULTS.md`` lives; :class:`CheckoutNotFound` without one."""
    root = find_checkout()
    if root is None:
        raise CheckoutNotFound(f"the published results are benchmarks/RESULTS.md of the noiselab git checkout, and "
                               f"none was found (not at {package_parent()}, where noiselab is installed, nor in "
                               f"{Path.cwd()} or above): run --publish from the checkout, or write elsewhere "
                               f"with --output")
    return root / "benchmarks"


def peer_python():
    """The interpreter of the peers' environment ``benchmarks/.venv-peers`` of the checkout (None without a checkout)."""
    root = find_checkout()
    return None if root is None else root / "benchmarks" / ".venv-peers" / "bin" / "python"
