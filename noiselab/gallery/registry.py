"""The one place figures are registered, and what a figure function returns.

A figure function draws one figure (or video) of the gallery::

    @figure("snow", "fig3_2", source="Zhang 2003, Fig. 3.2", title="The tent surface",
            params=dict(c=1.0, n=48), quick=dict(n=16), uses=("noiselab.spectral",))
    def tent(out, *, c, n):
        path = out / "tent.png"
        ...                                   # write files into the folder ``out``
        return Result([path], "the tent w_t = c w_y / |w|", measured={"energy on tent": 0.97})

It receives the folder to write into and its parameters as keywords (the
``quick`` values replace ``params`` for the fast test build), and returns a
:class:`Result`: the files it wrote and a caption. The builder adds the seed
figure it reproduces, the parameters, and the measured analyser figures to the
caption, so every caption carries all three.

Adding a figure is adding one decorated function to one of the modules listed
in :data:`noiselab.gallery.figures.GROUP_MODULES`.
"""
from __future__ import annotations

import ast
import dataclasses
import functools
import hashlib
import importlib
import inspect
import json
import textwrap
from pathlib import Path
from typing import Callable

from noiselab._core import renamed_parameters

__all__ = ["Result", "FigureSpec", "figure", "REGISTRY", "specs", "content_hash", "module_version"]


@dataclasses.dataclass
class Result:
    """What a figure function returns.

    Parameters
    ----------
    files : list of path-like
        The files it wrote, inside the folder it was given. PNG/GIF/JPEG are
        shown as images, MP4 as videos (with the GIF of the same stem as its
        preview), anything else (PLY, NPY) as a download link.
    caption : str
        What the figure shows. The builder prefixes the seed figure and appends
        the parameters and ``measured``.
    measured : dict
        Analyser figures measured on the output, name -> value (a number or a
        short string), shown in the caption.
    """

    files: list
    caption: str
    measured: dict = dataclasses.field(default_factory=dict)


@dataclasses.dataclass(frozen=True)
class FigureSpec:
    """A registered figure: its group, id, source (the seed figure it reproduces), title, parameters and function."""

    group: str
    name: str
    source: str
    title: str
    params: dict
    quick: dict
    uses: tuple
    func: Callable
    look: str = ""

    @property
    def key(self) -> str:
        return f"{self.group}/{self.name}"

    def parameters(self, quick: bool = False) -> dict:
        p = dict(self.params)
        if quick:
            p.update(self.quick)
        return p


REGISTRY: dict[str, FigureSpec] = {}


@renamed_parameters(seed="source")
def figure(group, name, *, source, title, params=None, quick=None, uses=(), look=""):
    """Register a figure function under ``group/name``.

    ``source`` names the figure of a seed document it reproduces (for example
    ``"Phillips 2004, Fig. 12"``) or says it is the lab's own; ``params`` are
    passed to the function as keywords; ``quick`` overrides some of them for a
    fast build; ``uses`` names the noiselab subpackages it calls, for the
    reader (the modules whose source enters the content hash are read from
    the figure's code and the import graph, :func:`figure_modules`; ``uses``
    only adds to them, and a test holds it to the code); ``look``
    is one line for the reader: what to look for in the figure.
    """
    params = dict(params or {})
    quick = dict(quick or {})
    unknown = set(quick) - set(params)
    if unknown:
        raise ValueError(f"figure {group}/{name}: quick overrides unknown parameters {sorted(unknown)}")

    def register(func):
        spec = FigureSpec(group, name, source, title, params, quick, tuple(uses), func, look)
        if spec.key in REGISTRY:
            raise ValueError(f"figure {spec.key} is registered twice")
        REGISTRY[spec.key] = spec
        return func

    return register


def specs(only=None) -> list[FigureSpec]:
    """Registered figures in registration order; ``only`` keeps a group name or one ``group/name``."""
    from . import figures  # noqa: F401  (importing registers every figure)
    importlib.import_module(f"{__package__}.figures.stimuli")   # the stimuli group, registered as figures/ does

    all_specs = list(REGISTRY.values())
    if not only:
        return all_specs
    wanted = [only] if isinstance(only, str) else list(only)
    groups = sorted({s.group for s in all_specs})
    chosen = []
    for w in wanted:
        hit = [s for s in all_specs if s.group == w or s.key == w]
        if not hit:
            raise ValueError(f"--only: no figure group or figure named {w!r}; groups are {', '.join(groups)}")
        chosen += [s for s in hit if s not in chosen]
    return chosen


# the folder that holds the noiselab package (a checkout, or site-packages when installed)
_ROOT = Path(__file__).resolve().parents[2]


def module_version(module: str) -> str:
    """A short hash of a module's source (every ``.py`` of a package), plus noiselab's version.

    Reads files only (never imports), so an unfinished module does not break
    the hash. A module that does not exist hashes to ``"missing"``.
    """
    rel = Path(*module.split("."))
    pkg = _ROOT / rel
    files = sorted(pkg.rglob("*.py")) if pkg.is_dir() else [pkg.with_suffix(".py")]
    h = hashlib.sha256()
    found = False
    for f in files:
        if f.is_file():
            found = True
            h.update(str(f.relative_to(_ROOT)).encode())
            h.update(f.read_bytes())
    return h.hexdigest()[:16] if found else "missing"


def _code_names(code):
    names = set(code.co_names)
    for const in code.co_consts:
        if inspect.iscode(const):
            names |= _code_names(const)
    return names


