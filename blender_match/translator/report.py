"""The translation report: coverage figures and what could not be translated (JSON-ready)."""
from __future__ import annotations

from .ir import IRGraph


def make_report(*, path: str, ir: IRGraph, stats, pruned: list[str], params_optimizable: int,
                seconds: float, graphs: list[str]) -> dict:
    outputs = {}
    for usage, r in ir.outputs.items():
        node = ir.nodes[r.node]
        outputs[usage] = {"node": r.node, "output": r.output, "channels": r.channels,
                          "size_log2": list(node.size_log2), "format": node.format}
    return {
        "file": path,
        "graph": ir.name,
        "graphs": graphs,
        "mode": ir.mode,
        "nodes_total": stats.total,
        "nodes_translated": stats.translated,
        "nodes_passthrough": stats.passthrough,
        "nodes_pruned": len(pruned),
        "nodes_in_program": len(ir.nodes),
        "subgraphs_inlined": stats.inlined,
        "channel_adapters": stats.adapters,
        "unsupported": dict(sorted(stats.unsupported.items())),
        "unsupported_functions": dict(sorted(stats.unsupported_functions.items())),
        "unconnected_graph_inputs": stats.unconnected_inputs,
        "params_dropped": stats.params_dropped,
        "params_dropped_names": dict(sorted(getattr(stats, "dropped", {}).items())),
        "params_optimizable": params_optimizable,
        "exposed": [{"name": e.name, "kind": e.kind, "default": e.default} for e in ir.exposed],
        "bindings": sum(len(n.bindings) for n in ir.nodes.values()),
        "outputs": outputs,
        "size_log2": list(ir.size_log2),
        "warnings": list(stats.warnings),
        "seconds": round(seconds, 4),
    }
