"""``blender-match bench accuracy [--quick] --out DIR``: speed against accuracy of the ways to fit a
graph to a photo (the MATch paper, section 6: optimisation from the default parameters, prediction
only, prediction + optimisation), on targets with a ground truth.

Every method (``accuracy_methods.METHODS``) runs on every target at several budgets; each result
is scored (``accuracy_metrics.Scorer``: descriptor loss at the evaluation size, parameter error, map
RMSE and novel-light RMSE against the truth), timed (wall seconds, peak memory) and classified
(success / degraded / failed / refused, ``accuracy_metrics.CLASSIFICATION_RULE``). Targets
(``accuracy_targets``): the "main" group (synthetic targets of every graph and the real photos),
the "seeds" group (the first synthetic target again with other fit seeds: the spread of a method's
result) and the "stress" group (photos no graph expresses, extreme photos), the last two at one
budget per method. ``--out`` gets results.json (every row), results.md (the tables),
speed_accuracy.png and convergence.png.
"""
from __future__ import annotations

import math
import os
import platform
import sys
import time
import traceback
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path

import torch

from ..diffmat.descriptor import TextureDescriptor
from ..diffmat.graph import MaterialGraph
from ..diffmat.optim import TargetLoss
from ..library import builtin_names, load_library_graph
from .accuracy_methods import METHODS, Selection, Unavailable, fit_sizes, run_method
from .accuracy_metrics import CLASSIFICATION_RULE, Scorer, classify, finite
from .accuracy_report import markdown
from .accuracy_targets import STRESS_KINDS, Target, graph_for_photo, real, real_photos, stress, synthetic
from .charts import convergence_chart, speed_accuracy_chart
from .results_files import write_json_and_markdown

FIT_SEED = 0


@dataclass(frozen=True)
class Config:
    """What a run covers. ``size``: the size targets are rendered/loaded and scored at, and the
    most any fit renders at. ``budgets``: iterations per method (generations for ``es``).
    ``prefix``: read our schedules' budgets from one run (``accuracy_methods``).
    ``graphs``/``real``: None for all. ``stress_budget``: "min" or "max", the budget of each method
    on the seeds and stress groups."""

    name: str
    graphs: tuple[str, ...] | None = None
    samples: tuple[int, ...] = (900,)
    real: tuple[str, ...] | None = None
    size: int = 512
    budgets: dict = field(default_factory=dict)
    methods: tuple[str, ...] = METHODS
    extra_seeds: tuple[int, ...] = (1, 2)
    stress: tuple[str, ...] = STRESS_KINDS
    stress_graph: str | None = None
    stress_budget: str = "min"
    es_population: int = 8
    prefix: bool = False
    convergence: tuple[str, ...] = ("paper", "draft", "balanced", "best", "predict+ours")


FULL = Config(
    "full", size=512,
    budgets={"paper": (25, 50, 100), "draft": (20, 40, 80), "balanced": (60, 120, 240),
             "best": (110, 225, 450), "predict": (0,), "predict+ours": (30, 60, 120),
             "bank+ours": (30, 60, 120), "es": (10, 20, 40)})

# --quick: 4 graphs x 1 target + 1 real photo, scored and fitted at 128 px, every budget read from
# the longest run, up to 16 iterations (8 generations of 4 for es), the stress photos but "white"
# (like "black") at the smallest budget: about 6 minutes on an otherwise idle 2-core CPU (target:
# under 15).
QUICK_BUDGETS = (2, 6, 16)
QUICK = Config(
    "quick", graphs=("asphalt", "leather", "bricks", "painted_metal"), real=("leather",), size=128,
    budgets={"paper": QUICK_BUDGETS, "draft": QUICK_BUDGETS, "balanced": QUICK_BUDGETS, "best": QUICK_BUDGETS,
             "predict": (0,), "predict+ours": QUICK_BUDGETS, "bank+ours": QUICK_BUDGETS, "es": (1, 3, 8)},
    extra_seeds=(1,), stress=tuple(k for k in STRESS_KINDS if k != "white"), es_population=4, prefix=True)


def _log(message: str, started: float):
    print(f"[{time.perf_counter() - started:7.1f}s] {message}", file=sys.stderr, flush=True)


