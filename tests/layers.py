"""The import contract of the package, read from its source (``python tests/layers.py`` prints a report).

noiselab is a house of layers; a module may import only from its own
subpackage, from a layer below its own, or from the leaves ``io``:

====  =====================================================  ==========================================
layer subpackages                                            what lives there
====  =====================================================  ==========================================
0     ``_core``                                              validation, workers and the one thread pool,
                                                             optional dependencies, dtypes, progress
1     ``spectral``, ``lattice``, ``analysis``, ``io``        the primitives (siblings do not import each
                                                             other, except that anyone may write with ``io``)
2     ``snowfall``, ``fractal``, ``testing``                     built from the primitives; the assertions
3     ``fields``, ``geometry``, ``stimuli``                  flow, warps, normals, meshes, shapes;
                                                             stimuli in physical units
4     ``lab``                                                the laboratory: experiments and measurements
5     ``scale``                                              the dask path, beside the in-memory core
6     ``gallery``                                            the figures
7     ``cli``                                                the ``noiselab`` command
====  =====================================================  ==========================================

Besides the layers, four rules: no import cycle between modules (imports
inside functions count too); nothing below ``scale`` imports ``noiselab.scale``,
``dask`` or ``distributed``; no underscore name (module, function, class) is
imported from another subpackage (``_core`` is the shared internal base and is
exempt); and a generator (layers 1 to 3 but ``analysis``) never imports an
analyser. The package root (``noiselab/__init__.py``, lazy re-exports) and
``__main__`` sit above everything; reading the root's dunder metadata
(``from noiselab import __version__``) is allowed from anywhere, since the
root imports no subpackage when it loads.
"""
from __future__ import annotations

import ast
import sys
from dataclasses import dataclass, field
from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parents[1] / "noiselab"

LAYERS = {
    "_core": 0,
    "spectral": 1, "lattice": 1, "analysis": 1, "io": 1,
    "snowfall": 2, "fractal": 2, "gabor": 2,
    # testing (the spectral assertions) builds on analysis only: layer 2, the lowest above analysis; nothing
    # below imports it (a generator must not lean on its own tests), so it is an analyser too
    "testing": 2,
    "fields": 3, "geometry": 3, "stimuli": 3,
    "lab": 4,
    "scale": 5,
    "gallery": 6,
    "cli": 7,
}
LEAVES = {"io"}                       # any layer may import these
ANALYSERS = {"analysis", "testing"}   # ... but no generator imports these
GENERATORS = {"spectral", "lattice", "io", "snowfall", "fractal", "gabor", "fields", "geometry", "stimuli"}
DASK_MODULES = {"dask", "distributed"}
# the package root (lazy re-exports) and ``python -m noiselab``: above every layer
TOP = {"__init__", "__main__"}


@dataclass
class Import:
    importer: str        # dotted module name, e.g. noiselab.snowfall.render
    target: str          # dotted module imported (a name imported from a module counts as that module)
    names: tuple         # names imported from it (empty for ``import x``)
    line: int


@dataclass
class Report:
    modules: list
    imports: list
    cycles: list = field(default_factory=list)
    upward: list = field(default_factory=list)
    core_to_dask: list = field(default_factory=list)
    private: list = field(default_factory=list)
    generator_to_analyser: list = field(default_factory=list)
    private_attributes: list = field(default_factory=list)
    unknown_packages: list = field(default_factory=list)

    def counts(self):
        return {"cycles": len(self.cycles), "upward imports": len(self.upward),
                "core -> dask imports": len(self.core_to_dask),
                "cross-package private imports": len(self.private),
                "generator -> analyser imports": len(self.generator_to_analyser),
                "cross-package private attribute uses": len(self.private_attributes),
                "subpackages without a layer": len(self.unknown_packages)}


