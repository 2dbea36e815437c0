"""The package's floors (docs/architecture.md), checked on the source: every import of every
module of ``blender_match``, function-local ones included, parsed with ``ast``.

- no import climbs a floor (a unit imports units on its own floor or below);
- no import circle between units (a top-level module or package is a unit), nor between modules;
- no module imports another module's private (underscore) name, nor a module private to
  another package;
- the foundation imports nothing but the standard library and itself; the add-on (what Blender
  imports, whose Python has no torch) never imports torch, and nothing it loads does at import time.
"""
from __future__ import annotations

import ast
import sys
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import pytest

PACKAGE = "blender_match"
ROOT = Path(__file__).resolve().parents[1] / PACKAGE

# Top to bottom; a unit may import its own floor and the floors below it.
FLOORS = (
    ("add-on", {"__init__", "preferences", "blender", "operators", "ui"}),
    ("worker", {"worker"}),
    ("commands", {"cli", "benchmarks", "__main__"}),
    ("pipeline", {"pipeline"}),
    ("selection", {"selection"}),
    ("library", {"library", "bundled_graphs"}),
    ("translator", {"translator"}),
    ("media", {"photo", "material_maps", "image_files", "exr_files"}),
    ("engine", {"diffmat"}),
    ("foundation", {"errors", "vocabulary", "colour", "version", "safe_files", "allocator"}),
)
FLOOR_OF = {unit: index for index, (_, units) in enumerate(FLOORS) for unit in units}
ADDON = FLOORS[0][1]
FOUNDATION = FLOORS[-1][1]
HEAVY = {"torch", "torchvision", "numpy", "PIL", "lxml", "bpy"}  # the foundation imports none of them


@dataclass(frozen=True)
class Import:
    source: str       # the importing module, dotted
    target: str       # the imported module, dotted (a submodule when ``from pkg import sub`` names one)
    names: tuple      # names imported from ``target`` (empty for ``import target``)
    local: bool       # inside a function (executed when called, not at import)
    line: int


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


@cache
def modules() -> dict[str, Path]:
    return {module_name(p): p for p in sorted(ROOT.rglob("*.py"))}


def unit_of(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "__init__"


def _type_checking(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _walk(node, local=False):
    """(node, inside a function) for every import statement, skipping ``if TYPE_CHECKING:``."""
    for child in ast.iter_child_nodes(node):
        if isinstance(child, ast.If) and _type_checking(child):
            continue
        if isinstance(child, (ast.Import, ast.ImportFrom)):
            yield child, local
        inner = local or isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda))
        yield from _walk(child, inner)


@cache
def imports_of(module: str) -> tuple[Import, ...]:
    path = modules()[module]
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = []
    for node, local in _walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found += [Import(module, a.name, (), local, node.lineno) for a in node.names]
            continue
        if node.level:
            base = package.split(".")[:len(package.split(".")) - (node.level - 1)]
            target = ".".join(base + ([node.module] if node.module else []))
        else:
            target = node.module or ""
        names = tuple(a.name for a in node.names)
        submodules = [n for n in names if f"{target}.{n}" in modules()]
        found += [Import(module, f"{target}.{n}", (), local, node.lineno) for n in submodules]
        rest = tuple(n for n in names if n not in submodules)
        if rest or not submodules:
            found.append(Import(module, target, rest, local, node.lineno))
    return tuple(found)


def internal(target: str) -> bool:
    return target == PACKAGE or target.startswith(PACKAGE + ".")


def all_imports():
    for module in modules():
        yield from (i for i in imports_of(module) if internal(i.target))


def test_every_unit_has_a_floor():
    units = {unit_of(m) for m in modules()}
    assert units - set(FLOOR_OF) == set(), "give the new unit a floor in FLOORS and docs/architecture.md"


def test_no_import_climbs_a_floor():
    upward = [f"{i.source}:{i.line} imports {i.target} ({FLOORS[FLOOR_OF[unit_of(i.target)]][0]} is above "
              f"{FLOORS[FLOOR_OF[unit_of(i.source)]][0]})"
              for i in all_imports() if FLOOR_OF[unit_of(i.target)] < FLOOR_OF[unit_of(i.source)]]
    assert upward == []


