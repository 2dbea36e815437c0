"""The matching pipeline (photo in, result folder out) and ``blender-match match``: files, report,
determinism, progress, cancel, refusal to overwrite, re-rendering from params.json, bad input.
Tiny budgets and sizes: these check the plumbing; tests/test_optim.py checks the fitting."""
from __future__ import annotations

import json

import numpy as np
import pytest
import torch
from PIL import Image

from blender_match.cli import main
from blender_match.diffmat.calibration import framed_maps, solve_gain, unclipped_level
from blender_match.diffmat.render import FlashCamera, linear_to_srgb, render_maps, srgb_to_linear
from blender_match.diffmat.zoom_search import ZOOMS
from blender_match.errors import BlenderMatchError, Cancelled
from blender_match.image_files import write_png
from blender_match.photo import load_photo
from blender_match.pipeline import MatchOptions, finish_calibration, fit_photo, load_graph, match_photo, render_params
from blender_match.safe_files import FileWriteError

TINY = dict(graph="plaster", size=64, quality="draft", iterations=2)
EXPECTED = {"basecolor.png", "normal.png", "roughness.png", "metallic.png", "height.png",
            "ambientocclusion.png", "params.json", "comparison.png", "report.json"}


@pytest.fixture
def photo(shared_dir):
    return shared_dir / "data" / "photos" / "real_plaster_wall_beige_desch18.png"


def png_size(path):
    data = path.read_bytes()
    return int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big"), data[24]


def test_match_writes_the_result_folder_and_report(photo, tmp_path):
    events = []
    report = match_photo(photo, tmp_path / "out", MatchOptions(**TINY), progress=events.append)
    out = tmp_path / "out"
    assert {p.name for p in out.iterdir()} == EXPECTED
    saved = json.loads((out / "report.json").read_text())
    assert saved == json.loads(json.dumps(report))
    for key in ("graph", "loss_initial", "loss_final", "iterations", "seconds", "device", "stages"):
        assert key in report
    assert report["graph"] == "plaster" and report["device"] == "cpu" and report["iterations"] == 2
    assert report["loss_final"] <= report["loss_initial"]
    assert set(report["stages"]) == {"reading photo", "fitting", "writing maps"}
    assert report["maps"]["metallic"]["flat"] is not None  # plaster: a constant, reported as such
    assert png_size(out / "basecolor.png") == (64, 64, 8)
    assert png_size(out / "normal.png") == (64, 64, 16) and png_size(out / "height.png") == (64, 64, 16)
    # progress: stages in order, the fraction never goes back and ends near 1
    stages = [e["stage"] for e in events]
    assert stages[0] == "reading photo" and stages[-1] == "writing maps"
    assert [s for i, s in enumerate(stages) if i == 0 or stages[i - 1] != s] == ["reading photo", "fitting",
                                                                              "writing maps"]
    fractions = [e["fraction"] for e in events]
    assert fractions == sorted(fractions) and fractions[-1] > 0.85
    fitting = [e for e in events if e["stage"] == "fitting" and "iteration" in e]
    assert [e["iteration"] for e in fitting] == [1, 2] and all(e["graph_count"] == 1 for e in fitting)


