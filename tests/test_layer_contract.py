"""The layer contract, checked two ways: statically by import-linter and at run time by ``sys.modules``.

import-linter (the ``[tool.importlinter]`` contracts of ``pyproject.toml``:
the layers, the in-memory core without dask, no generator importing an
analyser) reads every import statement, inside functions too. What an import
statement does not show (``importlib.import_module("noiselab.cli")``, or
``noiselab.gallery`` reached as an attribute of the root package) shows at
run time: importing every module of a layer's subpackages in a fresh
interpreter must load nothing from a layer above it. Both checks are shown to
fail on a copy of the package with such an import added.
"""
import ast
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
LINT_IMPORTS = Path(sys.executable).with_name("lint-imports")

# highest first, as in [tool.importlinter]; the package root sits above every layer
LAYERS = [["cli"], ["gallery"], ["scale"], ["lab"], ["fields", "geometry", "stimuli"],
          ["snowfall", "fractal", "testing", "gabor"], ["spectral", "lattice", "analysis"], ["io"], ["_core"]]
LEVEL = {name: len(LAYERS) - i for i, names in enumerate(LAYERS) for name in names}

_LOAD_ALL = """
import importlib, pkgutil, sys, warnings
warnings.simplefilter("ignore")
packages = sys.argv[2:]
for name in packages:
    module = importlib.import_module(f"noiselab.{name}")
    for info in pkgutil.walk_packages(module.__path__, f"noiselab.{name}."):
        if not info.name.rsplit(".", 1)[-1].startswith("__"):
            importlib.import_module(info.name)
print(" ".join(sorted(m for m in sys.modules if m.startswith("noiselab."))))
"""


def _lint(root):
    env = dict(os.environ, PYTHONPATH=str(root))
    return subprocess.run([str(LINT_IMPORTS), "--no-cache", "--config", str(root / "pyproject.toml")],
                          cwd=root, env=env, capture_output=True, text=True, timeout=300)


