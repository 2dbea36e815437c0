"""Automatic graph selection and parameter prediction (blender_match.selection, issue 6)."""
from __future__ import annotations

import json

import pytest
import sbs_snippets as W
import torch

from blender_match.cli.match import print_summary
from blender_match.diffmat.calibration import CLIP_LEVEL
from blender_match.diffmat.descriptor import TextureDescriptor
from blender_match.diffmat.optim import TargetLoss, resize_square
from blender_match.diffmat.render import FlashCamera, linear_to_srgb, render_maps, srgb_to_linear
from blender_match.errors import OptionError
from blender_match.library import builtin_names, library_names, load_library_graph
from blender_match.pipeline import match_schedule
from blender_match.pipeline.user_library import bank_batch
from blender_match.selection import predictor
from blender_match.selection.bank import (
    DEFAULTS_INDEX,
    SampleSpace,
    bank_is_current,
    build_bank,
    describe,
    load_bank,
    measured_supersample,
    nearest,
    render_images,
)
from blender_match.selection.descriptor import DESCRIPTOR_DIM, compact_descriptor, descriptor_distance, shared_vgg
from blender_match.selection.fit import frame_start
from blender_match.selection.index import selection_index
from blender_match.selection.predictor import (
    ParamPredictor,
    fit_params,
    load_predictor,
    masked_l1,
    predictor_is_current,
    save_predictor,
)
from blender_match.selection.rank import (
    EXPOSURE_WEIGHT,
    NO_MODELS,
    SHORTLIST,
    TINT_WEIGHT,
    NoSelectionModels,
    available_models,
    correction_cost,
    order_by_simplicity,
    rank_graphs,
)
from blender_match.translator import translate
from blender_match.vocabulary import GAIN, ranked_alternatives


@pytest.fixture(autouse=True)
def _one_thread():
    """These tests render and describe many small images: one torch thread avoids the
    oversubscription that makes small ops crawl on a shared 2-core machine."""
    threads = torch.get_num_threads()
    torch.set_num_threads(1)
    yield
    torch.set_num_threads(threads)


def test_compact_descriptor_shape_and_determinism():
    vgg = shared_vgg()
    images = torch.rand(2, 3, 64, 64, generator=torch.Generator().manual_seed(1))
    with torch.no_grad():
        a = compact_descriptor(vgg, images, size=64)
        b = compact_descriptor(vgg, images, size=64)
    assert a.shape == (2, DESCRIPTOR_DIM) == (2, 2944)
    assert torch.isfinite(a).all()
    assert torch.equal(a, b)
    d = descriptor_distance(a, b)
    assert d.shape == (2, 2) and d[0, 0] == 0 and d[0, 1] > 0


def test_a_bank_rendered_one_sample_at_a_time_is_the_batched_bank(tmp_path):
    """The user library renders its bank one sample at a time on a CPU (``bank_batch``: the peak
    memory of one sample) and eight at a time elsewhere; the bank is the same either way."""
    assert bank_batch("cpu") == 1 and bank_batch(torch.device("cpu")) == 1 and bank_batch("cuda:0") == 8
    one = load_bank("plaster", build_bank("plaster", n=3, size=64, directory=tmp_path / "one", batch=1).parent)
    eight = load_bank("plaster", build_bank("plaster", n=3, size=64, directory=tmp_path / "eight").parent)
    assert one is not None and eight is not None
    assert torch.equal(one["thetas"], eight["thetas"])
    assert torch.allclose(one["descriptors"], eight["descriptors"], atol=2e-2)


def test_a_user_bank_holds_the_graphs_own_defaults_first(tmp_path):
    """A user graph's samples move every parameter at once; its bank also holds the authored
    defaults (index DEFAULTS_INDEX), which a render of the defaults finds first."""
    bank = load_bank("plaster", build_bank("plaster", n=2, size=64, directory=tmp_path, with_defaults=True).parent)
    assert bank is not None and bank["indices"].tolist() == [DEFAULTS_INDEX, 0, 1]
    space = SampleSpace("plaster")
    assert torch.equal(bank["thetas"][0], space.default) and torch.equal(bank["thetas"][2], space.vector(1))
    image = render_images(space.graph, space.default[None], bank["seed"], 64)
    assert nearest(bank, describe(image, size=64))[0]["index"] == DEFAULTS_INDEX


