"""Declarations of nodes: what a node is called, what it takes and what it returns.

A NodeSpec pairs a stateless functional op with the description the runtime, the translator and
`blender-match nodes` need: Substance's identifiers for inputs, outputs and parameters (in lower
case, so a `.sbs` file maps onto a node without tables), each parameter's range and default, and
whether it may be optimised.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

KINDS = ("atomic", "non_atomic", "generator")
PARAM_KINDS = ("float", "int", "bool", "enum", "string")
CONTEXT_KEYS = ("size", "seed", "device", "dtype")


@dataclass(frozen=True)
class Param:
    """One node parameter.

    ``kind`` float is continuous: stored normalised in [0, 1] between ``min`` and ``max``,
    optimisable unless ``optimizable`` is False. ``size`` is the number of components (4 for an
    RGBA colour); None means "as many as the value given" (gradient keys, curve points). The other
    kinds are discrete and never optimised; ``choices`` lists an enum's allowed values.
    """

    name: str
    default: Any
    min: float = 0.0
    max: float = 1.0
    kind: str = "float"
    size: int | None = 1
    optimizable: bool = True
    choices: tuple = ()
    doc: str = ""

    @property
    def continuous(self) -> bool:
        return self.kind == "float"

    def describe(self) -> dict:
        out = {"name": self.name, "kind": self.kind, "default": self.default,
               "optimizable": self.continuous and self.optimizable}
        if self.continuous:
            out.update(min=self.min, max=self.max, size=self.size)
        if self.choices:
            out["choices"] = list(self.choices)
        return out


@dataclass(frozen=True)
class Input:
    """An image input slot: ``channels`` is "gray", "color" or "any"; optional slots may be None."""

    name: str
    channels: str = "any"
    optional: bool = False


@dataclass(frozen=True)
class NodeSpec:
    """A node: its functional op ``fn`` and its declaration.

    ``fn`` is called as ``fn(*images, **params, **context)``: images in ``inputs`` order, every
    parameter by its name, and the context keys listed in ``context`` (size, seed, device, dtype).
    A node with several ``outputs`` returns a tuple in that order.
    """

    name: str
    kind: str
    fn: Callable
    inputs: tuple[Input, ...] = ()
    outputs: tuple[str, ...] = ("output",)
    params: tuple[Param, ...] = ()
    context: tuple[str, ...] = ()
    aliases: tuple[str, ...] = ()
    doc: str = ""
    param_index: dict = field(default_factory=dict, compare=False, repr=False)

    def __post_init__(self):
        assert self.kind in KINDS, self.kind
        assert all(p.kind in PARAM_KINDS for p in self.params), self.name
        assert all(k in CONTEXT_KEYS for k in self.context), self.name
        self.param_index.update({p.name: p for p in self.params})

    def param(self, name: str) -> Param:
        return self.param_index[name]

    def describe(self) -> dict:
        return {"name": self.name, "kind": self.kind,
                "inputs": [{"name": i.name, "channels": i.channels, "optional": i.optional} for i in self.inputs],
                "outputs": list(self.outputs),
                "params": [p.describe() for p in self.params]}
