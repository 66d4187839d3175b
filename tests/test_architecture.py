"""The house rules of docs/architecture.md, checked on the source: no import cycle inside tutgen/, no
module reaching into another's ``_private`` names, no module of 800 lines or more.

The imports are read with :mod:`ast`, not by importing: module-level imports and function-local ones
(a function-local import that dodges a cycle is still a cycle of the design), but not those under
``if TYPE_CHECKING:``, which never run. An edge goes to the module an import names:
``from tutgen.engine import lagrange`` to ``tutgen.engine.lagrange``, ``from tutgen.engine.tidy import
tidy`` to ``tutgen.engine.tidy``; importing a submodule is not counted as an edge to its package.
"""

from __future__ import annotations

import ast
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "tutgen"
MAX_LINES = 800


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def all_modules() -> dict[str, Path]:
    return {module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


@dataclass(frozen=True)
class Use:
    """One import edge, or one reach for a private name, where the source has it."""

    module: str  # the importing module
    line: int
    target: str  # the tutgen module imported from
    name: str | None = None  # the name taken from it, if any


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _runtime_nodes(tree: ast.AST) -> Iterator[ast.AST]:
    """Every node of the tree except the bodies of ``if TYPE_CHECKING:`` (their ``else`` runs)."""
    todo: list[ast.AST] = [tree]
    while todo:
        node = todo.pop()
        yield node
        if isinstance(node, ast.If) and _is_type_checking(node.test):
            todo.extend(node.orelse)
            continue
        todo.extend(ast.iter_child_nodes(node))


def _resolve_from(module: str, is_package: bool, node: ast.ImportFrom) -> str:
    """The absolute module name of ``from X import ...`` (relative imports included)."""
    if not node.level:
        return node.module or ""
    base = module.split(".")
    if not is_package:
        base = base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join([*base, node.module] if node.module else base)


def _is_private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def _dotted(node: ast.expr) -> list[str] | None:
    """``a.b.c`` as ["a", "b", "c"]; None for anything that is not a plain dotted name."""
    parts: list[str] = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if not isinstance(node, ast.Name):
        return None
    parts.append(node.id)
    return parts[::-1]


def scan(
    module: str, source: str, modules: Mapping[str, object], is_package: bool = False
) -> tuple[list[Use], list[Use]]:
    """(import edges to other tutgen modules, uses of their private names) of one module's source.

    A private use is ``from tutgen.x import _name``, or ``m._name`` / ``tutgen.x._name`` where ``m``
    is bound to a tutgen module by an import in this module.
    """
    tree = ast.parse(source)
    edges: list[Use] = []
    private: list[Use] = []
    aliases: dict[str, str] = {}  # local name -> tutgen module it is bound to
    for node in _runtime_nodes(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name in modules:
                    edges.append(Use(module, node.lineno, alias.name))
                    if alias.asname:
                        aliases[alias.asname] = alias.name
        elif isinstance(node, ast.ImportFrom):
            base = _resolve_from(module, is_package, node)
            for alias in node.names:
                sub = f"{base}.{alias.name}"
                if sub in modules:  # from package import submodule
                    edges.append(Use(module, node.lineno, sub))
                    aliases[alias.asname or alias.name] = sub
                elif base in modules:
                    edges.append(Use(module, node.lineno, base, alias.name))
                    if _is_private(alias.name) and base != module:
                        private.append(Use(module, node.lineno, base, alias.name))
    for node in _runtime_nodes(tree):
        if not (isinstance(node, ast.Attribute) and _is_private(node.attr)):
            continue
        parts = _dotted(node.value)
        if parts is None:
            continue
        target = aliases.get(parts[0]) if len(parts) == 1 else None
        if target is None and ".".join(parts) in modules:
            target = ".".join(parts)  # tutgen.x._name, after ``import tutgen.x``
        if target is not None and target != module:
            private.append(Use(module, node.lineno, target, node.attr))
    return [e for e in edges if e.target != module], private


def find_cycles(graph: Mapping[str, set[str]]) -> list[list[str]]:
    """The import cycles of a graph: each strongly connected component of two or more modules (or one
    module importing itself), sorted, as a sorted list of its modules (Tarjan's algorithm, iterative).

    >>> find_cycles({"a": {"b"}, "b": {"a"}, "c": {"a"}})
    [['a', 'b']]
    """
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out: list[list[str]] = []
    counter = 0
    for root in sorted(graph):
        if root in index:
            continue
        work: list[tuple[str, Iterator[str]]] = [(root, iter(sorted(graph.get(root, ()))))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = counter
                    counter += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph.get(child, ())))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    top = stack.pop()
                    on_stack.discard(top)
                    component.append(top)
                    if top == node:
                        break
                if len(component) > 1 or node in graph.get(node, ()):
                    out.append(sorted(component))
    return sorted(out)


def project() -> tuple[dict[str, set[str]], list[Use], dict[str, list[Use]]]:
    """The import graph of tutgen/, its private uses, and the edges by (importer, target) for messages."""
    modules = all_modules()
    graph: dict[str, set[str]] = {m: set() for m in modules}
    private: list[Use] = []
    where: dict[str, list[Use]] = {}
    for name, path in modules.items():
        edges, priv = scan(name, path.read_text(encoding="utf-8"), modules, path.name == "__init__.py")
        for e in edges:
            graph[name].add(e.target)
            where.setdefault(f"{name}->{e.target}", []).append(e)
        private += priv
    return graph, private, where


# --- the rules on tutgen/ ---------------------------------------------------------------------


def test_architecture_no_import_cycle() -> None:
    graph, _, where = project()
    problems = []
    for component in find_cycles(graph):
        members = set(component)
        # every import inside the component, with its lines: any one of them removed may break the cycle
        steps = [
            f"  {a} -> {b} (line {', '.join(sorted({str(u.line) for u in where[f'{a}->{b}']}, key=int))})"
            for a in component
            for b in sorted(graph[a] & members)
        ]
        problems.append(f"cycle among {', '.join(component)}:\n" + "\n".join(steps))
    assert not problems, "import cycles inside tutgen/:\n" + "\n".join(problems)


def test_architecture_no_private_imports() -> None:
    _, private, _ = project()
    problems = sorted(f"{u.module}:{u.line} uses {u.target}.{u.name}" for u in private)
    assert not problems, "another module's private names:\n" + "\n".join(problems)


def test_architecture_modules_under_800_lines() -> None:
    sizes = {name: len(path.read_text(encoding="utf-8").splitlines()) for name, path in all_modules().items()}
    big = sorted(f"{name}: {n} lines" for name, n in sizes.items() if n >= MAX_LINES)
    assert not big, f"modules of {MAX_LINES} lines or more:\n" + "\n".join(big)


# --- the finders themselves, on tiny worlds -----------------------------------------------------


@pytest.mark.parametrize(
    ("graph", "expected"),
    [
        pytest.param({"a": {"b"}, "b": {"c"}, "c": set()}, [], id="chain"),
        pytest.param({"a": {"b"}, "b": {"a"}}, [["a", "b"]], id="two-cycle"),
        pytest.param({"a": {"a"}}, [["a"]], id="self-import"),
        pytest.param({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}, [["a", "b", "c"]], id="three-cycle-and-tail"),
        pytest.param(
            {"a": {"b"}, "b": {"a"}, "c": {"d"}, "d": {"c", "a"}}, [["a", "b"], ["c", "d"]], id="two-separate-cycles"
        ),
        pytest.param({"a": {"b", "c"}, "b": {"d"}, "c": {"d"}, "d": set()}, [], id="diamond"),
    ],
)
def test_find_cycles_on_synthetic_graph(graph: dict[str, set[str]], expected: list[list[str]]) -> None:
    assert find_cycles(graph) == expected


MODULES = {"tutgen.x": None, "tutgen.y": None, "tutgen.pkg": None, "tutgen.pkg.sub": None}


@pytest.mark.parametrize(
    ("source", "edges", "private"),
    [
        pytest.param("from tutgen.y import f\n", {"tutgen.y"}, set(), id="from-import"),
        pytest.param("def f():\n    from tutgen.y import g\n", {"tutgen.y"}, set(), id="function-local"),
        pytest.param(
            "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from tutgen.y import T\n",
            set(),
            set(),
            id="type-checking",
        ),
        pytest.param("from tutgen.pkg import sub\n", {"tutgen.pkg.sub"}, set(), id="submodule-from-package"),
        pytest.param("import tutgen.pkg.sub\n", {"tutgen.pkg.sub"}, set(), id="plain-import"),
        pytest.param("from tutgen.y import _g\n", {"tutgen.y"}, {"tutgen.y._g"}, id="private-name"),
        pytest.param("from tutgen import y\ny._g()\n", {"tutgen.y"}, {"tutgen.y._g"}, id="private-attribute-of-module"),
        pytest.param("import tutgen.y\ntutgen.y._g()\n", {"tutgen.y"}, {"tutgen.y._g"}, id="private-attribute-dotted"),
        pytest.param("import tutgen.y as m\nm._g\n", {"tutgen.y"}, {"tutgen.y._g"}, id="private-attribute-alias"),
        pytest.param("from tutgen.y import C\nC._cache\n", {"tutgen.y"}, set(), id="private-attribute-of-a-class"),
        pytest.param("from tutgen.y import __doc__\n", {"tutgen.y"}, set(), id="dunder-is-public"),
        pytest.param("from sympy.core.add import _addsort\n", set(), set(), id="outside-tutgen"),
        pytest.param("from . import y\n", {"tutgen.y"}, set(), id="relative-import"),
    ],
)
def test_scan_on_synthetic_source(source: str, edges: set[str], private: set[str]) -> None:
    found_edges, found_private = scan("tutgen.x", source, MODULES)
    assert {e.target for e in found_edges} == edges
    assert {f"{u.target}.{u.name}" for u in found_private} == private
