"""The package's floors (issue 22, item 4): errors.py and validation.py are the ground floor (they import nothing of
the package but errors), and no module imports one that imports it back, counting the imports inside functions
(those closed the circle of 20 modules the issue found). Read from the source, nothing imported."""

from __future__ import annotations

import ast
from pathlib import Path
from typing import Dict, Set

PACKAGE = Path(__file__).resolve().parents[2] / "python" / "frictionsim"


def module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports() -> Dict[str, Set[str]]:
    """Module -> the package's modules it imports anywhere in its body (``from . import _core`` is the extension,
    not the package's __init__)."""
    modules = {module_name(p): p for p in PACKAGE.rglob("*.py")}
    graph: Dict[str, Set[str]] = {}
    for name, path in modules.items():
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        targets = graph.setdefault(name, set())
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")[:len(package.split(".")) - node.level + 1]
                    source = ".".join(base + ([node.module] if node.module else []))
                else:
                    source = node.module or ""
                for alias in node.names:
                    full = f"{source}.{alias.name}"
                    target = full if full in modules or alias.name == "_core" else source
                    if target in modules and target != name:
                        targets.add(target)
            elif isinstance(node, ast.Import):
                targets.update(a.name for a in node.names if a.name in modules and a.name != name)
    return graph


def test_the_ground_floor_imports_nothing_of_the_package():
    graph = imports()
    assert graph["frictionsim.errors"] == set()
    assert graph["frictionsim.validation"] == {"frictionsim.errors"}


def test_no_import_circle_in_the_package():
    graph = imports()
    state: Dict[str, int] = {}  # 1 on the path, 2 done

    def visit(module: str, path: list) -> None:
        state[module] = 1
        for target in sorted(graph.get(module, ())):
            assert state.get(target) != 1, " -> ".join(path + [module, target])
            if target not in state:
                visit(target, path + [module])
        state[module] = 2

    for module in sorted(graph):
        if module not in state:
            visit(module, [])
