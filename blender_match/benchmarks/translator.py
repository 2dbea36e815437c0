"""``blender-match bench translator [--files F.sbs …]``: translation time of .sbs files and the
evaluation time of the translated graph at 512² (default files: the real packages in
``../shared/data/sbs``)."""
from __future__ import annotations

from pathlib import Path

import torch

from ..translator import Translation, translate
from .measure import best_of

DEFAULT_DIR = Path(__file__).resolve().parents[2].parent / "shared" / "data" / "sbs"


def run(device: str = "cpu", files: list[Path] | None = None, repeats: int = 3) -> list[dict]:
    files = [Path(f) for f in files] if files else sorted(DEFAULT_DIR.glob("*.sbs"))
    if not files:
        raise FileNotFoundError(f"{DEFAULT_DIR}: no .sbs files to translate (pass --files)")
    rows = []
    for path in files:
        translations: list[Translation] = []
        t = best_of(lambda: translations.append(translate(path)), repeats)
        result = translations[-1]
        graph = result.graph.to(device)
        report = result.report

        def evaluate():
            with torch.no_grad():
                graph(size=512)

        graph.clear_cache()
        e = best_of(evaluate, 1, device)
        rows.append({"file": path.name, "nodes": report["nodes_total"], "native": report["nodes_translated"],
                     "passthrough": report["nodes_passthrough"], "params": report["params_optimizable"],
                     "translate_s": t.seconds, "eval_512_s": e.seconds})
    return rows
