"""The documentation site builds from the project's sources with warnings as errors, and is whole.

One full HTML build per test session (the README's command, verbatim but for
the interpreter and the output folder): the HTML builder is the one readers
get, it resolves every cross-reference (``-W`` turns an unresolved one into a
failure) and sphinx-gallery executes every example, so no faster builder would
check less. On the shared 2-core development machine it takes 77 to 115 s of
wall time from a clean tree (numba's cache warm; 33 s of CPU, 31 s of it the
examples). A second build into another output folder runs at the same time:
both must succeed, and neither may write into ``docs/`` (the build reads its
own copy of the sources). The tests then read the built site:
every public name has its API page, a class page lists its methods and
attributes (and the search index has them), API pages link to their source
and to the examples that use them, every benchmark report has its rendered
page, every example (in its section) its figure and download link, no
internal link, anchor or image is broken, and pages open in headless Chromium
without a console error.

The docstrings' ``Examples`` run here too, as doctests, module by module.
"""
import doctest
import importlib
import os
import pkgutil
import re
import shlex
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"

pytest.importorskip("sphinx", reason="the docs extra (./install.sh docs, or ./install.sh test) is not installed")


def readme_build_command():
    """The one command the README gives for building the site."""
    text = (ROOT / "README.md").read_text()
    commands = re.findall(r"`(\.venv/bin/python -m sphinx [^`]*)`", text)
    assert len(commands) == 1, commands
    return commands[0]


def test_readme_gives_the_build_command_with_warnings_as_errors():
    assert readme_build_command() == ".venv/bin/python -m sphinx -W -b html docs docs/_build/html"
    assert "/docs/_build/" in (ROOT / ".gitignore").read_text().split()


