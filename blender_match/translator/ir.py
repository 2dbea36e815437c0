"""The translated graph before it becomes a MaterialGraph or a program: nodes named by the
translator (valid identifiers), registered node names, converted parameter values, bindings to
exposed parameters, connections. Both the MaterialGraph (assemble.py) and the generated program
(codegen.py) are produced from this one description, so they agree by construction."""
from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Ref:
    """An output of an IR node; ``channels`` 1, 4 or None (unknown)."""

    node: str
    output: str
    channels: int | None = None


@dataclass
class IRNode:
    name: str
    spec: str                                   # registered node name
    params: dict = field(default_factory=dict)  # converted values
    bindings: dict = field(default_factory=dict)  # param -> function graph of exposed parameters
    inputs: dict[str, Ref] = field(default_factory=dict)
    seed: int = 0
    origin: str = ""                            # what it was in the file (validated text only)
    status: str = "translated"                  # translated | passthrough | adapter | input
    size_log2: tuple[int, int] = (9, 9)
    format: int = 0


@dataclass
class Exposed:
    name: str                                   # validated identifier
    kind: str                                   # float | int | bool | string
    default: object
    min: float = 0.0
    max: float = 1.0


@dataclass
class IRGraph:
    name: str
    nodes: dict[str, IRNode] = field(default_factory=dict)
    outputs: dict[str, Ref] = field(default_factory=dict)
    exposed: list[Exposed] = field(default_factory=list)
    mode: str = "exposed_plus"
    size_log2: tuple[int, int] = (9, 9)
