"""Sphinx configuration of noiselab's documentation site.

Build it with ``.venv/bin/python -m sphinx -W -b html docs docs/_build/html``
(``./install.sh docs`` or ``./install.sh test`` installs the tools). Warnings
are errors.

Three parts of the site are generated here at build time, never written by hand:

- ``api/``: one page per public package, listing the package's ``__all__``
  through autosummary (a new subpackage with ``__all__`` appears by itself),
  and the top-level names of ``noiselab._API``;
- ``benchmarks/``: one page per ``benchmarks/*.md`` report and
  ``benchmarks/RESULTS.md``, each a MyST ``include`` of the file itself;
- ``guide/cli.md``'s option tables come from the command's own argparse parser
  (``cli_help.txt``).
"""
from __future__ import annotations

import importlib
import os
import pkgutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))
os.environ.setdefault("MPLBACKEND", "Agg")
os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")

import noiselab  # noqa: E402

project = "noiselab"
author = "the noiselab developers"
copyright = "2026, the noiselab developers"
version = release = noiselab.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "numpydoc",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "examples/README.txt", "examples/*.py",
                    "auto_examples/*.ipynb", "auto_examples/*.py", "auto_examples/*.zip",
                    "auto_examples/*.md5", "auto_examples/*.json"]
templates_path = ["_templates"]

# the site is read offline (and tested in a browser without internet): no CDN scripts
html_theme = "pydata_sphinx_theme"
html_title = f"noiselab {release}"
html_static_path = ["_static"]
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
}
html_sidebars = {"**": ["sidebar-nav-bs"]}
# without a default the theme's script logs a console error ("invalid theme mode") on a first visit
html_context = {"default_mode": "light"}
html_show_sourcelink = False

autosummary_generate = True
autosummary_imported_members = True
autodoc_default_options = {"members": False}
autodoc_typehints = "none"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks = set()

myst_enable_extensions = ["colon_fence"]

myst_heading_anchors = 3

sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "show_memory": False,
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
}


# --- the API reference -------------------------------------------------------

def public_packages():
    """Every ``noiselab.X`` subpackage with an ``__all__`` (the command line excepted: it has its own page)."""
    names = []
    for info in sorted(pkgutil.iter_modules(noiselab.__path__), key=lambda m: m.name):
        if info.name.startswith("_") or not info.ispkg or info.name == "cli":
            continue
        module = importlib.import_module(f"noiselab.{info.name}")
        if getattr(module, "__all__", None):
            names.append(info.name)
    return names


def top_level_names():
    """``(name, canonical dotted name)`` for each name of ``noiselab._API``: where its API page is."""
    rows = []
    for name, module_name in sorted(noiselab._API.items()):
        package = ".".join(module_name.split(".")[:2])
        where = package if name in importlib.import_module(package).__all__ else module_name
        rows.append((name, f"{where}.{name}"))
    return rows


def _first_line(module):
    doc = (module.__doc__ or "").strip().splitlines()
    return doc[0].rstrip(".") if doc else module.__name__


def write_api_pages(folder=HERE / "api"):
    folder.mkdir(exist_ok=True)
    packages = public_packages()
    pages = ["noiselab"]
    covered = set()
    for package in packages:
        module = importlib.import_module(f"noiselab.{package}")
        title = f"``noiselab.{package}``: {_first_line(module)}"
        names = list(dict.fromkeys(module.__all__))
        covered |= {f"noiselab.{package}.{n}" for n in names}
        lines = [title, "=" * len(title), "", f".. automodule:: noiselab.{package}", "   :no-members:", "",
                 f".. currentmodule:: noiselab.{package}", "", ".. autosummary::", "   :toctree: generated/",
                 "   :nosignatures:", ""] + [f"   {n}" for n in names] + [""]
        _write_if_changed(folder / f"noiselab.{package}.rst", "\n".join(lines))
        pages.append(f"noiselab.{package}")
    rows = top_level_names()
    extra = [dotted for _, dotted in rows if dotted not in covered]   # defined below a subpackage's __all__
    title = "``noiselab``: the top-level names"
    lines = [title, "=" * len(title), "",
             "``import noiselab`` gives these names (imported on first use); each is the same object as the",
             "subpackage's name it links to.", "", ".. autosummary::", "   :nosignatures:", ""]
    lines += [f"   {dotted}" for _, dotted in rows if dotted in covered]
    if extra:
        lines += ["", "Names defined in a module below their subpackage:", "", ".. autosummary::",
                  "   :toctree: generated/", "   :nosignatures:", ""] + [f"   {d}" for d in extra]
    _write_if_changed(folder / "noiselab.rst", "\n".join(lines) + "\n")
    index = ["API reference", "=============", "",
             "Generated from the packages' ``__all__`` and their numpydoc docstrings.", "",
             ".. toctree::", "   :maxdepth: 1", ""] + [f"   {p}" for p in pages]
    _write_if_changed(folder / "index.rst", "\n".join(index) + "\n")


# --- the benchmark reports -----------------------------------------------------

def write_benchmark_pages(folder=HERE / "benchmarks"):
    folder.mkdir(exist_ok=True)
    reports = sorted((ROOT / "benchmarks").glob("*.md"))
    names = []
    for report in reports:
        name = report.stem
        names.append(name)
        text = (f"```{{include}} ../../benchmarks/{report.name}\n:heading-offset: 0\n:relative-images:\n:relative-docs: results/\n```\n")
        if name != "RESULTS":
            text = f"# `benchmarks/{report.name}`\n\n" + text.replace(":heading-offset: 0", ":heading-offset: 1")
        _write_if_changed(folder / f"{name}.md", text)
    for stale in folder.glob("*.md"):
        if stale.stem not in names:
            stale.unlink()
    order = ["RESULTS"] + [n for n in names if n != "RESULTS"]
    index = ["# Benchmarks", "",
             "Each page is a report written by the script beside it in `benchmarks/` (the command that made it is",
             "in its header), included here as it is in the repository. `RESULTS.md` is the laboratory's run",
             "(`python3 benchmarks/lab_run.py --publish`); the guide's {doc}`../guide/laboratory` explains how to read it.", "",
             "```{toctree}", ":maxdepth: 1", ""] + order + ["```", ""]
    _write_if_changed(folder / "index.md", "\n".join(index))


# --- the command line ----------------------------------------------------------

def write_cli_help(path=HERE / "guide" / "cli_help.txt"):
    """Every subcommand's ``--help``, as argparse prints it (included by ``guide/cli.md``)."""
    import contextlib
    import io

    from noiselab.cli import build_parser

    parser = build_parser()
    out = []
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    os.environ["COLUMNS"] = "100"
    for name, subparser in sorted(sub.choices.items()):
        buf = io.StringIO()
        with contextlib.redirect_stdout(buf):
            subparser.print_help()
        out.append(f"$ noiselab {name} --help\n{buf.getvalue()}")
    _write_if_changed(path, "\n".join(out))


def _write_if_changed(path, text):
    path = Path(path)
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


write_api_pages()
write_benchmark_pages()
write_cli_help()
