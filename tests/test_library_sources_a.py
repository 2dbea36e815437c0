"""Material library sources (set A): wood planks, raw wood, bricks, ceramic tiles, leather, woven
fabric. Each builds, evaluates at 64 px with every material map in range, stays within the node and
parameter budgets, and its main exposed parameter really drives the maps (the binding works)."""
from __future__ import annotations

import importlib

import pytest
import torch

SOURCES = ("wood_planks", "raw_wood", "bricks", "ceramic_tiles", "leather", "woven_fabric")
CHANNELS = {"basecolor": 4, "normal": 4, "roughness": 1, "metallic": 1, "height": 1}


def _module(name):
    return importlib.import_module(f"blender_match.library.sources.{name}")


@pytest.fixture(scope="module")
def built():
    torch.manual_seed(0)
    out = {}
    for name in SOURCES:
        g = _module(name).build()
        with torch.no_grad():
            out[name] = (g, {k: v.detach() for k, v in g(size=64, seed=0).items()})
    return out


@pytest.mark.parametrize("name", SOURCES)
def test_source_contract(name):
    mod = _module(name)
    assert mod.__doc__ and len(mod.__doc__.strip()) > 100
    assert callable(mod.build) and isinstance(mod.SAMPLE_RANGES, dict) and mod.SAMPLE_RANGES


@pytest.mark.parametrize("name", SOURCES)
def test_maps_exist_with_channels_and_range(built, name):
    g, maps = built[name]
    for usage, channels in CHANNELS.items():
        assert usage in maps, f"{name}: no {usage} output"
        m = maps[usage]
        assert m.dim() == 4 and m.shape[1] == channels and m.shape[-2:] == (64, 64), (name, usage, m.shape)
        assert torch.isfinite(m).all(), (name, usage)
        assert m.min() >= 0.0 and m.max() <= 1.0, (name, usage, float(m.min()), float(m.max()))
    assert float(maps["metallic"].max()) == 0.0, f"{name}: a dielectric material must have metallic 0"
    assert float(maps["height"].std()) > 0.01, f"{name}: flat height"


@pytest.mark.parametrize("name", SOURCES)
def test_node_and_parameter_budgets(built, name):
    g, _ = built[name]
    assert 20 <= len(g.nodes) <= 150, (name, len(g.nodes))
    g.set_mode("exposed_plus")
    assert 30 <= g.num_params() <= 200, (name, g.num_params())
    assert 3 <= len(g.exposed.kinds) <= 6, (name, list(g.exposed.kinds))


@pytest.mark.parametrize("name", SOURCES)
def test_sample_ranges_name_real_parameters(built, name):
    g, _ = built[name]
    for key, (lo, hi) in _module(name).SAMPLE_RANGES.items():
        node, _, param = key.partition(".")
        if node == "exposed":
            assert param in g.exposed.ranges, (name, key)
            rlo, rhi = g.exposed.ranges[param]
        else:
            assert node in g.nodes and param in g.nodes[node].theta, (name, key)
            assert param not in g.bindings.get(node, {}), f"{name}: {key} is bound to an exposed parameter"
            rlo, rhi = g.nodes[node].ranges[param]
        los = lo if isinstance(lo, (tuple, list)) else [lo]
        his = hi if isinstance(hi, (tuple, list)) else [hi]
        assert len(los) == len(his), (name, key)
        for a, b in zip(los, his):
            assert rlo - 1e-6 <= a <= b <= rhi + 1e-6, (name, key, (a, b), (rlo, rhi))


@pytest.mark.parametrize("name", SOURCES)
def test_main_exposed_parameter_drives_the_maps(built, name):
    g, before = built[name]
    main = next(iter(g.exposed.kinds))
    lo, hi = g.exposed.ranges[main]
    current = g.exposed.values()[main]
    target = torch.where(current > (lo + hi) / 2, torch.full_like(current, lo + 0.1 * (hi - lo)),
                         torch.full_like(current, lo + 0.9 * (hi - lo)))
    g.exposed.set_values(**{main: target})
    try:
        with torch.no_grad():
            after = g(size=64, seed=0)
    finally:
        g.exposed.set_values(**{main: current})
    change = max(float((after[u] - before[u]).abs().max()) for u in ("basecolor", "height"))
    assert change > 0.02, f"{name}: exposed {main} does not change basecolor or height"