def test_a_graph_whose_look_depends_on_its_output_size_is_described_from_finer_renders(tmp_path):
    (tmp_path / "grain.sbs").write_text(W.white_noise_package())
    grain = translate(tmp_path / "grain.sbs").graph
    theta = grain.get_vector()[None]
    fine = render_images(grain, theta, 0, 32, factor=4)
    assert fine.shape[-1] == 32
    assert torch.equal(fine, resize_square(render_maps(grain(size=128, seed=0, theta=theta)).clamp(0, 1), 32))
    assert fine.std() < 0.5 * render_images(grain, theta, 0, 32).std()  # the pixel grain averages out
    assert measured_supersample(grain, 4) == 4
    space = SampleSpace("plaster")  # drawn relative to the texture: as it looks at 512, brought down
    assert measured_supersample(space.graph, 4) == 1


def test_bank_nearest_neighbour_finds_the_sample_itself(tmp_path):
    path = build_bank("plaster", n=3, size=64, directory=tmp_path)
    assert path == tmp_path / "plaster.bank.pt"
    stored = torch.load(path, weights_only=True)
    assert stored["codes"].dtype == torch.uint8 and stored["codes"].shape == (3, DESCRIPTOR_DIM)
    bank = load_bank("plaster", tmp_path)
    assert bank["descriptors"].shape == (3, DESCRIPTOR_DIM) and bank["thetas"].shape[0] == 3
    assert bank_is_current("plaster", tmp_path) and load_bank("marble", tmp_path) is None
    space = SampleSpace("plaster")
    theta = space.vector(1)
    assert torch.allclose(bank["thetas"][1], theta)
    image = render_images(space.graph, theta[None], bank["seed"], 64)
    hits = nearest(bank, describe(image, size=64), count=3)
    assert hits[0]["index"] == 1 and hits[0]["distance"] < 5e-3
    assert hits[1]["distance"] > 10 * hits[0]["distance"]
    assert torch.equal(hits[0]["theta"], bank["thetas"][1])


def test_the_selection_index_shortlists_the_graph_a_photo_comes_from(tmp_path):
    names = ["plaster", "marble", "bricks"]
    for name in names:
        build_bank(name, n=3, directory=tmp_path)
    index = selection_index(names, tmp_path)
    assert index.names == names and index.descriptors.shape == (9, DESCRIPTOR_DIM)
    assert selection_index(names, tmp_path) is index  # one index per process while nothing changes
    space = SampleSpace("marble")
    photo = render_images(space.graph, space.vector(2)[None], 0, 128)
    near = index.nearest_graphs(describe(photo))
    assert [e["graph"] for e in near][0] == "marble" and len(near) == 3
    assert near[0]["distance"] < near[1]["distance"] and torch.equal(near[0]["theta"], space.vector(2))
    build_bank("bricks", n=2, directory=tmp_path)  # a rebuilt bank makes a new index
    assert selection_index(names, tmp_path).descriptors.shape == (8, DESCRIPTOR_DIM)
    ranking = rank_graphs(photo, "bank", directory=tmp_path, shortlist=1)
    assert [e["graph"] for e in ranking] == ["marble"]  # only the shortlisted graph is rendered
    assert {e["graph"] for e in rank_graphs(photo, "bank", directory=tmp_path, shortlist=None)} == set(names)


