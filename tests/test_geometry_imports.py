"""noiselab.geometry has no import cycle: no module imports, even lazily inside a function, one that imports it back."""
import ast
import importlib
from pathlib import Path

PKG = Path(__file__).resolve().parents[1] / "noiselab" / "geometry"


def _graph():
    """Module -> set of sibling modules it imports (top level or inside functions), read from the source."""
    mods = {p.stem for p in PKG.glob("*.py") if p.stem != "__init__"}
    graph = {}
    for m in mods:
        deps = set()
        for node in ast.walk(ast.parse((PKG / f"{m}.py").read_text())):
            if isinstance(node, ast.ImportFrom) and node.level == 1:
                if node.module:
                    deps.add(node.module.split(".")[0])
                else:
                    deps.update(a.name for a in node.names)
        graph[m] = deps & mods
    return graph


def _cycle(graph):
    state, stack = {}, []

    def visit(n):
        state[n] = 1
        stack.append(n)
        for d in sorted(graph[n]):
            if state.get(d) == 1:
                return stack[stack.index(d):] + [d]
            if d not in state:
                found = visit(d)
                if found:
                    return found
        state[n] = 2
        stack.pop()
        return None

    for n in sorted(graph):
        if n not in state:
            found = visit(n)
            if found:
                return found
    return None


def test_the_checker_finds_a_cycle():
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert _cycle({"a": {"b"}, "b": set()}) is None


def test_geometry_import_graph_is_acyclic():
    graph = _graph()
    assert {"displace", "render", "shapes", "surfaces", "_mesh"} <= set(graph)
    assert graph["_mesh"] == set(), graph["_mesh"]
    assert _cycle(graph) is None, " -> ".join(_cycle(graph))


def test_moved_names_are_the_same_objects_where_they_were():
    mesh = importlib.import_module("noiselab.geometry._mesh")
    displace = importlib.import_module("noiselab.geometry.displace")
    shapes = importlib.import_module("noiselab.geometry.shapes")
    geometry = importlib.import_module("noiselab.geometry")
    assert displace.as_trimesh is mesh.as_trimesh is geometry.as_trimesh
    assert displace.AliasingWarning is mesh.AliasingWarning is geometry.AliasingWarning
    assert shapes.pyvista_to_trimesh is mesh.pyvista_to_trimesh
    assert shapes.trimesh_to_pyvista is mesh.trimesh_to_pyvista is geometry.trimesh_to_pyvista
