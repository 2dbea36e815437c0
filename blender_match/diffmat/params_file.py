"""Graph parameters as a JSON file: real (not normalised) values by "node.param", so a fitted
material can be re-rendered at another size, edited by hand, or shipped with a result.

Format: ``{"graph": NAME, "params": {"node.param": value or [values]}}``; graph-level parameter
sets appear like nodes (a translated graph's exposed parameters as ``exposed.NAME``). Loading checks every
entry against the graph (unknown node or parameter, wrong component count, a value outside the
parameter's range, a non-finite value) and raises DiffMatError naming the file and the entry;
nothing is changed unless the whole file is valid.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import torch

from ..safe_files import write_json_atomic
from .errors import DiffMatError


def graph_params(graph) -> dict[str, float | list[float]]:
    """Every continuous parameter's real value, by "owner.param" (a node, or a graph-level
    parameter set such as a translated graph's ``exposed``)."""
    out = {}
    for owner, ps in graph.parameter_sets().items():
        for param, value in ps.values().items():
            if param in ps.theta:
                flat = [round(float(v), 6) for v in value.detach().reshape(-1)]
                out[f"{owner}.{param}"] = flat[0] if len(flat) == 1 else flat
    return out


def save_params(graph, path: Path, overwrite: bool = False, **about):
    """Write the graph's parameters to ``path`` (atomically; refuses to replace a file unless asked);
    ``about``: more top-level entries, written between the graph's name and its parameters (a
    result folder's source and seed; ``load_params`` reads the parameters only)."""
    write_json_atomic(Path(path), {"graph": graph.name, **about, "params": graph_params(graph)}, overwrite=overwrite)


def _check_entry(graph, key: str, value, where: str) -> tuple[str, str, torch.Tensor]:
    owner, _, param = key.partition(".")
    sets = graph.parameter_sets()
    if owner not in sets:
        raise DiffMatError(f"{where}: unknown node {owner!r} in {key!r}")
    ps = sets[owner]
    if param not in ps.theta:
        raise DiffMatError(f"{where}: {owner!r} ({ps.label}) has no continuous parameter {param!r}")
    values = value if isinstance(value, list) else [value]
    if not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in values):
        raise DiffMatError(f"{where}: {key} must be a finite number or a list of them, got {value!r}")
    t = torch.tensor(values, dtype=torch.float32)
    if t.numel() != ps.theta[param].numel():
        raise DiffMatError(f"{where}: {key} has {t.numel()} component(s), expected {ps.theta[param].numel()}")
    lo, hi = ps.ranges[param]
    if t.min() < lo - 1e-6 or t.max() > hi + 1e-6:
        raise DiffMatError(f"{where}: {key} = {value!r} is outside [{lo:g}, {hi:g}]")
    return owner, param, t.clamp(lo, hi)


def read_params_file(path: Path) -> dict:
    """The JSON object of a parameter file (DiffMatError naming the file when it is unreadable)."""
    path = Path(path)
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise DiffMatError(f"{path}: parameter file not found") from None
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise DiffMatError(f"{path}: not a readable JSON parameter file ({exc})") from None
    if not isinstance(data, dict):
        raise DiffMatError(f"{path}: expected an object with a \"params\" object")
    return data


def load_params(graph, path: Path):
    """Set the graph's parameters from a file written by ``save_params`` (or by hand)."""
    data = read_params_file(path)
    if not isinstance(data.get("params"), dict):
        raise DiffMatError(f"{path}: expected an object with a \"params\" object")
    apply_params(graph, data["params"], str(path))


def apply_params(graph, params: dict, where: str = "parameters"):
    """Set parameters from a {"node.param": value} dict (the "params" of a file), checking every
    entry first; nothing changes unless all are valid. ``where`` names the source in errors."""
    checked = [_check_entry(graph, k, v, where) for k, v in params.items()]
    sets = graph.parameter_sets()
    for owner, param, t in checked:
        sets[owner].set_values(**{param: t})
    graph.clear_cache()