def test_predictor_forward_range_and_weights_only_round_trip(tmp_path):
    torch.manual_seed(0)
    model = ParamPredictor(DESCRIPTOR_DIM, 7, hidden=16).eval()
    model.mask.copy_(torch.tensor([1, 1, 0, 1, 0, 1, 1], dtype=torch.bool))
    model.default.copy_(torch.linspace(0, 1, 7))
    x = torch.randn(5, DESCRIPTOR_DIM) * 3
    with torch.no_grad():
        y = model(x)
    assert y.shape == (5, 7) and (y >= 0).all() and (y <= 1).all()
    assert torch.equal(y[:, 2], torch.full((5,), model.default[2].item()))
    meta = {"graph": "plaster", "descriptor_dim": DESCRIPTOR_DIM, "params": 7, "hidden": 16, "layers": 2,
            "sketch": model.sketch}
    save_predictor(model, "plaster", meta, tmp_path)
    state = torch.load(tmp_path / "plaster.predictor.pt", weights_only=True)
    assert state["net.0.weight"].dtype == torch.float16 and "bucket" not in state  # the sketch is not stored
    assert state["net.0.weight"].shape[1] == model.sketch < DESCRIPTOR_DIM
    loaded = load_predictor("plaster", tmp_path)
    with torch.no_grad():
        assert torch.allclose(loaded(x), y, atol=2e-3)
    assert not predictor_is_current("plaster", tmp_path)  # no graph hash recorded: stale


def test_parameter_training_lowers_the_parameter_loss(monkeypatch):
    monkeypatch.setattr(predictor, "LR", 3e-3)  # the real rate learns over hundreds of steps, not 36
    gen = torch.Generator().manual_seed(0)
    P, n = 6, 96
    truth = torch.rand(n, P, generator=gen)
    signal = truth.repeat(1, 40)  # the parameters, spread over 240 of the descriptor's dimensions
    x = torch.cat([signal, torch.zeros(n, DESCRIPTOR_DIM - signal.shape[1])], dim=1) \
        + 0.01 * torch.randn(n, DESCRIPTOR_DIM, generator=gen)
    model = ParamPredictor(DESCRIPTOR_DIM, P, hidden=32)
    model.in_mean.copy_(x[:80].mean(0))
    model.in_std.copy_(x[:80].std(0).clamp_min(0.05))
    mask = torch.ones(P, dtype=torch.bool)
    with torch.no_grad():
        before = float(masked_l1(model.eval()(x[80:]), truth[80:], mask))
    after = fit_params(model, x[:80], truth[:80], x[80:], truth[80:], mask, 12, None, None, 0)
    assert after < 0.85 * before


def test_the_final_choice_prefers_the_simpler_graph_on_a_near_tie():
    entries = [{"graph": "big", "distance": 1.000, "nodes": 40, "params": 120},
               {"graph": "small", "distance": 1.015, "nodes": 25, "params": 60},
               {"graph": "fewer_params", "distance": 1.010, "nodes": 25, "params": 50},
               {"graph": "far", "distance": 1.3, "nodes": 10, "params": 10}]
    assert [e["graph"] for e in order_by_simplicity(entries)] == ["fewer_params", "small", "big", "far"]
    clear = [dict(entries[0], distance=0.9), *entries[1:]]
    assert order_by_simplicity(clear)[0]["graph"] == "big"


@pytest.mark.parametrize("name", ["brushed_metal", "granite"])
def test_a_colour_cast_and_a_clipped_highlight_keep_the_true_graph_first(name):
    """A library graph's render under a flash twice too strong, with a warm white balance (linear
    gains 1.5, 1, 0.6): part of it clips, its colours are off, and the full library's ranking still
    puts the graph first, scoring it with a gain that warms its base colour back towards the cast."""
    graph = load_library_graph(name)
    with torch.no_grad():
        hot = render_maps(graph(size=256, seed=11), FlashCamera(power=1.6))[:1]
    target = linear_to_srgb(srgb_to_linear(hot) * torch.tensor([1.5, 1.0, 0.6]).view(1, 3, 1, 1))
    assert float((target >= CLIP_LEVEL).any(dim=1).float().mean()) > 0.1
    first = rank_graphs(target)[0]
    assert first["graph"] == name
    assert first["gain"][0] > 1.2 * first["gain"][2], first["gain"]


