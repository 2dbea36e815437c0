"""The zoom: the graph framed as the photo shows it (one period evaluated smaller or larger and
repeated or cropped), carried in params.json, never optimised, and found by ``search_zoom`` on a
target rendered at a known zoom."""
from __future__ import annotations

import pytest
import torch

from blender_match.diffmat import MaterialGraph
from blender_match.diffmat.calibration import framed_maps
from blender_match.diffmat.descriptor import TextureDescriptor
from blender_match.diffmat.optim import TargetLoss
from blender_match.diffmat.params_file import graph_params, load_params, save_params
from blender_match.diffmat.render import render_maps
from blender_match.diffmat.zoom_search import ZOOMS, search_zoom
from blender_match.vocabulary import CALIBRATION, ZOOM


def cells() -> MaterialGraph:
    """Large tiles with bevelled relief: a structure whose size the descriptor sees."""
    g = MaterialGraph("cells")
    g.add("tiles", "tile_generator", x_amount=4, y_amount=4)
    g.add("tint", "gradient", {"input1": "tiles"}, colors=(0.2, 0.15, 0.1, 1.0, 0.8, 0.6, 0.4, 1.0))
    g.add("relief", "normal", {"input1": "tiles"}, intensity=0.5)
    g.add("rough", "uniform", colorswitch=False, outputcolor=(0.5,) * 4)
    g.set_output("basecolor", "tint")
    g.set_output("normal", "relief")
    g.set_output("roughness", "rough")
    return g


@pytest.fixture(scope="module")
def descriptor():
    return TextureDescriptor(scales=(128,))


def test_zoom_one_is_the_graph_itself_and_other_zooms_repeat_or_crop_one_period():
    g = cells()
    plain = g(size=64, seed=2)
    framed = framed_maps(g, 64, seed=2)
    assert all(torch.equal(framed[u], plain[u]) for u in plain)
    g.calibration.set_values(**{ZOOM: 2.0})
    half = g(size=32, seed=2)
    framed = framed_maps(g, 64, seed=2)
    assert all(torch.equal(framed[u], half[u].repeat(1, 1, 2, 2)) for u in half)
    g.calibration.set_values(**{ZOOM: 0.5})
    double = g(size=128, seed=2)
    framed = framed_maps(g, 64, seed=2)
    assert all(torch.equal(framed[u], double[u][..., :64, :64]) for u in double)
    assert framed["basecolor"].shape[-1] == 64


def test_the_zoom_is_never_optimised_and_params_json_carries_it(tmp_path):
    g = cells()
    count = g.num_params()
    g.calibration.set_values(**{ZOOM: 2.0})
    assert g.num_params() == count
    assert graph_params(g)[f"{CALIBRATION}.{ZOOM}"] == pytest.approx(2.0)
    save_params(g, tmp_path / "params.json")
    fresh = cells()
    assert fresh.calibration.periods() == 1.0
    load_params(fresh, tmp_path / "params.json")
    assert fresh.calibration.periods() == pytest.approx(2.0)


@pytest.mark.parametrize("true_zoom", ZOOMS)
def test_search_finds_the_zoom_a_target_was_rendered_at(descriptor, true_zoom):
    """The target is the graph's own render framed at ``true_zoom`` with another noise seed; from
    the true parameters the search lands on that zoom and leaves the graph framed there."""
    g = cells()
    g.calibration.set_values(**{ZOOM: true_zoom})
    with torch.no_grad():
        target = render_maps(framed_maps(g, 128, seed=5))[:1]
    g.calibration.set_values(**{ZOOM: 1.0})
    loss = TargetLoss(target, descriptor)
    losses = search_zoom(g, loss, g.get_vector(), 128, (128,), seed=0)
    assert set(losses) == set(ZOOMS)
    assert g.calibration.periods() == true_zoom, losses
