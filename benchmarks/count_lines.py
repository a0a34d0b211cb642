"""Lines of code in a package folder, docstrings, comments and blank lines excluded.

Run from the repository root::

    python benchmarks/count_lines.py [FOLDER ...]   (default: noiselab/lattice)
    python benchmarks/count_lines.py --behind-one-call

A line counts when, after removing the lines of every docstring (module,
class and function docstrings, found with ``ast``), it holds something other
than whitespace or a ``#`` comment. Prints one line per file and the total.

``--behind-one-call`` counts the code behind one evaluation instead: in a
fresh process with ``NUMBA_DISABLE_JIT=1`` (so the compiled kernels run as
the Python they are written in), it builds ``LatticeNoise(3,
basis="gradient", kernel="quintic")`` (the default table hash) and then traces one call on 1,000 3-D
points with ``sys.settrace``, and prints the distinct lines of
``noiselab/`` that the call executed, per file (construction, imports and
the compiler are not counted; every helper the call reaches is).
"""
from __future__ import annotations

import ast
import sys
from pathlib import Path


def code_lines(path: Path) -> int:
    """Lines of ``path`` that hold code (not blank, not only a comment, not part of a docstring)."""
    text = path.read_text()
    skip = set()
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) \
                    and isinstance(first.value.value, str):
                skip.update(range(first.lineno, first.end_lineno + 1))
    return sum(1 for i, line in enumerate(text.splitlines(), 1)
               if i not in skip and line.strip() and not line.strip().startswith("#"))


def lines_behind_one_call():
    """{file: distinct lines of noiselab executed by one 3-D quintic gradient call}, run in this process."""
    import numpy as np

    from noiselab.lattice import LatticeNoise

    root = str(Path("noiselab").resolve())
    noise = LatticeNoise(3, 1, basis="gradient", kernel="quintic", rng=1)
    points = np.random.default_rng(0).random((1000, 3)) * 10
    noise(points[:4])   # what runs once per process (lazy imports, table set-up) is not the call's code
    seen = {}

    def trace(frame, event, arg):
        name = frame.f_code.co_filename
        if not name.startswith(root):
            return None
        if event == "line":
            seen.setdefault(name, set()).add(frame.f_lineno)
        return trace

    sys.settrace(trace)
    try:
        noise(points)
    finally:
        sys.settrace(None)
    return {Path(k).relative_to(Path(root).parent): v for k, v in seen.items()}


def behind_one_call():
    import os
    import subprocess

    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    code = ("import sys; sys.path.insert(0, 'benchmarks'); import count_lines as c; "
            "[print(len(v), k) for k, v in sorted(c.lines_behind_one_call().items())]")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout
    rows = [line.split(" ", 1) for line in out.splitlines()]
    for n, name in rows:
        print(f"{int(n):6d}  {name}")
    print(f"{sum(int(n) for n, _ in rows):6d}  lines executed by one call, in {len(rows)} files")


def main(argv=None):
    argv = argv if argv is not None else sys.argv[1:]
    if argv == ["--behind-one-call"]:
        return behind_one_call()
    folders = argv or ["noiselab/lattice"]
    total = 0
    for folder in folders:
        for path in sorted(Path(folder).glob("*.py")):
            n = code_lines(path)
            total += n
            print(f"{n:6d}  {path}")
    print(f"{total:6d}  total")


if __name__ == "__main__":
    main()
