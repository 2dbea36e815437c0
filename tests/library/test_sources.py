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


@pytest.mark.parametrize("name, painted", [("brushed_metal", {}), ("perforated_metal", {"paint": 1.0})])
def test_brushed_metals_are_anisotropic_and_the_fit_can_move_the_level(name, painted):
    """The level is a flat map bound to exposed parameters (a render's gradient reaches them; paint
    takes it away), the angle a pinned 0: the brushing streaks run along +u."""
    from blender_match.diffmat.render import render_maps

    torch.manual_seed(0)
    graph = build_source(name)
    maps = graph(size=32, seed=0)
    level, angle = maps["anisotropylevel"].detach(), maps["anisotropyangle"].detach()
    assert level.shape == angle.shape == (1, 1, 32, 32)
    assert float(level.max() - level.min()) < 1e-6 and float(level.mean()) > 0.3
    assert float(angle.abs().max()) == 0.0 and "outputcolor" in graph.bindings[graph.outputs["anisotropyangle"][0]]
    render_maps(maps).mean().backward()
    assert any(p.grad is not None and float(p.grad.abs().sum()) > 0 for p in graph.exposed.theta.values())
    if painted:
        graph.exposed.set_values(**{k: torch.tensor(v) for k, v in painted.items()})
        graph.clear_cache()
        with torch.no_grad():
            assert float(graph(size=32, seed=0)["anisotropylevel"].max()) == 0.0


def test_the_brushed_metal_streaks_run_along_u(built):
    """The angle map's 0 is where the streaks point: the height changes far more from row to row
    than along a row."""
    _, maps = built("brushed_metal")
    height = maps["height"][0, 0]
    across = float((height.roll(-1, 0) - height).pow(2).mean())
    along = float((height.roll(-1, 1) - height).pow(2).mean())
    assert across > 5 * along  # 8 times at 64 px
