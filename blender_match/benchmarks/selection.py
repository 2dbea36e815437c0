"""``blender-match bench selection``: automatic graph selection and parameter prediction on
synthetic targets whose graph and parameters are known.

Targets: for each library graph with a model, ``sample_params(graph, k)`` with k = 100000 + t
(beyond every bank and training index) rendered at ``target_size`` (256) px with graph seed
200000 + t (training uses seeds below 100000, the bank seed 0), so no target was seen in
training and none aligns pixel for pixel with what the ranking renders. Per graph:

- ``top1`` / ``top3``: targets whose true graph ranks first / in the top 3 (``rank_graphs``,
  ``method``), and the true graph's ranks;
- ``pred_err``, ``bank_err``, ``default_err``: mean absolute error in normalised parameter space,
  over the components the library samples, of the predictor's output, of the bank's nearest
  sample and of the graph's default parameters, against the truth;
- on the first ``fit_targets`` targets: the quality preset (``draft``, rescaled to ``iterations``)
  fitted from the default start and from the predicted start; ``its_default`` is the iteration at
  which the fit from the default first reached its own final loss, ``its_pred`` the iteration at
  which the fit from the prediction first reached that same loss (None: never), ``its_ratio``
  their ratio (target: at most 0.5).

The last row ("all") sums or averages over the graphs. Options for a quick run: ``graphs``,
``targets`` (per graph), ``fit_targets``, ``iterations``, ``quick`` (1 target, 1 fitted, 30 iterations).
"""
from __future__ import annotations

import sys
import time

TARGET_K0 = 100_000
TARGET_SEED0 = 200_000


def _reach(history, threshold: float):
    return next((it for _, it, loss in history if loss <= threshold * (1 + 1e-9)), None)


def run(device: str = "cpu", graphs=None, targets: int = 2, fit_targets: int = 1, iterations: int = 40,
        quality: str = "draft", target_size: int = 256, method: str = "both", quick: bool = False, **_ignored) -> list[dict]:
    from ..diffmat.descriptor import TextureDescriptor
    from ..diffmat.optim import QUALITY_SCHEDULES, TargetLoss, fit
    from ..pipeline import resolve_device
    from ..selection.bank import SampleSpace, describe, load_bank, nearest, render_images
    from ..selection.predictor import load_predictor, masked_l1
    from ..selection.select import available_models, rank_graphs

    if quick:
        targets, fit_targets, iterations = 1, 1, 30
    device = resolve_device(device)
    names = available_models(method)
    if not names:
        raise FileNotFoundError("no selection models: create them with `blender-match train --all`")
    chosen = [n for n in (graphs or names) if n in names]
    schedule = QUALITY_SCHEDULES[quality].scaled(iterations)
    descriptor = TextureDescriptor().to(device)
    materials: dict = {}
    rows, started = [], time.perf_counter()
    for name in chosen:
        space = SampleSpace(name)
        graph = space.graph.to(device)
        model, bank = load_predictor(name), load_bank(name)
        row = {"graph": name, "targets": 0, "top1": 0, "top3": 0, "ranks": [], "pred_err": 0.0, "bank_err": 0.0,
               "default_err": 0.0, "its_default": [], "its_pred": [], "loss_default_start": [], "loss_pred_start": [],
               "seconds": 0.0}
        t0 = time.perf_counter()
        for t in range(targets):
            truth = space.vector(TARGET_K0 + t)
            photo = render_images(graph, truth[None].to(device), TARGET_SEED0 + t, target_size)
            ranking = rank_graphs(photo, method, device=device, materials=materials)
            rank = next(i for i, e in enumerate(ranking) if e["graph"] == name) + 1
            row["targets"] += 1
            row["ranks"].append(rank)
            row["top1"] += rank == 1
            row["top3"] += rank <= 3
            desc = describe(photo, device)
            predicted = model(desc)[0].detach() if model is not None else space.default
            from_bank = nearest(bank, desc)[0]["theta"] if bank is not None else space.default
            for key, theta in (("pred_err", predicted), ("bank_err", from_bank), ("default_err", space.default)):
                row[key] += float(masked_l1(theta[None], truth[None], space.mask)) / targets
            if t < fit_targets:
                loss = TargetLoss(photo, descriptor)
                base = fit(graph, loss, schedule, seed=0, theta0=space.default)
                pred = fit(graph, loss, schedule, seed=0, theta0=predicted)
                row["its_default"].append(_reach(base.history, base.loss_final))
                row["its_pred"].append(_reach(pred.history, base.loss_final))
                row["loss_default_start"].append(round(base.loss_initial, 5))
                row["loss_pred_start"].append(round(pred.loss_initial, 5))
            graph.clear_cache()
        row["seconds"] = round(time.perf_counter() - t0, 1)
        rows.append(row)
        print(f"bench selection: {name}: ranks {row['ranks']}, {row['seconds']}s", file=sys.stderr, flush=True)
    summary = {"graph": "all", "targets": sum(r["targets"] for r in rows), "top1": sum(r["top1"] for r in rows),
               "top3": sum(r["top3"] for r in rows), "ranks": "", "seconds": round(time.perf_counter() - started, 1)}
    n = max(1, len(rows))
    for key in ("pred_err", "bank_err", "default_err"):
        summary[key] = sum(r[key] for r in rows) / n
    pairs = [(d, p) for r in rows for d, p in zip(r["its_default"], r["its_pred"])]
    reached = [(d, p) for d, p in pairs if p is not None and d]
    summary["its_default"] = sum(d for d, _ in pairs if d) / max(1, len(pairs))
    summary["its_pred"] = f"{len(reached)}/{len(pairs)} reached"
    summary["loss_default_start"] = summary["loss_pred_start"] = ""
    # ratio: iterations from the prediction over iterations from the default, a miss counting as the full budget
    ratios = [(p if p is not None else schedule.iterations) / max(1, d) for d, p in pairs if d]
    summary["its_ratio"] = round(sorted(ratios)[len(ratios) // 2], 3) if ratios else None
    out = []
    for r in rows:
        rr = {k: v for k, v in r.items()}
        rt = [(p if p is not None else schedule.iterations) / max(1, d) for d, p in zip(r["its_default"], r["its_pred"]) if d]
        rr["its_ratio"] = round(sum(rt) / len(rt), 3) if rt else None
        rr["top3_rate"] = round(r["top3"] / max(1, r["targets"]), 3)
        for key in ("ranks", "its_default", "its_pred", "loss_default_start", "loss_pred_start"):
            rr[key] = ",".join(str(v) for v in r[key])
        out.append(rr)
    summary["top3_rate"] = round(summary["top3"] / max(1, summary["targets"]), 3)
    out.append({k: summary.get(k) for k in out[0]} if out else summary)
    return out
