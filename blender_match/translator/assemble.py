"""From the IR to a runnable SbsGraph (a MaterialGraph), checking every node's parameters first
so that the graph and the generated program (codegen.py) are built from the same, valid values."""
from __future__ import annotations

from ..diffmat.errors import DiffMatError
from ..diffmat.functional import function_graph as fg_engine
from ..diffmat.nodes import Node, get_spec
from .ir import IRGraph
from .runtime import SbsGraph


def finalize(ir: IRGraph, warn) -> None:
    """Drop parameter values and bindings the engine refuses (reported through ``warn``)."""
    exposed = {e.name for e in ir.exposed}
    for name, node in ir.nodes.items():
        spec = get_spec(node.spec)
        try:
            Node(spec, node.params, seed=node.seed, widen_ranges=True)
        except DiffMatError:
            good = {}
            for p, v in node.params.items():
                try:
                    Node(spec, {p: v}, widen_ranges=True)
                    good[p] = v
                except DiffMatError as exc:
                    warn(f"{name}.{p}: {exc}; default kept")
            node.params = good
        for p, graph in list(node.bindings.items()):
            try:
                fg_engine.validate(graph)
                if not fg_engine.variables_of(graph) <= exposed:
                    raise DiffMatError("reads unknown variables")
            except DiffMatError as exc:
                warn(f"{name}.{p}: binding dropped ({exc})")
                del node.bindings[p]


def assemble(ir: IRGraph, order: list[str]) -> SbsGraph:
    graph = SbsGraph(ir.name)
    for e in ir.exposed:
        graph.expose(e.name, e.default, kind=e.kind, min=e.min, max=e.max)
    for name in order:
        node = ir.nodes[name]
        graph.add(name, Node(node.spec, node.params, seed=node.seed, widen_ranges=True),
                  {slot: f"{r.node}:{r.output}" for slot, r in node.inputs.items()})
        for p, fg in node.bindings.items():
            graph.bind(name, p, fg)
    for usage, r in ir.outputs.items():
        graph.set_output(usage, f"{r.node}:{r.output}")
    graph.set_mode(ir.mode)
    return graph