@pytest.mark.parametrize("name", ["plaster", "marble"])
def test_the_ranking_offers_a_graphs_own_defaults_as_a_named_fit_does(name):
    """A render of the graph at its authored defaults: the defaults, which a named fit's start
    weighs too (``choose_start``), score nearer it than either model's proposal, and the ranking
    keeps them; a ranking by one model alone never offers them."""
    with torch.no_grad():
        photo = render_maps(load_library_graph(name)(size=256, seed=11))[:1].clamp(0, 1)
    (both,) = rank_graphs(photo, "both", graphs=[name])
    (predicted,) = rank_graphs(photo, "predictor", graphs=[name])
    (bank,) = rank_graphs(photo, "bank", graphs=[name])
    assert both["start"] == "default" and predicted["start"] == "predicted" and bank["start"] == "bank"
    assert both["distance"] < min(predicted["distance"], bank["distance"])
    assert torch.allclose(both["theta"], load_library_graph(name).get_vector())


def test_a_tint_costs_the_ranking_more_than_an_exposure():
    """The cost of a proposal's gain: none for none; a stop of exposure costs EXPOSURE_WEIGHT, a
    tint of a stop either way around the same exposure TINT_WEIGHT x its mean stops."""
    cost = correction_cost(torch.tensor([[1.0, 1.0, 1.0], [2.0, 2.0, 2.0], [0.5, 0.5, 0.5], [2.0, 1.0, 0.5]]))
    expected = torch.tensor([0.0, EXPOSURE_WEIGHT, EXPOSURE_WEIGHT, TINT_WEIGHT * 2 / 3])
    assert torch.allclose(cost, expected, atol=1e-6), cost
    assert TINT_WEIGHT > EXPOSURE_WEIGHT > 0


@pytest.mark.parametrize("calibrate", [True, False])
def test_a_fit_starts_with_the_photos_exposure_and_white_balance(calibrate):
    """``frame_start`` gives the graph, at its start, the base colour gain of a colour-cast photo of
    the graph itself (a warm cast, half a stop darker), unless told not to; the parameters stay."""
    graph = load_library_graph("plaster")
    cast = torch.tensor([1.4, 0.7, 0.5])
    graph.calibration.set_values(**{GAIN: cast})
    with torch.no_grad():
        photo = render_maps(graph(size=128, seed=3))[:1]
    graph.calibration.set_values(**{GAIN: torch.ones(3)})
    theta = graph.get_vector().clone()
    loss = TargetLoss(photo, TextureDescriptor(vgg=shared_vgg("cpu")))
    frame_start(graph, loss, theta, match_schedule("draft"), seed=3, zoom=1.0, lighting=False, calibrate=calibrate)
    expected = cast if calibrate else torch.ones(3)
    assert torch.allclose(graph.calibration.gain(), expected, rtol=0.03), graph.calibration.gain()
    assert torch.equal(graph.get_vector(), theta)


def test_missing_models_say_how_to_create_them(tmp_path):
    with pytest.raises(NoSelectionModels, match="blender-match train --all"):
        rank_graphs(torch.rand(1, 3, 64, 64), directory=tmp_path)
    assert "blender-match train --all" in NO_MODELS


def test_the_library_is_trained_and_indexed():
    names = library_names()
    assert len(names) >= 16
    missing = [n for n in names if not (predictor_is_current(n) and bank_is_current(n))]
    assert not missing, f"stale or missing selection models: {missing} (blender-match train --all)"
    assert available_models("both") == names
    from blender_match.library import MODELS_DIR, library_entry

    for name in names:
        meta = json.loads((MODELS_DIR / f"{name}.predictor.json").read_text())
        assert meta["params"] == library_entry(name)["params_optimizable"]
        assert meta["descriptor_dim"] == DESCRIPTOR_DIM and meta["training_samples"] > 0
    total = sum(p.stat().st_size for p in MODELS_DIR.glob("*.pt"))
    assert total < 50 * 2 ** 20