def test_same_seed_same_maps_and_rerender_at_another_size(photo, tmp_path):
    match_photo(photo, tmp_path / "a", MatchOptions(**TINY))
    match_photo(photo, tmp_path / "b", MatchOptions(**TINY))
    for name in ("basecolor.png", "normal.png", "roughness.png", "height.png", "params.json"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes(), name
    report = render_params(tmp_path / "a" / "params.json", tmp_path / "big", 128)
    assert png_size(tmp_path / "big" / "basecolor.png")[:2] == (128, 128)
    assert report["rendered_from"].endswith("params.json") and report["size"] == 128
    params = json.loads((tmp_path / "a" / "params.json").read_text())
    assert params["source"] == "plaster" and params["seed"] == 0 and params["params"]
    assert params["params"]["calibration.basecolor_gain"] != [1.0, 1.0, 1.0]  # the photo's exposure, carried
    render_params(tmp_path / "a" / "params.json", tmp_path / "same", 64)
    same, first = (np.asarray(Image.open(tmp_path / d / "basecolor.png"), dtype=np.int16) for d in ("same", "a"))
    assert np.abs(same - first).max() <= 1  # params.json rounds to 6 decimals


@pytest.mark.parametrize("exposure", [0.6, 1.5])
def test_the_fitted_base_colour_takes_the_photos_exposure_and_white_balance(photo, exposure):
    """The photo, darkened and tinted in linear light: the calibrated render has its level (``unclipped_level``)
    (over unclipped pixels); without calibration the gain stays one."""
    image = load_photo(photo, 128)
    shifted = linear_to_srgb(srgb_to_linear(image) * exposure * torch.tensor([1.0, 0.85, 0.7]).view(1, 3, 1, 1))
    match = fit_photo(shifted, MatchOptions(**TINY))
    with torch.no_grad():
        rendered = render_maps(framed_maps(match.graph, 128, seed=0), match.camera)[:1]
    assert torch.allclose(unclipped_level(rendered), unclipped_level(shifted), rtol=0.03)
    assert match.report["calibration"]["basecolor_gain"] == pytest.approx(match.graph.calibration.gain().tolist(),
                                                                          abs=1e-4)
    plain = fit_photo(shifted, MatchOptions(**TINY, calibrate=False))
    assert "basecolor_gain" not in plain.report["calibration"]
    assert torch.equal(plain.graph.calibration.gain(), torch.ones(3))
    ideal = fit_photo(shifted, MatchOptions(**TINY, lighting=False))
    assert "falloff" not in ideal.report["calibration"] and ideal.camera == FlashCamera()


def test_finish_calibration_gives_a_moved_material_the_photos_level_again(photo):
    """The gain solved for a start no longer fits once the fit has moved the colour: every match (and
    ``bench recovery``, which scores what a match delivers) solves it again for the fitted material."""
    image = load_photo(photo, 64)
    graph = load_graph("plaster")
    solve_gain(graph, image, seed=0)
    started = graph.calibration.gain().clone()
    theta = graph.get_vector()
    colour = [i for i, name in enumerate(graph.param_names()) if name.startswith("exposed.color")]
    theta[colour] *= 0.5  # a darker plaster than the start's (within the gain's three stops)
    graph.set_vector(theta)
    camera, entries = finish_calibration(graph, image, 0, FlashCamera())
    with torch.no_grad():
        rendered = render_maps(framed_maps(graph, 64, seed=0), camera)[:1]
    assert torch.allclose(unclipped_level(rendered), unclipped_level(image), rtol=0.03)
    assert (graph.calibration.gain() > started * 2).all()
    assert entries["basecolor_gain"] == pytest.approx(graph.calibration.gain().tolist(), abs=1e-4)
    assert set(entries) == {"zoom", "falloff", "basecolor_gain"}
    gain = graph.calibration.gain().clone()
    assert set(finish_calibration(graph, image, 0, FlashCamera(), lighting=False, calibrate=False)[1]) == {"zoom"}
    assert torch.equal(graph.calibration.gain(), gain)


def test_a_fixed_zoom_is_reported_carried_and_checked(photo, tmp_path):
    """``zoom`` fixes the texture periods across the photo: report.json and params.json carry it, the
    maps stay one period at the asked size, and a re-render keeps it; a zoom out of range is refused."""
    report = match_photo(photo, tmp_path / "z", MatchOptions(**TINY, zoom=2.0))
    assert report["calibration"]["zoom"] == 2.0
    params = json.loads((tmp_path / "z" / "params.json").read_text())
    assert params["params"]["calibration.zoom"] == 2.0
    assert png_size(tmp_path / "z" / "basecolor.png")[:2] == (64, 64)
    render_params(tmp_path / "z" / "params.json", tmp_path / "again", 64)
    assert json.loads((tmp_path / "again" / "params.json").read_text())["params"]["calibration.zoom"] == 2.0
    assert len(report["calibration"]["falloff"]) == 5  # the photo's flash, solved: in the report only
    assert not any(key.endswith("falloff") for key in params["params"])
    assert fit_photo(photo, MatchOptions(**TINY)).report["calibration"]["zoom"] == 1.0  # the default
    assert fit_photo(photo, MatchOptions(**TINY, zoom=None)).report["calibration"]["zoom"] in ZOOMS  # searched
    with pytest.raises(BlenderMatchError, match="zoom 16"):
        match_photo(photo, tmp_path / "bad", MatchOptions(**TINY, zoom=16))
    assert not (tmp_path / "bad").exists()


def test_fit_photo_returns_the_match_without_writing(photo, tmp_path, monkeypatch):
    """``fit_photo`` fits as ``match_photo`` does (same parameters) and writes nothing."""
    monkeypatch.chdir(tmp_path)
    match = fit_photo(photo, MatchOptions(**TINY))
    assert list(tmp_path.iterdir()) == []
    assert match.graph.name == "plaster" and match.photo.shape == (1, 3, 512, 512)
    assert match.report["iterations"] == 2 and set(match.report["stages"]) == {"reading photo", "fitting"}
    report = match_photo(photo, tmp_path / "out", MatchOptions(**TINY))
    assert report["loss_final"] == match.report["loss_final"]
    assert report["start"] == match.report["start"] and report["graph"] == match.graph.name


def test_cancel_writes_nothing(photo, tmp_path):
    seen = []

    def cancel():
        return any(e["stage"] == "fitting" for e in seen)

    with pytest.raises(Cancelled):
        match_photo(photo, tmp_path / "out", MatchOptions(**TINY), progress=seen.append, cancel=cancel)
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_existing_files_are_refused_before_any_work(photo, tmp_path):
    (tmp_path / "report.json").write_text("mine")
    with pytest.raises(FileWriteError, match="report.json: already exists"):
        match_photo(photo, tmp_path, MatchOptions(**TINY))
    assert (tmp_path / "report.json").read_text() == "mine"
    assert [p.name for p in tmp_path.iterdir()] == ["report.json"]
    match_photo(photo, tmp_path, MatchOptions(**TINY, overwrite=True))
    assert json.loads((tmp_path / "report.json").read_text())["graph"] == "plaster"


@pytest.mark.parametrize("kind", ["black", "white"])
def test_extreme_photos_give_finite_maps(kind, tmp_path):
    value = 0.0 if kind == "black" else 1.0
    path = tmp_path / f"{kind}.png"
    write_png(path, torch.full((1, 3, 160, 200), value))
    report = match_photo(path, tmp_path / "out", MatchOptions(**TINY))
    assert report["loss_final"] == report["loss_final"]  # not NaN
    assert (tmp_path / "out" / "basecolor.png").is_file()


@pytest.mark.parametrize("options, message", [
    (dict(quality="fast"), "quality 'fast'"),
    (dict(size=100), "size 100: expected a power of two"),
    (dict(device="tpu"), "device 'tpu'"),
    (dict(graph="no_such_graph"), "no_such_graph: not a bundled graph"),
])
def test_bad_options_are_one_line_errors(options, message, photo, tmp_path):
    with pytest.raises(BlenderMatchError, match=message):
        match_photo(photo, tmp_path / "out", MatchOptions(**{**TINY, **options}))
    assert not (tmp_path / "out").exists()


def test_cli_match_prints_the_report_and_errors_in_one_line(photo, tmp_path, capsys):
    out = tmp_path / "cli"
    argv = ["match", str(photo), "--graph", "plaster", "--out", str(out), "--size", "64", "--quality", "draft",
            "--iterations", "1", "--json"]
    assert main(argv) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["graph"] == "plaster" and report["size"] == 64
    assert main(argv) == 2  # the folder holds a result now: refused without --overwrite
    err = capsys.readouterr().err
    assert err.startswith("blender-match: error: ") and "already exists" in err and err.count("\n") == 1
    assert main(["match", str(tmp_path / "missing.jpg"), "--graph", "plaster", "--out", str(out)]) == 2
    assert "missing.jpg" in capsys.readouterr().err