def machine() -> dict:
    model = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {"cpu": model, "cores": os.cpu_count(), "torch": torch.__version__,
            "threads": torch.get_num_threads(), "python": platform.python_version(), "os": platform.platform()}


def build_targets(config: Config, log=None) -> list[Target]:
    names = list(config.graphs or builtin_names())
    targets = [synthetic(name, k, config.size) for name in names for k in config.samples]
    if config.real != ():
        known = builtin_names()
        for path in real_photos(config.real):
            graph = graph_for_photo(path, known)
            if graph is not None:
                targets.append(real(path, graph, config.size))
    if targets and targets[0].truth is not None:
        for s in config.extra_seeds:
            first = targets[0]
            targets.append(replace(first, name=f"{first.name}@seed{s}", group="seeds", kind=f"seed {s}"))
    graph = config.stress_graph or names[0]
    for kind in config.stress:
        try:
            targets.append(stress(kind, graph, config.size))
        except FileNotFoundError as exc:
            if log:
                log(f"stress {kind}: skipped ({exc})")
    return targets


def _seed_of(target: Target) -> int:
    return int(target.kind.split()[1]) if target.group == "seeds" else FIT_SEED


def _budgets(config: Config, method: str, group: str):
    budgets = sorted(config.budgets.get(method, (1,)))
    if group == "main":
        return budgets
    return [budgets[0] if config.stress_budget == "min" else budgets[-1]]


def _base_row(target: Target, method: str, seed: int) -> dict:
    return {"target": target.name, "group": target.group, "kind": target.kind, "graph": target.graph,
            "method": method, "fit_seed": seed}


def run_target(target: Target, config: Config, graphs, descriptor, selection, device: str, started: float,
               histories: dict | None = None) -> list[dict]:
    """Every method on one target: one row per (method, budget)."""
    seed = _seed_of(target)
    if target.photo is None:
        return [{**_base_row(target, m, seed), "status": "refused", "error": target.refusal} for m in config.methods]
    graph, default = graphs(target.graph)
    photo = target.photo.to(device)
    loss = TargetLoss(photo, descriptor)
    scorer = Scorer(descriptor, photo, config.size, target.truth, fit_seed=seed)
    default_score = scorer.score(graph, default)
    with torch.no_grad():  # the graph's caches at the fit's seed are built here, not in the first method's time
        for size, scales in sorted(fit_sizes(config.methods, config.size)):
            loss(graph, default[None].to(device), size, scales, seed)
    rows = []
    for method in config.methods:
        base = _base_row(target, method, seed)
        try:
            points = run_method(method, graph, loss, _budgets(config, method, target.group), cap=config.size,
                                seed=seed, default=default, photo=photo, graph_name=target.graph,
                                selection=selection, device=device, es_population=config.es_population,
                                prefix=config.prefix)
        except Unavailable as exc:
            rows.append({**base, "status": "unavailable", "error": str(exc)})
            _log(f"{target.name} {method}: unavailable ({exc})", started)
            continue
        except Exception as exc:  # noqa: BLE001 - a crash is a result here: it is classified "failed"
            rows.append({**base, "status": "failed", "error": f"{type(exc).__name__}: {exc}",
                         "traceback": traceback.format_exc(limit=4)})
            _log(f"{target.name} {method}: {type(exc).__name__}: {exc}", started)
            continue
        start_scores = {}
        for point in points:
            key = id(point.start)
            if key not in start_scores:
                start_scores[key] = default_score if torch.equal(point.start, default) else scorer.score(
                    graph, point.start)
            start_score = start_scores[key]
            score = scorer.score(graph, point.theta)
            status = classify(loss_start=start_score["descriptor_loss"], loss_final=score["descriptor_loss"],
                              theta_finite=finite(point.theta), param_error=score.get("param_error"),
                              param_error_default=default_score.get("param_error"))
            rows.append({**base, "budget": point.budget, "iterations": point.iterations,
                         "seconds": round(point.seconds, 3), "peak_mb": round(point.peak_bytes / 2 ** 20, 1),
                         "status": status, "loss_start": start_score["descriptor_loss"],
                         "loss_default": default_score["descriptor_loss"], **score,
                         "param_error_default": default_score.get("param_error")})
            if histories is not None and method in config.convergence and point is points[-1]:
                histories[method] = [(h[0] + point.offset, h[2]) for h in point.history]
        last = rows[-1]
        _log(f"{target.name} {method}: {last.get('status')} loss {last.get('descriptor_loss', math.nan):.4g} "
             f"in {last.get('seconds', 0):.1f}s", started)
    return rows


