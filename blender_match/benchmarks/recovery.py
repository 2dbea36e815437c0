"""``blender-match bench recovery``: does each quality preset move a material toward the truth?

The paper's own test. A target is a library graph at a sampled variant (``sample_params(graph, k)``,
k >= ``TARGET_K0``: beyond every bank and training index) rendered at ``size`` px with noise seed
``TRUTH_SEED``, which no fit uses. Each preset (draft, balanced, best) fits it as ``blender-match
match --graph NAME`` does (``pipeline.fit_named_graph``: from the start the product chooses, with
graph seed ``FIT_SEED``; then ``pipeline.finish_calibration``, the base colour's gain solved again
for the fitted material, as every match ends). The start (with the gain solved for it) and the
fitted material are scored at ``size`` by three measures that no fit minimises:

- ``patch``: ``image_distances.patch_distance`` between the target photo and the flash render with
  the fit's seed (what the user sees);
- ``maps``: the mean over the maps (base colour, normal, roughness, metallic, height) of each map's
  RMSE against the truth's maps, the parameters rendered with the truth's seed (pixel-aligned: a
  fit's seed is arbitrary, and between two seeds the RMSE of uncorrelated noise is smallest for a
  flat map, which would reward a fit that erased the texture);
- ``novel``: RMSE of the sRGB render under a light moved away from the camera (``NOVEL_LIGHT``)
  against the truth's, rendered the same way.

Each is divided by the same measure for the truth's parameters re-rendered with the fit's seed,
so 1.0 is "as good as the truth itself": for ``maps`` and ``novel``, an error as large as the one
the noise seed alone makes. Per preset the table gives the median ratio of each measure, the share
of targets that end closer than they started by each, the share whose fit ends *past the truth*
(its own loss below ``loss_truth``, the fit's loss of the truth's parameters with the fit's seed:
the descriptor can no longer tell the target from itself under another noise seed, so what the fit
gains beyond it is the target's particular noise), and the median seconds (start choice and fit;
the 2K maps that ``match`` writes afterwards are not part of it). ``--quick``: one target for
each of ``QUICK_GRAPHS`` (the full run: every library graph; ``--graphs`` picks others), every
preset (``--quality draft,balanced``: those). ``per_map`` breaks the map measure down: for each
map, how many targets end closer to the truth's than they started. A target that fails (a graph
that does not load, a device error) is listed under the config's ``failed`` and the run goes on.
"""
from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

import torch

from ..diffmat.calibration import framed_maps
from ..diffmat.optim import final_stage_loss
from ..diffmat.render import render_maps
from ..library import apply_params, builtin_names, load_library_graph, sample_params
from ..pipeline import finish_calibration, fit_named_graph, match_schedule, photo_loss, resolve_device
from ..vocabulary import QUALITY_NAMES
from .accuracy_metrics import NOVEL_LIGHT, image_rmse, make_truth, map_rmse
from .charts import recovery_chart
from .image_distances import patch_distance
from .markdown import table
from .results_files import write_json_and_markdown

TARGET_K0 = 300_000
TRUTH_SEED = 7771
FIT_SEED = 0
MEASURES = ("patch", "maps", "novel")
PRESETS = QUALITY_NAMES
QUICK_GRAPHS = ("asphalt", "bricks", "leather", "plaster", "raw_wood", "woven_fabric")
SIZE = 512


def measures(graph, theta: torch.Tensor, photo: torch.Tensor, truth, size: int, map_seed: int) -> dict[str, float]:
    """The three yardsticks of ``graph`` at ``theta`` (P,), framed at its zoom (a fit that chose
    another scale than the truth's pays for it in every measure): the patch distance of its
    render with ``FIT_SEED``, the map and novel-light errors of its maps with ``map_seed``."""
    theta = theta.reshape(1, -1).to(photo.device)
    with torch.no_grad():
        shown = framed_maps(graph, size, FIT_SEED, theta)
        render = render_maps(shown)[:1]
        maps = shown if map_seed == FIT_SEED else framed_maps(graph, size, map_seed, theta)
        novel = render_maps(maps, light_offset=NOVEL_LIGHT)[:1]
    rmse = map_rmse(maps, truth.maps)
    return {"patch": patch_distance(photo, render), "maps": statistics.fmean(rmse.values()),
            "novel": image_rmse(novel, truth.novel), **{f"rmse_{name}": value for name, value in rmse.items()}}


