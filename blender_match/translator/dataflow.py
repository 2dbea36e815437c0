"""Data-flow analysis (the MATch paper, section 5.7 step 3) and topological sorting (step 4).

Works on two levels: ``toposort`` orders the nodes of a .sbs graph by their connections (refusing
cycles and connections to missing nodes before anything is built), and ``prune`` / ``order`` keep
the IR nodes that reach an output and sort them so that every node comes after its sources.
"""
from __future__ import annotations

from ..diffmat.toposort import topological_order
from .errors import TranslatorError
from .ir import IRGraph


def toposort(edges: dict[str, list[str]], path, what: str) -> list[str]:
    """Order node ids so that sources come first; ``edges[n]`` lists the sources of n.
    TranslatorError on a cycle or a source that is not a node. Ties keep the input order."""
    for n, srcs in edges.items():
        for s in srcs:
            if s not in edges:
                raise TranslatorError(path, f"{what}: node {n[:30]} is connected to missing node {s[:30]}")
    out, stuck = topological_order(edges)
    if stuck:
        raise TranslatorError(path, f"{what}: cycle through nodes {', '.join(s[:20] for s in stuck[:5])}")
    return out


def reachable(ir: IRGraph) -> set[str]:
    """Nodes an output depends on (backward search from the outputs)."""
    seen: set[str] = set()
    stack = [r.node for r in ir.outputs.values()]
    while stack:
        n = stack.pop()
        if n in seen:
            continue
        seen.add(n)
        stack.extend(r.node for r in ir.nodes[n].inputs.values())
    return seen


def prune(ir: IRGraph) -> list[str]:
    """Remove the IR nodes that reach no output; returns their names."""
    keep = reachable(ir)
    dead = [n for n in ir.nodes if n not in keep]
    for n in dead:
        del ir.nodes[n]
    return dead


def order(ir: IRGraph, path) -> list[str]:
    """IR node names in topological order (sources first)."""
    return toposort({n: [r.node for r in node.inputs.values()] for n, node in ir.nodes.items()}, path,
                    f"graph {ir.name}")
