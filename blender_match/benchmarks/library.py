"""``blender-match bench library``: per library graph, its node and optimisable-parameter counts,
the number of exposed parameters, and the time of one evaluation (no gradients, cache cleared) at
512² and 2048²."""
from __future__ import annotations

import torch

from ..library import builtin_names, library_entry, load_library_graph
from .measure import best_of

SIZES = (512, 2048)


def run(device: str = "cpu", graphs: list[str] | None = None, sizes=SIZES, repeats: int = 1) -> list[dict]:
    names = graphs or builtin_names()
    if not names:
        raise FileNotFoundError("no library graphs are built (python -m blender_match.library.build)")
    rows = []
    for name in names:
        entry = library_entry(name)
        graph = load_library_graph(name).to(device)
        row = {"graph": name, "nodes": entry["nodes"], "params_optimizable": entry["params_optimizable"],
               "exposed": len(entry["exposed"])}
        for size in sizes:
            def evaluate():
                graph.clear_cache()
                with torch.no_grad():
                    graph(size=size)
            row[f"render_{size}_s"] = best_of(evaluate, repeats, device).seconds
        rows.append(row)
    return rows