@pytest.mark.parametrize("name", builtin_names())
def test_the_shipped_banks_describe_what_the_engine_renders_now(name):
    """A node change that moves a library graph's look leaves its models describing renders the
    engine no longer draws, with no file hash to notice: re-rendering a bank's first samples must
    give their stored descriptors back (stored in 8 bits: about 2e-3 apart; another sample of the
    same graph is about 0.5 away)."""
    bank = load_bank(name)
    images = render_images(load_library_graph(name), bank["thetas"][:2], bank["seed"], bank["size"])
    moved = descriptor_distance(describe(images, "cpu", bank["size"]), bank["descriptors"][:2].float()).diagonal()
    assert float(moved.max()) < 0.01, (f"{name}: the engine renders it differently from its bank ({moved.tolist()}): "
                                       "raise diffmat.revision.RENDER_REVISION and retrain (blender-match train --all)")


def test_a_new_render_revision_makes_the_models_stale(monkeypatch):
    from blender_match.diffmat import revision
    from blender_match.selection import bank as bank_module

    assert bank_is_current("plaster") and predictor_is_current("plaster")
    monkeypatch.setattr(bank_module, "RENDER_REVISION", revision.RENDER_REVISION + 1)
    assert not bank_is_current("plaster") and not predictor_is_current("plaster")


def _synthetic_photo(tmp_path, name="marble", k=100_003, seed=300_001):
    from blender_match.image_files import write_png

    space = SampleSpace(name)
    image = render_images(space.graph, space.vector(k)[None], seed, 128)
    path = tmp_path / f"{name}.png"
    write_png(path, image)
    return path


def test_match_without_a_graph_selects_fits_and_reports(tmp_path, capsys):
    from blender_match.pipeline import MatchOptions, match_photo

    photo = _synthetic_photo(tmp_path)
    events = []
    report = match_photo(photo, tmp_path / "out", MatchOptions(size=64, quality="draft", iterations=2, candidates=3),
                         progress=events.append)
    saved = json.loads((tmp_path / "out" / "report.json").read_text())
    assert saved["graph"] == report["graph"]
    ranking = saved["ranking"]
    # the selection index lets the SHORTLIST graphs nearest the photo through to be rendered
    assert len(ranking) == SHORTLIST and set(e["graph"] for e in ranking) < set(library_names())
    assert all(e["distance"] >= 0 and len(e["gain"]) == 3 for e in ranking)
    distances = [e["distance"] for e in ranking]
    assert distances == sorted(distances)  # by distance alone: simplicity only picks among the fitted
    fitted = saved["fitted"]
    assert len(fitted) == 3 and [f["graph"] for f in fitted] == [e["graph"] for e in ranking[:3]]
    assert all(f["iterations"] >= 1 and f["loss_final"] >= 0 and f["seconds"] >= 0 for f in fitted)
    # each graph's loss says how it was measured (a graph dropped after the probe: the probe's size)
    assert all(f["loss_final"] == f["rounds"][-1]["loss_final"] and f["rounds"][-1]["measured_at"]["size"] > 0
               for f in fitted)
    assert saved["graph"] in [f["graph"] for f in fitted]
    assert (tmp_path / "out" / "basecolor.png").is_file()
    # the graphs ranked next after the kept one (the rest of the top 3), which the panel offers and
    # the command line prints
    alternatives = [e["graph"] for e in ranking if e["graph"] != saved["graph"]][:2]
    assert ranked_alternatives(saved) == alternatives and len(alternatives) == 2
    print_summary(saved, tmp_path / "out")
    lines = capsys.readouterr().out.splitlines()
    assert f"also close       {alternatives[0]}, {alternatives[1]} (ranked next: --graph NAME matches one of them)" \
        in lines
    assert lines[0].startswith(f"graph {saved['graph']}: loss ")
    stages = [e["stage"] for e in events]
    assert "selecting" in stages and "fitting" in stages
    fitting = [e for e in events if e["stage"] == "fitting" and "loss" in e]
    assert fitting and all(e["graph_count"] == 3 and 1 <= e["graph_index"] <= 3 for e in fitting)
    assert [e["fraction"] for e in events] == sorted(e["fraction"] for e in events)
    selecting = [e["fraction"] for e in events if e["stage"] == "selecting"]
    assert selecting[-1] > selecting[0]  # the bar moves while the library is ranked


