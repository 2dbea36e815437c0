"""``blender-match bench selection``: automatic graph selection and parameter prediction on
synthetic targets whose graph and parameters are known.

Targets: for each library graph with a model, ``sample_params(graph, k)`` with k = 100000 + t
(beyond every bank and training index) rendered at ``target_size`` (256) px with graph seed
200000 + t (training uses seeds below 100000, the bank seed 0), so no target was seen in
training and none aligns pixel for pixel with what the ranking renders. Per graph:

- ``top1`` / ``top3``: targets whose true graph ranks first / in the top 3 (``rank_graphs``,
  ``method``), and the true graph's ranks ("-": the selection index did not shortlist it);
- ``rank_s``: the median seconds of ``rank_graphs`` (everything before a fit starts);
- ``pred_err``, ``bank_err``, ``default_err``: mean absolute error in normalised parameter space,
  over the components the library samples, of the predictor's output, of the bank's nearest
  sample and of the graph's default parameters, against the truth;
- on the first ``fit_targets`` targets: the quality preset (``draft``, rescaled to ``iterations``)
  fitted from the default start and from the predicted start; ``its_default`` is the iteration at
  which the fit from the default first reached its own final loss, ``its_pred`` the iteration at
  which the fit from the prediction first reached that same loss (None: never), ``its_ratio``
  their ratio (target: at most 0.5).

The row "all" sums or averages over the graphs. Then rows "rank@N": the median seconds of
ranking the first targets of up to 8 graphs against only the first N graphs of the library, for
N = 16, 32, ... and the whole library (how ranking grows with the library). Options for a quick run: ``graphs``,
``targets`` (per graph), ``fit_targets``, ``iterations``, ``quick`` (1 target, 1 fitted, 30 iterations).
"""
from __future__ import annotations

import statistics
import sys
import time
from dataclasses import asdict, dataclass, field

from ..diffmat.descriptor import TextureDescriptor
from ..diffmat.optim import TargetLoss, fit
from ..pipeline import match_schedule, resolve_device
from ..selection import available_models, rank_graphs
from ..selection.bank import SampleSpace, describe, load_bank, nearest, render_images
from ..selection.predictor import load_predictor, masked_l1

TARGET_K0 = 100_000
TARGET_SEED0 = 200_000


def _reach(history, threshold: float) -> int | None:
    return next((it for _, it, loss in history if loss <= threshold * (1 + 1e-9)), None)


@dataclass
class _GraphTally:
    """One graph's results over its targets; ``row`` formats them as a row of the table."""

    graph: str
    targets: int = 0
    top1: int = 0
    top3: int = 0
    ranks: list[int | str] = field(default_factory=list)
    pred_err: float = 0.0
    bank_err: float = 0.0
    default_err: float = 0.0
    its_default: list[int | None] = field(default_factory=list)
    its_pred: list[int | None] = field(default_factory=list)
    loss_default_start: list[float] = field(default_factory=list)
    loss_pred_start: list[float] = field(default_factory=list)
    rank_seconds: list[float] = field(default_factory=list)
    seconds: float = 0.0

    def ratios(self, budget: int) -> list[float]:
        """Iterations from the prediction over iterations from the default, a miss counting as the
        full ``budget``."""
        return [(p if p is not None else budget) / max(1, d) for d, p in zip(self.its_default, self.its_pred) if d]

    def row(self, budget: int) -> dict:
        row = asdict(self)
        ratios = self.ratios(budget)
        row["its_ratio"] = round(sum(ratios) / len(ratios), 3) if ratios else None
        row["top3_rate"] = round(self.top3 / max(1, self.targets), 3)
        row["rank_seconds"] = round(_median(self.rank_seconds), 2)
        for key in ("ranks", "its_default", "its_pred", "loss_default_start", "loss_pred_start"):
            row[key] = ",".join(str(v) for v in row[key])
        return row


