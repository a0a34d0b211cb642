"""Sphinx configuration of noiselab's documentation site.

Build it with ``.venv/bin/python -m sphinx -W -b html docs docs/_build/html``
(``./install.sh docs`` or ``./install.sh test`` installs the tools). Warnings
are errors.

The build leaves the source tree untouched. It reads a copy of ``docs/`` that
it owns, beside its output folder (``docs/_build/.html-source/docs`` for the
command above; one per output folder), kept in step with ``docs/`` file by
file (unchanged files keep their times, so a second build is incremental),
and generates its pages there, never written by hand:

- ``api/``: one page per public package, listing the package's ``__all__``
  through autosummary (a new subpackage with ``__all__`` appears by itself),
  and the top-level names of ``noiselab._API``; a class page lists its
  methods and attributes, each with its docstring, and every page ends with
  the examples that use the name (sphinx-gallery's backreferences);
- ``benchmarks/``: one page per ``benchmarks/*.md`` report and
  ``benchmarks/RESULTS.md``, each a MyST ``include`` of the file itself;
- ``guide/cli.md``'s option tables come from the command's own argparse parser
  (``cli_help.txt``);
- ``auto_examples/``: sphinx-gallery's pages, one section per subfolder of
  ``docs/examples/``.

So two builds from one checkout into two output folders can run at once.

Links to numpy, scipy, dask, trimesh, pyvista and matplotlib (intersphinx)
need those projects' ``objects.inv`` inventories; the build never fetches
them (it runs offline). It uses the ones found in ``$NOISELAB_INTERSPHINX``
(a folder of ``<project>.inv`` files; ``python docs/fetch_inventories.py``
fills ``~/.cache/noiselab/intersphinx``, the default, where the internet is
reachable), and builds without the links for the others.
"""
from __future__ import annotations

import importlib
import os
import pkgutil
import re
import shutil
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
    "sphinx.ext.intersphinx",
    "sphinx.ext.viewcode",
    "numpydoc",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "examples/**", "fetch_inventories.py",
                    "auto_examples/**.ipynb", "auto_examples/**.py", "auto_examples/**.zip",
                    "auto_examples/**.md5", "auto_examples/**.json", "auto_examples/**.txt"]
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
autodoc_default_options = {}   # each page says what it shows (the class template lists the members)
autodoc_typehints = "none"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks = set()

myst_enable_extensions = ["colon_fence"]

myst_heading_anchors = 3

# the gallery's sections, in reading order (each a subfolder of docs/examples with its README.txt)
EXAMPLE_SECTIONS = ["spectral", "snow", "lattice", "geometry", "stimuli", "measuring", "scale"]

sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "auto_examples",
    "subsection_order": [f"examples/{name}" for name in EXAMPLE_SECTIONS],
    # "Examples using X" on each API page: which examples call which noiselab names
    "backreferences_dir": "api/generated/backreferences",
    "doc_module": ("noiselab",),
    "reference_url": {"noiselab": None},
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "show_memory": False,
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
}


# --- links to the libraries noiselab works with (offline: local inventories only) ------------

INTERSPHINX = {
    "python": "https://docs.python.org/3/",
    "numpy": "https://numpy.org/doc/stable/",
    "scipy": "https://docs.scipy.org/doc/scipy/",
    "dask": "https://docs.dask.org/en/stable/",
    "trimesh": "https://trimesh.org/",
    "pyvista": "https://docs.pyvista.org/",
    "matplotlib": "https://matplotlib.org/stable/",
}


def inventory_folder() -> Path:
    """Where the build looks for ``<project>.inv`` files: ``$NOISELAB_INTERSPHINX``, else the user's cache."""
    env = os.environ.get("NOISELAB_INTERSPHINX")
    return Path(env) if env else Path.home() / ".cache" / "noiselab" / "intersphinx"


def intersphinx_from(folder) -> dict:
    """The intersphinx mapping for the inventories present in ``folder``: never a URL to fetch."""
    folder = Path(folder)
    return {name: (url, str(folder / f"{name}.inv")) for name, url in INTERSPHINX.items()
            if (folder / f"{name}.inv").is_file()}


intersphinx_mapping = intersphinx_from(inventory_folder())
intersphinx_timeout = 1


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


def write_api_pages(folder):
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
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

def write_benchmark_pages(folder):
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
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

def write_cli_help(path):
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


# --- the build's own copy of the sources ------------------------------------------

# made by the build, never copied from docs/ (a tree built in place by an older conf.py may hold them)
GENERATED = ("_build", "api", "benchmarks", "auto_examples", "guide/cli_help.txt", "sg_execution_times.rst",
             "sg_api_usage.rst", "__pycache__")


def _generated(rel: Path) -> bool:
    text = rel.as_posix()
    return any(text == g or text.startswith(g + "/") for g in GENERATED)


def sync_sources(src: Path, dst: Path) -> None:
    """Make ``dst`` hold the files of ``src`` (generated paths aside), copying only what differs.

    Copies keep their modification times, so Sphinx rebuilds only the pages
    whose source changed; files gone from ``src`` go from ``dst``.
    """
    wanted = set()
    for path in sorted(src.rglob("*")):
        rel = path.relative_to(src)
        if _generated(rel) or not path.is_file():
            continue
        wanted.add(rel)
        target = dst / rel
        st = path.stat()
        if target.is_file() and (target.stat().st_size, target.stat().st_mtime_ns) == (st.st_size, st.st_mtime_ns):
            continue
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(path, target)
    if dst.is_dir():
        for path in sorted(dst.rglob("*"), reverse=True):
            rel = path.relative_to(dst)
            if path.is_file() and not _generated(rel) and rel not in wanted:
                path.unlink()


def build_sources(outdir) -> Path:
    """The build's copy of ``docs/`` for output folder ``outdir``, synced and with its generated pages."""
    owned = Path(outdir).resolve().parent / f".{Path(outdir).name}-source"
    src = owned / "docs"
    sync_sources(HERE, src)
    link = owned / "benchmarks"   # the reports' includes and images: ../../benchmarks/ from a page
    if not link.exists():
        link.symlink_to(ROOT / "benchmarks", target_is_directory=True)
    write_api_pages(src / "api")
    write_benchmark_pages(src / "benchmarks")
    write_cli_help(src / "guide" / "cli_help.txt")
    return src


_BACKLINK = re.compile(r'href="([^"]*api/generated/)([\w.]+)\.html#([\w.]+)"')


def _fix_source_backlinks(app, pagename, templatename, context, doctree):
    """On a ``[source]`` page, point each "[docs]" link at the anchor of the page it opens.

    A function documented under two public names (``noiselab.analysis.michelson_contrast``
    and ``noiselab.snowfall.michelson_contrast``, one object) gets one entry in viewcode's
    table, whose page and anchor can come from the two names; an API page's anchor is its
    own full name.
    """
    if not pagename.startswith("_modules/") or "body" not in context:
        return

    def fix(match):
        folder, page, anchor = match.groups()
        if anchor != page and anchor.rsplit(".", 1)[-1] == page.rsplit(".", 1)[-1]:
            anchor = page
        return f'href="{folder}{page}.html#{anchor}"'

    context["body"] = _BACKLINK.sub(fix, context["body"])


def setup(app):
    # read the build's own copy (Sphinx takes the source folder from here on: the project is made after setup)
    app.srcdir = build_sources(app.outdir)
    app.connect("html-page-context", _fix_source_backlinks)
