"""The parsed form of a .sbs package: plain dataclasses, no XML (parse.py fills them)."""
from __future__ import annotations

from dataclasses import dataclass, field

from .values import Value


@dataclass
class Param:
    """A node (or instance, or graph base) parameter: a constant or a function graph."""

    name: str
    relative_to: int | None = None
    constant: Value | None = None
    dynamic: dict | None = None      # function graph (engine format) with the file's variable names
    error: str | None = None         # why neither could be read


@dataclass
class Connection:
    identifier: str                  # input slot of the consumer, as in the file
    source: str                      # uid of the source node
    source_output: str | None = None  # uid of the source's compOutput


@dataclass
class Node:
    uid: str
    impl: str                        # filter | instance | input | output | unknown
    name: str = ""                   # filter name, or the instance path
    params: dict[str, Param] = field(default_factory=dict)         # by lower-case name
    arrays: dict[str, list[dict[str, Value]]] = field(default_factory=dict)
    connections: list[Connection] = field(default_factory=list)
    outputs: list[tuple[str, int | None]] = field(default_factory=list)   # (uid, comptype)
    bridgings: dict[str, str] = field(default_factory=dict)       # output uid -> identifier
    ref: str | None = None           # input bridge: paraminput uid; output bridge: graphoutput uid


@dataclass
class ParamInput:
    identifier: str
    uid: str
    type: int | None
    default: Value | None = None
    min: float | None = None
    max: float | None = None


@dataclass
class GraphOutput:
    identifier: str
    uid: str
    usages: list[str] = field(default_factory=list)


@dataclass
class Graph:
    identifier: str
    uid: str
    path: str                        # group folders + identifier, "/"-separated
    paraminputs: list[ParamInput] = field(default_factory=list)
    outputs: list[GraphOutput] = field(default_factory=list)
    nodes: dict[str, Node] = field(default_factory=dict)
    base_params: dict[str, Param] = field(default_factory=dict)
    options: dict[str, str] = field(default_factory=dict)


@dataclass
class Package:
    path: str
    graphs: list[Graph] = field(default_factory=list)
    dependencies: dict[str, str] = field(default_factory=dict)   # uid -> filename
    warnings: list[str] = field(default_factory=list)

    def find_graph(self, name: str) -> Graph | None:
        """A graph by identifier or by path inside the package (case-sensitive, then not)."""
        for exact in (True, False):
            for g in self.graphs:
                keys = (g.identifier, g.path)
                if exact and name in keys:
                    return g
                if not exact and name.lower() in (k.lower() for k in keys):
                    return g
        return None
