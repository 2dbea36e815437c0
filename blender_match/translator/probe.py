"""A shape probe: run the translated IR once at a tiny size, node by node, to make it runnable.

Where an engine node's actual channel count differs from what the file recorded (or from what
the consumer's slot needs), a channel-conversion node is inserted; a node the engine refuses for
these inputs (DiffMatError) is replaced by a pass-through of its first input (or a uniform gray)
and reported. Returns the new topological order.
"""
from __future__ import annotations

import torch

from ..diffmat.errors import DiffMatError
from ..diffmat.nodes import EvalContext, Node, get_spec
from .build import USAGES
from .ir import Ref

PROBE_SIZE = 16


def probe(builder, order: list[str]) -> list[str]:
    ir = builder.ir
    ctx = EvalContext(size=PROBE_SIZE, seed=0)
    values: dict[str, tuple] = {}
    new_order: list[str] = []

    def run(name):
        node = ir.nodes[name]
        spec = get_spec(node.spec)
        args = [values[node.inputs[s.name].node][get_spec(ir.nodes[node.inputs[s.name].node].spec).outputs.index(
            node.inputs[s.name].output)] if s.name in node.inputs else None for s in spec.inputs]
        with torch.no_grad():
            out = Node(spec, node.params, seed=node.seed, widen_ranges=True)(*args, ctx=ctx)
        values[name] = out if isinstance(out, tuple) else (out,)

    for name in order:
        node = ir.nodes[name]
        spec = get_spec(node.spec)
        for slot in spec.inputs:
            r = node.inputs.get(slot.name)
            if r is None:
                continue
            src_spec = get_spec(ir.nodes[r.node].spec)
            actual = values[r.node][src_spec.outputs.index(r.output)].shape[1]
            need = {"gray": 1, "color": 4}.get(slot.channels) or r.channels
            if need is not None and actual != need:
                fixed = builder.adapt(Ref(r.node, r.output, actual), need)
                if fixed.node not in values:
                    run(fixed.node)
                    new_order.append(fixed.node)
                node.inputs[slot.name] = fixed
        try:
            run(name)
        except DiffMatError as exc:
            builder.stats.warn(f"{name} ({node.spec}) fails on these inputs ({exc}); replaced by a pass-through")
            builder.stats.unsupported[f"failed_{node.spec}"] += 1
            builder.stats.failed += 1
            first = next(iter(node.inputs.values()), None)
            node.params, node.bindings, node.seed, node.status = {}, {}, 0, "passthrough"
            if first is not None:
                node.spec, node.inputs = "passthrough", {"input": first}
            else:
                node.spec, node.inputs = "uniform", {}
                node.params = {"outputcolor": [0.5, 0.5, 0.5, 1.0], "colorswitch": True}
            run(name)
        new_order.append(name)
    # outputs: the channel count their usage needs
    for usage, r in list(ir.outputs.items()):
        actual = values[r.node][get_spec(ir.nodes[r.node].spec).outputs.index(r.output)].shape[1]
        if actual != USAGES[usage]:
            fixed = builder.adapt(Ref(r.node, r.output, actual), USAGES[usage])
            if fixed.node not in values:
                run(fixed.node)
                new_order.append(fixed.node)
            ir.outputs[usage] = fixed
    return new_order