def run(device: str = "cpu", graphs=None, targets: int = 2, fit_targets: int = 1, iterations: int = 40,
        quality: str = "draft", target_size: int = 256, method: str = "both", quick: bool = False) -> list[dict]:
    if quick:
        targets, fit_targets, iterations = 1, 1, 30
    torch_device = resolve_device(device)
    names = available_models(method)
    if not names:
        raise FileNotFoundError("no selection models: create them with `blender-match train --all`")
    chosen = [n for n in (graphs or names) if n in names]
    schedule = match_schedule(quality, iterations)
    descriptor = TextureDescriptor().to(torch_device)
    materials: dict = {}
    tallies, started = [], time.perf_counter()
    for name in chosen:
        space = SampleSpace(name)
        graph = space.graph.to(torch_device)
        model, bank = load_predictor(name), load_bank(name)
        tally = _GraphTally(name)
        t0 = time.perf_counter()
        for t in range(targets):
            truth = space.vector(TARGET_K0 + t)
            photo = render_images(graph, truth[None].to(torch_device), TARGET_SEED0 + t, target_size)
            t_rank = time.perf_counter()
            ranking = rank_graphs(photo, method, device=torch_device, materials=materials)
            tally.rank_seconds.append(time.perf_counter() - t_rank)
            rank = next((i + 1 for i, e in enumerate(ranking) if e["graph"] == name), None)
            tally.targets += 1
            tally.ranks.append(rank if rank is not None else "-")
            tally.top1 += rank == 1
            tally.top3 += rank is not None and rank <= 3
            desc = describe(photo, torch_device)
            predicted = model(desc)[0].detach() if model is not None else space.default
            from_bank = nearest(bank, desc)[0]["theta"] if bank is not None else space.default

            def error(theta) -> float:
                return float(masked_l1(theta[None], truth[None], space.mask)) / targets

            tally.pred_err += error(predicted)
            tally.bank_err += error(from_bank)
            tally.default_err += error(space.default)
            if t < fit_targets:
                loss = TargetLoss(photo, descriptor)
                base = fit(graph, loss, schedule, seed=0, theta0=space.default)
                pred = fit(graph, loss, schedule, seed=0, theta0=predicted)
                tally.its_default.append(_reach(base.history, base.loss_final))
                tally.its_pred.append(_reach(pred.history, base.loss_final))
                tally.loss_default_start.append(round(base.loss_initial, 5))
                tally.loss_pred_start.append(round(pred.loss_initial, 5))
            graph.clear_cache()
        tally.seconds = round(time.perf_counter() - t0, 1)
        tallies.append(tally)
        print(f"bench selection: {name}: ranks {tally.ranks}, {tally.seconds}s", file=sys.stderr, flush=True)
    rows = _table(tallies, schedule.iterations, time.perf_counter() - started)
    return rows + _scaling(names, rows[0], method, torch_device, materials, target_size)


def _median(values) -> float:
    values = list(values)
    return statistics.median(values) if values else 0.0


def _scaling(names: list[str], template: dict, method: str, device, materials: dict, target_size: int,
             photos: int = 8) -> list[dict]:
    """Rows "rank@N": median seconds of ranking the first target of ``photos`` graphs among the
    first N library graphs, N = 16, 32, ... and all."""
    sizes = sorted({*range(16, len(names), 16), len(names)})
    targets = []
    for name in names[:: max(1, len(names) // photos)][:photos]:
        space = SampleSpace(name)
        graph = space.graph.to(device)
        targets.append(render_images(graph, space.vector(TARGET_K0)[None].to(device), TARGET_SEED0, target_size))
        graph.clear_cache()
    rows = []
    for size in sizes:
        seconds = []
        for photo in targets:
            t0 = time.perf_counter()
            rank_graphs(photo, method, device=device, graphs=names[:size], materials=materials)
            seconds.append(time.perf_counter() - t0)
        row: dict = {key: "" for key in template}
        row.update(graph=f"rank@{size}", targets=len(targets), rank_seconds=round(_median(seconds), 2))
        rows.append(row)
        print(f"bench selection: ranking among {size} graphs: {row['rank_seconds']}s", file=sys.stderr, flush=True)
    return rows


def _table(tallies: list[_GraphTally], budget: int, seconds: float) -> list[dict]:
    """A row per graph, then the row "all": sums of counts, means of errors, the median ratio."""
    pairs = [(d, p) for t in tallies for d, p in zip(t.its_default, t.its_pred)]
    ratios = sorted(r for t in tallies for r in t.ratios(budget))
    count = max(1, len(tallies))
    targets, top3 = sum(t.targets for t in tallies), sum(t.top3 for t in tallies)
    summary = {"graph": "all", "targets": targets, "top1": sum(t.top1 for t in tallies), "top3": top3, "ranks": "",
               "pred_err": sum(t.pred_err for t in tallies) / count,
               "bank_err": sum(t.bank_err for t in tallies) / count,
               "default_err": sum(t.default_err for t in tallies) / count,
               "its_default": sum(d for d, _ in pairs if d) / max(1, len(pairs)),
               "its_pred": f"{sum(1 for d, p in pairs if p is not None and d)}/{len(pairs)} reached",
               "loss_default_start": "", "loss_pred_start": "", "seconds": round(seconds, 1),
               "its_ratio": round(ratios[len(ratios) // 2], 3) if ratios else None,
               "rank_seconds": round(_median([r for t in tallies for r in t.rank_seconds]), 2),
               "top3_rate": round(top3 / max(1, targets), 3)}
    rows = [t.row(budget) for t in tallies]
    rows.append({k: summary[k] for k in rows[0]} if rows else summary)
    return rows
