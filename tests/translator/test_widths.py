"""Vector-width mismatches between a parameter's declared type and the value an instance gives it,
which Substance accepts by converting: a scalar spreads, extra components are dropped, a float3
colour into a float4 one gets alpha 1. Both a constant value and a function graph of an exposed
parameter, in every mode, give the same result."""
from __future__ import annotations

import pytest
import sbs_snippets as W
import torch

from blender_match.translator import translate
from blender_match.translator.function_graphs import result_width

TYPES = {1: (256, "get_float1", "constantValueFloat1"), 3: (1024, "get_float3", "constantValueFloat3"),
         4: (2048, "get_float4", "constantValueFloat4")}
VALUES = {1: "0.5", 3: "0.5 0.25 0", 4: "0.5 0.25 0 0.75"}


def _sub_graph(width: int) -> str:
    """Sub-graph: a uniform colour read from its parameter ``tint`` declared ``width`` wide."""
    code, getter, tag = TYPES[width]
    color = W.dyn_param("outputcolor", 1, [W.fnode(1, getter, data=("constantValueString", "tint"), type_code=code)])
    nodes = [W.filter_node(10, "uniform", params=[color], outputs=[(11, 1)]), W.output_node(20, 200, 10, 11)]
    return W.graph("Sub", nodes, outputs=[(200, "out", "baseColor")],
                   paraminputs=[W.paraminput("tint", 6, code, tag, VALUES[width])])


def _doc(declared: int, given: int, exposed: bool) -> str:
    """Main graph instancing Sub with a ``given``-wide value for its ``declared``-wide parameter:
    a constant, or (``exposed``) a getter of an exposed parameter of the main graph."""
    code, getter, tag = TYPES[given]
    if exposed:
        params = [W.dyn_param("tint", 1, [W.fnode(1, getter, data=("constantValueString", "top"), type_code=code)])]
        pis = [W.paraminput("top", 7, code, tag, VALUES[given])]
    else:
        params, pis = [W.param("tint", tag, VALUES[given])], []
    nodes = [W.instance_node(10, "pkg:///Sub?dependency=9", params=params, outputs=[(11, "out", 1)]),
             W.output_node(20, 100, 10, 11)]
    main = W.graph("Main", nodes, outputs=[(100, "basecolor", "baseColor")], paraminputs=pis)
    return W.package([main, _sub_graph(declared)], dependencies=[(9, "?himself")])


@pytest.mark.parametrize("mode", ["exposed_plus", "all"])
@pytest.mark.parametrize("exposed", [False, True])
@pytest.mark.parametrize(("declared", "given", "expected"), [
    (4, 3, [0.5, 0.25, 0.0, 1.0]),  # float3 into float4: opaque
    (3, 4, [0.5, 0.25, 0.0, 1.0]),  # float4 into float3: alpha dropped (the uniform's own alpha is 1)
    (4, 1, [0.5, 0.5, 0.5, 0.5]),  # a scalar spreads
    (1, 4, [0.5, 0.5, 0.5, 0.5]),  # a float1 keeps the first component
])
def test_instance_values_take_the_declared_width(tmp_path, mode, exposed, declared, given, expected):
    path = tmp_path / "widths.sbs"
    path.write_text(_doc(declared, given, exposed))
    t = translate(path, graph_name="Main", mode=mode)
    out = t.graph(size=8)["basecolor"]
    torch.testing.assert_close(out[0, :, 0, 0], torch.tensor(expected))
    assert not any("component" in w for w in t.report["warnings"])


def test_result_width_reads_function_names_and_follows_arithmetic():
    graph = {"nodes": {"0": {"function": "get_float3", "inputs": {}, "data": "a"},
                       "1": {"function": "const_float1", "inputs": {}, "data": 2.0},
                       "2": {"function": "mul", "inputs": {"a": "0", "b": "1"}},
                       "3": {"function": "dot", "inputs": {"a": "0", "b": "0"}}},
             "root": "2"}
    assert result_width(graph) == 3
    assert result_width({**graph, "root": "3"}) == 1
