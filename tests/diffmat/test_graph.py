"""The graph runtime: building, validation, topological order, pruning, the parameter vector,
freezing, batched evaluation, caching of constant nodes, dtype moves; and Node's parameter rules."""
from __future__ import annotations

import pytest
import torch

from blender_match.diffmat import DiffMatError, MaterialGraph, Node


def chain() -> MaterialGraph:
    g = MaterialGraph("chain")
    g.add("color", "uniform", outputcolor=(0.2, 0.4, 0.6, 1.0))
    g.add("dot", "passthrough", {"input": "color"})
    g.add("unused", "uniform")
    g.set_output("basecolor", "dot")
    return g


def test_evaluates_outputs_in_order():
    g = chain()
    assert g.order() == ["color", "dot"]
    out = g(size=8)["basecolor"]
    assert out.shape == (1, 4, 8, 8)
    torch.testing.assert_close(out[0, :, 3, 5], torch.tensor([0.2, 0.4, 0.6, 1.0]))


def test_building_errors_are_clear():
    g = chain()
    with pytest.raises(DiffMatError, match="missing node 'nope'"):
        g.add("x", "passthrough", {"input": "nope"})
    with pytest.raises(DiffMatError, match="has no input 'source'"):
        g.connect("color", "dot", "source")
    with pytest.raises(DiffMatError, match="already exists"):
        g.add("color", "uniform")
    with pytest.raises(DiffMatError, match="not an identifier"):
        g.add("bad name", "uniform")
    with pytest.raises(DiffMatError, match="unknown node"):
        g.add("y", "no_such_node")
    with pytest.raises(DiffMatError, match="unknown output usage"):
        g.set_output("albedo", "dot")
    with pytest.raises(DiffMatError, match="not a power-of-two"):
        g(size=100)


def test_cycle_is_an_error():
    g = MaterialGraph("cyclic")
    g.add("a", "passthrough")
    g.add("b", "passthrough", {"input": "a"})
    g.connect("b", "a", "input")
    g.set_output("height", "b")
    with pytest.raises(DiffMatError, match="cycle"):
        g(size=8)


def test_prune_removes_what_reaches_no_output():
    g = chain()
    assert g.prune() == ["unused"]
    assert list(g.nodes) == ["color", "dot"]


def test_parameter_vector_round_trip_and_freeze():
    g = chain()
    assert g.num_params() == 8
    assert g.param_names()[:2] == ["color.outputcolor[0]", "color.outputcolor[1]"]
    v = g.get_vector()
    v[0] = 0.9
    g.set_vector(v)
    assert g(size=4)["basecolor"][0, 0, 0, 0].item() == pytest.approx(0.9)
    g.freeze("unused*")
    assert g.num_params() == 4
    g.freeze()
    assert g.num_params() == 0
    g.unfreeze("color.outputcolor")
    assert g.num_params() == 4
    with pytest.raises(DiffMatError, match="no parameter matches"):
        g.freeze("zzz")
    with pytest.raises(DiffMatError, match="parameter vector has 3 values"):
        g.set_vector(torch.zeros(3))


def test_batched_theta_gives_a_batch():
    g = chain()
    g.freeze("unused")
    theta = torch.tensor([[0.1, 0.2, 0.3, 1.0], [0.5, 0.6, 0.7, 1.0]])
    out = g(size=4, theta=theta)["basecolor"]
    assert out.shape == (2, 4, 4, 4)
    torch.testing.assert_close(out[:, :3, 0, 0], theta[:, :3])
    with pytest.raises(DiffMatError, match="theta must be"):
        g(size=4, theta=torch.zeros(2, 3))


def test_constant_nodes_are_cached_and_trainable_ones_are_not():
    g = chain()
    first = g(size=8)["basecolor"]
    assert g(size=8)["basecolor"] is not first  # trainable: recomputed
    g.freeze()
    cached = g(size=8)["basecolor"]
    assert g(size=8)["basecolor"] is cached
    assert g(size=16)["basecolor"].shape[-1] == 16  # a new size is a new cache entry
    g.unfreeze()
    assert g(size=8)["basecolor"] is not cached


def test_gradients_reach_the_parameters():
    g = chain()
    out = g(size=4)["basecolor"]
    out[:, 0].mean().backward()
    grad = g.nodes["color"].theta["outputcolor"].grad
    assert grad[0] == pytest.approx(1.0) and grad[1] == 0


def test_dtype_moves_with_the_graph():
    g = chain().double()
    assert g(size=4)["basecolor"].dtype == torch.float64


def test_node_parameter_rules():
    with pytest.raises(DiffMatError, match="outside"):
        Node("uniform", {"outputcolor": (1.5, 0, 0, 1)})
    wide = Node("uniform", {"outputcolor": (1.5, 0, 0, 1)}, widen_ranges=True)
    assert wide.ranges["outputcolor"] == (0.0, 1.5)
    with pytest.raises(DiffMatError, match="expected 4 component"):
        Node("uniform", {"outputcolor": (0.1, 0.2)})
    with pytest.raises(DiffMatError, match="unknown parameter"):
        Node("uniform", {"colour": 1})
    with pytest.raises(DiffMatError, match="expected a boolean"):
        Node("uniform", {"colorswitch": "yes"})
    node = Node("uniform")
    node.theta["outputcolor"].data.fill_(1.7)  # an optimiser overshooting
    assert node.values()["outputcolor"].max().item() == 1.0


def test_plan_is_computed_once_and_reused():
    g = chain()
    g(size=4)
    plan = g.plan()
    assert plan.order == ["color", "dot"] and plan.num_params == 8
    g(size=8)
    g(size=4, theta=g.get_vector()[None])
    assert g.plan() is plan


@pytest.mark.parametrize("mutate", [
    lambda g: g.add("extra", "uniform"),
    lambda g: g.connect("unused", "dot", "input"),
    lambda g: g.set_output("height", "color"),
    lambda g: g.prune(),
    lambda g: g.freeze("color"),
    lambda g: g.nodes["color"].theta["outputcolor"].requires_grad_(False),  # by hand
    lambda g: g.double(),
])
def test_plan_is_rebuilt_after_a_mutation(mutate):
    g = chain()
    g(size=4)
    plan = g.plan()
    mutate(g)
    assert g.plan() is not plan


def test_a_mutation_shows_in_the_output():
    g = chain()
    g.freeze()  # the whole chain is static and cached
    before = g(size=4)["basecolor"]
    g.add("red", "uniform", outputcolor=(1.0, 0.0, 0.0, 1.0))
    g.connect("red", "dot", "input")
    after = g(size=4)["basecolor"]
    torch.testing.assert_close(after[0, :, 0, 0], torch.tensor([1.0, 0.0, 0.0, 1.0]))
    assert not torch.equal(before, after)
    g.set_output("basecolor", "color")
    torch.testing.assert_close(g(size=4)["basecolor"], before)
    assert g.plan().static == frozenset({"color"})
    g.unfreeze("color")
    assert g.plan().static == frozenset()
