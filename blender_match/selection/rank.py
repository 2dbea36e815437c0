"""Ranking the library graphs for a photo (the MATch paper, section 4.2).

``rank_graphs(photo)``: the selection index (``selection.index``) first lets through the
``SHORTLIST`` graphs whose bank samples come nearest the photo's compact descriptor, so that the
cost below grows with the shortlist, not with the library. For each of them, a candidate parameter
vector (the predictor's, the bank's nearest sample's, or with both models those two and the graph's
own defaults, as a named graph's fit chooses its start: ``start.choose_start``; the best kept) is
rendered at 128 px (finer and brought down for a graph whose look depends on its output size:
``bank.supersample``) and scored by the fit's own style loss (Gram descriptor at 128) against the
photo, after the photo's exposure and white balance are given to it: the per-channel gain on its
base colour that the match's own calibration would solve (``calibration.proposal_gains``), each
stop of it costing a little (``correction_cost``). Without the gain a graph whose sampled colours
happen to reach the photo's (a flat glossy paint, a galvanized sheet) beat the photo's own material
in another colour, which the match would have re-tinted anyway; the graphs come best first, by that
distance alone. Simplicity decides only the final choice among the fitted graphs
(``selection.fit``): ordering near-ties by simplicity here pushed the true graph out of the top 3
on 2 of the 32 targets of ``bench selection`` (30/32 in the top 3 by distance, 28/32 with the tie
rule), while fitting one more candidate costs time, never the simpler answer (the final choice
still prefers it).
"""
from __future__ import annotations

import math

import torch

from ..diffmat.calibration import proposal_gains, with_gain
from ..diffmat.descriptor import TextureDescriptor, style_loss
from ..diffmat.optim import resize_square
from ..diffmat.render import render_maps
from ..errors import BlenderMatchError, Cancelled, OptionError
from ..library import MODELS_DIR, library_entry, library_names, load_library_graph, user_library_dir
from .bank import bank_is_current, current_bank, nearest, supersample
from .descriptor import DESCRIPTOR_SIZE, compact_descriptor, shared_vgg
from .index import selection_index
from .predictor import load_predictor, predictor_is_current

METHODS = ("predictor", "bank", "both")
RANK_SIZE = 128
TIE_TOLERANCE = 0.02
SHORTLIST = 10  # graphs the selection index lets through to be rendered (see docs/benchmarks.md)
# A proposal's distance is its style loss times exp(EXPOSURE_WEIGHT x |e| + TINT_WEIGHT x the mean
# |c|), where its gain is 2^(e + c) per channel: e the stops of exposure (the mean over channels),
# c each channel's stops of white balance around it. The photo's exposure and white balance are
# forgiven, as the match's own calibration forgives them, but of two graphs that match the
# structure alike the one that needs less of a correction comes first; a tint costs more than an
# exposure, which a flash photo leaves unknown by stops (docs/benchmarks.md).
EXPOSURE_WEIGHT = 0.1
TINT_WEIGHT = 0.2
NO_MODELS = ("automatic graph selection needs the selection models (parameter predictors or sample banks) "
             "and none were found in {where}; create them with `blender-match train --all`")


class NoSelectionModels(BlenderMatchError):
    """No library graph has a current predictor or bank, so none can be ranked."""


def available_models(method: str = "both", directory=None) -> list[str]:
    """Library graphs that have a current model of the kind ``method`` uses."""
    if method not in METHODS:
        raise OptionError(f"method {method!r}: expected one of {', '.join(METHODS)}")
    names = []
    for name in library_names():
        has_pred = method in ("predictor", "both") and predictor_is_current(name, directory)
        has_bank = method in ("bank", "both") and bank_is_current(name, directory)
        if has_pred or has_bank:
            names.append(name)
    return names


def simplicity(entry: dict) -> tuple:
    return (entry["nodes"], entry["params"])


def order_by_simplicity(entries: list[dict], tolerance: float = TIE_TOLERANCE, key: str = "distance") -> list[dict]:
    """Entries best (lowest ``key``) first, where everything within ``tolerance`` (relative) of
    the best remaining entry ties and the simplest of a tie (fewer nodes, then parameters) comes
    first."""
    left = sorted(entries, key=lambda e: e[key])
    out = []
    while left:
        best = left[0][key]
        limit = best + abs(best) * tolerance
        tied = [e for e in left if e[key] <= limit]
        pick = min(tied, key=lambda e: (*simplicity(e), e[key]))
        out.append(pick)
        left.remove(pick)
    return out


def propose_starts(name: str, graph, descriptor: torch.Tensor, method: str = "both",
                   directory=None, bank_start: torch.Tensor | None = None) -> list[tuple[str, torch.Tensor]]:
    """(start kind, normalised (P,) theta) the models propose for one graph, given the photo's
    compact descriptor; with both models (``method`` "both"), the graph's own defaults first, so
    that a ranking and a named graph's fit (``start.choose_start``) weigh the same starts. None at
    all when no model of ``method`` has a proposal. ``bank_start``: the bank's nearest sample when
    the caller already has it (the selection index's); else the graph's bank is read."""
    out = []
    P = graph.num_params()
    if method in ("predictor", "both") and predictor_is_current(name, directory):
        model = load_predictor(name, directory)
        if model is not None and model.default.numel() == P:
            with torch.no_grad():
                out.append(("predicted", model(descriptor.cpu())[0].clamp(0, 1)))
    if method in ("bank", "both"):
        if bank_start is None:
            bank = current_bank(name, directory)
            bank_start = nearest(bank, descriptor.cpu())[0]["theta"] if bank is not None else None
        if bank_start is not None and bank_start.numel() == P:
            out.append(("bank", bank_start))
    if out and method == "both":
        out.insert(0, ("default", graph.get_vector()))
    return out


