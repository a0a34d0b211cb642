"""The one-way house: the package's imports point down its layers (see ``tests/layers.py`` and the README's layout)."""
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import layers

HERE = Path(__file__).resolve().parent


@pytest.fixture(scope="module")
def report():
    return layers.check()


def _listing(items):
    return "\n".join(map(str, items))


def test_every_subpackage_has_a_layer(report):
    assert report.unknown_packages == [], report.unknown_packages
    assert set(layers.subpackage(m) for m in report.modules) - layers.TOP <= set(layers.LAYERS)


def test_no_import_cycle(report):
    assert report.cycles == [], _listing(report.cycles)


def test_imports_only_point_down(report):
    assert report.upward == [], _listing(report.upward)


def test_the_core_never_imports_the_dask_path(report):
    assert report.core_to_dask == [], _listing(report.core_to_dask)


def test_no_private_name_crosses_a_subpackage(report):
    assert report.private == [], _listing(report.private)
    assert report.private_attributes == [], _listing(report.private_attributes)


def test_a_generator_never_needs_an_analyser(report):
    assert report.generator_to_analyser == [], _listing(report.generator_to_analyser)


# ---------------------------------------------------------------- the checker itself finds what it should

def _write(root, files):
    for rel, text in files.items():
        path = root / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text))


def test_the_checker_finds_each_kind_of_violation(tmp_path):
    pkg = tmp_path / "noiselab"
    _write(pkg, {
        "__init__.py": "",
        "_core/__init__.py": "def _helper(): pass\n",
        "spectral/__init__.py": "from ..snowfall import thing\nfrom .._core import _helper\n",   # upward; _core exempt
        "spectral/synthesis.py": "def _plan(): pass\nclass Noise:\n    def _grid(self): pass\n",
        "snowfall/__init__.py": "from ..spectral.synthesis import _plan\nthing = 1\n",                # private
        "snowfall/render.py": "def f(noise):\n    return noise._grid()\n",                            # private attribute
        "fractal/__init__.py": "def f():\n    import dask.array\n    from ..scale import x\n",   # core -> dask (x2), upward
        "scale/__init__.py": "x = 1\n",
        "lattice/__init__.py": "from ..analysis import spectrum\n",                               # generator -> analyser
        "analysis/__init__.py": "spectrum = 1\n",
        "lab/a.py": "from . import b\n",
        "lab/b.py": "def f():\n    from . import a\n",                                             # cycle (lazy import)
        "extra/__init__.py": "",                                                                   # no layer
    })
    rep = layers.check(pkg)
    assert rep.cycles == [["noiselab.lab.a", "noiselab.lab.b"]]
    assert {(i.importer, i.target) for i in rep.upward} == {
        ("noiselab.spectral", "noiselab.snowfall"), ("noiselab.fractal", "noiselab.scale"),
        ("noiselab.lattice", "noiselab.analysis")}                                               # siblings too
    assert sorted(i.target for i in rep.core_to_dask) == ["dask.array", "noiselab.scale"]
    assert [(i.importer, i.names) for i in rep.private] == [("noiselab.snowfall", ("_plan",))]
    assert [(m, name) for m, _, name, _ in rep.private_attributes] == [("noiselab.snowfall.render", "_grid")]
    assert [i.importer for i in rep.generator_to_analyser] == ["noiselab.lattice"]
    assert rep.unknown_packages == ["extra"]


@pytest.mark.parametrize("module", ["noiselab.spectral", "noiselab.lattice", "noiselab.snowfall", "noiselab.fractal",
                                    "noiselab.io", "noiselab.analysis", "noiselab.geometry"])
def test_importing_the_core_loads_no_dask(module):
    """In a fresh interpreter, the in-memory core loads neither the scale-out layer nor dask."""
    code = (f"import sys, {module}\n"
            "bad = sorted(m for m in sys.modules if m.split('.')[0] in ('dask', 'distributed', 'zarr') "
            "or m.startswith('noiselab.scale'))\n"
            "print(' '.join(bad))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "", f"{module} loaded: {out.stdout.strip()}"


def test_the_root_imports_no_subpackage_when_it_loads():
    """``from noiselab import __version__`` is allowed anywhere because the root loads nothing else."""
    code = "import sys, noiselab; print(' '.join(sorted(m for m in sys.modules if m.startswith('noiselab.'))))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""
