"""Library material sources (concrete, plaster, rough stone, marble, ground, asphalt): each builds,
evaluates to finite maps with the right channel counts, stays within the node / parameter budget,
and its main exposed parameter changes the look."""
from __future__ import annotations

import importlib

import pytest
import torch

SOURCES = {
    # module: (main exposed parameter, value to move it to)
    "concrete": ("color", [0.3, 0.3, 0.28]),
    "plaster": ("color", [0.85, 0.83, 0.8]),
    "rough_stone": ("color", [0.5, 0.45, 0.4]),
    "marble": ("vein_color", [0.7, 0.2, 0.1]),
    "ground": ("soil_color", [0.6, 0.5, 0.4]),
    "asphalt": ("wear", 0.0),
}
CHANNELS = {"basecolor": 4, "normal": 4, "roughness": 1, "metallic": 1, "height": 1}


def _load(name):
    return importlib.import_module(f"blender_match.library.sources.{name}")


@pytest.mark.parametrize("name", sorted(SOURCES))
def test_source_builds_and_evaluates(name):
    mod = _load(name)
    assert mod.__doc__ and len(mod.__doc__) > 100
    g = mod.build()
    g.set_mode("exposed_plus")
    assert 20 <= len(g.nodes) <= 150
    assert 30 <= g.num_params() <= 200
    with torch.no_grad():
        maps = g(size=64, seed=0)
    for usage, channels in CHANNELS.items():
        assert usage in maps, usage
        x = maps[usage]
        assert x.shape == (1, channels, 64, 64), (usage, x.shape)
        assert torch.isfinite(x).all(), usage
        assert x.min() >= 0.0 and x.max() <= 1.0, usage
    assert maps["metallic"].max() == 0.0


@pytest.mark.parametrize("name", sorted(SOURCES))
def test_main_exposed_parameter_changes_the_look(name):
    mod = _load(name)
    g = mod.build()
    param, value = SOURCES[name]
    with torch.no_grad():
        before = g(size=64, seed=0)
        g.exposed.set_values(**{param: value})
        g.clear_cache()
        after = g(size=64, seed=0)
    change = max((before[k] - after[k]).abs().max().item() for k in ("basecolor", "height"))
    assert change > 0.02


@pytest.mark.parametrize("name", sorted(SOURCES))
def test_sample_ranges_name_real_parameters(name):
    mod = _load(name)
    g = mod.build()
    for key, (lo, hi) in mod.SAMPLE_RANGES.items():
        node, param = key.split(".", 1)
        if node == "exposed":
            assert param in g.exposed.ranges, key
            rlo, rhi = g.exposed.ranges[param]
        else:
            assert node in g.nodes and param in g.nodes[node].theta, key
            assert param not in g.bindings.get(node, {}), key
            rlo, rhi = g.nodes[node].ranges[param]
        los = lo if isinstance(lo, (list, tuple)) else [lo]
        his = hi if isinstance(hi, (list, tuple)) else [hi]
        for a, b in zip(los, his):
            assert rlo - 1e-6 <= a <= b <= rhi + 1e-6, key
