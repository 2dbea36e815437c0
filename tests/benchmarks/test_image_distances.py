"""The yardstick distances of the benchmarks (benchmarks.image_distances) on known answers: an
image against itself, against another seed of the same material, against another material."""
from __future__ import annotations

import numpy as np
import pytest
import torch

from blender_match.benchmarks.image_distances import (
    as_array,
    colour_distance,
    laplacian_pyramid,
    patch_distance,
    resize,
)
from blender_match.diffmat.render import render_maps
from blender_match.library import load_library_graph


def render(name: str, seed: int, size: int = 256) -> torch.Tensor:
    with torch.no_grad():
        return render_maps(load_library_graph(name)(size=size, seed=seed))[:1]


@pytest.fixture(scope="module")
def asphalt():
    return render("asphalt", 7), render("asphalt", 8)


def test_an_image_is_at_distance_zero_from_itself(asphalt):
    assert patch_distance(asphalt[0], asphalt[0]) == pytest.approx(0.0, abs=1e-9)
    assert colour_distance(asphalt[0], asphalt[0]) == pytest.approx(0.0, abs=1e-9)


def test_another_seed_is_near_and_another_material_is_far(asphalt):
    same_material = patch_distance(asphalt[0], asphalt[1])
    other_material = patch_distance(asphalt[0], render("plaster", 7))
    assert other_material > 5 * same_material
    assert colour_distance(asphalt[0], render("plaster", 7)) > colour_distance(asphalt[0], asphalt[1])


def test_erasing_fine_grain_is_seen(asphalt):
    """A blur keeps the colours but loses the speckle: the patch distance grows many times."""
    blurred = torch.nn.functional.avg_pool2d(asphalt[1], 5, 1, 2, count_include_pad=False)
    assert patch_distance(asphalt[0], blurred) > 3 * patch_distance(asphalt[0], asphalt[1])


def test_colour_distance_of_a_known_shift():
    grey = np.full((64, 64, 3), 0.5)
    assert colour_distance(grey, grey + 0.1) == pytest.approx(100 * np.sqrt(3 * 0.01))


def test_resize_and_pyramid_shapes():
    image = np.random.default_rng(0).random((384, 300, 3))
    square = as_array(image)
    assert square.shape == (300, 300, 3)
    small = resize(square, 256)
    assert small.shape == (256, 256, 3) and abs(small.mean() - square.mean()) < 1e-3
    levels = laplacian_pyramid(small)
    assert [lv.shape[0] for lv in levels] == [256, 128, 64, 32]
    assert resize(np.ones((512, 512, 3)), 256).shape == (256, 256, 3)


def test_bad_shapes_are_refused():
    with pytest.raises(ValueError, match="expected an"):
        patch_distance(np.zeros((8, 8)), np.zeros((8, 8)))
