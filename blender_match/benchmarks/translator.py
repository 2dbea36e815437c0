"""``blender-match bench translator [--files F.sbs|DIR …]``: translate and render every .sbs file
given (a folder: every .sbs under it, as ``library add`` reads one), and count how many translate
and how many render.

Per file: the translation time (best of 3), the node counts (native, passed through, and the kinds
passed through), the optimisable parameters, the evaluation time of the translated graph at 512²
and whether every map it renders is finite. A file that does not translate or render is a row with
its one-line error, and the run goes on: a sweep over a folder of production files is the point.
The last row counts the files, those translated and those rendered. Default files: the real
packages in ``../shared/data/sbs``. With ``out``: ``results.json`` (the files given, every row and
the count) and ``results.md``."""
from __future__ import annotations

from pathlib import Path

import torch

from ..errors import BlenderMatchError
from ..pipeline.user_library import sbs_files
from ..translator import Translation, translate
from .markdown import table
from .measure import best_of
from .results_files import write_json_and_markdown

DEFAULT_DIR = Path(__file__).resolve().parents[2].parent / "shared" / "data" / "sbs"
SIZE = 512


def _passthrough_kinds(report: dict) -> str:
    return ", ".join(f"{kind} ×{count}" if count > 1 else kind for kind, count in report["unsupported"].items())


def _translate(path: Path, repeats: int, row: dict) -> Translation:
    translations: list[Translation] = []
    t = best_of(lambda: translations.append(translate(path)), repeats)
    report = translations[-1].report
    row |= {"nodes": report["nodes_total"], "native": report["nodes_translated"],
            "passthrough": report["nodes_passthrough"], "passed_through": _passthrough_kinds(report),
            "params": report["params_optimizable"], "translate_s": t.seconds}
    return translations[-1]


def _render(path: Path, result: Translation, device: str, row: dict):
    graph = result.graph.to(device)
    maps: dict[str, torch.Tensor] = {}

    def evaluate():
        with torch.no_grad():
            maps.update(graph(size=SIZE))

    graph.clear_cache()
    row["eval_512_s"] = best_of(evaluate, 1, device).seconds
    bad = [name for name, image in maps.items() if not torch.isfinite(image).all()]
    if bad:
        raise BlenderMatchError(f"{path}: maps not finite: {', '.join(bad)}")


def run(device: str = "cpu", files: list[Path] | None = None, repeats: int = 3, out: Path | None = None) -> list[dict]:
    given = [Path(f) for f in files] if files else [DEFAULT_DIR]
    paths = [f for g in files for f in sbs_files(g)] if files else sorted(DEFAULT_DIR.glob("*.sbs"))
    if not paths:
        raise FileNotFoundError(f"{', '.join(map(str, given))}: no .sbs files to translate"
                                + ("" if files else " (pass --files)"))
    rows = []
    for path in paths:
        row: dict = {"file": path.name}
        try:
            _render(path, _translate(path, repeats, row), device, row)
            row |= {"rendered": True, "error": ""}
        except (BlenderMatchError, OSError, ValueError, RuntimeError) as exc:
            row |= {"rendered": False, "error": (str(exc).splitlines() or [type(exc).__name__])[0][:200]}
        rows.append(row)
    translated = sum("nodes" in r for r in rows)
    rendered = sum(r["rendered"] for r in rows)
    columns = dict.fromkeys(k for r in rows for k in r)
    rows = [{k: r.get(k, "") for k in columns} for r in rows]
    summary = dict.fromkeys(columns, "")
    summary |= {"file": f"all: {len(rows)} files", "nodes": f"{translated} translated",
                "rendered": f"{rendered} rendered", "error": f"{len(rows) - rendered} failed"}
    if out is not None:
        count = {"files": len(rows), "translated": translated, "rendered": rendered}
        write_json_and_markdown(out, {"config": {"files": [str(g) for g in given], "size": SIZE, "device": device,
                                                 "repeats": repeats}, "summary": count, "rows": rows},
                                "\n\n".join(["# bench translator", table([count], list(count)), "## Per file",
                                             table(rows, list(columns))]))
    return rows + [summary]
