"""``bench accuracy`` (issue 8): the metrics on known answers, the classification rule, the Pareto
front, the novel-light renderer, the evolution strategy, the selection adapter, and a tiny run
through the CLI that writes results.json, results.md and both charts. Sizes are 64 px and budgets
one or two iterations, on the cheapest library graph."""
from __future__ import annotations

import json
import math

import pytest
import torch

from blender_match.benchmarks import accuracy, accuracy_methods
from blender_match.benchmarks.accuracy_methods import Selection, Unavailable, _prefix_points, cap_schedule
from blender_match.benchmarks.accuracy_metrics import Scorer, classify, make_truth, map_rmse, pareto_front
from blender_match.benchmarks.accuracy_targets import stress
from blender_match.benchmarks.charts import convergence_chart, speed_accuracy_chart
from blender_match.benchmarks.evolution import evolve
from blender_match.diffmat.descriptor import TextureDescriptor
from blender_match.diffmat.optim import PAPER_SCHEDULE, QUALITY_SCHEDULES, FitResult, TargetLoss
from blender_match.diffmat.render import render_flash
from blender_match.library import apply_params, load_library_graph, sample_params
from blender_match.selection import NoSelectionModels

GRAPH = "woven_fabric"  # the cheapest library graph to evaluate
PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def descriptor():
    return TextureDescriptor(scales=(64,))


@pytest.fixture(scope="module")
def graph():
    return load_library_graph(GRAPH)


@pytest.fixture(scope="module")
def truth_theta():
    g = load_library_graph(GRAPH)
    apply_params(g, sample_params(GRAPH, 900))
    return g.get_vector()


def test_a_target_against_itself_scores_zero(graph, descriptor, truth_theta):
    photo, truth = make_truth(graph, truth_theta, 64, 1234)
    score = Scorer(descriptor, photo, 64, truth).score(graph, truth_theta)
    assert score["descriptor_loss"] == pytest.approx(0.0, abs=1e-7)
    assert score["param_error"] == 0.0
    assert set(score["map_rmse"]) >= {"basecolor", "normal", "roughness"}
    assert all(v == pytest.approx(0.0, abs=1e-7) for v in score["map_rmse"].values())
    assert score["novel_rmse"] == pytest.approx(0.0, abs=1e-7)


def test_a_shifted_noise_seed_keeps_the_look_but_not_the_pixels(graph, descriptor, truth_theta):
    photo, truth = make_truth(graph, truth_theta, 64, 1234)
    scorer = Scorer(descriptor, photo, 64, truth)
    shifted = scorer.score(graph, truth_theta, seed=1235)
    wrong = scorer.score(graph, (1 - truth_theta).clamp(0, 1))
    assert 0 < shifted["descriptor_loss"] < 0.5 * wrong["descriptor_loss"]
    assert shifted["param_error"] == 0.0
    assert shifted["map_rmse_mean"] > 0.01  # the same material, other noise: maps not aligned
    with torch.no_grad():
        other = graph(size=64, seed=1235, theta=truth_theta[None])
    assert map_rmse(other, truth.maps)["basecolor"] > 0.005


def test_classification_rule():
    assert classify(loss_start=1.0, loss_final=0.5, refused=True) == "refused"
    assert classify(loss_start=1.0, loss_final=0.5, error="RuntimeError: boom") == "failed"
    assert classify(loss_start=1.0, loss_final=math.nan) == "failed"
    assert classify(loss_start=1.0, loss_final=0.5, theta_finite=False) == "failed"
    assert classify(loss_start=1.0, loss_final=1.05) == "failed"  # worse than the start
    assert classify(loss_start=1.0, loss_final=1.005) == "degraded"  # within the noise tolerance
    assert classify(loss_start=1.0, loss_final=0.95) == "degraded"  # less than 10% better
    assert classify(loss_start=1.0, loss_final=0.5, param_error=0.3, param_error_default=0.2) == "degraded"
    assert classify(loss_start=1.0, loss_final=0.5, param_error=0.1, param_error_default=0.2) == "success"
    assert classify(loss_start=1.0, loss_final=0.85) == "success"