def test_automatic_match_keeps_the_rankings_first_by_default(tmp_path):
    from blender_match.pipeline import MatchOptions, fit_photo

    assert MatchOptions().candidates == 1
    photo = _synthetic_photo(tmp_path)
    match = fit_photo(photo, MatchOptions(quality="draft", iterations=2))
    assert [f["graph"] for f in match.report["fitted"]] == [match.report["ranking"][0]["graph"]] == [match.source]
    with pytest.raises(OptionError, match="candidates 0"):
        fit_photo(photo, MatchOptions(quality="draft", iterations=2, candidates=0))


def test_match_with_a_named_graph_reports_its_start(tmp_path):
    from blender_match.pipeline import MatchOptions, match_photo

    photo = _synthetic_photo(tmp_path)
    report = match_photo(photo, tmp_path / "out", MatchOptions(graph="marble", size=64, quality="draft", iterations=1))
    assert report["start"] in ("default", "predicted", "bank")
    assert json.loads((tmp_path / "out" / "report.json").read_text())["start"] == report["start"]


def test_train_command_writes_models_and_skips_up_to_date_graphs(tmp_path, capsys):
    from blender_match.cli import main

    argv = ["train", "--graph", "plaster", "--models", str(tmp_path), "--samples", "10", "--bank", "2",
            "--epochs", "2", "--render-steps", "1", "--keep-data"]
    assert main(argv) == 0
    meta = json.loads((tmp_path / "plaster.predictor.json").read_text())
    assert meta["training_samples"] + meta["validation_samples"] == 10 and meta["bank_samples"] == 2
    assert meta["descriptor_dim"] == DESCRIPTOR_DIM and meta["dtype"] == "float16"
    assert {"val_param_error", "val_param_error_default", "graph_sha256", "seconds"} <= set(meta)
    assert predictor_is_current("plaster", tmp_path) and bank_is_current("plaster", tmp_path)
    assert load_bank("plaster", tmp_path)["descriptors"].shape == (2, DESCRIPTOR_DIM)
    assert (tmp_path / "plaster.train.pt").is_file()  # --keep-data
    assert main(argv) == 0
    assert "plaster: up to date (skipped)" in capsys.readouterr().out
    # --resume --force re-trains on the kept examples without rendering them again
    data = torch.load(tmp_path / "plaster.train.pt", weights_only=True)
    assert main(argv + ["--resume", "--force"]) == 0
    again = torch.load(tmp_path / "plaster.train.pt", weights_only=True)
    assert torch.equal(again["descriptors"], data["descriptors"]) and again["seconds"] == data["seconds"]


def _render_of(name: str, size: int = 64) -> torch.Tensor:
    return render_maps(load_library_graph(name)(size=size, seed=5)).clamp(0, 1)


@pytest.mark.parametrize("margin, kept", [(0.0, "bricks"), (1000.0, "plaster")])
def test_the_final_choice_handicaps_lower_ranked_graphs(monkeypatch, margin, kept):
    """A target rendered from bricks, ranked with plaster first: by the fits' losses alone bricks
    wins; with a handicap larger than any loss ratio, the ranking's first is kept."""
    from blender_match.diffmat.descriptor import TextureDescriptor
    from blender_match.diffmat.optim import TargetLoss
    from blender_match.pipeline import match_schedule
    from blender_match.selection import fit as fit_module

    with torch.no_grad():
        target = _render_of("bricks")
    monkeypatch.setattr(fit_module, "RANK_MARGIN", margin)
    ranking = []
    for name in ("plaster", "bricks"):
        graph = load_library_graph(name)
        entry = {"graph": name, "distance": 0.0, "theta": graph.get_vector(), "start": "default", "nodes": 1,
                 "params": 1}
        ranking.append(entry)
    loss = TargetLoss(target, TextureDescriptor(vgg=shared_vgg()))
    best, fits = fit_module.select_and_fit(loss, ranking, 2, match_schedule("draft", 2))
    assert best.graph == kept and [f.graph for f in fits] == ["plaster", "bricks"]
