"""The documentation site builds from the project's sources with warnings as errors, and is whole.

One full HTML build per test session (the README's command, verbatim but for
the interpreter and the output folder): the HTML builder is the one readers
get, it resolves every cross-reference (``-W`` turns an unresolved one into a
failure) and sphinx-gallery executes every example, so no faster builder would
check less. On the shared 2-core development machine it takes 77 to 115 s of
wall time from a clean tree (numba's cache warm; 33 s of CPU, 31 s of it the
examples). The tests then read the built site:
every public name has its API page, every benchmark report its rendered page,
every example its figure and download link, no internal link, anchor or image
is broken, and pages open in headless Chromium without a console error.

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


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    out = tmp_path_factory.mktemp("site")
    argv = shlex.split(readme_build_command())
    assert argv[:3] == [".venv/bin/python", "-m", "sphinx"] and argv[-2:] == ["docs", "docs/_build/html"]
    cmd = [sys.executable, *argv[1:-1], "-d", str(out / "doctrees"), str(out / "html"), "-q"]
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""), MPLBACKEND="Agg")
    # the build writes its generated pages into docs/ (api/, benchmarks/, auto_examples/): one build at a
    # time when pytest-xdist runs this module in two workers
    import fcntl

    (DOCS / "_build").mkdir(exist_ok=True)
    with open(DOCS / "_build" / ".test-lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        proc = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True, timeout=900)
    assert proc.returncode == 0, f"sphinx -W failed:\n{proc.stderr[-6000:]}\n{proc.stdout[-2000:]}"
    return out / "html"


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
    pages = sorted((site / "auto_examples").glob("plot_*.html"))
    sources = sorted((DOCS / "examples").glob("plot_*.py"))
    assert len(sources) >= 12 and len(pages) == len(sources), (len(sources), len(pages))
    for path in pages:
        page = _parse(path)
        figures = [s for s in page.images if "sphx_glr_" in s and s.endswith(".png")]
        assert figures, f"{path.name} shows no figure"
        for src in figures:
            assert (path.parent / src).stat().st_size > 2000, f"{path.name}: empty figure {src}"
        assert any(h.endswith(f"{path.stem}.py") for h in page.refs), f"{path.name} has no download link"


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
             "auto_examples/index.html", "auto_examples/plot_tent_schematic.html", "benchmarks/RESULTS.html"]
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
