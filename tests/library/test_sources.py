"""The library's authoring contract, one parametrised test over every material source that
``library.source_names()`` finds (a new source cannot be missed): each source module documents
itself, builds within the node and parameter budgets, evaluates at 64 px to every material map in
range, names real parameters in its sampling ranges, and its main exposed parameter really drives
the maps (the binding works)."""
from __future__ import annotations

import pytest
import torch

from blender_match.library import FAMILIES, build_source, source_module, source_names

CHANNELS = {"basecolor": 4, "normal": 4, "roughness": 1, "metallic": 1, "height": 1}
SOURCES = source_names()


@pytest.fixture(scope="module")
def built():
    cache = {}

    def get(name):
        if name not in cache:
            torch.manual_seed(0)
            graph = build_source(name)
            with torch.no_grad():
                cache[name] = (graph, {k: v.detach() for k, v in graph(size=64, seed=0).items()})
        return cache[name]

    return get


def test_every_source_is_found():
    assert len(SOURCES) >= 16 and "plaster" in SOURCES


@pytest.mark.parametrize("name", SOURCES)
def test_source_documents_itself(name):
    mod = source_module(name)
    assert mod.__doc__ and len(mod.__doc__.strip()) > 100, f"sources/{name}.py: no docstring"
    assert callable(mod.build) and isinstance(mod.SAMPLE_RANGES, dict) and mod.SAMPLE_RANGES
    assert mod.FAMILY in FAMILIES, f"sources/{name}.py: FAMILY {mod.FAMILY!r} is not a library family"


@pytest.mark.parametrize("name", SOURCES)
def test_maps_exist_with_channels_and_range(built, name):
    _, maps = built(name)
    for usage, channels in CHANNELS.items():
        assert usage in maps, f"{name}: no {usage} output"
        m = maps[usage]
        assert m.shape == (1, channels, 64, 64), (name, usage, m.shape)
        assert torch.isfinite(m).all(), (name, usage)
        assert m.min() >= 0.0 and m.max() <= 1.0, (name, usage, float(m.min()), float(m.max()))
    assert float(maps["height"].std()) > 0.01, f"{name}: flat height"
    if source_module(name).FAMILY == "metal":
        assert float(maps["metallic"].max()) > 0.5, f"{name}: a metal with no metallic area"
    elif "metallic" not in name:
        assert float(maps["metallic"].max()) == 0.0, f"{name}: a dielectric material must have metallic 0"


@pytest.mark.parametrize("name", SOURCES)
def test_node_and_parameter_budgets(built, name):
    graph, _ = built(name)
    assert 20 <= len(graph.nodes) <= 150, (name, len(graph.nodes))
    graph.set_mode("exposed_plus")
    assert 30 <= graph.num_params() <= 200, (name, graph.num_params())
    assert 3 <= len(graph.exposed.kinds) <= 8, (name, list(graph.exposed.kinds))
    graph.set_mode("exposed")


@pytest.mark.parametrize("name", SOURCES)
def test_sample_ranges_name_real_parameters(built, name):
    graph, _ = built(name)
    for key, (lo, hi) in source_module(name).SAMPLE_RANGES.items():
        node, _, param = key.partition(".")
        if node == "exposed":
            assert param in graph.exposed.ranges, (name, key)
            rlo, rhi = graph.exposed.ranges[param]
        else:
            assert node in graph.nodes and param in graph.nodes[node].theta, (name, key)
            assert param not in graph.bindings.get(node, {}), f"{name}: {key} is bound to an exposed parameter"
            rlo, rhi = graph.nodes[node].ranges[param]
        los = lo if isinstance(lo, (tuple, list)) else [lo]
        his = hi if isinstance(hi, (tuple, list)) else [hi]
        assert len(los) == len(his), (name, key)
        for a, b in zip(los, his):
            assert rlo - 1e-6 <= a <= b <= rhi + 1e-6, (name, key, (a, b), (rlo, rhi))


@pytest.mark.parametrize("name", SOURCES)
def test_main_exposed_parameter_drives_the_maps(built, name):
    graph, before = built(name)
    main = next(iter(graph.exposed.kinds))
    lo, hi = graph.exposed.ranges[main]
    current = graph.exposed.values()[main]
    target = torch.where(current > (lo + hi) / 2, torch.full_like(current, lo + 0.1 * (hi - lo)),
                         torch.full_like(current, lo + 0.9 * (hi - lo)))
    graph.exposed.set_values(**{main: target})
    try:
        graph.clear_cache()
        with torch.no_grad():
            after = graph(size=64, seed=0)
    finally:
        graph.exposed.set_values(**{main: current})
        graph.clear_cache()
    change = max(float((after[u] - before[u]).abs().max()) for u in ("basecolor", "height"))
    assert change > 0.02, f"{name}: exposed {main} does not change basecolor or height"