def _cycles(edges: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one node (Tarjan)."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return found


def test_no_import_circle_between_units():
    edges: dict[str, set[str]] = {}
    for i in all_imports():
        if unit_of(i.source) != unit_of(i.target):
            edges.setdefault(unit_of(i.source), set()).add(unit_of(i.target))
    assert _cycles(edges) == []


def test_no_import_circle_between_modules():
    """A package's ``__init__`` re-exporting its modules is not a circle with them: an import of
    the package from one of its own modules is."""
    edges: dict[str, set[str]] = {}
    for i in all_imports():
        if i.target in modules() and i.target != i.source:
            edges.setdefault(i.source, set()).add(i.target)
    assert _cycles(edges) == []


def _private_module(module: str) -> str | None:
    """The package that owns ``module`` when it is private to it (``cli._progress``: ``cli``)."""
    parts = module.split(".")
    for n, part in enumerate(parts):
        if part.startswith("_") and not part.startswith("__"):
            return ".".join(parts[:n])
    return None


def test_no_private_name_is_imported_from_another_module():
    """Private names stay in their module; a private module (``operators._job_runner``) stays in
    its package."""
    private = [f"{i.source}:{i.line} imports {name} from {i.target}" for i in all_imports() for name in i.names
               if name.startswith("_") and not name.startswith("__")]
    private += [f"{i.source}:{i.line} imports the private module {i.target}" for i in all_imports()
                if _private_module(i.target) and not i.source.startswith(_private_module(i.target) + ".")]
    assert private == []


def _module_aliases(tree: ast.Module, package: str) -> set[str]:
    """Local names an ``import`` statement binds to one of the package's modules."""
    aliases = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            aliases |= {a.asname for a in node.names if a.asname and internal(a.name)}
        elif isinstance(node, ast.ImportFrom):
            base = package.split(".")[:len(package.split(".")) - (node.level - 1)] if node.level else []
            target = ".".join(base + ([node.module] if node.module else []))
            aliases |= {a.asname or a.name for a in node.names if f"{target}.{a.name}" in modules()}
    return aliases


def test_no_private_name_is_reached_through_another_module():
    """``module._name`` is the same breach as ``from module import _name``."""
    reached = []
    for module, path in modules().items():
        package = module if path.name == "__init__.py" else module.rpartition(".")[0]
        tree = ast.parse(path.read_text(encoding="utf-8"))
        aliases = _module_aliases(tree, package)
        reached += [f"{module}:{n.lineno} reaches {n.value.id}.{n.attr}" for n in ast.walk(tree)
                    if isinstance(n, ast.Attribute) and isinstance(n.value, ast.Name) and n.value.id in aliases
                    and n.attr.startswith("_") and not n.attr.startswith("__")]
    assert reached == []


def test_the_foundation_imports_only_the_standard_library_and_itself():
    bad = []
    for module in modules():
        if unit_of(module) not in FOUNDATION:
            continue
        for i in imports_of(module):
            top = i.target.split(".")[0]
            if internal(i.target):
                if unit_of(i.target) not in FOUNDATION:
                    bad.append(f"{module}:{i.line} imports {i.target}")
            elif top not in sys.stdlib_module_names or top in HEAVY:
                bad.append(f"{module}:{i.line} imports {i.target}")
    assert bad == []


def _parents(module: str):
    """The packages Python imports before ``module`` (their ``__init__`` runs first)."""
    parts = module.split(".")
    return [".".join(parts[:n]) for n in range(1, len(parts))]


def loaded_by_the_addon() -> dict[str, str]:
    """Every module the add-on loads (module -> the module that imports it): the add-on's own
    modules with all their imports, function-local ones included (Blender runs them), and what
    those load at import time (module-level imports, parent packages)."""
    addon = [m for m in modules() if unit_of(m) in ADDON]
    seen = {m: "(add-on)" for m in addon}
    todo = list(addon)
    while todo:
        module = todo.pop()
        targets = [i.target for i in imports_of(module) if internal(i.target)
                   and (unit_of(module) in ADDON or not i.local)]
        for target in targets:
            for name in [*_parents(target), target]:
                if name in modules() and name not in seen:
                    seen[name] = module
                    todo.append(name)
    return seen


@pytest.mark.parametrize("forbidden", ["torch", "torchvision"])
def test_the_addon_loads_no_torch(forbidden):
    loaded = loaded_by_the_addon()
    bad = [f"{module} (loaded by {by}) imports {forbidden} at line {i.line}"
           for module, by in loaded.items() for i in imports_of(module)
           if i.target.split(".")[0] == forbidden and (unit_of(module) in ADDON or not i.local)]
    assert bad == []


def test_the_addon_loads_the_shared_vocabulary_and_errors():
    """The point of the foundation: Blender reads the same words and errors as the engine."""
    assert {f"{PACKAGE}.vocabulary", f"{PACKAGE}.errors", f"{PACKAGE}.library.catalog"} <= set(loaded_by_the_addon())