def test_pareto_front():
    points = [(1.0, 5.0), (2.0, 3.0), (2.0, 4.0), (3.0, 3.5), (4.0, 1.0), (0.5, math.nan), (5.0, 1.0)]
    assert pareto_front(points) == [0, 1, 4]
    assert pareto_front([]) == []
    assert pareto_front([(1.0, 1.0)]) == [0]


def test_novel_light_renderer():
    torch.manual_seed(1)
    base = torch.rand(1, 3, 16, 16, requires_grad=True)
    normal = torch.cat([torch.rand(1, 2, 16, 16) * 0.3 + 0.35, torch.ones(1, 1, 16, 16)], dim=1)
    rough, metal = torch.rand(1, 1, 16, 16), torch.rand(1, 1, 16, 16)
    flash = render_flash(base, normal, rough, metal)
    assert torch.equal(flash, render_flash(base, normal, rough, metal, light_offset=None))
    assert torch.allclose(render_flash(base, normal, rough, metal, light_offset=(0.0, 0.0)), flash, atol=1e-4)
    moved = render_flash(base, normal, rough, metal, light_offset=(0.5, 0.25))
    assert (moved - flash).abs().mean() > 0.01
    moved.sum().backward()
    assert torch.isfinite(base.grad).all() and base.grad.abs().sum() > 0


def test_evolution_strategy_is_deterministic_and_never_worse(graph, descriptor, truth_theta):
    photo, _ = make_truth(graph, truth_theta, 64, 1234)
    loss = TargetLoss(photo, descriptor)
    runs = [evolve(graph, loss, 2, population=2, parents=1, size=64, scales=(64,), seed=3) for _ in range(2)]
    assert torch.equal(runs[0].theta, runs[1].theta)
    assert runs[0].loss_final <= runs[0].loss_initial and math.isfinite(runs[0].loss_final)
    assert len(runs[0].history) == len(runs[0].snapshots) == 2


def test_prefix_points_are_what_a_shorter_fit_returns():
    start = torch.zeros(2)
    snaps = [(1.0, torch.full((2,), 0.1)), (2.0, torch.full((2,), 0.2)), (3.0, torch.full((2,), 0.3))]
    # history[i] is the loss of the point step i started from: start, snap 0, snap 1
    result = FitResult(theta=snaps[0][1], loss_initial=1.0, loss_final=0.5, iterations=3, seconds=3.0,
                       history=[(1.0, 1, 1.0), (2.0, 2, 0.5), (3.0, 3, 0.7)], snapshots=snaps)
    points = _prefix_points(result, start, [1, 2, 3], peak=0, evaluated_points=True)
    assert [p.budget for p in points] == [1, 2, 3]
    assert torch.equal(points[0].theta, start)  # one step: only the start was evaluated
    assert torch.equal(points[1].theta, snaps[0][1]) and torch.equal(points[2].theta, snaps[0][1])
    assert [p.seconds for p in points] == [1.0, 2.0, 3.0]


def test_cap_schedule():
    capped = cap_schedule(PAPER_SCHEDULE.scaled(3), 256)
    assert capped.stages[0].size == 256 and capped.stages[0].scales == (256, 128)
    best = cap_schedule(QUALITY_SCHEDULES["best"], 64)
    assert {s.size for s in best.stages} == {64} and all(s.scales == (64,) for s in best.stages)


def test_selection_adapter(monkeypatch):
    calls = []

    def rank_graphs(photo, method="both", *, device="cpu", graphs=None):
        calls.append((method, graphs))
        if method == "bank":
            raise FileNotFoundError("bank.pt")
        if graphs == ["marble"]:
            raise NoSelectionModels("automatic graph selection needs the selection models")
        return [{"graph": "bricks", "distance": 0.1, "theta": [0.5]}, {"graph": GRAPH, "distance": 0.2,
                                                                         "theta": torch.full((3,), 0.25)}]

    monkeypatch.setattr(accuracy_methods, "rank_graphs", rank_graphs)
    sel, photo = Selection(), torch.zeros(1, 3, 8, 8)
    theta, seconds = sel.start(photo, GRAPH, "predictor")
    assert torch.equal(theta, torch.full((3,), 0.25)) and seconds >= 0
    sel.start(photo, GRAPH, "predictor")
    assert calls == [("predictor", [GRAPH])]  # one graph ranked, cached per photo
    with pytest.raises(Unavailable, match="model files"):
        sel.start(photo, GRAPH, "bank")
    with pytest.raises(Unavailable, match="no model"):
        sel.start(photo, "marble", "predictor")
    with pytest.raises(Unavailable, match="no prediction"):
        sel.start(photo, "plaster", "predictor")


