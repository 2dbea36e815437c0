"""The optimiser (diffmat.optim): the loss falls, parameters move toward the truth on a small graph
(the paper's recovery protocol: different noise seeds for target and fit), determinism, cancel,
progress, and no NaN on extreme photos. Small images keep it quick."""
from __future__ import annotations

import math

import pytest
import torch

from blender_match.diffmat import MaterialGraph
from blender_match.diffmat.descriptor import TextureDescriptor
from blender_match.diffmat.errors import DiffMatError
from blender_match.diffmat.optim import (
    PAPER_SCHEDULE,
    QUALITY_SCHEDULES,
    Schedule,
    Stage,
    TargetLoss,
    fit,
    quarter_crop,
)
from blender_match.diffmat.render import render_maps
from blender_match.errors import Cancelled

SMALL = Schedule("test", (Stage(64, (64,), 40, 0.05),), patience=None)


@pytest.fixture(scope="module")
def descriptor():
    return TextureDescriptor(scales=(64,))


def two_tone(c1=(0.5, 0.5, 0.5, 1.0), c2=(0.5, 0.5, 0.5, 1.0), rough=(0.5, 0.5, 0.5, 1.0)) -> MaterialGraph:
    """Two colours mixed by a fixed noise, a uniform roughness, a normal from the noise."""
    g = MaterialGraph("two_tone")
    g.add("noise", "clouds_2", seed=3)
    g.add("c1", "uniform", outputcolor=c1)
    g.add("c2", "uniform", outputcolor=c2)
    g.add("mix", "blend", {"source": "c1", "destination": "c2", "opacity": "noise"})
    g.add("rough", "uniform", outputcolor=rough)
    g.add("nrm", "normal", {"input1": "noise"})
    g.set_output("basecolor", "mix")
    g.set_output("roughness", "rough")
    g.set_output("normal", "nrm")
    for fixed in ("noise", "c2", "mix", "nrm", "rough"):  # c1 is to be found
        g.freeze(fixed)
    return g


def truth_graph():
    return two_tone((0.85, 0.35, 0.15, 1.0), (0.15, 0.3, 0.7, 1.0), (0.25, 0.25, 0.25, 1.0))


def start_graph():
    return two_tone(c2=(0.15, 0.3, 0.7, 1.0), rough=(0.25, 0.25, 0.25, 1.0))


def target_photo(seed=7, size=64):
    with torch.no_grad():
        return render_maps(truth_graph()(size=size, seed=seed))


def test_fit_recovers_a_small_graph(descriptor):
    truth = truth_graph().get_vector()
    graph = start_graph()
    start = graph.get_vector()
    result = fit(graph, TargetLoss(target_photo(), descriptor), SMALL, seed=0)
    assert result.loss_final < 0.75 * result.loss_initial  # the noise differs: the floor is not 0
    assert result.iterations == 40 and len(result.history) == 40
    # the colour moves toward the truth (the noise differs: seed 0 against 7)
    before = (start - truth).abs().mean()
    after = (result.theta - truth).abs().mean()
    assert after < 0.6 * before, (before, after)
    # the graph itself is left unchanged
    torch.testing.assert_close(graph.get_vector(), start)


def test_fit_is_deterministic_and_reports_progress(descriptor):
    events = []
    schedule = SMALL.scaled(6)
    a = fit(start_graph(), TargetLoss(target_photo(), descriptor), schedule, seed=1, progress=events.append)
    b = fit(start_graph(), TargetLoss(target_photo(), descriptor), schedule, seed=1)
    torch.testing.assert_close(a.theta, b.theta, rtol=0, atol=0)
    assert [e["iteration"] for e in events] == list(range(1, 7))
    assert all(e["eta_seconds"] >= 0 and math.isfinite(e["loss"]) for e in events)
    assert events[-1]["eta_seconds"] == 0


def test_cancel_stops_the_fit(descriptor):
    calls = []

    def cancel():
        calls.append(1)
        return len(calls) > 3

    with pytest.raises(Cancelled):
        fit(start_graph(), TargetLoss(target_photo(), descriptor), SMALL, cancel=cancel)
    assert len(calls) == 4


def test_plateau_ends_a_stage_early(descriptor):
    target = target_photo()
    graph = start_graph()
    graph.set_vector(truth_graph().get_vector())  # already at the truth: nothing left to gain
    schedule = Schedule("plateau", (Stage(64, (64,), 200, 0.001),), patience=5, min_improvement=0.05)
    result = fit(graph, TargetLoss(target, descriptor), schedule)
    assert result.stopped == "plateau" and result.iterations < 50


def test_the_best_point_is_kept_not_the_last(descriptor):
    # a huge learning rate makes the last steps jump around; the result is the best point seen
    schedule = Schedule("wild", (Stage(64, (64,), 12, 5.0, final_lr_ratio=1.0),))
    loss = TargetLoss(target_photo(), descriptor)
    result = fit(start_graph(), loss, schedule)
    with torch.no_grad():
        rescored = float(loss(start_graph(), result.theta[None], 64, (64,))[0])
    assert rescored == pytest.approx(result.loss_final, rel=1e-4)
    assert result.loss_final <= min(h[2] for h in result.history) + 1e-9


