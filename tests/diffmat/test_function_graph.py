"""The function-graph evaluator (diffmat/functional/function_graph.py) and the processor nodes."""
from __future__ import annotations

import json

import pytest
import torch

from blender_match.diffmat import DiffMatError, EvalContext, Node
from blender_match.diffmat.functional import function_graph as fg


def G(root, **nodes):
    return {"nodes": nodes, "root": root}


def N(function, data=None, **inputs):
    node = {"function": function, "inputs": inputs}
    if data is not None:
        node["data"] = data
    return node


def test_constants_and_arithmetic():
    g = G("r", a=N("const_float1", 2.0), b=N("const_float1", 3.0), m=N("mul", a="a", b="b"),
          r=N("sub", a="m", b="a"))
    assert fg.evaluate(g).tolist() == [4.0]
    g = G("v", x=N("const_float2", [1.0, 2.0]), y=N("const_float2", [3.0, 4.0]), v=N("vector4", componentsin="x",
                                                                                   componentslast="y"))
    assert fg.evaluate(g).tolist() == [1.0, 2.0, 3.0, 4.0]
    g["nodes"]["s"] = N("swizzle2", [3, 0], vector="v")
    g["root"] = "s"
    assert fg.evaluate(g).tolist() == [4.0, 1.0]


def test_missing_constant_is_zero_and_int_division_truncates():
    assert fg.evaluate(G("c", c=N("const_float3"))).tolist() == [0.0, 0.0, 0.0]
    g = G("d", a=N("const_int1", 7), b=N("const_int1", 2), d=N("div", a="a", b="b"))
    value, kind = fg.evaluate(g, kind=True)
    assert value.tolist() == [3.0] and kind == "int"
    g["nodes"]["b"] = N("const_int1", 0)
    assert fg.evaluate(g).tolist() == [0.0]  # no crash on integer division by zero


@pytest.mark.parametrize("fn,a,b,expected", [
    ("min", 1.0, 2.0, 1.0), ("max", 1.0, 2.0, 2.0), ("gt", 1.0, 2.0, 0.0), ("lr", 1.0, 2.0, 1.0),
    ("eq", 2.0, 2.0, 1.0), ("noteq", 2.0, 2.0, 0.0), ("gteq", 2.0, 2.0, 1.0), ("lreq", 3.0, 2.0, 0.0),
    ("mod", 7.0, 3.0, 1.0), ("add", 1.5, 2.0, 3.5), ("pow", 2.0, 3.0, 8.0),
])
def test_binary_functions(fn, a, b, expected):
    g = G("r", a=N("const_float1", a), b=N("const_float1", b), r=N(fn, a="a", b="b"))
    assert fg.evaluate(g).item() == pytest.approx(expected)


def test_ifelse_lerp_and_unary():
    g = G("r", c=N("const_bool", True), a=N("const_float1", 1.0), b=N("const_float1", 5.0),
          r=N("ifelse", condition="c", ifpath="a", elsepath="b"))
    assert fg.evaluate(g).item() == 1.0
    g["nodes"]["c"] = N("const_bool", False)
    assert fg.evaluate(g).item() == 5.0
    g = G("l", a=N("const_float1", 2.0), b=N("const_float1", 4.0), x=N("const_float1", 0.25),
          l=N("lerp", a="a", b="b", x="x"))
    assert fg.evaluate(g).item() == pytest.approx(2.5)
    g = G("r", a=N("const_float1", -2.25), f=N("floor", a="a"), r=N("abs", a="f"))
    assert fg.evaluate(g).item() == 3.0
    assert fg.evaluate(G("r", a=N("const_float1", 3.0), r=N("pow2", a="a"))).item() == 8.0


def test_variables_batches_and_gradients():
    g = G("r", x=N("get_float1", "contrast"), k=N("const_float1", 3.0), r=N("mul", a="x", b="k"))
    x = torch.tensor([[0.1], [0.5]], dtype=torch.float64, requires_grad=True)
    out = fg.evaluate(g, {"contrast": x}, dtype=torch.float64)
    assert out.shape == (2, 1)
    out.sum().backward()
    assert x.grad.tolist() == [[3.0], [3.0]]
    g2 = G("r", x=N("get_float2", "v"), s=N("sin", a="x"), r=N("dot", a="s", b="x"))
    v = torch.tensor([0.3, 0.7], dtype=torch.float64, requires_grad=True)
    assert torch.autograd.gradcheck(lambda t: fg.evaluate(g2, {"v": t}, dtype=torch.float64), (v,))
    with pytest.raises(DiffMatError):
        fg.evaluate(g, {})


def test_rand_is_seeded_and_in_range():
    g = G("r", a=N("const_float1", 2.0), r=N("rand", a="a"))
    one, two = fg.evaluate(g, seed=1), fg.evaluate(g, seed=1)
    assert torch.equal(one, two) and 0.0 <= one.item() < 2.0
    assert not torch.equal(one, fg.evaluate(g, seed=2))


