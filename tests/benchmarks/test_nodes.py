"""``bench nodes`` splits an optimisation step into its forward (with autograd) and its backward
pass, in one process, on the bundled 50-node graph (at a tiny size: figures belong to the bench)."""
from __future__ import annotations

from blender_match.benchmarks.nodes import case


def test_a_step_is_split_into_forward_and_backward():
    step = case("backward", 32, repeats=2)
    assert step["nodes"] == 50
    assert step["forward_seconds"] > 0 and step["backward_seconds"] > 0
    # the fastest step is no faster than its fastest forward and fastest backward together
    assert step["seconds"] >= step["forward_seconds"] + step["backward_seconds"] - 1e-9
    forward = case("forward", 32, repeats=1)
    assert forward["seconds"] > 0 and "backward_seconds" not in forward