def test_stress_photos_go_through_the_loader():
    tiny = stress("tiny", GRAPH, 64)
    assert tiny.photo is None and "too small" in tiny.refusal
    wide = stress("nonsquare", GRAPH, 64)
    assert wide.photo.shape == (1, 3, 64, 64) and torch.isfinite(wide.photo).all()


def test_charts_are_written(tmp_path):
    curves = {"paper": [(1.0, 0.9), (2.0, 0.8)], "draft": [(0.5, 0.95), (1.5, 0.7)], "es": [(1.0, math.nan)]}
    speed_accuracy_chart(tmp_path / "s.png", [("relative loss", curves), ("param error", curves)])
    convergence_chart(tmp_path / "c.png", {"paper": [(0.1, 1.0), (0.2, 0.9)]}, {"paper": [(0.2, 0.95)]})
    for name in ("s.png", "c.png"):
        assert (tmp_path / name).read_bytes()[:8] == PNG


TINY = accuracy.Config(
    "quick", graphs=(GRAPH,), real=(), size=64, methods=("paper", "predict", "bank+ours", "balanced", "es"),
    budgets={"paper": (1, 2), "balanced": (1, 2), "predict": (0,), "es": (1, 2)},
    extra_seeds=(1,), stress=("black", "tiny"), es_population=2)


@pytest.fixture(scope="module")
def tiny_run(tmp_path_factory):
    from blender_match.cli import main

    out = tmp_path_factory.mktemp("bench") / "out"
    patch = pytest.MonkeyPatch()
    patch.setattr(accuracy, "QUICK", TINY)
    # the selection models come and go with the library: a stand-in predictor (a fixed guess) and
    # a missing bank keep the run independent of them
    size = load_library_graph(GRAPH).num_params()

    def rank_graphs(photo, method="both", *, device="cpu", graphs=None):
        if method == "bank":
            raise FileNotFoundError("woven_fabric.bank.pt")
        return [{"graph": GRAPH, "distance": 0.0, "theta": torch.full((size,), 0.45)}]

    patch.setattr(accuracy_methods, "rank_graphs", rank_graphs)
    try:
        status = main(["bench", "--quick", "--out", str(out)])
    finally:
        patch.undo()
    return status, out


def test_the_cli_writes_the_results_and_charts(tiny_run):
    status, out = tiny_run
    assert status == 0
    for name in ("results.json", "results.md", "speed_accuracy.png", "convergence.png"):
        assert (out / name).is_file() and (out / name).stat().st_size > 0, name
    assert (out / "speed_accuracy.png").read_bytes()[:8] == PNG
    assert (out / "convergence.png").read_bytes()[:8] == PNG
    result = json.loads((out / "results.json").read_text())
    rows = result["rows"]
    statuses = {(r["target"], r["method"]): r["status"] for r in rows}
    assert statuses[("stress:tiny", "paper")] == "refused"
    assert all(r["status"] != "failed" for r in rows), [r for r in rows if r["status"] == "failed"]
    scored = [r for r in rows if "descriptor_loss" in r]
    assert {r["method"] for r in scored} == {"paper", "predict", "balanced", "es"}
    assert {r["status"] for r in rows if r["method"] == "bank+ours"} <= {"unavailable", "refused"}
    assert all(math.isfinite(r["descriptor_loss"]) for r in scored)
    paper = sorted((r for r in scored if r["method"] == "paper" and r["group"] == "main"), key=lambda r: r["budget"])
    assert [r["budget"] for r in paper] == [1, 2]
    assert all(math.isfinite(r["param_error"]) and math.isfinite(r["novel_rmse"]) for r in paper)
    summary = {s["method"]: s for s in result["summary"]}
    assert set(summary) == set(TINY.methods) and summary["bank+ours"]["budget"] == "unavailable"
    assert summary["predict"]["budget"] == 0 and summary["predict"]["runs"] > 0
    assert result["spread"] and result["convergence"]["histories"]
    md = (out / "results.md").read_text()
    assert "| method |" in md and "failure rate" in md and "Classification" in md