def correction_cost(gains: torch.Tensor) -> torch.Tensor:
    """The log-distance cost (N,) of the base colour gains (N, 3) a ranking gives its proposals
    (``EXPOSURE_WEIGHT``, ``TINT_WEIGHT``)."""
    stops = gains.log2()
    exposure = stops.mean(dim=1, keepdim=True)
    return EXPOSURE_WEIGHT * exposure[:, 0].abs() + TINT_WEIGHT * (stops - exposure).abs().mean(dim=1)


def check_photo(photo: torch.Tensor) -> torch.Tensor:
    """The photo as a float (1, 3, H, W) tensor in [0, 1] (OptionError for another shape)."""
    if photo.dim() == 3:
        photo = photo[None]
    if photo.dim() != 4 or photo.shape[:2] != (1, 3):
        raise OptionError(f"photo must be a (1, 3, H, W) RGB tensor, got {tuple(photo.shape)}")
    return photo.float().clamp(0, 1)


def best_finite(losses: torch.Tensor) -> int:
    """The index of the lowest loss, non-finite losses counting as infinite."""
    losses = torch.where(torch.isfinite(losses), losses, torch.full_like(losses, math.inf))
    return int(torch.argmin(losses))


def load_material(name: str, device, materials: dict | None = None):
    """Library graph ``name`` on ``device``, from the ``materials`` cache
    when it holds it, else loaded (and cached)."""
    graph = materials.get(name) if materials is not None else None
    if graph is None:
        graph = load_library_graph(name).to(device)
        if materials is not None:
            materials[name] = graph
    return graph


def rank_graphs(photo: torch.Tensor, method: str = "both", *, seed: int = 0, device="cpu", directory=None,
                graphs=None, shortlist: int | None = SHORTLIST, progress=None, cancel=None,
                materials: dict | None = None) -> list[dict]:
    """The library graphs with a model that come nearest the photo, best first: {"graph",
    "distance" (style loss at 128 px of the proposed parameters' render under its "gain", times
    the gain's ``correction_cost``), "theta" (normalised (P,)), "start" ("predicted" | "bank" | "default"),
    "gain" (the base colour gain, 3 values), "nodes", "params"}. With banks (``method`` "bank" or
    "both"), only the ``shortlist`` graphs the selection index puts nearest (and any graph with
    a predictor but no bank) are rendered and returned; ``shortlist=None`` renders them all.
    ``photo``: (1, 3, H, W) sRGB in [0, 1] (moved to ``device`` once); ``graphs`` limits the
    names; ``materials`` caches loaded graphs by name (filled as graphs are loaded; they are only
    evaluated with explicit parameters here, so their own are unchanged). ``progress`` gets
    {"graph", "graph_index", "graph_count"}; ``cancel()`` raises Cancelled."""
    photo = check_photo(photo).to(device)
    names = available_models(method, directory)
    if graphs is not None:
        wanted = set(graphs)
        names = [n for n in names if n in wanted]
    if not names:
        where = directory if directory is not None else f"{MODELS_DIR} nor {user_library_dir() / 'models'}"
        raise NoSelectionModels(NO_MODELS.format(where=where))
    vgg = shared_vgg(device)
    gram = TextureDescriptor(scales=(RANK_SIZE,), vgg=vgg)
    with torch.no_grad():
        descriptor = compact_descriptor(vgg, photo, DESCRIPTOR_SIZE)
        small = resize_square(photo, RANK_SIZE)
        target = gram(small, (RANK_SIZE,))
    bank_starts: dict[str, torch.Tensor] = {}
    if method != "predictor":
        banks = selection_index(names, directory)
        bank_starts = {e["graph"]: e["theta"] for e in banks.nearest_graphs(descriptor, shortlist)}
        names = list(bank_starts) + [n for n in names if n not in banks.names]
    entries = []
    for index, name in enumerate(names):
        if cancel is not None and cancel():
            raise Cancelled()
        if progress is not None:
            progress({"graph": name, "graph_index": index + 1, "graph_count": len(names)})
        graph = load_material(name, device, materials)
        proposals = propose_starts(name, graph, descriptor, method, directory, bank_starts.get(name))
        if not proposals:
            continue
        thetas = torch.stack([t for _, t in proposals]).to(device)
        entry = library_entry(name)
        size = RANK_SIZE * supersample(entry)
        with torch.no_grad():
            maps = {u: m.expand(thetas.shape[0], -1, -1, -1)
                    for u, m in graph(size=size, seed=seed, theta=thetas).items()}
            gains = proposal_gains(maps, resize_square(photo, size))
            image = resize_square(render_maps(with_gain(maps, gains)).clamp(0, 1), RANK_SIZE)
            losses = style_loss(gram(image, (RANK_SIZE,)), target)
            losses = (losses * torch.exp(correction_cost(gains))).cpu()
        best = best_finite(losses)
        entries.append({"graph": name, "distance": float(losses[best]), "theta": proposals[best][1].cpu(),
                        "start": proposals[best][0], "gain": [round(float(g), 4) for g in gains[best]],
                        "nodes": entry["nodes"], "params": entry["params_optimizable"]})
        graph.clear_cache()
    return sorted(entries, key=lambda e: e["distance"])
