"""The registry of every implemented node, by name (Substance's name) and by alias."""
from __future__ import annotations

from ..errors import DiffMatError
from .spec import NodeSpec

_SPECS: dict[str, NodeSpec] = {}
_ALIASES: dict[str, str] = {}


def register(spec: NodeSpec) -> NodeSpec:
    """Add ``spec`` to the registry; a name or alias may be registered once."""
    for key in (spec.name, *spec.aliases):
        if key in _SPECS or key in _ALIASES:
            raise RuntimeError(f"node name {key!r} registered twice")
    _SPECS[spec.name] = spec
    _ALIASES.update({a: spec.name for a in spec.aliases})
    return spec


def get_spec(name: str) -> NodeSpec:
    """The spec registered as ``name`` (or an alias of it); DiffMatError when unknown."""
    key = _ALIASES.get(name, name)
    try:
        return _SPECS[key]
    except KeyError:
        raise DiffMatError(f"unknown node {name!r}") from None


def has_spec(name: str) -> bool:
    return name in _SPECS or name in _ALIASES


def all_specs() -> list[NodeSpec]:
    """Every registered spec, sorted by kind then name."""
    order = {"atomic": 0, "non_atomic": 1, "generator": 2}
    return sorted(_SPECS.values(), key=lambda s: (order[s.kind], s.name))


def all_names() -> set[str]:
    """Every name and alias a node answers to."""
    return set(_SPECS) | set(_ALIASES)