def _docs_tree():
    """Every file under docs/ with its size and modification time (the build folder aside)."""
    return {str(p.relative_to(DOCS)): (p.stat().st_size, p.stat().st_mtime_ns) for p in DOCS.rglob("*")
            if p.is_file() and "_build" not in p.relative_to(DOCS).parts and "__pycache__" not in p.parts}


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """The site, built twice at once from this checkout into two output folders; the first is read."""
    argv = shlex.split(readme_build_command())
    assert argv[:3] == [".venv/bin/python", "-m", "sphinx"] and argv[-2:] == ["docs", "docs/_build/html"]
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""), MPLBACKEND="Agg")
    before = _docs_tree()
    outs = [tmp_path_factory.mktemp("site"), tmp_path_factory.mktemp("site-again")]
    procs = [subprocess.Popen([sys.executable, *argv[1:-1], "-d", str(out / "doctrees"), str(out / "html"), "-q"],
                              cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for out in outs]
    results = [proc.communicate(timeout=900) for proc in procs]
    for proc, (stdout, stderr) in zip(procs, results):
        assert proc.returncode == 0, f"sphinx -W failed:\n{stderr[-6000:]}\n{stdout[-2000:]}"
    assert (outs[1] / "html" / "api" / "generated" / "noiselab.lattice.LatticeNoise.html").is_file()
    assert _docs_tree() == before, "the build wrote into docs/"
    return outs[0] / "html"


def test_the_configuration_writes_nothing_and_fetches_nothing(tmp_path):
    """Reading conf.py changes no file; intersphinx uses only inventories on disk (the build runs offline)."""
    before = _docs_tree()
    conf = _conf()
    assert _docs_tree() == before
    assert conf.intersphinx_from(tmp_path) == {}
    (tmp_path / "numpy.inv").write_bytes(b"# Sphinx inventory version 2\n")
    assert conf.intersphinx_from(tmp_path) == {"numpy": ("https://numpy.org/doc/stable/", str(tmp_path / "numpy.inv"))}
    assert {"numpy", "scipy", "dask", "trimesh", "pyvista", "matplotlib"} <= set(conf.INTERSPHINX)
    for _, location in conf.intersphinx_mapping.values():
        assert Path(location).is_file()   # a local file each, never a URL


def _conf():
    spec = importlib.util.spec_from_file_location("noiselab_docs_conf", DOCS / "conf.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class _Page(HTMLParser):
    def __init__(self):
        super().__init__()
        self.ids, self.refs, self.images = set(), [], []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        for key in ("id", "name"):
            if attrs.get(key):
                self.ids.add(attrs[key])
        if tag == "a" and attrs.get("href"):
            self.refs.append(attrs["href"])
        if tag in ("img", "script") and attrs.get("src"):
            (self.images if tag == "img" else self.refs).append(attrs["src"])
        if tag == "link" and attrs.get("href"):
            self.refs.append(attrs["href"])


def _parse(path, cache={}):
    if path not in cache:
        page = _Page()
        page.feed(path.read_text(errors="replace"))
        cache[path] = page
    return cache[path]


def test_every_public_name_has_an_api_page(site):
    conf = _conf()
    packages = conf.public_packages()
    assert {"analysis", "geometry", "io", "lattice", "spectral", "snowfall", "fractal", "scale", "fields"} <= set(packages)
    missing = []
    for package in packages:
        module = importlib.import_module(f"noiselab.{package}")
        for name in module.__all__:
            dotted = f"noiselab.{package}.{name}"
            page = site / "api" / "generated" / f"{dotted}.html"
            if not page.is_file() or not {dotted, f"module-{dotted}"} & _parse(page).ids:
                missing.append(dotted)
    assert not missing, f"public names without an API page: {missing}"
    top = _parse(site / "api" / "noiselab.html")
    linked = {unquote(urlsplit(h).fragment) for h in top.refs}
    for name, dotted in conf.top_level_names():
        assert dotted in linked, f"noiselab.{name} is not on the top-level API page"
        page = site / "api" / "generated" / f"{dotted}.html"
        assert page.is_file() and dotted in _parse(page).ids, dotted


def test_no_internal_link_anchor_or_image_is_broken(site):
    broken, checked = [], 0
    for page_path in sorted(site.rglob("*.html")):
        if page_path.parent.name == "_static":   # the theme's own templates, copied as they are
            continue
        page = _parse(page_path)
        for ref, kind in [(r, "link") for r in page.refs] + [(s, "image") for s in page.images]:
            parts = urlsplit(ref)
            if parts.scheme or parts.netloc or ref.startswith(("mailto:", "javascript:")):
                continue
            target = (page_path.parent / unquote(parts.path)).resolve() if parts.path else page_path
            checked += 1
            if not target.exists():
                broken.append(f"{page_path.relative_to(site)}: {kind} {ref}")
            elif parts.fragment and target.suffix == ".html" and unquote(parts.fragment) not in _parse(target).ids:
                broken.append(f"{page_path.relative_to(site)}: anchor {ref}")
    assert checked > 1000, checked
    assert not broken, "\n".join(broken[:40]) + f"\n({len(broken)} broken of {checked})"


def test_at_least_twelve_examples_ran_and_show_a_figure_and_a_download_link(site):
    pages = sorted((site / "auto_examples").rglob("plot_*.html"))
    sources = sorted((DOCS / "examples").rglob("plot_*.py"))
    assert len(sources) >= 12 and len(pages) == len(sources), (len(sources), len(pages))
    for path in pages:
        page = _parse(path)
        figures = [s for s in page.images if "sphx_glr_" in s and s.endswith(".png")]
        assert figures, f"{path.name} shows no figure"
        for src in figures:
            assert (path.parent / src).stat().st_size > 2000, f"{path.name}: empty figure {src}"
        assert any(h.endswith(f"{path.stem}.py") for h in page.refs), f"{path.name} has no download link"


def test_the_examples_gallery_is_in_sections(site):
    sections = ["spectral", "snow", "lattice", "geometry", "stimuli", "measuring", "scale"]
    assert sorted(p.name for p in (DOCS / "examples").iterdir() if p.is_dir()) == sorted(sections)
    assert not list((DOCS / "examples").glob("plot_*.py"))   # every example is in a section
    index = (site / "auto_examples" / "index.html").read_text()
    titles = [(DOCS / "examples" / s / "README.txt").read_text().splitlines()[0] for s in sections]
    positions = [index.find(t) for t in titles]
    assert all(p >= 0 for p in positions) and positions == sorted(positions), list(zip(titles, positions))
    for section in sections:
        for source in (DOCS / "examples" / section).glob("plot_*.py"):
            assert (site / "auto_examples" / section / f"{source.stem}.html").is_file(), source


def test_a_class_page_lists_its_methods_and_the_search_finds_them(site):
    page = site / "api" / "generated" / "noiselab.lattice.LatticeNoise.html"
    ids = _parse(page).ids
    for method in ("grid", "gradient", "evaluate", "evaluate_grid", "jacobian"):
        assert f"noiselab.lattice.LatticeNoise.{method}" in ids, method
    linked = {unquote(urlsplit(h).fragment) for h in _parse(page).refs}
    assert "noiselab.lattice.LatticeNoise.grid" in linked   # the list of methods at the top links to each
    index = (site / "searchindex.js").read_text()
    assert '"noiselab.lattice.LatticeNoise.grid"' in index or "LatticeNoise.grid" in index
    from noiselab.stimuli import Display

    display = _parse(site / "api" / "generated" / "noiselab.stimuli.Display.html").ids
    methods = [n for n, v in vars(Display).items() if callable(v) and not n.startswith("_")]
    assert methods and all(f"noiselab.stimuli.Display.{n}" in display for n in methods), methods


def test_api_pages_link_to_their_source_and_to_the_examples_using_them(site):
    for name in ("noiselab.lattice.LatticeNoise", "noiselab.snowfall.snow", "noiselab.spectral.spectral_noise"):
        page = site / "api" / "generated" / f"{name}.html"
        text = page.read_text()
        sources = [h for h in _parse(page).refs if "_modules/" in h]
        assert sources and all((page.parent / urlsplit(h).path).resolve().is_file() for h in sources), name
        assert "Examples using" in text and "sphx-glr-thumbcontainer" in text, name
    assert "changelog.html" in {urlsplit(h).path for h in _parse(site / "index.html").refs}
    assert (site / "changelog.html").is_file()


def test_benchmark_pages_are_rendered_from_the_reports_themselves(site):
    reports = sorted((ROOT / "benchmarks").glob("*.md"))
    assert reports
    for report in reports:
        page = site / "benchmarks" / f"{report.stem}.html"
        assert page.is_file(), page
        # the report's first table row (or first line) appears on the page: included, not a stale copy
        lines = [ln for ln in report.read_text().splitlines() if ln.strip()]
        row = next((ln for ln in lines if ln.startswith("| ") and not ln.startswith("| ---")), lines[0])
        first_cell = row.strip("| ").split(" | ")[0].strip("`* ")
        text = re.sub(r"<[^>]+>", "", page.read_text())
        assert first_cell and first_cell.split()[0] in text, (report.name, first_cell)


def test_the_guide_keeps_every_section_the_readme_had(site):
    """The README's sections moved into the guide: each guide page is on the site, headings intact."""
    expected = ["conventions", "layout", "snow", "lattice", "derivatives", "scale", "analysis", "geometry",
                "gallery", "laboratory", "cli"]
    for name in expected:
        assert (site / "guide" / f"{name}.html").is_file(), name
    for page in ("getting_started", "peers", "citing", "api/index", "benchmarks/index", "auto_examples/index"):
        assert (site / f"{page}.html").is_file(), page


def test_the_site_opens_in_headless_chromium_without_a_console_error(site):
    from noiselab.gallery.browser import check_page, find_chromium

    if not find_chromium():
        pytest.skip("no Chromium (./install.sh test installs Debian's chromium)")
    pages = ["index.html", "getting_started.html", "guide/snow.html", "api/generated/noiselab.lattice.LatticeNoise.html",
             "auto_examples/index.html", "auto_examples/snow/plot_tent_schematic.html", "benchmarks/RESULTS.html"]
    for name in pages:
        report = check_page(site / name)
        assert not report["console_errors"], (name, report["console_errors"])
        bad = [img["src"] for img in report["images"] if not img["ok"]]
        assert not bad, (name, bad)


# --- the docstrings' Examples, as doctests --------------------------------------

def _public_modules():
    """Every public module of the documented packages (the command line and the gallery excepted), and every
    module, private ones included, that defines a name of a public package's ``__all__``."""
    names = set()
    for info in pkgutil.walk_packages([str(ROOT / "noiselab")], prefix="noiselab."):
        parts = info.name.split(".")
        if parts[1] in ("cli", "gallery") or any(p.startswith("_") for p in parts[1:]):
            continue
        names.add(info.name)
    for package in [n for n in names if n.count(".") == 1]:
        module = importlib.import_module(package)
        for name in getattr(module, "__all__", ()):
            defined_in = getattr(getattr(module, name), "__module__", None)
            if defined_in and defined_in.startswith("noiselab.") and not defined_in.startswith("noiselab.gallery"):
                names.add(defined_in)
    return sorted(names)


@pytest.mark.parametrize("module_name", _public_modules())
def test_docstring_examples_run(module_name):
    module = importlib.import_module(module_name)
    result = doctest.testmod(module, optionflags=doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS, verbose=False)
    assert result.failed == 0, f"{result.failed} of {result.attempted} doctest examples of {module_name} failed"
