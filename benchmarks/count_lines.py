"""Lines of code in a package folder, docstrings, comments and blank lines excluded.

Run from the repository root::

    python benchmarks/count_lines.py [FOLDER ...]   (default: noiselab/lattice)

A line counts when, after removing the lines of every docstring (module,
class and function docstrings, found with ``ast``), it holds something other
than whitespace or a ``#`` comment. Prints one line per file and the total.
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


def main(argv=None):
    folders = (argv if argv is not None else sys.argv[1:]) or ["noiselab/lattice"]
    total = 0
    for folder in folders:
        for path in sorted(Path(folder).glob("*.py")):
            n = code_lines(path)
            total += n
            print(f"{n:6d}  {path}")
    print(f"{total:6d}  total")


if __name__ == "__main__":
    main()
