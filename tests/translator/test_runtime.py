"""SbsGraph's evaluation plan: binding, exposing and mode changes rebuild it, and a bound node
fed by a trainable exposed parameter is never cached."""
from __future__ import annotations

from functools import partial

import pytest
import torch

from blender_match.diffmat.errors import DiffMatError
from blender_match.diffmat.functional import function_graph as fg
from blender_match.translator.runtime import SbsGraph


def bound_graph() -> SbsGraph:
    g = SbsGraph("bound")
    g.expose("level", 0.25)
    g.add("color", "uniform", outputcolor=(0.2, 0.4, 0.6, 1.0))
    g.set_output("basecolor", "color")
    return g


def getter() -> dict:
    return {"nodes": {"0": {"function": "get_float1", "inputs": {}, "data": "level"},
                      "1": {"function": "vector4", "inputs": {"componentsin": "2", "componentslast": "0"}},
                      "2": {"function": "const_float3", "inputs": {}, "data": [0.1, 0.2, 0.3]}},
            "root": "1"}


def test_bind_and_mode_changes_rebuild_the_plan():
    g = bound_graph()
    plan = g.plan()
    g.bind("color", "outputcolor", getter())
    assert g.plan() is not plan
    assert "color" not in g.plan().static  # fed by a trainable exposed parameter
    out = g(size=4)["basecolor"]
    torch.testing.assert_close(out[0, :, 0, 0], torch.tensor([0.1, 0.2, 0.3, 0.25]))
    plan = g.plan()
    g.set_mode("exposed")
    assert g.plan() is not plan
    g.freeze("exposed")
    assert "color" in g.plan().static  # frozen exposed parameters: cacheable
    g.expose("other", 0.5)
    assert g.plan().num_params == 1 and fg.variables_of(getter()) == {"level"}


def test_theta_drives_the_bound_parameter():
    g = bound_graph()
    g.bind("color", "outputcolor", getter())
    g.set_mode("exposed")
    out = g(size=4, theta=torch.tensor([[0.5], [1.0]]))["basecolor"]
    torch.testing.assert_close(out[:, 3, 0, 0], torch.tensor([0.5, 1.0]))


def test_a_batch_whose_bound_integer_differs_is_drawn_item_by_item():
    """A node takes one value of a discrete parameter for its whole batch: a cell count bound to
    an exposed parameter used to take the first item's count for every item (a production cork's
    and our cork's and carpet's sample banks were drawn so). Each item now gets its own."""
    g = SbsGraph("cells")
    g.expose("size", 0.5)
    g.add("cells", "cells_4", seed=3, scale=8, disorder=0.5)
    g.bind("cells", "scale", {"nodes": {"0": {"function": "get_float1", "inputs": {}, "data": "size"},
                                        "1": {"function": "const_float1", "inputs": {}, "data": 16.0},
                                        "2": {"function": "mul", "inputs": {"a": "0", "b": "1"}}},
                              "root": "2"})
    g.set_output("height", "cells")
    g.set_mode("exposed")
    theta = torch.tensor([[0.25], [1.0], [0.25]])
    batch = g(size=32, theta=theta)["height"]
    for i in range(3):
        alone = SbsGraph.forward(g, size=32, theta=theta[i:i + 1])["height"]
        torch.testing.assert_close(batch[i:i + 1], alone)
    assert (batch[0] - batch[1]).abs().max() > 0.1      # 4 cells against 16
    torch.testing.assert_close(batch[0], batch[2])


def test_a_binding_is_compiled_once(monkeypatch):
    g = bound_graph()
    g.bind("color", "outputcolor", getter())
    monkeypatch.setattr(fg, "_compile_node", lambda nid, node: pytest.fail("compiled again"))
    g(size=4)
    g(size=4, theta=g.get_vector()[None])


def colour3(values) -> dict:
    return {"nodes": {"0": {"function": "const_float3", "inputs": {}, "data": list(values)}}, "root": "0"}


def test_a_float3_function_bound_to_an_rgba_parameter_keeps_its_alpha():
    """A production file binds Replace Color's target colour (RGBA here) to a float3 function;
    Substance accepts it, and so do we: the missing alpha keeps the parameter's default."""
    g = SbsGraph("widths")
    g.add("color", "uniform", outputcolor=(0.5, 0.5, 0.5, 1.0))
    g.add("swap", "replace_color", {"input": "color"}, sourcecolor=(0.5, 0.5, 0.5, 1.0))
    g.bind("swap", "targetcolor", colour3([0.8, 0.3, 0.1]))
    g.set_output("basecolor", "swap")
    out = g(size=4)["basecolor"][0, :, 0, 0]
    assert torch.isfinite(out).all()
    assert out[0] > out[1] > out[2]  # the warm target colour arrives, not a refusal or a grey
    torch.testing.assert_close(out[3], torch.tensor(1.0))


def test_fit_components_broadcasts_truncates_and_pads_from_the_default():
    fit = partial(fg.fit_components, what="test")
    torch.testing.assert_close(fit(torch.tensor([0.3]), 3, fill=(0.0, 0.0, 0.0)), torch.tensor([0.3, 0.3, 0.3]))
    torch.testing.assert_close(fit(torch.tensor([1.0, 2.0, 3.0, 4.0]), 3, fill=0.0), torch.tensor([1.0, 2.0, 3.0]))
    torch.testing.assert_close(fit(torch.tensor([[0.1, 0.2, 0.3]]), 4, fill=(0.5, 0.5, 0.5, 1.0)),
                               torch.tensor([[0.1, 0.2, 0.3, 1.0]]))
    torch.testing.assert_close(fit(torch.tensor([0.1, 0.2]), 4, fill=0.5), torch.tensor([0.1, 0.2, 0.5, 0.5]))
    with pytest.raises(DiffMatError, match="test has 2 component"):  # no fill: a variable too narrow
        fit(torch.tensor([0.1, 0.2]), 4)