def module_name(path: Path, root: Path = PACKAGE_DIR) -> str:
    rel = path.relative_to(root.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def subpackage(module: str) -> str:
    """``noiselab.snowfall.render`` -> ``snow``; ``noiselab`` and ``noiselab.__main__`` -> ``__init__``/``__main__``."""
    parts = module.split(".")
    if len(parts) == 1:
        return "__init__"
    return parts[1]


def _resolve(importer: str, is_package: bool, node: ast.ImportFrom) -> str:
    if node.level == 0:
        return node.module or ""
    base = importer.split(".")
    if not is_package:
        base = base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def read_imports(root: Path = PACKAGE_DIR):
    """Every import statement of the package (module level or inside functions), as :class:`Import` records."""
    modules, imports = [], []
    for path in sorted(root.rglob("*.py")):
        if "__pycache__" in path.parts:
            continue
        mod = module_name(path, root)
        modules.append(mod)
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                for alias in node.names:
                    imports.append(Import(mod, alias.name, (), node.lineno))
            elif isinstance(node, ast.ImportFrom):
                target = _resolve(mod, path.name == "__init__.py", node)
                imports.append(Import(mod, target, tuple(a.name for a in node.names), node.lineno))
    return modules, imports


def _module_edges(modules, imports, pkg):
    """Module -> modules of the package it imports (``from pkg.sub import mod`` counts ``pkg.sub.mod``)."""
    known = set(modules)
    graph = {m: set() for m in modules}
    for imp in imports:
        if imp.target != pkg and not imp.target.startswith(pkg + "."):
            continue
        hits = {f"{imp.target}.{n}" for n in imp.names if f"{imp.target}.{n}" in known}
        if imp.target in known and (not imp.names or len(hits) < len(imp.names)):
            hits.add(imp.target)
        for h in hits:
            if h != imp.importer:
                graph[imp.importer].add(h)
    return graph


def find_cycles(graph):
    """The strongly connected components with more than one module (Tarjan), each as a sorted list."""
    index, low, on_stack, stack, out = {}, {}, set(), [], []
    counter = [0]

    def strong(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(max(sys.getrecursionlimit(), 10000))
    for v in sorted(graph):
        if v not in index:
            strong(v)
    return out


def private_attribute_uses(root: Path = PACKAGE_DIR):
    """``obj._name`` where ``_name`` is defined (``def``/``class``) only in other subpackages, not in the user's own.

    Catches ``noise._grid(...)`` from ``fractal`` reaching into ``lattice``'s
    ``LatticeNoise``: an import rule alone cannot see a private method.
    Returns ``(module, line, name, defining subpackages)`` tuples.
    """
    defined, trees = {}, {}
    for path in sorted(root.rglob("*.py")):
        if "__pycache__" in path.parts:
            continue
        mod = module_name(path, root)
        tree = trees[mod] = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and _is_private(node.name):
                defined.setdefault(node.name, set()).add(subpackage(mod))
    out = []
    for mod, tree in trees.items():
        own = subpackage(mod)
        if own in TOP:
            continue
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and _is_private(node.attr):
                owners = defined.get(node.attr, set())
                if owners and own not in owners and owners - {"_core"}:
                    out.append((mod, node.lineno, node.attr, tuple(sorted(owners))))
    return out


def _is_private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def check(root: Path = PACKAGE_DIR, layers=LAYERS) -> Report:
    pkg = root.name
    modules, imports = read_imports(root)
    report = Report(modules, imports)
    report.cycles = find_cycles(_module_edges(modules, imports, pkg))
    report.unknown_packages = sorted({subpackage(m) for m in modules} - set(layers) - TOP)
    for imp in imports:
        src = subpackage(imp.importer)
        if src in TOP:
            continue
        top_level = imp.target.split(".")[0]
        if top_level in DASK_MODULES and layers.get(src, 99) < layers["scale"]:
            report.core_to_dask.append(imp)
        if top_level != pkg:
            continue
        dst = subpackage(imp.target)
        if dst == "__init__" and imp.names:      # ``from noiselab import spectral``
            dst = imp.names[0] if imp.names[0] in layers else "__init__"
        if dst == src:
            continue
        if dst == "scale" and layers.get(src, 99) < layers["scale"]:
            report.core_to_dask.append(imp)
        if dst in TOP:
            # the root imports nothing eagerly (lazy re-exports), so reading its metadata is no upward dependency
            if not (imp.names and all(n.startswith("__") and n.endswith("__") for n in imp.names)):
                report.upward.append(imp)
        elif dst not in LEAVES and layers.get(dst, 99) >= layers.get(src, -1):
            report.upward.append(imp)
        if src in GENERATORS and dst in ANALYSERS:
            report.generator_to_analyser.append(imp)
        if dst != "_core":
            rel = imp.target.split(".")[2:]
            if any(_is_private(p) for p in rel) or any(_is_private(n) for n in imp.names):
                report.private.append(imp)
    report.private_attributes = private_attribute_uses(root)
    return report


def describe(report: Report) -> str:
    lines = [f"{len(report.modules)} modules, {len(report.imports)} import statements"]
    for what, n in report.counts().items():
        lines.append(f"  {what}: {n}")
    for cyc in report.cycles:
        lines.append("  cycle: " + " <-> ".join(cyc))
    for title, items in (("upward", report.upward), ("core -> dask", report.core_to_dask),
                         ("private", report.private), ("generator -> analyser", report.generator_to_analyser)):
        for imp in items:
            names = f" ({', '.join(imp.names)})" if imp.names else ""
            lines.append(f"  {title}: {imp.importer}:{imp.line} -> {imp.target}{names}")
    for mod, line, name, owners in report.private_attributes:
        lines.append(f"  private attribute: {mod}:{line} .{name} (defined in {', '.join(owners)})")
    for name in report.unknown_packages:
        lines.append(f"  no layer: {name}")
    return "\n".join(lines)


if __name__ == "__main__":
    print(describe(check(Path(sys.argv[1]) if len(sys.argv) > 1 else PACKAGE_DIR)))
