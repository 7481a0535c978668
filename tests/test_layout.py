"""The import graph of the project's packages: the declared layering, no circles, no private names across them.

Read from the sources with :mod:`ast` (nothing is imported): every ``import`` and
``from ... import`` of a module of ``numerics``, ``lubrication``, ``dynamics``,
``validation`` or ``benchmarks``, at any depth in the module (a function's lazy
import is an import too).

* Layers: ``numerics`` (no physics) below ``lubrication`` (the fluid forces) below
  ``dynamics`` (the bodies' motion) below ``validation`` and ``benchmarks``; a
  package imports only itself and the packages below it.
* The engine and the hybrid driver (``numerics.engine``, ``numerics.hybrid``)
  import nothing of the project's physics, which ``numerics`` as a whole already
  guarantees.
* No cycle among the modules of a package, lazy imports included.
* No name of another package that starts with an underscore (a private module or a
  private name); a package's own privates are its business.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
LAYERS = {"numerics": 0, "lubrication": 1, "dynamics": 2, "validation": 3, "benchmarks": 3}


def _module_name(path: Path, root: Path = ROOT) -> str:
    parts = list(path.relative_to(root).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _imports(path: Path, root: Path = ROOT) -> list[tuple[str, str]]:
    """(module imported, name imported or "") of every import in ``path`` (a file under ``root``), relative
    imports resolved."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    name = _module_name(path, root)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(alias.name, "") for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[:len(package.split(".")) - node.level + 1]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module
            found += [(module, alias.name) for alias in node.names]
    return found


@pytest.fixture(scope="module")
def graph() -> dict[str, list[tuple[str, str]]]:
    return {_module_name(path): _imports(path) for package in LAYERS for path in sorted((ROOT / package).rglob("*.py"))}


def _project(module: str) -> str | None:
    top = module.split(".")[0]
    return top if top in LAYERS else None


def test_every_package_imports_only_itself_and_the_layers_below(graph):
    wrong = [(module, imported) for module, imports in graph.items() for imported, _ in imports
             if _project(imported) and LAYERS[_project(imported)] > LAYERS[_project(module)]
             or (_project(imported) and _project(imported) != _project(module)
                 and LAYERS[_project(imported)] == LAYERS[_project(module)])]
    assert not wrong


def test_no_private_name_of_another_package_is_imported(graph):
    def private(module: str, name: str) -> bool:
        return any(part.startswith("_") and not part.startswith("__") for part in [*module.split("."), name])

    wrong = [(module, imported, name) for module, imports in graph.items() for imported, name in imports
             if _project(imported) and _project(imported) != _project(module) and private(imported, name)]
    assert not wrong


def test_the_modules_of_each_package_form_no_circle(graph):
    modules = set(graph)

    def target(imported: str, name: str) -> str | None:
        for candidate in (f"{imported}.{name}", imported):  # "from a import b" may import the module a.b
            if candidate in modules:
                return candidate
        return None

    edges = {m: {t for imported, name in imports if (t := target(imported, name)) and t != m
                 and _project(t) == _project(m) and not m.startswith(t + ".") and not t.startswith(m + ".")}
             for m, imports in graph.items()}
    state: dict[str, int] = {}
    cycles = []

    def visit(node: str, stack: list[str]) -> None:
        state[node] = 1
        for nxt in sorted(edges.get(node, ())):
            if state.get(nxt) == 1:
                cycles.append(stack[stack.index(nxt):] + [nxt])
            elif nxt not in state:
                visit(nxt, [*stack, nxt])
        state[node] = 2

    for node in sorted(edges):
        if node not in state:
            visit(node, [node])
    assert not cycles


def test_the_check_sees_a_planted_violation(tmp_path):
    """The graph reader finds an upward import, a private name across packages and a relative import."""
    # planted in a copy's layout, not in the sources: the kernels' cache is keyed on every source file
    planted = tmp_path / "lubrication" / "_planted_for_the_layout_test.py"
    planted.parent.mkdir()
    planted.write_text("from dynamics.equations.full import _A\nfrom . import kernels\n")
    imports = _imports(planted, tmp_path)
    assert ("dynamics.equations.full", "_A") in imports and ("lubrication", "kernels") in imports


def test_every_name_the_packages_export_on_first_use_is_there():
    """The lazy exports of ``dynamics`` and ``lubrication`` name modules that exist and define them."""
    import dynamics
    import lubrication

    for package in (dynamics, lubrication):
        missing = [name for name in package.__all__ if getattr(package, name, None) is None]
        assert not missing, (package.__name__, missing)


def test_the_check_modules_draw_and_word_nothing(graph):
    """A study of ``validation`` computes and checks; its figures and markdown are in ``validation.reports``.

    No check module imports matplotlib or ``validation.reports`` (lazily neither); only the
    suite and the command line, which run the groups, import the reports.
    """
    runners = {"validation.suite", "validation.cli"}
    checks = [m for m in graph
              if m.startswith("validation") and not m.startswith("validation.reports") and m not in runners]
    wrong = [(module, imported) for module in checks for imported, _ in graph[module]
             if imported.split(".")[0] == "matplotlib" or imported.startswith("validation.reports")]
    assert not wrong
    assert any(m.startswith("validation.reports.") for m in graph)