@pytest.mark.parametrize("kind", ["black", "white", "saturated", "noise"])
def test_extreme_photos_give_finite_fits_on_a_library_graph(kind, descriptor):
    from blender_match.library import load_library_graph

    g = torch.Generator().manual_seed(0)
    photo = {"black": torch.zeros(1, 3, 64, 64), "white": torch.ones(1, 3, 64, 64),
             "saturated": torch.tensor([1.0, 0.0, 0.0]).reshape(1, 3, 1, 1).expand(1, 3, 64, 64).clone(),
             "noise": torch.rand(1, 3, 64, 64, generator=g)}[kind]
    graph = load_library_graph("plaster")
    result = fit(graph, TargetLoss(photo, descriptor), Schedule("x", (Stage(64, (64,), 4, 0.05),)))
    assert torch.isfinite(result.theta).all() and result.theta.min() >= 0 and result.theta.max() <= 1
    assert math.isfinite(result.loss_final) and result.loss_final <= result.loss_initial


def test_schedules_are_well_formed():
    assert PAPER_SCHEDULE.stages[0].lr == 5e-4 and PAPER_SCHEDULE.stages[0].scales == (512, 256, 128)
    for name, schedule in QUALITY_SCHEDULES.items():
        assert schedule.name == name
        for stage in schedule.stages:
            assert max(stage.scales) <= stage.size
    scaled = QUALITY_SCHEDULES["balanced"].scaled(4)
    assert all(s.iterations >= 1 for s in scaled.stages) and scaled.iterations <= 5
    with pytest.raises(DiffMatError, match="at least 1"):
        SMALL.scaled(0)


def test_every_preset_renders_at_the_photo_size():
    """A graph rendered below the photo's size is not the photo shrunk (fine relief shades
    non-linearly): every stage renders at the size the pipeline gives the photo."""
    from blender_match.pipeline import PHOTO_SIZE

    assert {s.size for schedule in QUALITY_SCHEDULES.values() for s in schedule.stages} == {PHOTO_SIZE}


def test_every_preset_ends_describing_the_grain_at_its_own_size():
    """The last stage of every preset sees a grain of a few pixels at the render's size: described
    at half that size or more, or with a full-resolution crop."""
    for schedule in QUALITY_SCHEDULES.values():
        last = schedule.stages[-1]
        assert last.crop is not None or 2 * max(last.scales) >= last.size, schedule.name


def test_a_crop_shows_the_grain_that_a_small_description_averages_away(descriptor):
    """A one-pixel checker over a flat grey: described whole at a quarter of its size it is the
    flat grey, a crop of it at full resolution is not."""
    graph = MaterialGraph("flat")
    graph.add("grey", "uniform", outputcolor=(0.5, 0.5, 0.5, 1.0))
    graph.set_output("basecolor", "grey")
    theta = graph.get_vector()[None]
    with torch.no_grad():
        flat = render_maps(graph(size=128, seed=0))
        rows, cols = torch.meshgrid(torch.arange(128), torch.arange(128), indexing="ij")
        checker = ((rows + cols) % 2 * 2 - 1).float()
        loss = TargetLoss((flat * (1 + 0.5 * checker)).clamp(0, 1), TextureDescriptor(scales=(32,), vgg=descriptor.vgg))
        whole = float(loss(graph, theta, 128, (32,))[0])
        cropped = float(loss(graph, theta, 128, (32,), crop=32)[0])
        itself = TargetLoss(flat, TextureDescriptor(scales=(32,), vgg=descriptor.vgg))
        assert float(itself(graph, theta, 128, (32,), crop=32)[0]) < 1e-6
    assert cropped > 100 * whole


def test_the_crop_window_is_off_the_highlight_and_inside_the_image():
    """A flash photo's highlight sits at its centre: the window is centred a quarter in."""
    image = torch.arange(512 * 512, dtype=torch.float32).reshape(1, 1, 512, 512)
    window = quarter_crop(image, 128)
    assert window.shape[-2:] == (128, 128) and window[0, 0, 0, 0] == image[0, 0, 64, 64]
    assert quarter_crop(image, 384)[0, 0, 0, 0] == image[0, 0, 0, 0]
    assert quarter_crop(image[..., :64, :64], 128).shape[-1] == 64


def test_a_render_is_never_larger_than_the_photo(descriptor):
    """A 64-px photo: a stage of 512 px described at 512/256/128 renders and describes at 64."""
    graph = start_graph()
    loss = TargetLoss(target_photo(size=64), TextureDescriptor(scales=(64,), vgg=descriptor.vgg))
    theta = graph.get_vector()[None]
    with torch.no_grad():
        capped = loss(graph, theta, 512, (512, 256, 128))
        direct = loss(graph, theta, 64, (64,))
    assert torch.equal(capped, direct)


def test_nothing_to_fit_is_an_error(descriptor):
    graph = start_graph()
    graph.freeze("*")
    with pytest.raises(DiffMatError, match="nothing to fit"):
        fit(graph, TargetLoss(target_photo(), descriptor), SMALL)


def _library_names():
    from blender_match.library import library_names

    return library_names()


@pytest.mark.parametrize("name", _library_names())
def test_every_library_graph_fits_a_noise_photo_without_nan(name, descriptor):
    from blender_match.library import load_library_graph

    photo = torch.rand(1, 3, 64, 64, generator=torch.Generator().manual_seed(1))
    result = fit(load_library_graph(name), TargetLoss(photo, descriptor), Schedule("x", (Stage(64, (64,), 2, 0.05),)))
    assert torch.isfinite(result.theta).all()
    assert all(math.isfinite(h[2]) for h in result.history) and result.loss_final <= result.loss_initial