def _loaded_above(root, level, packages):
    """The noiselab modules above ``level`` that importing every module of ``packages`` loads."""
    env = dict(os.environ, PYTHONPATH=str(root), MPLBACKEND="Agg",
               VTK_DEFAULT_OPENGL_WINDOW="vtkEGLRenderWindow")
    out = subprocess.run([sys.executable, "-c", _LOAD_ALL, str(level), *packages], cwd=root, env=env,
                         capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    loaded = out.stdout.split()
    return sorted(m for m in loaded if LEVEL.get(m.split(".")[1], 0) > level)


def _copy(tmp_path):
    """A copy of the package and its pyproject.toml, to break on purpose."""
    shutil.copytree(ROOT / "noiselab", tmp_path / "noiselab", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    return tmp_path


def test_the_layer_table_is_the_import_linter_one():
    import tomllib

    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["importlinter"]
    layers = next(c for c in config["contracts"] if c["type"] == "layers")["layers"]
    assert [[p.strip().removeprefix("noiselab.") for p in layer.split("|")] for layer in layers] == LAYERS
    packages = {p.name for p in (ROOT / "noiselab").iterdir() if (p / "__init__.py").is_file()}
    assert packages == set(LEVEL), packages ^ set(LEVEL)   # every subpackage has its layer


def test_import_linter_contracts_are_kept():
    out = _lint(ROOT)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "0 broken" in out.stdout and "3 kept" in out.stdout, out.stdout


def test_import_linter_finds_an_upward_import(tmp_path):
    root = _copy(tmp_path)
    grid = root / "noiselab" / "lattice" / "grid.py"
    grid.write_text(grid.read_text() + "\n\ndef _reach_up():\n    from ..gallery import registry\n    return registry\n")
    out = _lint(root)
    assert out.returncode != 0 and "BROKEN" in out.stdout and "noiselab.lattice.grid -> noiselab.gallery" in out.stdout


@pytest.mark.parametrize("layer", [names for names in LAYERS[1:]], ids=lambda names: "+".join(names))
def test_importing_a_layer_loads_nothing_above_it(layer):
    """Every module of the layer's subpackages, imported in a fresh interpreter: nothing above it in sys.modules."""
    level = LEVEL[layer[0]]
    assert _loaded_above(ROOT, level, layer) == []


def test_the_runtime_check_finds_a_dynamic_import_and_an_attribute_reach(tmp_path):
    """import-linter cannot see these two; the sys.modules check can."""
    root = _copy(tmp_path)
    tables = root / "noiselab" / "lattice" / "tables.py"
    tables.write_text(tables.read_text() + '\n\nimport importlib as _il\n_cli = _il.import_module("noiselab.cli")\n')
    grid = root / "noiselab" / "spectral" / "__init__.py"
    grid.write_text(grid.read_text() + "\n\nimport noiselab as _root\n_gallery = _root.gallery\n")
    assert _lint(root).returncode == 0   # invisible to the static check
    above = _loaded_above(root, LEVEL["lattice"], ["spectral", "lattice", "analysis"])
    assert "noiselab.cli" in above and "noiselab.gallery" in above, above


def _code_strings(path):
    tree = ast.parse(path.read_text())
    docs = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant):
                docs.add(id(first.value))
    return [n.value for n in ast.walk(tree)
            if isinstance(n, ast.Constant) and isinstance(n.value, str) and id(n) not in docs]


def test_nothing_below_the_scale_layer_names_it_in_its_code():
    """The dispatch registry is filled by the scale layer; the core holds no string naming it."""
    offenders = []
    for path in sorted((ROOT / "noiselab").rglob("*.py")):
        parts = path.relative_to(ROOT / "noiselab").parts
        if len(parts) < 2 or LEVEL.get(parts[0], 99) >= LEVEL["scale"]:
            continue
        offenders += [f"{path.relative_to(ROOT)}: {s!r}" for s in _code_strings(path) if "noiselab.scale" in s]
    assert offenders == []


def test_a_chunked_call_reaches_the_dask_implementation_through_the_registry():
    """``chunks=`` from a bare interpreter: the core asks dispatch, the root's providers register the dask side."""
    code = ("import sys\nfrom noiselab.spectral import spectral_noise\n"
            "assert not any(m.startswith('noiselab.scale') for m in sys.modules)\n"
            "a = spectral_noise((16, 16), chunks=8)\n"
            "print(type(a).__module__.split('.')[0], 'noiselab.scale' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], env=dict(os.environ, PYTHONPATH=str(ROOT)),
                         capture_output=True, text=True, timeout=300)
    assert out.stdout.split() == ["dask", "True"], out.stderr


def dynamic_reaches(path, module):
    """``(line, target)`` for each ``import_module("noiselab.X")``/``__import__`` literal and each ``noiselab.X``
    reached as an attribute of the root package, in the code of one module (inside functions too)."""
    import noiselab

    tree = ast.parse(path.read_text())
    roots = {a.asname or a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names
             if a.name == "noiselab"}
    found = []
    for node in ast.walk(tree):
        if (isinstance(node, ast.Call) and getattr(node.func, "attr", getattr(node.func, "id", None))
                in ("import_module", "__import__") and node.args and isinstance(node.args[0], ast.Constant)
                and str(node.args[0].value).startswith("noiselab.")):
            found.append((node.lineno, node.args[0].value))
        elif isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in roots:
            target = noiselab._API.get(node.attr, f"noiselab.{node.attr}")
            found.append((node.lineno, target))
    return found


def _upward(module, targets):
    own = LEVEL.get(module.split(".")[1], 0)
    return [(line, t) for line, t in targets if LEVEL.get(t.split(".")[1] if t.count(".") else "", 0) > own]


def test_no_module_reaches_a_layer_above_it_dynamically():
    """What import-linter cannot read: a literal ``import_module`` or ``noiselab.X`` on the root, anywhere in a module."""
    offenders = []
    for path in sorted((ROOT / "noiselab").rglob("*.py")):
        rel = path.relative_to(ROOT).with_suffix("")
        parts = rel.parts[:-1] if rel.name == "__init__" else rel.parts
        if len(parts) < 2 or parts[1] not in LEVEL:   # the root sits above every layer
            continue
        module = ".".join(parts)
        offenders += [f"{module}:{line} -> {t}" for line, t in _upward(module, dynamic_reaches(path, module))]
    assert offenders == []


def test_the_dynamic_check_finds_both_kinds(tmp_path):
    source = tmp_path / "m.py"
    source.write_text("import importlib\nimport noiselab\n\ndef f():\n    importlib.import_module('noiselab.cli')\n"
                      "    return noiselab.gallery, noiselab.snow, noiselab.LatticeNoise\n")
    found = dynamic_reaches(source, "noiselab.lattice.m")
    assert sorted(t for _, t in _upward("noiselab.lattice.m", found)) == ["noiselab.cli", "noiselab.gallery",
                                                                           "noiselab.snowfall"]