class _Graphs:
    """Library graphs loaded once per run, on the device, with their default parameters."""

    def __init__(self, device: str):
        self.device = device
        self._graphs: dict[str, tuple[MaterialGraph, torch.Tensor]] = {}

    def __call__(self, name: str):
        if name not in self._graphs:
            graph = load_library_graph(name).to(self.device)
            self._graphs[name] = (graph, graph.get_vector().cpu())
        return self._graphs[name]


def _mean(values):
    values = [v for v in values if v is not None and math.isfinite(v)]
    return sum(values) / len(values) if values else None


def curves(rows: list[dict], methods) -> dict[str, list[dict]]:
    """Per method, one point per budget over the main group: mean seconds and errors; the
    relative loss is the descriptor loss over the default parameters', averaged over targets."""
    out = {}
    for method in methods:
        mine = [r for r in rows if r["method"] == method and r["group"] == "main" and "budget" in r]
        points = []
        for budget in sorted({r["budget"] for r in mine}):
            at = [r for r in mine if r["budget"] == budget]
            synthetic_rows = [r for r in at if r.get("param_error") is not None]
            points.append({
                "budget": budget, "targets": len(at), "seconds": _mean([r["seconds"] for r in at]),
                "iterations": _mean([r["iterations"] for r in at]),
                "descriptor_loss": _mean([r["descriptor_loss"] for r in at]),
                "relative_loss": _mean([r["descriptor_loss"] / r["loss_default"] for r in at
                                        if r["loss_default"] and r["loss_default"] > 0]),
                "param_error": _mean([r["param_error"] for r in synthetic_rows]),
                "map_rmse": _mean([r["map_rmse_mean"] for r in synthetic_rows]),
                "novel_rmse": _mean([r["novel_rmse"] for r in synthetic_rows]),
                "peak_mb": max((r["peak_mb"] for r in at), default=None),
            })
        out[method] = points
    return out


def summarise(rows: list[dict], methods) -> list[dict]:
    """One row per method at its best budget (lowest mean relative loss; the cheaper on a tie),
    with its failure and degraded rates over all its runs (every group and budget)."""
    table = []
    per_method = curves(rows, methods)
    for method in methods:
        mine = [r for r in rows if r["method"] == method]
        ran = [r for r in mine if r["status"] != "unavailable"]
        row = {"method": method}
        points = [p for p in per_method[method] if p["relative_loss"] is not None]
        if all(r["status"] in ("unavailable", "refused") for r in mine):
            reason = next((r.get("error") for r in mine if r.get("error")), "")
            table.append({**row, "budget": "unavailable", "note": reason})
            continue
        if points:
            best = min(points, key=lambda p: (p["relative_loss"], p["seconds"] or 0))
            row.update({k: best[k] for k in ("budget", "targets", "seconds", "descriptor_loss", "relative_loss",
                                             "param_error", "map_rmse", "novel_rmse", "peak_mb")})
        counts = {s: sum(r["status"] == s for r in ran) for s in ("success", "degraded", "failed", "refused")}
        row.update({"runs": len(ran), "failed": counts["failed"], "failure_rate": counts["failed"] / len(ran),
                    "degraded_rate": counts["degraded"] / len(ran), "refused": counts["refused"]})
        table.append(row)
    return table


def spread(rows: list[dict], config: Config) -> list[dict]:
    """Per method, the final descriptor loss and parameter error over the fit seeds of the first
    synthetic target, at the seeds group's budget."""
    seeds_rows = [r for r in rows if r["group"] == "seeds"]
    if not seeds_rows:
        return []
    base_target = seeds_rows[0]["target"].split("@")[0]
    out = []
    for method in config.methods:
        mine = [r for r in seeds_rows if r["method"] == method and "budget" in r]
        if not mine:
            continue
        budget = mine[0]["budget"]
        mine += [r for r in rows if r["target"] == base_target and r["method"] == method and r.get("budget") == budget]
        losses = [r["descriptor_loss"] for r in mine]
        errors = [r["param_error"] for r in mine if r.get("param_error") is not None]
        out.append({"method": method, "budget": budget, "seeds": sorted(r["fit_seed"] for r in mine),
                    "loss_min": min(losses), "loss_max": max(losses), "loss_std": _std(losses),
                    "param_error_min": min(errors, default=None), "param_error_max": max(errors, default=None),
                    "param_error_std": _std(errors)})
    return out


