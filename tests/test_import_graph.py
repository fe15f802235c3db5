"""No import cycles between the package's modules: the import graph, read from the source.

Every ``import`` and ``from … import`` of a hexaleg module counts, wherever it is in the file —
at module level, inside a function, under ``if TYPE_CHECKING:`` — since a lazy or type-only
import hides a cycle rather than removing it. ``from hexaleg.x import name`` is an import of the
module ``hexaleg.x.name`` when that is a module, else of ``hexaleg.x`` (a package's
``__init__``); relative imports are resolved against the importing module's package. A cycle is
a strongly connected component of more than one module (Tarjan, "Depth-first search and linear
graph algorithms", SIAM J. Comput. 1(2), 1972; written iteratively here).
"""

from __future__ import annotations

import ast
from collections.abc import Mapping
from pathlib import Path

import hexaleg

SRC = Path(hexaleg.__file__).resolve().parent


def module_names(src: Path, package: str) -> dict[str, Path]:
    """Dotted name → file of every module of the package in ``src / package``."""
    names = {}
    for path in sorted((src / package).rglob("*.py")):
        parts = (package, *path.relative_to(src / package).with_suffix("").parts)
        names[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return names


def imported_modules(path: Path, name: str, modules: Mapping[str, Path]) -> set[str]:
    """The modules of ``modules`` that module ``name`` (file ``path``) imports anywhere in its
    source (module docstring), itself left out."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            module = node.module or ""
            if node.level:
                base = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
                module = f"{base}.{module}" if module else base
            for alias in node.names:
                child = f"{module}.{alias.name}"
                found.add(child if child in modules else module)
    return (found & set(modules)) - {name}


def import_graph(src: Path, package: str) -> dict[str, set[str]]:
    """Module → the package's modules it imports, for every module of ``package``."""
    modules = module_names(src, package)
    return {name: imported_modules(path, name, modules) for name, path in modules.items()}


def cycles(graph: Mapping[str, set[str]]) -> list[frozenset[str]]:
    """The strongly connected components of ``graph`` with more than one node (Tarjan's
    algorithm with an explicit stack), in the order Tarjan completes them."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found = []
    for start in graph:
        if start in index:
            continue
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        work = [(start, iter(sorted(graph[start])))]
        while work:
            node, targets = work[-1]
            for target in targets:
                if target not in index:
                    index[target] = low[target] = len(index)
                    stack.append(target)
                    on_stack.add(target)
                    work.append((target, iter(sorted(graph.get(target, ())))))
                    break
                if target in on_stack:
                    low[node] = min(low[node], index[target])
            else:  # every edge of node done
                work.pop()
                if work:
                    parent = work[-1][0]
                    low[parent] = min(low[parent], low[node])
                if low[node] == index[node]:
                    component = set()
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        component.add(member)
                        if member == node:
                            break
                    if len(component) > 1:
                        found.append(frozenset(component))
    return found


def test_the_package_has_no_import_cycles():
    found = cycles(import_graph(SRC.parent, "hexaleg"))
    rings = [sorted(c) for c in found]
    assert not rings, "import cycles (break each at its seam):\n" + "\n".join(map(str, rings))


def _package(tmp_path: Path, files: Mapping[str, str]) -> Path:
    for name, text in files.items():
        path = tmp_path / "pkg" / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return tmp_path


def test_lazy_type_only_and_relative_imports_close_a_cycle(tmp_path):
    src = _package(tmp_path, {
        "__init__.py": "",
        "a.py": "def f():\n    from pkg.b import thing\n    return thing\n",
        "b.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from . import c\n"
                "thing = 1\n",
        "c.py": "from .a import f\n",
        "d.py": "import pkg.a\nfrom pkg import c\n",  # imports the cycle, is not on it
        "sub/__init__.py": "from ..d import x\n",
        "sub/e.py": "from pkg.sub import name\n",  # not a module: the package's __init__
    })
    graph = import_graph(src, "pkg")
    assert graph["pkg.a"] == {"pkg.b"} and graph["pkg.b"] == {"pkg.c"}
    assert graph["pkg.d"] == {"pkg.a", "pkg.c"} and graph["pkg.sub"] == {"pkg.d"}
    assert graph["pkg.sub.e"] == {"pkg.sub"} and graph["pkg"] == set()
    assert cycles(graph) == [frozenset({"pkg.a", "pkg.b", "pkg.c"})]


def test_each_cycle_is_its_own_component():
    graph = {"a": {"b"}, "b": {"a", "c"}, "c": {"d"}, "d": {"e"}, "e": {"c", "f"}, "f": set(),
             "g": {"g"}}
    assert sorted(map(sorted, cycles(graph))) == [["a", "b"], ["c", "d", "e"]]
    assert cycles({"a": {"b"}, "b": {"c"}, "c": set()}) == []