def truth_loss(graph, truth_theta: torch.Tensor, photo: torch.Tensor, schedule, device) -> float:
    """The fit's loss (``schedule``'s, as ``FitResult.loss_final`` is measured) of the truth's
    parameters rendered with the fit's seed under the ideal flash the target was made with: the
    descriptor's distance from the target to itself under another noise seed."""
    return final_stage_loss(photo_loss(photo, device), graph, truth_theta.to(device), schedule, FIT_SEED)


def recover(name: str, k: int, size: int, presets, device, iterations: int | None = None, zoom: float | None = 1.0,
            lighting: bool = True) -> list[dict]:
    """One target (graph ``name``, variant ``k``) fitted by each preset (rescaled to ``iterations``
    when given; ``zoom`` and ``lighting`` as ``fit_named_graph`` takes them): one row per preset.
    The measures render under the ideal flash the target was made with."""
    graph = load_library_graph(name).to(device)
    apply_params(graph, sample_params(name, k))
    truth_theta = graph.get_vector()
    photo, truth = make_truth(graph, truth_theta, size, TRUTH_SEED)
    reference = measures(graph, truth_theta, photo, truth, size, FIT_SEED)  # what the seed alone costs
    rows = []
    for preset in presets:
        fresh = load_library_graph(name)
        schedule = match_schedule(preset, iterations)
        started = time.perf_counter()
        result, start, theta0, camera = fit_named_graph(fresh, name, photo, schedule, FIT_SEED, device, zoom=zoom,
                                                         lighting=lighting)
        seconds = time.perf_counter() - started
        before = measures(fresh, theta0, photo, truth, size, TRUTH_SEED)  # with the gain solved at the start
        fresh.set_vector(result.theta)
        finish_calibration(fresh, photo, FIT_SEED, camera, lighting)  # as every match ends
        after = measures(fresh, result.theta, photo, truth, size, TRUTH_SEED)
        row = {"target": f"{name}/{k}", "graph": name, "preset": preset, "start": start, "seconds": round(seconds, 2),
               "iterations": result.iterations, "loss_initial": result.loss_initial, "loss_final": result.loss_final,
               "loss_truth": truth_loss(graph, truth_theta, photo, schedule, device)}
        row["past_truth"] = row["loss_final"] < row["loss_truth"]
        row |= {f"{key}_start": value for key, value in before.items() if key.startswith("rmse_")}
        row |= {f"{key}_final": value for key, value in after.items() if key.startswith("rmse_")}
        for m in MEASURES:
            row[f"{m}_truth"] = reference[m]
            row[f"{m}_start"] = before[m]
            row[f"{m}_final"] = after[m]
            row[f"{m}_ratio"] = after[m] / max(reference[m], 1e-9)
            row[f"{m}_start_ratio"] = before[m] / max(reference[m], 1e-9)
            row[f"{m}_closer"] = after[m] < before[m]
        rows.append(row)
    return rows


def summarise(rows: list[dict], presets) -> list[dict]:
    """One row per preset: median ratios, shares of targets ending closer than they started, seconds."""
    out = []
    for preset in presets:
        mine = [r for r in rows if r["preset"] == preset]
        if not mine:
            continue
        row = {"preset": preset, "targets": len(mine)}
        for m in MEASURES:
            row[f"{m}_ratio"] = round(statistics.median(r[f"{m}_ratio"] for r in mine), 3)
        for m in MEASURES:
            row[f"{m}_closer"] = f"{sum(r[f'{m}_closer'] for r in mine) / len(mine):.0%}"
        row["past_truth"] = f"{sum(r['past_truth'] for r in mine) / len(mine):.0%}"
        row["start_patch_ratio"] = round(statistics.median(r["patch_start_ratio"] for r in mine), 3)
        row["seconds"] = round(statistics.median(r["seconds"] for r in mine), 1)
        out.append(row)
    return out


