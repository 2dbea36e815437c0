"""Graph parameters as a JSON file: real (not normalised) values by "node.param", so a fitted
material can be re-rendered at another size, edited by hand, or shipped with a result.

Format: ``{"graph": NAME, "params": {"node.param": value or [values]}}``. A graph with exposed
parameters (the translator's SbsGraph) also lists its exposed float parameters as ``exposed.NAME``. Loading checks every
entry against the graph (unknown node or parameter, wrong component count, a value outside the
parameter's range, a non-finite value) and raises DiffMatError naming the file and the entry;
nothing is changed unless the whole file is valid.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import torch

from .errors import DiffMatError


def graph_params(graph) -> dict[str, float | list[float]]:
    """Every continuous parameter's real value, by "node.param"."""
    out = {}
    for name, node in graph.nodes.items():
        for param, value in node.values().items():
            flat = [round(float(v), 6) for v in value.detach().reshape(-1)]
            out[f"{name}.{param}"] = flat[0] if len(flat) == 1 else flat
    exposed = getattr(graph, "exposed", None)
    if exposed is not None and "exposed" not in graph.nodes:
        for param, value in exposed.values().items():
            if param in exposed.theta:
                flat = [round(float(v), 6) for v in value.detach().reshape(-1)]
                out[f"exposed.{param}"] = flat[0] if len(flat) == 1 else flat
    return out


def save_params(graph, path: Path, overwrite: bool = False):
    """Write the graph's parameters to ``path`` (atomically; refuses to replace a file unless asked)."""
    from ..image_files import write_atomic

    text = json.dumps({"graph": graph.name, "params": graph_params(graph)}, indent=1)
    write_atomic(Path(path), text.encode("utf-8"), overwrite=overwrite)


def _check_entry(graph, key: str, value, where: str) -> tuple[str, str, torch.Tensor]:
    node_name, _, param = key.partition(".")
    exposed = getattr(graph, "exposed", None)
    if node_name == "exposed" and exposed is not None and node_name not in graph.nodes:
        if param not in exposed.theta:
            raise DiffMatError(f"{where}: the graph has no exposed float parameter {param!r}")
        return _checked_value(key, value, exposed.theta[param].numel(), exposed.ranges[param], where, node_name, param)
    if node_name not in graph.nodes:
        raise DiffMatError(f"{where}: unknown node {node_name!r} in {key!r}")
    node = graph.nodes[node_name]
    if param not in node.theta:
        raise DiffMatError(f"{where}: node {node_name!r} ({node.spec.name}) has no continuous parameter {param!r}")
    return _checked_value(key, value, node.theta[param].numel(), node.ranges[param], where, node_name, param)


def _checked_value(key, value, numel, bounds, where, node_name, param):
    values = value if isinstance(value, list) else [value]
    if not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in values):
        raise DiffMatError(f"{where}: {key} must be a finite number or a list of them, got {value!r}")
    t = torch.tensor(values, dtype=torch.float32)
    if t.numel() != numel:
        raise DiffMatError(f"{where}: {key} has {t.numel()} component(s), expected {numel}")
    lo, hi = bounds
    if t.min() < lo - 1e-6 or t.max() > hi + 1e-6:
        raise DiffMatError(f"{where}: {key} = {value!r} is outside [{lo:g}, {hi:g}]")
    return node_name, param, t.clamp(lo, hi)


def load_params(graph, path: Path):
    """Set the graph's parameters from a file written by ``save_params`` (or by hand)."""
    path = Path(path)
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise DiffMatError(f"{path}: parameter file not found") from None
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise DiffMatError(f"{path}: not a readable JSON parameter file ({exc})") from None
    if not isinstance(data, dict) or not isinstance(data.get("params"), dict):
        raise DiffMatError(f"{path}: expected an object with a \"params\" object")
    apply_params(graph, data["params"], str(path))


def apply_params(graph, params: dict, where: str = "parameters"):
    """Set parameters from a {"node.param": value} dict (the "params" of a file), checking every
    entry first; nothing changes unless all are valid. ``where`` names the source in errors."""
    checked = [_check_entry(graph, k, v, where) for k, v in params.items()]
    for node_name, param, t in checked:
        if node_name == "exposed" and node_name not in graph.nodes:
            graph.exposed.set_values(**{param: t})
        else:
            graph.nodes[node_name].set_values(**{param: t})
    graph.clear_cache()
