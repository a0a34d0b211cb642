"""Temporary files and folders are made by :mod:`tempfile` (``mkdtemp``, ``mkstemp``, ``TemporaryDirectory``):
a fresh name, created owner-only by the call that returns it. A path built by hand in the temporary
directory (``tempfile.gettempdir() / "noiselab-..."``, ``"/tmp/..."``) has a name another user can
guess and create first, so the package has none; this reads every module's code (docstrings aside)."""
import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "noiselab"


def _docstrings(tree):
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
                yield body[0].value


def guessable_temp_paths(source: str) -> list:
    """``(line, what)`` for each temp path built by name in ``source``: gettempdir()/tempdir, or a "/tmp" literal."""
    tree = ast.parse(source)
    docs = {id(d) for d in _docstrings(tree)}
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and node.attr in ("gettempdir", "tempdir", "gettempdirb"):
            found.append((node.lineno, f"tempfile.{node.attr}"))
        elif isinstance(node, ast.Name) and node.id in ("gettempdir", "gettempdirb"):
            found.append((node.lineno, node.id))
        elif (isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs
              and node.value.lstrip().startswith(("/tmp", "/var/tmp", "/dev/shm"))):
            found.append((node.lineno, repr(node.value)))
    return found


def test_the_scan_finds_a_guessable_temp_folder():
    bad = ('import os, tempfile\n'
           'folder = os.path.join(tempfile.gettempdir(), f"noiselab-{os.getuid()}-kernels")\n'
           'other = "/tmp/noiselab-cache"\n'
           'def f():\n    """Writes to /tmp/x in the docstring: not code."""\n'
           '    return tempfile.mkdtemp(prefix="noiselab-")\n')
    assert sorted(line for line, _ in guessable_temp_paths(bad)) == [2, 3]


_FILES = sorted(str(p.relative_to(PACKAGE)) for p in PACKAGE.rglob("*.py") if "__pycache__" not in p.parts)


@pytest.mark.parametrize("name", _FILES)
def test_no_module_builds_a_temp_path_by_name(name):
    assert guessable_temp_paths((PACKAGE / name).read_text()) == []