def _std(values):
    values = [v for v in values if v is not None and math.isfinite(v)]
    if len(values) < 2:
        return 0.0 if values else None
    mean = sum(values) / len(values)
    return math.sqrt(sum((v - mean) ** 2 for v in values) / (len(values) - 1))


def write_outputs(out: Path, result: dict) -> list[Path]:
    """results.json, results.md and the two charts in ``out``."""
    write_json_and_markdown(out, result, markdown(result), default=_json_default)
    per_method = result["curves"]
    panels = [("descriptor loss / default's (mean over main targets)",
               {m: [(p["seconds"], p["relative_loss"]) for p in pts] for m, pts in per_method.items()}),
              ("parameter error (mean abs, synthetic targets)",
               {m: [(p["seconds"], p["param_error"]) for p in pts] for m, pts in per_method.items()})]
    order = list(result["config"]["methods"])
    speed_accuracy_chart(out / "speed_accuracy.png", panels, order=order,
                         title=f"Speed against accuracy ({result['config']['name']} run, "
                               f"{result['machine']['cores']} cores)")
    conv = result["convergence"]
    markers = {m: [(r["seconds"], r["descriptor_loss"]) for r in result["rows"]
                   if r["target"] == conv["target"] and r["method"] == m and "budget" in r]
               for m in conv["histories"]}
    convergence_chart(out / "convergence.png", {m: [tuple(p) for p in h] for m, h in conv["histories"].items()},
                      markers, order=order,
                      title=f"Convergence on {conv['target']}\nlines: each fit's own loss (its stages' size, scales, "
                            "seed)\ndiamonds: the benchmark's measure (truth seed) at each budget")
    return [out / n for n in ("results.json", "results.md", "speed_accuracy.png", "convergence.png")]


def _json_default(value):
    if isinstance(value, torch.Tensor):
        return value.tolist()
    return str(value)


def run(device: str = "cpu", graphs=None, quick: bool = False, out: Path | None = None,
        config: Config | None = None) -> list[dict]:
    """Run the benchmark; write the outputs to ``out`` when given; return the summary table."""
    config = config or (QUICK if quick else FULL)
    if graphs:
        config = replace(config, graphs=tuple(graphs))

    started = time.perf_counter()
    descriptor = TextureDescriptor().to(device)
    targets = build_targets(config, log=lambda m: _log(m, started))
    _log(f"{len(targets)} targets, methods {', '.join(config.methods)}", started)
    loaded, selection = _Graphs(device), Selection(device)
    rows: list[dict] = []
    histories: dict[str, list[tuple[int, float]]] = {}
    for i, target in enumerate(targets):
        rows += run_target(target, config, loaded, descriptor, selection, device, started,
                           histories if i == 0 else None)
    summary = summarise(rows, config.methods)
    result = {"config": {**asdict(config), "device": device}, "machine": machine(),
              "wall_seconds": round(time.perf_counter() - started, 1), "rule": CLASSIFICATION_RULE,
              "command": "blender-match bench accuracy" + (" --quick" if config.name == "quick" else ""),
              "rows": rows, "curves": curves(rows, config.methods), "summary": summary,
              "spread": spread(rows, config),
              "convergence": {"target": targets[0].name if targets else None, "histories": histories}}
    if out is not None:
        write_outputs(Path(out), result)
    _log(f"done in {time.perf_counter() - started:.0f}s", started)
    columns = ("method", "budget", "seconds", "descriptor_loss", "relative_loss", "param_error", "map_rmse",
               "novel_rmse", "peak_mb", "runs", "failure_rate")
    return [{k: (round(row[k], 4) if isinstance(row.get(k), float) else row.get(k)) for k in columns}
            for row in summary]