def function_sources(func) -> dict:
    """Source of ``func`` and of every function of its own module that it calls, transitively.

    So a figure is rebuilt when a helper it shares with other figures changes,
    and only the figures that use that helper are.
    """
    seen, todo = {}, [func]
    while todo:
        f = todo.pop()
        if f.__qualname__ in seen:
            continue
        seen[f.__qualname__] = inspect.getsource(f)
        for name in _code_names(f.__code__):
            g = f.__globals__.get(name)
            if inspect.isfunction(g) and g.__module__ == func.__module__ and g.__qualname__ not in seen:
                todo.append(g)
    return dict(sorted(seen.items()))


def _unit(module: str) -> str:
    """The unit whose source is hashed: a gallery module itself, else its whole subpackage (``noiselab.spectral``)."""
    parts = module.split(".")
    if parts[:2] == ["noiselab", "gallery"]:
        return module if len(parts) > 2 else "noiselab.gallery._common"
    return ".".join(parts[:2])


@functools.lru_cache(maxsize=None)
def _top_level_names() -> dict:
    """The package root's table of top-level names (name -> defining module), read from its source."""
    tree = ast.parse((_ROOT / "noiselab" / "__init__.py").read_text(encoding="utf-8"))
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == "_API" for t in node.targets):
            return ast.literal_eval(node.value)
    return {}


def _imported(tree, module: str, is_package: bool) -> set:
    """The noiselab modules that the code in ``tree`` (of ``module``) imports or reaches as ``noiselab.X``."""
    api = _top_level_names()
    package = module if is_package else module.rpartition(".")[0]
    found = set()

    def add(name, attrs=()):
        if name == "noiselab":   # the root: a subpackage or a top-level name (its defining module)
            for a in attrs:
                if a in api:
                    found.add(api[a])
                elif (_ROOT / "noiselab" / a).is_dir() or (_ROOT / "noiselab" / f"{a}.py").is_file():
                    found.add(f"noiselab.{a}")
        elif name.startswith("noiselab."):
            found.add(name)
            for a in attrs:   # ``from noiselab.gallery import scenes``: a module, when there is one
                if (_ROOT / Path(*name.split(".")) / f"{a}.py").is_file():
                    found.add(f"{name}.{a}")

    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                add(alias.name)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                name = ".".join(base + ([node.module] if node.module else []))
            else:
                name = node.module or ""
            add(name, [a.name for a in node.names])
        elif (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "noiselab"):
            add("noiselab", [node.attr])
        elif (isinstance(node, ast.Call) and isinstance(node.func, (ast.Attribute, ast.Name))
              and getattr(node.func, "attr", getattr(node.func, "id", "")) == "import_module" and node.args
              and isinstance(node.args[0], ast.Constant) and isinstance(node.args[0].value, str)):
            add(node.args[0].value)
    return found


def _files(unit: str) -> list:
    path = _ROOT / Path(*unit.split("."))
    return sorted(path.rglob("*.py")) if path.is_dir() else [path.with_suffix(".py")]


@functools.lru_cache(maxsize=None)
def module_closure(unit: str) -> frozenset:
    """``unit`` and every unit its code imports, transitively (read from the source; nothing is imported)."""
    seen, todo = set(), [unit]
    while todo:
        u = todo.pop()
        if u in seen:
            continue
        seen.add(u)
        for f in _files(u):
            if not f.is_file():
                continue
            rel = f.relative_to(_ROOT).with_suffix("")
            name = ".".join(rel.parts[:-1] if rel.name == "__init__" else rel.parts)
            tree = ast.parse(f.read_text(encoding="utf-8"))
            todo += [_unit(m) for m in _imported(tree, name, rel.name == "__init__") if _unit(m) not in seen]
    return frozenset(seen)


def figure_modules(spec: FigureSpec) -> list:
    """The noiselab modules whose source decides a figure: what its code imports, transitively, and ``uses``.

    Read from the figure function and the module-local helpers it calls
    (:func:`function_sources`) and from its module's top-level imports, then
    closed over the import graph of the package's source, so a change in any
    module the figure reaches rebuilds it (a subpackage counts whole; a
    gallery module counts alone). ``uses=`` of :func:`figure` adds to this.
    """
    module = spec.func.__module__
    file = Path(inspect.getsourcefile(spec.func))
    top = ast.parse(file.read_text(encoding="utf-8"))
    direct = _imported(ast.Module(body=[n for n in top.body if isinstance(n, (ast.Import, ast.ImportFrom))],
                                  type_ignores=[]), module, False)
    for source in function_sources(spec.func).values():
        direct |= _imported(ast.parse(textwrap.dedent(source)), module, False)
    units = {_unit(m) for m in direct | set(spec.uses) | {"noiselab.gallery._common"}}
    units -= {_unit("noiselab.gallery.registry")}   # the registry itself: how figures are filed, not drawn
    closure = set()
    for u in units:
        closure |= module_closure(u)
    return sorted(closure - {"noiselab.gallery.registry"})


def content_hash(spec: FigureSpec, quick: bool = False) -> str:
    """Hash of (function source and its module-local helpers, parameters, noiselab version and source of the modules it reaches)."""
    from noiselab import __version__

    modules = figure_modules(spec)
    payload = {
        "key": spec.key,
        "source": function_sources(spec.func),
        "params": spec.parameters(quick),
        "noiselab": __version__,
        "modules": {m: module_version(m) for m in modules},
    }
    return hashlib.sha256(json.dumps(payload, sort_keys=True, default=repr).encode()).hexdigest()