def per_map(rows: list[dict], presets) -> list[dict]:
    """One row per preset and map: of the targets where the map is not flat and equal to the
    truth's at both ends (a metallic 0 against a metallic 0), how many end closer to the truth's
    map than they started, and the median of the final RMSE over the start's: which maps a fit
    moves toward the truth and which away."""
    out = []
    for preset in presets:
        mine = [r for r in rows if r["preset"] == preset]
        names = dict.fromkeys(k[len("rmse_"):-len("_start")] for r in mine for k in r
                              if k.startswith("rmse_") and k.endswith("_start"))
        for name in names:
            pairs = [(r[f"rmse_{name}_start"], r[f"rmse_{name}_final"]) for r in mine
                     if f"rmse_{name}_start" in r and max(r[f"rmse_{name}_start"], r[f"rmse_{name}_final"]) > 1e-6]
            if pairs:
                out.append({"preset": preset, "map": name, "targets": len(pairs),
                            "closer": f"{sum(b < a for a, b in pairs)}/{len(pairs)}",
                            "final_over_start": round(statistics.median(b / max(a, 1e-9) for a, b in pairs), 3)})
    return out


def markdown(summary: list[dict], maps: list[dict], rows: list[dict], config: dict) -> str:
    per_target = ["target", "preset", "start", "seconds", "patch_start_ratio", "patch_ratio", "maps_ratio",
                  "novel_ratio", "loss_final", "loss_truth"]
    legend = (f"size {config['size']} px, truth seed {TRUTH_SEED}, fit seed {FIT_SEED}, device {config['device']}, "
              f"torch threads {config['threads']}; ratios: the measure over the truth's own (1.0 = as good as the "
              "truth re-rendered with the fit's seed); closer: share of targets that end closer to the truth than "
              "their start; past_truth: share whose fit's loss ends below loss_truth, the loss of the truth's own "
              "parameters with the fit's seed")
    failed = [f"{f['target']}: {f['error']}" for f in config.get("failed", ())]
    return "\n\n".join([
        "# bench recovery", legend, table(summary, list(summary[0])) if summary else "(no rows)",
        *(["Failed targets (no row):\n\n" + "\n".join(f"- {f}" for f in failed)] if failed else []),
        "## Per map (RMSE against the truth's map, final against start)",
        table(maps, list(maps[0])) if maps else "(no rows)",
        "## Per target", table(rows, per_target) if rows else "(no rows)"]) + "\n"


def run(device: str = "cpu", graphs=None, quick: bool = False, quality: str | None = None, out: Path | None = None,
        size: int | None = None, targets: int = 1, iterations: int | None = None, zoom: float | None = 1.0,
        lighting: bool = True) -> list[dict]:
    torch_device = resolve_device(device)
    names = list(graphs or (QUICK_GRAPHS if quick else builtin_names()))
    presets = tuple(quality.split(",")) if quality else PRESETS  # "draft,balanced": those two
    size = size or SIZE
    rows: list[dict] = []
    failed: list[dict] = []
    started = time.perf_counter()
    for name in names:
        for t in range(targets):
            try:
                last = recover(name, TARGET_K0 + t, size, presets, torch_device, iterations, zoom, lighting)
            except Exception as exc:  # noqa: BLE001 - one target's failure is its own, not the whole run's
                failed.append({"target": f"{name}/{TARGET_K0 + t}", "error": f"{type(exc).__name__}: {exc}"})
                print(f"[{time.perf_counter() - started:6.0f}s] {name}: failed: {failed[-1]['error']}",
                      file=sys.stderr, flush=True)
            else:
                rows.extend(last)
                print(f"[{time.perf_counter() - started:6.0f}s] {name}: " + ", ".join(
                    f"{r['preset']} patch {r['patch_start_ratio']:.2f}->{r['patch_ratio']:.2f} "
                    f"maps {r['maps_start_ratio']:.2f}->{r['maps_ratio']:.2f} ({r['seconds']:.0f}s)" for r in last),
                    file=sys.stderr, flush=True)
            if out is not None:  # after every target, so that a cut-short run leaves its results
                write_results(Path(out), rows, presets, {"size": size, "iterations": iterations,
                              "device": str(torch_device), "threads": torch.get_num_threads(), "graphs": names,
                              "presets": list(presets), "failed": failed,
                              "seconds": round(time.perf_counter() - started, 1)})
    return summarise(rows, presets)


def write_results(out: Path, rows: list[dict], presets, config: dict):
    """results.json, results.md and (once a target has a row) recovery.png in ``out``."""
    summary, maps = summarise(rows, presets), per_map(rows, presets)
    write_json_and_markdown(out, {"config": config, "summary": summary, "per_map": maps, "rows": rows},
                            markdown(summary, maps, rows, config))
    if rows:  # nothing to chart while every target so far has failed
        recovery_chart(out / "recovery.png", rows, presets, MEASURES)