@pytest.mark.parametrize("graph", [
    {"nodes": {}, "root": "x"},
    G("a", a=N("frobnicate")),
    G("a", a=N("abs", a="b"), b=N("const_float1", 1.0, q="a")),
    G("a", a=N("abs", a="b"), b=N("abs", a="a")),
    G("a", a=N("abs", a="missing")),
    G("a", a=N("swizzle1", [7], vector="b"), b=N("const_float4")),
    G("a", a=N("const_float1", "text")),
    "not a graph",
])
def test_malformed_graphs_are_diffmat_errors(graph):
    with pytest.raises(DiffMatError):
        fg.validate(graph)


def test_json_round_trip():
    g = G("r", a=N("const_float1", 2.0), r=N("neg", a="a"))
    assert fg.loads(fg.dumps(g)) == g
    with pytest.raises(DiffMatError):
        fg.loads("{not json")


def test_pixel_processor_positions_and_sampling():
    pos = G("s", p=N("get_float2", "$pos"), s=N("swizzle1", [0], vector="p"))
    node = Node("pixelprocessor", {"perpixel": fg.dumps(pos), "colorswitch": False})
    out = node(ctx=EvalContext(size=8))
    assert out.shape == (1, 1, 8, 8)
    torch.testing.assert_close(out[0, 0, 0], (torch.arange(8) + 0.5) / 8)
    # shift the input one pixel to the right by sampling at $pos - (1/W, 0)
    shift = G("c", p=N("get_float2", "$pos"), d=N("const_float2", [1 / 8, 0.0]), q=N("sub", a="p", b="d"),
              c=N("samplecol", {"input": 0, "filtering": 1}, pos="q"))
    img = torch.rand(1, 4, 8, 8)
    out = Node("pixelprocessor", {"perpixel": fg.dumps(shift)})(img, ctx=EvalContext(size=8))
    torch.testing.assert_close(out, torch.roll(img, 1, dims=-1))
    lum = G("c", p=N("get_float2", "$pos"), c=N("samplelum", {"input": 1}, pos="p"))
    gray = torch.rand(1, 1, 8, 8)
    out = Node("pixelprocessor", {"perpixel": fg.dumps(lum), "colorswitch": False})(None, gray, ctx=EvalContext(size=8))
    torch.testing.assert_close(out, gray)


def test_value_processor_is_a_uniform_image():
    g = G("c", c=N("const_float4", [0.25, 0.5, 0.75, 1.0]))
    out = Node("valueprocessor", {"function": fg.dumps(g)})(ctx=EvalContext(size=4))
    assert out.shape == (1, 4, 4, 4)
    assert out[0, :, 2, 3].tolist() == [0.25, 0.5, 0.75, 1.0]
    with pytest.raises(DiffMatError):
        Node("valueprocessor", {"function": json.dumps(G("c", c=N("nope")))})(ctx=EvalContext(size=4))


def _mixed_graph():
    """Reads a variable, branches, draws a random number and sets a variable in a sequence."""
    return G("s", v=N("get_float2", "x"), one=N("const_float1", 1.0), n=N("length", a="v"),
             c=N("gt", a="n", b="one"), r=N("rand", a="n"), e=N("ifelse", condition="c", ifpath="n", elsepath="r"),
             st=N("set", "y", value="e"), g=N("get_float1", "y"), m=N("mul", a="g", b="one"),
             s=N("sequence", seqin="st", seqlast="m"))


def test_a_compiled_graph_gives_what_evaluate_gives():
    g = _mixed_graph()
    run = fg.compile_graph(g)
    assert run.variables == {"x", "y"}
    for x in ([0.3, 0.4], [3.0, 4.0], torch.rand(5, 2, generator=torch.Generator().manual_seed(1))):
        for seed in (0, 9):
            assert torch.equal(run({"x": x}, seed=seed), fg.evaluate(g, {"x": x}, seed=seed))
    assert run({"x": [3.0, 4.0]}, kind=True)[1] == "float"
    with pytest.raises(DiffMatError, match="variable 'x' is not set"):
        run({})


def test_function_graphs_are_compiled_once(monkeypatch):
    compiled_nodes = []
    real = fg._compile_node
    monkeypatch.setattr(fg, "_compile_node", lambda nid, node: compiled_nodes.append(nid) or real(nid, node))
    text = fg.dumps(G("c", p=N("get_float2", "$pos"), c=N("swizzle1", [0], vector="p")))
    node = Node("pixelprocessor", {"perpixel": text, "colorswitch": False})
    first = node(ctx=EvalContext(size=8))
    count = len(compiled_nodes)
    assert count == 2
    assert torch.equal(node(ctx=EvalContext(size=8)), first)
    assert len(compiled_nodes) == count  # the second evaluation reuses the closures
    assert fg.compiled(text) is fg.compiled(text)
